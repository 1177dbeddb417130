// OBJ + MTL to glTF 2.0, for the tests of the glTF loader: an independent writer that gives the
// loader the geometry the OBJ loader makes from the same file (host/scene/obj_loader.cpp), so that
// a scene read from either renders the same. Written from the glTF 2.0 specification
// (registry.khronos.org/glTF/specs/2.0/glTF-2.0.html) and the KHR_materials_transmission, _ior and
// _volume extensions, not from the loader.
#pragma once

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <tiny_obj_loader.h>

#include "scene/mtl_material.h"
#include "scene/mtl_parser.h"
#include "scene/scene.h"

namespace vitrum::testing {

namespace gltf_writer {

namespace fs = std::filesystem;

// glTF's enumerations (glTF 2.0, "Accessor Data Types", "Buffer View", "Meshes").
constexpr int kFloat = 5126, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kTriangles = 4;

// The one binary buffer of the file, with a buffer view and an accessor for each array.
struct Buffer {
    std::vector<char> bytes;
    nlohmann::json views = nlohmann::json::array();
    nlohmann::json accessors = nlohmann::json::array();

    // Every component is 4 bytes, so each view starts aligned as the specification asks.
    int add(const void* data, std::size_t size, int target, nlohmann::json accessor) {
        const std::size_t offset = bytes.size();
        bytes.resize(offset + size);
        if (size > 0) std::memcpy(bytes.data() + offset, data, size);
        views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}, {"target", target}});
        accessor["bufferView"] = views.size() - 1;
        accessors.push_back(std::move(accessor));
        return int(accessors.size() - 1);
    }

    int vec3(const std::vector<glm::vec3>& values, bool withBounds) {
        nlohmann::json accessor = {{"componentType", kFloat}, {"count", values.size()}, {"type", "VEC3"}};
        // POSITION must carry its bounds (glTF 2.0, "Meshes: Overview"); float to double is exact.
        if (withBounds) {
            glm::vec3 low = values.front(), high = values.front();
            for (const glm::vec3& v : values) {
                low = glm::min(low, v);
                high = glm::max(high, v);
            }
            accessor["min"] = {double(low.x), double(low.y), double(low.z)};
            accessor["max"] = {double(high.x), double(high.y), double(high.z)};
        }
        return add(values.data(), values.size() * sizeof(glm::vec3), kArrayBuffer, std::move(accessor));
    }
    int vec2(const std::vector<glm::vec2>& values) {
        return add(values.data(), values.size() * sizeof(glm::vec2), kArrayBuffer,
                   {{"componentType", kFloat}, {"count", values.size()}, {"type", "VEC2"}});
    }
    int indices(const std::vector<std::uint32_t>& values) {
        return add(values.data(), values.size() * sizeof(std::uint32_t), kElementArrayBuffer,
                   {{"componentType", kUnsignedInt}, {"count", values.size()}, {"type", "SCALAR"}});
    }
};

// A relative path as a URI reference: '/' between its parts, every byte other than RFC 3986's
// unreserved characters percent-encoded (glTF 2.0, "URIs").
inline std::string uriOf(const fs::path& relative) {
    std::string uri;
    for (unsigned char c : relative.generic_string()) {
        if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/') {
            uri += char(c);
        } else {
            static constexpr char kHex[] = "0123456789ABCDEF";
            uri += '%';
            uri += kHex[c >> 4];
            uri += kHex[c & 15];
        }
    }
    return uri;
}

// Hands tinyobjloader the names of an MTL file, in the order of the file, as the OBJ loader's
// LibraryReader does, and keeps each record with the file it came from.
class NameReader : public tinyobj::MaterialReader {
public:
    NameReader(fs::path objFolder, std::optional<fs::path> mtlOverride)
        : objFolder_(std::move(objFolder)), mtlOverride_(std::move(mtlOverride)) {}

    bool operator()(const std::string& mtllib, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* names, std::string*, std::string*) override {
        const fs::path file = mtlOverride_ ? *mtlOverride_ : objFolder_ / mtllib;
        if (!fs::exists(file)) return true;  // the OBJ loader warns and gives its faces the default
        for (const MtlEntry& entry : parseMtlFile(file)) {
            if (names->count(entry.name)) continue;  // the first definition wins, as in the OBJ loader
            (*names)[entry.name] = int(materials->size());
            materials->emplace_back().name = entry.name;
            records.push_back({entry, file});
        }
        return true;
    }

