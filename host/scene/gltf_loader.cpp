#include "scene/gltf_loader.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <stdexcept>
#include <sstream>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include "scene/tinygltf.h"

#include "common/error.h"
#include "common/file_extension.h"
#include "common/input_file.h"
#include "scene/gltf_compression.h"
#include "scene/gltf_draco.h"
#include "scene/gltf_errors.h"
#include "scene/gltf_materials.h"
#include "scene/instances.h"
#include "scene/quote_input.h"

namespace vitrum {

namespace fs = std::filesystem;

glm::mat4 gltfToZUp() {
    glm::mat4 m(0.0f);  // glm is column-major: m[column][row]
    m[0][0] = 1.0f;     // x stays x
    m[1][2] = 1.0f;     // y (up) becomes z
    m[2][1] = -1.0f;    // z (towards the viewer) becomes -y
    m[3][3] = 1.0f;
    return m;
}

namespace {

constexpr std::size_t kMaxElementsWithoutView = std::size_t(1) << 24;

// A glTF vector (x, y, z) in vitrum's z-up coordinates: a swap and a negation, exact in floats,
// so that a converted OBJ gives the OBJ's own numbers (tests/gpu/gltf_scenes_test.cpp).
glm::vec3 zUp(float x, float y, float z) { return {x, -z, y}; }

// A node's matrix in glTF's y-up coordinates conjugated into vitrum's z-up ones: the matrix that
// acts on zUp(p) as the node's acts on p. Exact (entries are moved and negated).
glm::dmat4 zUpMatrix(const glm::dmat4& m) {
    const glm::dmat4 r = glm::dmat4(gltfToZUp());
    return r * m * glm::transpose(r);
}

glm::dmat4 localMatrix(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data());  // column-major, as glm
    glm::dmat4 m(1.0);
    if (node.translation.size() == 3) m = glm::translate(m, glm::make_vec3(node.translation.data()));
    if (node.rotation.size() == 4) {
        const auto& q = node.rotation;  // glTF writes x, y, z, w
        m = m * glm::mat4_cast(glm::normalize(glm::dquat(q[3], q[0], q[1], q[2])));
    }
    if (node.scale.size() == 3) m = glm::scale(m, glm::make_vec3(node.scale.data()));
    return m;
}

std::size_t componentBytes(int type) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;
    }
}