    std::vector<std::pair<MtlEntry, fs::path>> records;  // tinyobj material id -> MTL record, its file

private:
    fs::path objFolder_;
    std::optional<fs::path> mtlOverride_;
};

// The glTF material whose loader mapping gives back the MTL record's material (materialFromMtl:
// the model, the sRGB decoding, the defaults of scene.h and the clamping the OBJ loader applies).
inline nlohmann::json material(const MtlEntry& entry, const fs::path& mtlFile, const fs::path& outFolder,
                               nlohmann::json& images, nlohmann::json& textures, std::set<std::string>& extensions) {
    const Material m = materialFromMtl(entry, mtlFile);
    auto rgba = [](glm::vec3 c) { return nlohmann::json{double(c.r), double(c.g), double(c.b), 1.0}; };
    nlohmann::json out = {{"name", entry.name}};
    nlohmann::json& pbr = out["pbrMetallicRoughness"];
    if (m.model == MaterialModel::Glass) {
        // The base colour of a volume is its surface's tint.
        pbr = {{"baseColorFactor", rgba(m.tint)}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.0}};
        out["extensions"]["KHR_materials_transmission"] = {{"transmissionFactor", 1.0}};
        out["extensions"]["KHR_materials_ior"] = {{"ior", double(m.ior)}};
        // A volume of non-zero thickness: a closed mesh, not a thin wall. Beer-Lambert's mu is
        // -ln(attenuationColor) / attenuationDistance (KHR_materials_volume, "Properties").
        nlohmann::json volume = {{"thicknessFactor", 1.0}};
        if (m.attenuation != glm::vec3(0.0f)) {
            volume["attenuationDistance"] = 1.0;
            volume["attenuationColor"] = {std::exp(-double(m.attenuation.r)), std::exp(-double(m.attenuation.g)),
                                          std::exp(-double(m.attenuation.b))};
        }
        out["extensions"]["KHR_materials_volume"] = volume;
        extensions.insert({"KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume"});
        return out;
    }
    if (m.model == MaterialModel::Mirror) {
        pbr = {{"baseColorFactor", rgba(m.specular)}, {"metallicFactor", 1.0}, {"roughnessFactor", 0.0}};
        return out;
    }
    // The inverse of the loader's Ns = 2 / alpha^2 - 2 (the Phong exponent of a Beckmann width,
    // Walter et al., "Microfacet Models for Refraction", EGSR 2007, section 5.2) with alpha =
    // roughness^2 (glTF 2.0, Appendix B).
    const double roughness = std::pow(2.0 / (double(m.shininess) + 2.0), 0.25);
    pbr = {{"baseColorFactor", rgba(m.diffuse)}, {"metallicFactor", 0.0}, {"roughnessFactor", roughness}};
    if (m.model == MaterialModel::ThinGlass) {
        // Transmission without a volume: thin-walled, tinted by the base colour (Kd, map_Kd below).
        out["extensions"]["KHR_materials_transmission"] = {{"transmissionFactor", 1.0}};
        extensions.insert("KHR_materials_transmission");
    }
    if (m.model == MaterialModel::Phong) {
        // Ks as the specular layer's colour over F0 of the material's IOR (the loader's
        // min(F0 * specularColorFactor, 1) * specularFactor, KHR_materials_specular).
        const double f0 = std::pow((double(m.ior) - 1.0) / (double(m.ior) + 1.0), 2.0);
        out["extensions"]["KHR_materials_specular"] = {
            {"specularColorFactor", {m.specular.r / f0, m.specular.g / f0, m.specular.b / f0}}};
        extensions.insert("KHR_materials_specular");
    }
    if (m.model == MaterialModel::Lambert) {
        // No specular layer (KHR_materials_specular's specularFactor 0): the loader's Lambert.
        out["extensions"]["KHR_materials_specular"] = {{"specularFactor", 0.0}};
        extensions.insert("KHR_materials_specular");
    }
    if (entry.ni) {
        out["extensions"]["KHR_materials_ior"] = {{"ior", double(m.ior)}};
        extensions.insert("KHR_materials_ior");
    }
    if (entry.mapKd) {
        std::string name = *entry.mapKd;
        std::replace(name.begin(), name.end(), '\\', '/');  // as the OBJ loader reads it
        const fs::path image = fs::absolute(mtlFile.parent_path() / name);
        // A texture the OBJ loader cannot find falls back to Kd there; here it is left out.
        if (fs::is_regular_file(image)) {
            const std::string uri = uriOf(fs::relative(image, fs::absolute(outFolder)));
            auto found = std::find_if(images.begin(), images.end(), [&](const auto& i) { return i["uri"] == uri; });
            const std::size_t source = std::size_t(std::distance(images.begin(), found));
            if (found == images.end()) images.push_back({{"uri", uri}});
            textures.push_back({{"source", source}});
            pbr["baseColorTexture"] = {{"index", textures.size() - 1}};
            // The texture alone is the colour, as in the OBJ loader (base colour = factor * texture).
            pbr["baseColorFactor"] = {1.0, 1.0, 1.0, 1.0};
        }
    }
    return out;
}

// One glTF vertex: what the OBJ loader reads at a face corner.
using Corner = std::tuple<int, int, int>;  // vertex, texture coordinate, normal; -1 where absent

}  // namespace gltf_writer

// Writes `outGltf` and its buffer (same stem, ".bin") from the OBJ file `obj` with its MTL (its
// own mtllib, or `mtlOverride` as a JSON scene's "mtl" gives it). Each OBJ shape with a triangle
// is one mesh under one root node named after it; its faces, in file order and fanned from their
// first corner as the OBJ loader does, go into one primitive per run of faces with one material
// (and with or without normals), so the triangles keep their order. Primitives are indexed
// (UNSIGNED_INT) and not in turn. vitrum's z-up point (x, y, z) is glTF's y-up (x, z, -y)
// (gltfToZUp's inverse); texture coordinates (u, v) become (u, 1 - v), glTF's v running down the
// image. Faces without a material get none. Throws std::runtime_error where the OBJ cannot be read
// or says something glTF cannot (a face with normals at some corners only).
inline void writeGltfFromObj(const std::filesystem::path& obj, const std::optional<std::filesystem::path>& mtlOverride,
                             const std::filesystem::path& outGltf) {
    namespace fs = std::filesystem;
    using namespace gltf_writer;
    std::ifstream in(obj, std::ios::binary);
    if (!in) throw std::runtime_error(obj.string() + ": cannot be read");
    std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    // An override replaces the file's mtllib; a file without one gets one, as in the OBJ loader.
    if (mtlOverride && text.find("mtllib") == std::string::npos) text.insert(0, "mtllib override\n");
    std::istringstream stream(text);
    NameReader reader(obj.parent_path(), mtlOverride);
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> names;
    std::string warnings, errors;
    if (!tinyobj::LoadObj(&attrib, &shapes, &names, &warnings, &errors, &stream, &reader, false) || !errors.empty())
        throw std::runtime_error(obj.string() + ": " + errors);

    const fs::path outFolder = outGltf.parent_path().empty() ? fs::path(".") : outGltf.parent_path();
    const fs::path binFile = fs::path(outGltf).replace_extension(".bin");
    Buffer buffer;
    nlohmann::json materials = nlohmann::json::array(), images = nlohmann::json::array(),
                   textures = nlohmann::json::array(), meshes = nlohmann::json::array(),
                   nodes = nlohmann::json::array();
    std::set<std::string> extensions;
    std::map<int, int> gltfMaterial;  // tinyobj material id -> glTF material, in order of first use
    int primitiveCount = 0;

    for (std::size_t s = 0; s < shapes.size(); ++s) {
        const tinyobj::mesh_t& mesh = shapes[s].mesh;
        std::string shapeName = shapes[s].name;
        shapeName.erase(shapeName.find_last_not_of(" \t\r") + 1);
        nlohmann::json primitives = nlohmann::json::array();
        std::size_t offset = 0, f = 0;
        const std::size_t faces = mesh.num_face_vertices.size();
        while (f < faces) {
            // One run: faces of the same material and the same presence of normals.
            auto withNormals = [&](std::size_t face, std::size_t first) {
                std::size_t have = 0;
                for (std::size_t k = 0; k < mesh.num_face_vertices[face]; ++k)
                    have += mesh.indices[first + k].normal_index >= 0;
                if (have != 0 && have != mesh.num_face_vertices[face])
                    throw std::runtime_error(obj.string() + ": a face of \"" + shapeName +
                                             "\" has normals at some corners only");
                return have != 0;
            };
            const int tinyMaterial = mesh.material_ids[f];
            const bool normals = withNormals(f, offset);
            std::vector<Corner> triangleCorners;
            for (; f < faces && mesh.material_ids[f] == tinyMaterial && withNormals(f, offset) == normals; ++f) {
                const std::size_t corners = mesh.num_face_vertices[f];
                auto corner = [&](std::size_t k) {
                    const tinyobj::index_t& i = mesh.indices[offset + k];
                    return Corner{i.vertex_index, i.texcoord_index, i.normal_index};
                };
                for (std::size_t k = 1; k + 1 < corners; ++k)
                    triangleCorners.insert(triangleCorners.end(), {corner(0), corner(k), corner(k + 1)});
                offset += corners;
            }
            if (triangleCorners.empty()) continue;  // faces of fewer than three corners make no triangle

            const bool indexed = primitiveCount++ % 2 == 0;
            std::vector<Corner> vertices;
            std::vector<std::uint32_t> indices;
            if (indexed) {
                std::map<Corner, std::uint32_t> numbers;
                for (const Corner& c : triangleCorners) {
                    auto [at, added] = numbers.emplace(c, std::uint32_t(vertices.size()));
                    if (added) vertices.push_back(c);
                    indices.push_back(at->second);
                }
            } else {
                vertices = triangleCorners;
            }
            std::vector<glm::vec3> positions, normalValues;
            std::vector<glm::vec2> uvs;
            bool anyUv = false;
            for (const auto& [v, t, n] : vertices) {
                const tinyobj::real_t* p = &attrib.vertices[3 * std::size_t(v)];
                positions.emplace_back(float(p[0]), float(p[2]), -float(p[1]));
                if (normals) {
                    const tinyobj::real_t* q = &attrib.normals[3 * std::size_t(n)];
                    normalValues.emplace_back(float(q[0]), float(q[2]), -float(q[1]));
                }
                // A corner without one reads (0, 0) in the OBJ loader.
                const glm::vec2 uv = t >= 0 ? glm::vec2(float(attrib.texcoords[2 * std::size_t(t)]),
                                                        float(attrib.texcoords[2 * std::size_t(t) + 1]))
                                            : glm::vec2(0.0f);
                uvs.emplace_back(uv.x, 1.0f - uv.y);
                anyUv = anyUv || t >= 0;
            }
            nlohmann::json primitive = {{"mode", kTriangles}};
            primitive["attributes"]["POSITION"] = buffer.vec3(positions, true);
            if (normals) primitive["attributes"]["NORMAL"] = buffer.vec3(normalValues, false);
            if (anyUv) primitive["attributes"]["TEXCOORD_0"] = buffer.vec2(uvs);
            if (indexed) primitive["indices"] = buffer.indices(indices);
            if (tinyMaterial >= 0 && std::size_t(tinyMaterial) < reader.records.size()) {
                auto [at, added] = gltfMaterial.emplace(tinyMaterial, int(materials.size()));
                if (added) {
                    const auto& [entry, mtlFile] = reader.records[std::size_t(tinyMaterial)];
                    materials.push_back(material(entry, mtlFile, outFolder, images, textures, extensions));
                }
                primitive["material"] = at->second;
            }
            primitives.push_back(std::move(primitive));
        }
        if (primitives.empty()) continue;  // the OBJ loader makes no object of a shape without triangles
        nlohmann::json node = {{"mesh", meshes.size()}};
        nlohmann::json meshJson = {{"primitives", std::move(primitives)}};
        if (!shapeName.empty()) node["name"] = meshJson["name"] = shapeName;
        meshes.push_back(std::move(meshJson));
        nodes.push_back(std::move(node));
    }

    nlohmann::json gltf = {{"asset", {{"version", "2.0"}, {"generator", "vitrum tests"}}}, {"scene", 0}};
    nlohmann::json roots = nlohmann::json::array();
    for (std::size_t i = 0; i < nodes.size(); ++i) roots.push_back(i);
    gltf["scenes"] = {{{"nodes", roots}}};
    gltf["nodes"] = nodes;
    gltf["meshes"] = meshes;
    if (!materials.empty()) gltf["materials"] = materials;
    if (!textures.empty()) gltf["textures"] = textures;
    if (!images.empty()) gltf["images"] = images;
    if (!extensions.empty()) gltf["extensionsUsed"] = extensions;
    gltf["accessors"] = buffer.accessors;
    gltf["bufferViews"] = buffer.views;
    gltf["buffers"] = {{{"byteLength", buffer.bytes.size()}, {"uri", uriOf(binFile.filename())}}};

    std::ofstream bin(binFile, std::ios::binary);
    bin.write(buffer.bytes.data(), std::streamsize(buffer.bytes.size()));
    std::ofstream json(outGltf, std::ios::binary);
    json << gltf.dump(1) << '\n';
    if (!bin || !json) throw std::runtime_error(outGltf.string() + ": cannot be written");
}

}  // namespace vitrum::testing