// One component as the glTF spec reads it: floats as they are, normalized integers scaled to
// [0, 1] or [-1, 1] (glTF 2.0, 3.11 "Animations" table of normalization), integers as integers.
double component(const unsigned char* at, int type, bool normalized) {
    auto load = [&](auto value) {
        std::memcpy(&value, at, sizeof value);
        return value;
    };
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const double v = load(std::int8_t());
            return normalized ? std::max(v / 127.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            const double v = load(std::uint8_t());
            return normalized ? v / 255.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            const double v = load(std::int16_t());
            return normalized ? std::max(v / 32767.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            const double v = load(std::uint16_t());
            return normalized ? v / 65535.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load(std::uint32_t());
        default: return load(float());
    }
}

// Keeps an image's encoded bytes; they are decoded when a material uses the image. tinygltf 2.7
// passes an image's buffer view without checking it against its buffer (found by fuzzing): bytes
// that do not lie within one of the model's buffers (or a data URI's own copy, then `size` is
// its length) are refused here.
bool keepEncodedImage(tinygltf::Image* image, const int, std::string* err, std::string*, int, int,
                      const unsigned char* bytes, int size, void* model) {
    const bool fromBufferView = image->bufferView >= 0;
    if (fromBufferView) {
        const auto begin = reinterpret_cast<std::uintptr_t>(bytes);
        const auto& buffers = static_cast<const tinygltf::Model*>(model)->buffers;
        const bool within = size >= 0 && std::any_of(buffers.begin(), buffers.end(), [&](const tinygltf::Buffer& b) {
            const auto first = reinterpret_cast<std::uintptr_t>(b.data.data());
            return !b.data.empty() && begin >= first && begin - first <= b.data.size() &&
                   std::size_t(size) <= b.data.size() - (begin - first);
        });
        if (!within) {
            if (err) *err += "image \"" + image->name + "\": its buffer view reaches beyond its buffer\n";
            return false;
        }
    }
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
    return true;
}

class GltfReader {
public:
    GltfReader(Scene& scene, fs::path file, const SceneLoadOptions& load, const GltfOptions& options)
        : scene_(scene),
          file_(std::move(file)),
          load_(load),
          options_(options),
          materials_(scene_, model_, file_, load_.texelLimit) {}

    GltfResult read() {
        if (options_.placements.empty() || (options_.takeCamera && options_.placements.size() != 1))
            throw std::invalid_argument("loadGltf: a camera is taken from a file placed once");
        parse();
        chooseVariant();
        const std::vector<int> roots = rootNodes();
        // A mesh placed twice or more, by two nodes or by two placements of the file, is stored once
        // and placed by instances (docs/scene-format.md, "Instancing").
        std::map<int, std::size_t> uses;
        visit(roots, [&](const GltfPlacement&, int, const tinygltf::Node& node, const glm::dmat4&) {
            if (node.mesh >= 0) ++uses[node.mesh];
        });
        auto instanced = [&](int mesh) { return load_.instancing && uses[mesh] >= 2; };
        // Triangles first counted, so that a scene too large for the device is refused before any
        // is made (SceneLoadOptions::checkTriangles), then made.
        for (const auto& [mesh, count] : uses) trianglesToMake_ += meshTriangles(mesh) * (instanced(mesh) ? 1 : count);
        if (load_.checkTriangles) load_.checkTriangles(scene_.triangles.size() + trianglesToMake_);
        const std::size_t firstTriangle = scene_.triangles.size();
        GltfResult result;
        std::vector<std::pair<int, glm::dmat4>> cameras;
        struct Placing {
            int node;
            glm::dmat4 world;
            const GltfPlacement* by;
        };
        std::map<int, std::vector<Placing>> placings;  // a mesh's nodes, their matrices and placements
        visit(roots, [&](const GltfPlacement& by, int index, const tinygltf::Node& node, const glm::dmat4& world) {
            if (node.mesh >= 0 && instanced(node.mesh)) placings[node.mesh].push_back({index, world, &by});
            else if (node.mesh >= 0) addMesh(index, node, world);
            if (node.camera >= 0) cameras.emplace_back(node.camera, world);
            if (addLight(node, world)) ++result.lights;
        });
        for (const auto& [meshIndex, nodes] : placings) {
            const std::size_t meshFirst = scene_.triangles.size(), meshObject = scene_.objectNames.size();
            addMesh(nodes.front().node, model_.nodes[std::size_t(nodes.front().node)], glm::dmat4(1.0));
            if (scene_.triangles.size() == meshFirst) continue;
            std::vector<std::string> names;
            const std::uint32_t mesh = makeMesh(scene_, meshFirst, meshObject, names);
            const FloatBox box = meshBox(scene_, scene_.meshes[mesh]);
            for (const Placing& p : nodes) {
                const tinygltf::Node& node = model_.nodes[std::size_t(p.node)];
                const std::string where =
                    "nodes[" + std::to_string(p.node) + "]" + (p.by->by.empty() ? "" : ", placed by " + p.by->by + ",");
                Instance instance;
                try {
                    instance = makeInstance(mesh, std::uint32_t(scene_.objectNames.size()), glm::mat4(p.world));
                } catch (const std::invalid_argument&) {
                    // A matrix without an inverse (a scale of 0 hides a node) cannot move rays into
                    // the mesh: that copy is made in the world, as a mesh placed once would be.
                    addMesh(p.node, node, p.world);
                    continue;
                }
                const FloatBox placed = instanceBox(instance, box);
                const glm::vec3 size = placed.max - placed.min;
                if (!(std::isfinite(size.x) && std::isfinite(size.y) && std::isfinite(size.z)))
                    fail(where + " moves its mesh's vertices beyond the range of float");
                scene_.instances.push_back(instance);
                scene_.objectNames.push_back(file_.filename().string() + "/" + nodeName(p.node, node));
            }
        }
        putMeshesLast(scene_);
        if (scene_.triangles.size() == firstTriangle) throw inputError(file_, 0, "contains no triangles");
        if (options_.takeCamera) result.camera = takeCamera(cameras);
        return result;
    }

private:
    [[noreturn]] void fail(const std::string& message) const { throw inputError(file_, 0, message); }
    void warnAbout(const std::string& message) const { warn(file_.string() + ": " + message); }

    // A .glb's header gives its length (glTF 2.0, 4.4.3): a file cut short in a download or a copy
    // is named as such, not as tinygltf's "Invalid glTF binary".
    void checkGlbLength() const {
        std::error_code ec;
        const std::uintmax_t size = fs::file_size(file_, ec);
        std::ifstream in(file_, std::ios::binary);
        std::uint32_t header[3] = {0, 0, 0};
        if (ec || !in.read(reinterpret_cast<char*>(header), sizeof header))
            fail("is not a glTF binary: it has no 12-byte header");
        if (header[0] != 0x46546C67u) fail("is not a glTF binary: it does not begin with \"glTF\"");
        if (header[2] > size)
            fail("is cut short: its header gives " + std::to_string(header[2]) + " bytes, the file has " +
                 std::to_string(size));
    }

    void parse() {
        tinygltf::TinyGLTF parser;
        parser.SetImageLoader(keepEncodedImage, &model_);
        std::string errors, warnings;
        const bool binary = lowerCaseExtension(file_) == ".glb";
        std::error_code ec;
        if (!fs::is_regular_file(file_, ec)) fail(fs::exists(file_, ec) ? "not a regular file" : "no such file");
        if (binary) checkGlbLength();
        GltfCompression compression(file_);
        const std::vector<unsigned char> document =
            compression.prepare(readInputFile(file_, "the glTF file", kMaxGltfFileBytes), binary);
        parser.SetFsCallbacks(compression.fileCallbacks());
        const std::string baseDir = file_.parent_path().string();
        const bool ok =
            binary ? parser.LoadBinaryFromMemory(&model_, &errors, &warnings, document.data(), unsigned(document.size()), baseDir)
                   : parser.LoadASCIIFromString(&model_, &errors, &warnings, reinterpret_cast<const char*>(document.data()),
                                                unsigned(document.size()), baseDir);
        if (!ok || !errors.empty())
            fail(describeGltfErrors(file_, errors));
        compression.decodeMeshopt(model_);
        std::istringstream lines(warnings);
        for (std::string w; std::getline(lines, w);)
            if (!w.empty()) warnAbout(w);
        for (const std::string& name : model_.extensionsRequired)
            if (!isReadGltfExtension(name))
                fail("requires the glTF extension " + name + ", which vitrum does not read");
        quantized_ = std::find(model_.extensionsUsed.begin(), model_.extensionsUsed.end(), "KHR_mesh_quantization") !=
                     model_.extensionsUsed.end();
    }

    // The scene's root nodes: the default scene's, else the first scene's, else every node that is
    // no node's child (glTF 2.0, 3.5.1: without a scene, what to show is the application's choice).
    std::vector<int> rootNodes() const {
        const int nodeCount = int(model_.nodes.size());
        auto checked = [&](const std::vector<int>& nodes) {
            for (int n : nodes)
                if (n < 0 || n >= nodeCount) fail("a scene names nodes[" + std::to_string(n) + "], which does not exist");
            return nodes;
        };
        if (model_.defaultScene >= int(model_.scenes.size())) fail("\"scene\" names a scene that does not exist");
        if (model_.defaultScene >= 0) return checked(model_.scenes[std::size_t(model_.defaultScene)].nodes);
        if (!model_.scenes.empty()) return checked(model_.scenes[0].nodes);
        std::vector<bool> isChild(model_.nodes.size(), false);
        for (const tinygltf::Node& node : model_.nodes)
            for (int child : node.children)
                if (child >= 0 && child < nodeCount) isChild[std::size_t(child)] = true;
        std::vector<int> roots;
        for (int n = 0; n < nodeCount; ++n)
            if (!isChild[std::size_t(n)]) roots.push_back(n);
        return roots;
    }

    // A node's transform of another length than glTF 2.0's node schema gives it would be left out, and
    // its mesh placed where the file does not put it: refused.
    void checkTransformLengths(int index, const tinygltf::Node& node) const {
        auto check = [&](const std::vector<double>& values, std::size_t length, const char* what) {
            if (!values.empty() && values.size() != length)
                fail("nodes[" + std::to_string(index) + "]: its " + what + " has " + std::to_string(values.size()) +
                     " numbers; glTF 2.0 gives it " + std::to_string(length));
        };
        check(node.matrix, 16, "matrix");
        check(node.translation, 3, "translation");
        check(node.rotation, 4, "rotation");
        check(node.scale, 3, "scale");
    }

    // Depth-first over the node tree, parents before children, once a placement of the file, with
    // each node's matrix to vitrum's world (the placement's transform times the z-up chain of node
    // matrices).
    template <typename Visit>
    void visit(const std::vector<int>& roots, Visit&& onNode) const {
        std::vector<bool> onPath(model_.nodes.size(), false);
        for (const GltfPlacement& placement : options_.placements) {
            auto walk = [&](auto& self, int index, const glm::dmat4& parent) -> void {
                if (index < 0 || std::size_t(index) >= model_.nodes.size())
                    fail("a node's children name nodes[" + std::to_string(index) + "], which does not exist");
                if (onPath[std::size_t(index)]) fail("nodes[" + std::to_string(index) + "] is its own ancestor");
                onPath[std::size_t(index)] = true;
                const tinygltf::Node& node = model_.nodes[std::size_t(index)];
                checkTransformLengths(index, node);
                const glm::dmat4 matrix = parent * zUpMatrix(localMatrix(node));
                onNode(placement, index, node, matrix);
                for (int child : node.children) self(self, child, matrix);
                onPath[std::size_t(index)] = false;
            };
            for (int root : roots) walk(walk, root, glm::dmat4(placement.transform));
        }
    }

    const tinygltf::Accessor& accessor(int index, const std::string& what) const {
        if (index < 0 || std::size_t(index) >= model_.accessors.size())
            fail(what + " names accessors[" + std::to_string(index) + "], which does not exist");
        return model_.accessors[std::size_t(index)];
    }

    // An accessor's elements as doubles, `components` a element, with byte strides, normalized
    // integers and sparse substitution (glTF 2.0, 3.6.2), every byte checked against its buffer.
    // The component types glTF 2.0 allows a vertex attribute (3.7.2.1): FLOAT for POSITION and
    // NORMAL, and for texture coordinates also normalized unsigned bytes and shorts; with
    // KHR_mesh_quantization also (its table of attribute types) bytes and shorts, normalized or not,
    // for positions and texture coordinates, and normalized bytes and shorts for normals.
    enum class Attribute { Position, Normal, TexCoord };
    void checkComponentType(int index, const std::string& what, Attribute attribute) const {
        const tinygltf::Accessor& a = accessor(index, what);
        const int type = a.componentType;
        if (type == TINYGLTF_COMPONENT_TYPE_FLOAT) return;
        const bool unsignedInteger =
            type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
        const bool signedInteger = type == TINYGLTF_COMPONENT_TYPE_BYTE || type == TINYGLTF_COMPONENT_TYPE_SHORT;
        bool allowed = false;
        std::string others;  // what else the file may use
        switch (attribute) {
            case Attribute::Position:
                allowed = quantized_ && (signedInteger || unsignedInteger);
                others = quantized_ ? " or bytes (5120, 5121) or shorts (5122, 5123)" : "";
                break;
            case Attribute::Normal:
                allowed = quantized_ && a.normalized && signedInteger;
                others = quantized_ ? " or normalized signed bytes (5120) or shorts (5122)" : "";
                break;
            case Attribute::TexCoord:
                allowed = (a.normalized && unsignedInteger) || (quantized_ && (signedInteger || unsignedInteger));
                others = quantized_ ? " or bytes (5120, 5121) or shorts (5122, 5123)"
                                    : " or normalized unsigned bytes (5121) or shorts (5123)";
                break;
        }
        if (!allowed)
            fail("accessors[" + std::to_string(index) + "] (" + what + ") has component type " + std::to_string(type) +
                 (a.normalized ? " (normalized)" : "") + "; " +
                 (quantized_ ? "KHR_mesh_quantization allows it" : "glTF 2.0 allows it") + " FLOAT (5126)" + others +
                 (quantized_ ? "" : " (more with KHR_mesh_quantization, which the file does not declare)"));
    }

    std::vector<double> elements(int index, int components, const std::string& what) const {
        const tinygltf::Accessor& a = accessor(index, what);
        const std::string name = "accessors[" + std::to_string(index) + "] (" + what + ")";
        const int expectedType = components == 1 ? TINYGLTF_TYPE_SCALAR : components;
        if (a.type != expectedType) fail(name + " has the wrong type");
        const std::size_t size = componentBytes(a.componentType);
        if (size == 0) fail(name + " has an unsupported component type " + std::to_string(a.componentType));
        const std::size_t count = a.count;
        // Without a buffer view an accessor is zeros (and its sparse values): nothing in the file
        // bounds its count, so vitrum does (the size of a big model's vertex array).
        if (a.bufferView < 0 && count > kMaxElementsWithoutView)
            fail(name + " has " + std::to_string(count) + " elements and no buffer view; vitrum reads at most " +
                 std::to_string(kMaxElementsWithoutView) + " of those");
        // Never more elements than the view's bytes can hold, checked before the room is made
        // (gather checks each element's bytes exactly).
        if (a.bufferView >= 0 && std::size_t(a.bufferView) < model_.bufferViews.size() &&
            count > model_.bufferViews[std::size_t(a.bufferView)].byteLength / (size * std::size_t(components)) + 1)
            fail(name + " reaches beyond its buffer");
        std::vector<double> values(count * std::size_t(components), 0.0);
        auto gather = [&](int viewIndex, std::size_t offset, std::size_t n, int type, int comps,
                          auto&& put) {
            if (n == 0) return;
            if (viewIndex < 0 || std::size_t(viewIndex) >= model_.bufferViews.size())
                fail(name + " names a buffer view that does not exist");
            const tinygltf::BufferView& view = model_.bufferViews[std::size_t(viewIndex)];
            if (view.buffer < 0 || std::size_t(view.buffer) >= model_.buffers.size())
                fail(name + " uses a buffer that does not exist");
            const std::vector<unsigned char>& buffer = model_.buffers[std::size_t(view.buffer)].data;
            const std::size_t bytes = componentBytes(type) * std::size_t(comps);
            if (bytes == 0) fail(name + " has an unsupported component type " + std::to_string(type));
            const std::size_t stride = view.byteStride ? view.byteStride : bytes;
            // Written so that no sum can overflow: the view within its buffer, then the last
            // element within the view.
            if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset ||
                offset > view.byteLength || bytes > view.byteLength - offset || stride < bytes ||
                (n - 1) > (view.byteLength - offset - bytes) / stride)
                fail(name + " reaches beyond its buffer");
            const unsigned char* base = buffer.data() + view.byteOffset + offset;
            for (std::size_t i = 0; i < n; ++i) put(i, base + i * stride);
        };
        if (a.bufferView >= 0)
            gather(a.bufferView, a.byteOffset, count, a.componentType, components, [&](std::size_t i, const unsigned char* at) {
                for (int c = 0; c < components; ++c)
                    values[i * std::size_t(components) + std::size_t(c)] = component(at + std::size_t(c) * size, a.componentType, a.normalized);
            });
        if (a.sparse.isSparse) {
            const auto& s = a.sparse;
            if (s.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                s.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                s.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
                fail(name + " has sparse indices that are not unsigned integers");
            std::vector<std::size_t> targets(std::size_t(std::max(s.count, 0)));
            gather(s.indices.bufferView, std::size_t(s.indices.byteOffset), targets.size(), s.indices.componentType, 1,
                   [&](std::size_t i, const unsigned char* at) {
                       const double t = component(at, s.indices.componentType, false);
                       if (!(t >= 0.0 && t < double(count))) fail(name + " has a sparse index beyond its count");
                       targets[i] = std::size_t(t);
                   });
            gather(s.values.bufferView, std::size_t(s.values.byteOffset), targets.size(), a.componentType, components,
                   [&](std::size_t i, const unsigned char* at) {
                       for (int c = 0; c < components; ++c)
                           values[targets[i] * std::size_t(components) + std::size_t(c)] =
                               component(at + std::size_t(c) * size, a.componentType, a.normalized);
                   });
        }
        return values;
    }

    const tinygltf::Mesh& mesh(int index) const {
        if (index < 0 || std::size_t(index) >= model_.meshes.size())
            fail("a node names meshes[" + std::to_string(index) + "], which does not exist");
        return model_.meshes[std::size_t(index)];
    }

    std::size_t meshTriangles(int index) const {
        std::size_t triangles = 0;
        for (const tinygltf::Primitive& p : mesh(index).primitives) {
            if (p.mode != TINYGLTF_MODE_TRIANGLES || !p.attributes.count("POSITION")) continue;
            const int corners = p.indices >= 0 ? p.indices : p.attributes.at("POSITION");
            triangles += accessor(corners, "a primitive").count / 3;
        }
        return triangles;
    }

    // KHR_materials_variants: the variant --variant names (its index in the file's list), or -1
    // for none; without one, a file that has variants says so, naming them.
    void chooseVariant() {
        std::vector<std::string> names;
        if (const auto found = model_.extensions.find("KHR_materials_variants"); found != model_.extensions.end()) {
            const tinygltf::Value& variants = found->second.Get("variants");
            if (!variants.IsArray()) fail("KHR_materials_variants has no list of variants");
            for (int i = 0; i < int(variants.ArrayLen()); ++i) {
                const tinygltf::Value& name = variants.Get(i).Get("name");
                if (!name.IsString()) fail("KHR_materials_variants's variants[" + std::to_string(i) + "] has no name");
                names.push_back(name.Get<std::string>());
            }
        }
        std::string list;
        for (const std::string& name : names) list += (list.empty() ? "" : ", ") + quoteInput(name);
        if (load_.variant.empty()) {
            if (!names.empty())
                warnAbout(
                    "has material variants (" + list +
                    "): each primitive is rendered with its default material; choose a variant with --variant NAME");
            return;
        }
        const auto chosen = std::find(names.begin(), names.end(), load_.variant);
        if (chosen == names.end())
            fail("has no material variant named " + quoteInput(load_.variant) +
                 (names.empty() ? std::string(" (it has none)") : "; its variants: " + list));
        variant_ = int(chosen - names.begin());
    }

    // The glTF material a primitive is rendered with: the one its KHR_materials_variants mappings
    // give the chosen variant, else its default (glTF's `material`).
    int primitiveMaterial(const tinygltf::Primitive& primitive, const std::string& where) const {
        const auto found = primitive.extensions.find("KHR_materials_variants");
        if (variant_ < 0 || found == primitive.extensions.end()) return primitive.material;
        const tinygltf::Value& mappings = found->second.Get("mappings");
        if (!mappings.IsArray()) fail(where + ": KHR_materials_variants has no mappings");
        for (int i = 0; i < int(mappings.ArrayLen()); ++i) {
            const tinygltf::Value& material = mappings.Get(i).Get("material");
            const tinygltf::Value& variants = mappings.Get(i).Get("variants");
            if (!material.IsNumber() || !variants.IsArray())
                fail(where + ": KHR_materials_variants's mappings[" + std::to_string(i) +
                     "] is not a material and its variants");
            for (int k = 0; k < int(variants.ArrayLen()); ++k)
                if (variants.Get(k).IsNumber() && variants.Get(k).GetNumberAsInt() == variant_)
                    return material.GetNumberAsInt();
        }
        return primitive.material;
    }

    std::string nodeName(int nodeIndex, const tinygltf::Node& node) const {
        const tinygltf::Mesh& m = mesh(node.mesh);
        return !node.name.empty() ? node.name : !m.name.empty() ? m.name : "node" + std::to_string(nodeIndex);
    }

    void addMesh(int nodeIndex, const tinygltf::Node& node, const glm::dmat4& world) {
        const tinygltf::Mesh& m = mesh(node.mesh);
        const std::string name = nodeName(nodeIndex, node);
        const glm::mat4 transform(world);
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(transform)));
        const bool mirrored = glm::determinant(glm::mat3(transform)) < 0.0f;  // keep the winding outward-facing
        if (node.skin >= 0 && !warnedSkin_) {
            warnAbout("skins are ignored: skinned meshes are rendered in their bind pose");
            warnedSkin_ = true;
        }
        const auto objectIndex = std::uint32_t(scene_.objectNames.size());
        bool anyTriangle = false;
        for (std::size_t p = 0; p < m.primitives.size(); ++p) {
            const tinygltf::Primitive& primitive = m.primitives[p];
            const std::string where = "meshes[" + std::to_string(node.mesh) + "].primitives[" + std::to_string(p) + "]" +
                                      (m.name.empty() ? "" : " (mesh " + quoteInput(m.name) + ")");
            if (primitive.mode != TINYGLTF_MODE_TRIANGLES) {
                static const char* kModes[] = {"points", "lines", "a line loop", "a line strip", "triangles",
                                               "a triangle strip", "a triangle fan"};
                const bool known = primitive.mode >= 0 && primitive.mode <= 6;
                warnAbout(where + " is " + (known ? kModes[primitive.mode] : "of an unknown mode") +
                          ", not triangles: skipped");
                continue;
            }
            if (!primitive.attributes.count("POSITION")) {
                warnAbout(where + " has no POSITION: skipped");
                continue;
            }
            if (!primitive.targets.empty() && !warnedMorph_) {
                warnAbout("morph targets are ignored: meshes are rendered without their weights");
                warnedMorph_ = true;
            }
            const PrimitiveVertices vertices = readPrimitive(primitive, where);
            const std::vector<double>&positions = vertices.positions, &normals = vertices.normals, &uvs = vertices.uvs;
            const std::vector<std::size_t>& corners = vertices.corners;
            if (corners.size() % 3 != 0)
                warnAbout(where + " has " + std::to_string(corners.size()) + " corners, not a multiple of 3: the last " +
                          std::to_string(corners.size() % 3) + " ignored");
            const int gltfMaterial = primitiveMaterial(primitive, where);
            const std::uint32_t material = materials_.sceneMaterial(gltfMaterial);
            const glm::dmat3* uvTransform = materials_.uvTransform(gltfMaterial);
            scene_.triangles.reserve(scene_.triangles.size() + corners.size() / 3);
            for (std::size_t k = 0; k + 2 < corners.size(); k += 3) {
                std::size_t c[3] = {corners[k], corners[k + 1], corners[k + 2]};
                if (mirrored) std::swap(c[1], c[2]);
                Triangle t;
                t.material = material;
                t.object = objectIndex;
                for (int i = 0; i < 3; ++i) {
                    const double* p = &positions[3 * c[i]];
                    t.position[i] = glm::vec3(transform * glm::vec4(zUp(float(p[0]), float(p[1]), float(p[2])), 1.0f));
                    if (!std::isfinite(t.position[i].x) || !std::isfinite(t.position[i].y) ||
                        !std::isfinite(t.position[i].z))
                        fail(where + ": vertex " + std::to_string(c[i]) + " is not finite after its transform");
                    // glTF's v runs down the image from its top row, vitrum's up from the bottom.
                    if (!uvs.empty()) {
                        glm::vec2 uv = glm::vec2(float(uvs[2 * c[i]]), float(uvs[2 * c[i] + 1]));
                        if (uvTransform) uv = glm::vec2(*uvTransform * glm::dvec3(glm::dvec2(uvs[2 * c[i]], uvs[2 * c[i] + 1]), 1.0));
                        t.uv[i] = glm::vec2(uv.x, 1.0f - uv.y);
                    }
                }
                glm::vec3 geometric = glm::cross(t.position[1] - t.position[0], t.position[2] - t.position[0]);
                const float length = glm::length(geometric);
                geometric = length > 0.0f && std::isfinite(length) ? geometric / length : glm::vec3(0.0f, 0.0f, 1.0f);
                for (int i = 0; i < 3; ++i) {
                    glm::vec3 n(0.0f);
                    if (!normals.empty()) {
                        const double* v = &normals[3 * c[i]];
                        n = normalMatrix * zUp(float(v[0]), float(v[1]), float(v[2]));
                    }
                    const float nl = glm::length(n);
                    t.normal[i] = nl > 0.0f && std::isfinite(nl) ? n / nl : geometric;
                }
                scene_.triangles.push_back(t);
                anyTriangle = true;
                if (load_.progress && ++trianglesMade_ % 65536 == 0)
                    load_.progress("triangles of " + file_.filename().string(),
                                   double(trianglesMade_) / double(std::max<std::size_t>(trianglesToMake_, 1)));
            }
        }
        if (anyTriangle) scene_.objectNames.push_back(file_.filename().string() + "/" + name);
    }

    // A primitive's vertices and triangles' corners: from its accessors, or decoded from its
    // KHR_draco_mesh_compression data (whose accessors have no buffer views), with the attributes
    // that data does not hold from their accessors.
    PrimitiveVertices readPrimitive(const tinygltf::Primitive& primitive, const std::string& where) const {
        PrimitiveVertices v;
        const auto draco = primitive.extensions.find("KHR_draco_mesh_compression");
        if (draco != primitive.extensions.end()) {
            try {
                v = decodeDracoPrimitive(model_, primitive, draco->second, where);
            } catch (const std::invalid_argument& e) {
                fail(e.what());
            }
            if (v.positions.empty()) fail(where + ": KHR_draco_mesh_compression holds no POSITION");
        } else {
            checkComponentType(primitive.attributes.at("POSITION"), where + ".attributes.POSITION", Attribute::Position);
            v.positions = elements(primitive.attributes.at("POSITION"), 3, where + ".attributes.POSITION");
        }
        const std::size_t vertexCount = v.positions.size() / 3;
        if (auto n = primitive.attributes.find("NORMAL"); n != primitive.attributes.end() && v.normals.empty()) {
            checkComponentType(n->second, where + ".attributes.NORMAL", Attribute::Normal);
            v.normals = elements(n->second, 3, where + ".attributes.NORMAL");
            if (v.normals.size() != v.positions.size()) fail(where + " has a NORMAL for some vertices only");
        }
        if (auto t = primitive.attributes.find("TEXCOORD_0"); t != primitive.attributes.end() && v.uvs.empty()) {
            checkComponentType(t->second, where + ".attributes.TEXCOORD_0", Attribute::TexCoord);
            // glTF requires VEC2; assimp 5.2 writes VEC3 with a zero third: its first two read.
            const bool vec3 = accessor(t->second, where + ".attributes.TEXCOORD_0").type == TINYGLTF_TYPE_VEC3;
            v.uvs = elements(t->second, vec3 ? 3 : 2, where + ".attributes.TEXCOORD_0");
            if (vec3) {
                for (std::size_t i = 0; i < v.uvs.size() / 3; ++i) {
                    v.uvs[2 * i] = v.uvs[3 * i];
                    v.uvs[2 * i + 1] = v.uvs[3 * i + 1];
                }
                v.uvs.resize(v.uvs.size() / 3 * 2);
            }
            if (v.uvs.size() / 2 != vertexCount) fail(where + " has a TEXCOORD_0 for some vertices only");
        }
        if (draco != primitive.extensions.end()) return v;  // its corners are the Draco mesh's
        if (primitive.indices >= 0) {
            const tinygltf::Accessor& a = accessor(primitive.indices, where + ".indices");
            if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
                fail(where + " has indices that are not unsigned integers");
            const std::vector<double> indices = elements(primitive.indices, 1, where + ".indices");
            v.corners.reserve(indices.size());
            for (double i : indices) {
                if (i >= double(vertexCount))
                    fail(where + " uses vertex " + std::to_string(std::size_t(i)) + ", but it has " +
                         std::to_string(vertexCount));
                v.corners.push_back(std::size_t(i));
            }
        } else {
            v.corners.resize(vertexCount);
            for (std::size_t i = 0; i < vertexCount; ++i) v.corners[i] = i;
        }
        return v;
    }

    // KHR_lights_punctual: a point light is colour times intensity with the inverse-square
    // fall-off; a spot light is approximated by a point light; a directional light has no place
    // in the render model's point lights and is skipped. Each with a warning.
    bool addLight(const tinygltf::Node& node, const glm::dmat4& world) {
        auto found = node.extensions.find("KHR_lights_punctual");
        if (found == node.extensions.end() || !found->second.Has("light")) return false;
        const tinygltf::Value& index = found->second.Get("light");
        if (!index.IsNumber() || index.GetNumberAsInt() < 0 || std::size_t(index.GetNumberAsInt()) >= model_.lights.size())
            fail("a node names a light of KHR_lights_punctual.lights that does not exist");
        const tinygltf::Light& light = model_.lights[std::size_t(index.GetNumberAsInt())];
        const std::string quoted = "extensions.KHR_lights_punctual.lights[" + std::to_string(index.GetNumberAsInt()) + "]" +
                                   (light.name.empty() ? "" : " (" + quoteInput(light.name) + ")");
        if (light.type == "directional") {
            warnAbout(quoted + " is directional, which vitrum does not render: skipped");
            return false;
        }
        if (light.type == "spot") warnAbout(quoted + " is a spot light: rendered as a point light, its cone ignored");
        else if (light.type != "point") {
            warnAbout(quoted + " is of the unknown type " + quoteInput(light.type) + ": skipped");
            return false;
        }
        const glm::vec3 colour = light.color.size() == 3 ? glm::vec3(glm::make_vec3(light.color.data())) : glm::vec3(1.0f);
        PointLight point;
        point.position = glm::vec3(world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
        point.colour = glm::max(colour * float(light.intensity), glm::vec3(0.0f));
        point.inverseSquare = true;
        if (!std::isfinite(point.position.x + point.position.y + point.position.z) ||
            !std::isfinite(point.colour.x + point.colour.y + point.colour.z))
            fail(quoted + " has a position or colour that is not finite");
        scene_.lights.push_back(point);
        return true;
    }

    // The named camera, else the first in node order; its node looks down its local -z with +y up
    // (glTF 2.0, 3.10.1), which the z-up matrix has already turned into +y and +z.
    bool takeCamera(const std::vector<std::pair<int, glm::dmat4>>& cameras) {
        auto cameraName = [&](int index) {
            if (index < 0 || std::size_t(index) >= model_.cameras.size())
                fail("a node names cameras[" + std::to_string(index) + "], which does not exist");
            return model_.cameras[std::size_t(index)].name;
        };
        for (const auto& c : cameras) cameraName(c.first);  // every camera node names a camera
        const std::pair<int, glm::dmat4>* chosen = nullptr;
        if (!load_.camera.empty()) {
            std::string names;
            for (const auto& c : cameras) {
                if (!chosen && cameraName(c.first) == load_.camera) chosen = &c;
                names += (names.empty() ? "" : ", ") + quoteInput(cameraName(c.first));
            }
            if (!chosen)
                fail("has no camera named " + quoteInput(load_.camera) +
                     (names.empty() ? std::string(" (it has no camera in its scene)") : "; its cameras: " + names));
        } else if (!cameras.empty()) {
            chosen = &cameras.front();
        }
        if (!chosen) return false;
        const tinygltf::Camera& g = model_.cameras[std::size_t(chosen->first)];
        const std::string quoted = "cameras[" + std::to_string(chosen->first) + "]" + (g.name.empty() ? "" : " (" + quoteInput(g.name) + ")");
        if (g.type != "perspective")
            fail(quoted + " is " + (g.type.empty() ? std::string("of no type") : g.type) +
                 ", which vitrum does not render: it renders perspective cameras (choose one with --camera NAME)");
        const glm::dmat4& w = chosen->second;
        Camera& c = scene_.camera;
        c.from = glm::vec3(w * glm::dvec4(0.0, 0.0, 0.0, 1.0));
        const glm::dvec3 forward = glm::dmat3(w) * glm::dvec3(0.0, 1.0, 0.0), up = glm::dmat3(w) * glm::dvec3(0.0, 0.0, 1.0);
        if (!(glm::length(forward) > 0.0) || !(glm::length(glm::cross(forward, up)) > 0.0))
            fail(quoted + "'s node matrix collapses its view direction or its up");
        c.at = c.from + glm::vec3(glm::normalize(forward));
        c.up = glm::vec3(glm::normalize(up));
        const double fovY = glm::degrees(g.perspective.yfov);
        if (!validFovY(fovY))
            fail(quoted + " has yfov " + std::to_string(g.perspective.yfov) + " radians; vitrum renders " + kFovYRange);
        c.fovY = float(fovY);
        c.width = 640;
        c.height = 480;
        if (g.perspective.aspectRatio > 0.0)
            c.height = std::uint32_t(std::clamp(std::lround(640.0 / g.perspective.aspectRatio), 1l, long(kMaxImageSide)));
        return true;
    }

    Scene& scene_;
    fs::path file_;
    const SceneLoadOptions& load_;
    GltfOptions options_;
    tinygltf::Model model_;
    GltfMaterials materials_;
    std::size_t trianglesToMake_ = 0, trianglesMade_ = 0;
    bool warnedSkin_ = false, warnedMorph_ = false;
    int variant_ = -1;        // the chosen KHR_materials_variants variant (chooseVariant)
    bool quantized_ = false;  // the file uses KHR_mesh_quantization
};

}  // namespace

GltfResult loadGltf(Scene& scene, const fs::path& file, const SceneLoadOptions& loadOptions, const GltfOptions& options) {
    return GltfReader(scene, file, loadOptions, options).read();
}

}  // namespace vitrum
