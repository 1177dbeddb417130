// glTF 2.0 input (docs/scene-format.md, "glTF 2.0"): files written here byte by byte, each
// checked against what the glTF 2.0 specification and its KHR extensions say they mean.
#include "scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <meshoptimizer.h>
#include <stb/stb_image_write.h>
#include <webp/encode.h>
#include <nlohmann/json.hpp>

#include "analysis/scene_features.h"
#include "common/error.h"
#include "image/image.h"
#include "image/srgb.h"
#include "scene/instances.h"
#include "scene/scene_loader.h"
#include "../support/temporary_folder_test.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::TemporaryFolderTest;

std::string base64(const std::vector<unsigned char>& bytes) {
    static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const unsigned v = unsigned(bytes[i]) << 16 | (i + 1 < bytes.size() ? unsigned(bytes[i + 1]) << 8 : 0) |
                           (i + 2 < bytes.size() ? bytes[i + 2] : 0);
        for (int k = 0; k < 4; ++k)
            out += std::size_t(k) <= std::min<std::size_t>(bytes.size() - i, 3) ? kDigits[(v >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

// A glTF document under construction: data appended to one buffer, accessors over it.
class GltfBuilder {
public:
    GltfBuilder() {
        doc_ = {{"asset", {{"version", "2.0"}}}, {"scene", 0}, {"scenes", json::array({json{{"nodes", json::array()}}})}};
    }

    template <typename T>
    int accessor(const std::vector<T>& values, int componentType, const std::string& type, std::size_t count) {
        while (bin_.size() % 4) bin_.push_back(0);
        const std::size_t offset = bin_.size();
        bin_.resize(offset + values.size() * sizeof(T));
        std::memcpy(bin_.data() + offset, values.data(), values.size() * sizeof(T));
        doc_["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * sizeof(T)}});
        doc_["accessors"].push_back({{"bufferView", doc_["bufferViews"].size() - 1},
                                     {"componentType", componentType},
                                     {"count", count},
                                     {"type", type}});
        return int(doc_["accessors"].size() - 1);
    }
    int positions(const std::vector<float>& xyz) { return accessor(xyz, 5126, "VEC3", xyz.size() / 3); }
    // `bytes` appended to the file's buffer (buffer 0); returns their offset.
    std::size_t append(const std::vector<unsigned char>& bytes) {
        while (bin_.size() % 4) bin_.push_back(0);
        const std::size_t offset = bin_.size();
        bin_.insert(bin_.end(), bytes.begin(), bytes.end());
        return offset;
    }
    // A buffer after buffer 0 (the file's data); returns its index.
    int buffer(json buffer) {
        moreBuffers_.push_back(std::move(buffer));
        return int(moreBuffers_.size());
    }

    // A mesh of one primitive; returns its index.
    int mesh(json primitive) {
        doc_["meshes"].push_back({{"primitives", json::array({std::move(primitive)})}});
        return int(doc_["meshes"].size() - 1);
    }
    int node(json node, bool root = true) {
        doc_["nodes"].push_back(std::move(node));
        const int index = int(doc_["nodes"].size() - 1);
        if (root) doc_["scenes"][0]["nodes"].push_back(index);
        return index;
    }
    int material(json material) {
        doc_["materials"].push_back(std::move(material));
        return int(doc_["materials"].size() - 1);
    }
    json& doc() { return doc_; }

    // `image` as the file's one texture, a PNG in a data URI (written to `scratch` and read back).
    void embedTexture(const Image& image, const fs::path& scratch) {
        writeImage(image, scratch);
        std::ifstream file(scratch, std::ios::binary);
        const std::vector<unsigned char> png{std::istreambuf_iterator<char>(file), {}};
        doc_["images"] = json::array({{{"uri", "data:image/png;base64," + base64(png)}}});
        doc_["textures"] = json::array({{{"source", 0}}});
    }

    fs::path write(const fs::path& file) {
        json doc = doc_;
        if (!bin_.empty())
            doc["buffers"] = json::array({{{"byteLength", bin_.size()},
                                           {"uri", "data:application/octet-stream;base64," + base64(bin_)}}});
        for (const json& buffer : moreBuffers_) doc["buffers"].push_back(buffer);
        std::ofstream(file) << doc.dump(1);
        return file;
    }
    // The binary container (glTF 2.0, 4.4 "GLB File Format Specification").
    fs::path writeGlb(const fs::path& file) {
        json doc = doc_;
        doc["buffers"] = json::array({{{"byteLength", bin_.size()}}});
        for (const json& buffer : moreBuffers_) doc["buffers"].push_back(buffer);
        std::string text = doc.dump();
        while (text.size() % 4) text += ' ';
        std::vector<unsigned char> bin = bin_;
        while (bin.size() % 4) bin.push_back(0);
        std::ofstream out(file, std::ios::binary);
        auto u32 = [&](std::uint32_t v) { out.write(reinterpret_cast<const char*>(&v), 4); };
        u32(0x46546C67);  // "glTF"
        u32(2);
        u32(std::uint32_t(12 + 8 + text.size() + 8 + bin.size()));
        u32(std::uint32_t(text.size()));
        u32(0x4E4F534A);  // "JSON"
        out.write(text.data(), std::streamsize(text.size()));
        u32(std::uint32_t(bin.size()));
        u32(0x004E4942);  // "BIN"
        out.write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
        return file;
    }

private:
    json doc_;
    std::vector<unsigned char> bin_;
    std::vector<json> moreBuffers_;
};

// One triangle in glTF coordinates, counter-clockwise seen from +z (glTF's viewer side).
const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

Scene load(const fs::path& file, const std::string& camera = "") {
    SceneLoadOptions options;
    options.camera = camera;
    return loadScene(file, options);
}

void expectNear(glm::vec3 a, glm::vec3 b, float tolerance = 1e-6f) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

class GltfLoader : public TemporaryFolderTest {};

// +Y up becomes +Z up: (x, y, z) is (x, -z, y); the node's TRS is T * R * S (glTF 2.0, 3.5.3),
// under its parent's matrix (column-major).
TEST_F(GltfLoader, YUpBecomesZUpAndNodeTransformsCompose) {
    GltfBuilder b;
    const int mesh = b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}});
    // The child: scale 2, a quarter turn about +y (x goes to -z), then up by 3 along glTF's y.
    const double s = std::sqrt(0.5);
    const int child = b.node({{"mesh", mesh}, {"scale", {2, 2, 2}}, {"rotation", {0, s, 0, s}}, {"translation", {0, 3, 0}}},
                             false);
    // The parent: a translation by (10, 0, 0) written as a matrix.
    b.node({{"children", {child}}, {"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 10, 0, 0, 1}}});
    Scene scene = load(b.write(dir_ / "tree.gltf"));
    ASSERT_EQ(scene.triangles.size(), 1u);
    // glTF: (0,0,0) -> (10, 3, 0); (1,0,0) -> scaled (2,0,0), turned (0,0,-2) -> (10, 3, -2);
    // (0,1,0) -> (0,2,0) -> (10, 5, 0). In vitrum's z-up: (x, -z, y).
    const Triangle& t = scene.triangles[0];
    expectNear(t.position[0], {10, 0, 3}, 1e-5f);
    expectNear(t.position[1], {10, 2, 3}, 1e-5f);
    expectNear(t.position[2], {10, 0, 5}, 1e-5f);
    // No NORMAL: the geometric normal, the winding kept (the rotation keeps the handedness).
    const glm::vec3 n = glm::normalize(glm::cross(t.position[1] - t.position[0], t.position[2] - t.position[0]));
    expectNear(t.normal[0], n);
    EXPECT_EQ(scene.objectNames, std::vector<std::string>{"tree.gltf/node0"});
}

// A node with a negative determinant (a mirror) keeps its triangles' outward winding, as OBJ
// transforms do (docs/scene-format.md).
TEST_F(GltfLoader, MirroringNodeKeepsTheWindingOutward) {
    GltfBuilder b;
    const int mesh = b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}});
    b.node({{"mesh", mesh}});
    b.node({{"mesh", mesh}, {"scale", {-1, 1, 1}}});
    Scene scene = loadScene(b.write(dir_ / "mirror.gltf"), {.instancing = false});
    ASSERT_EQ(scene.triangles.size(), 2u);
    auto normal = [](const Triangle& t) {
        return glm::normalize(glm::cross(t.position[1] - t.position[0], t.position[2] - t.position[0]));
    };
    // The plain triangle faces glTF's +z, vitrum's -y; mirrored in x it still faces -y.
    expectNear(normal(scene.triangles[0]), {0, -1, 0});
    expectNear(normal(scene.triangles[1]), {0, -1, 0});
    EXPECT_EQ(scene.objectNames.size(), 2u);  // each mesh instance is an object
}

// A mesh that two nodes use is stored once and placed twice (docs/scene-format.md,
// "Instancing"): its copies are the triangles the nodes would each have made.
TEST_F(GltfLoader, AMeshTwoNodesUseIsStoredOnceAndPlacedTwice) {
    GltfBuilder b;
    const int mesh = b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}});
    b.node({{"mesh", mesh}, {"translation", {0, 0, 2}}, {"name", "plain"}});
    b.node({{"mesh", mesh}, {"scale", {-1, 1, 1}}, {"name", "mirrored"}});
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}})}, {"name", "once"}});
    const fs::path file = b.write(dir_ / "twice.gltf");
    const Scene scene = load(file);
    ASSERT_EQ(scene.meshes.size(), 1u);
    ASSERT_EQ(scene.instances.size(), 2u);
    EXPECT_EQ(scene.triangles.size(), 2u);  // the mesh once, and the one-node mesh in the world
    EXPECT_EQ(worldTriangleCount(scene), 1u);
    EXPECT_EQ(scene.objectNames, (std::vector<std::string>{"twice.gltf/once", "twice.gltf/plain", "twice.gltf/mirrored"}));
    const Scene placed = flattened(scene);
    const Scene loaded = loadScene(file, {.instancing = false});
    ASSERT_EQ(placed.triangles.size(), loaded.triangles.size());
    for (const Triangle& t : placed.triangles) {
        // The same triangle, corners in the same order, wherever the flat load put it.
        const auto same = std::find_if(loaded.triangles.begin(), loaded.triangles.end(), [&](const Triangle& u) {
            return glm::all(glm::lessThan(glm::abs(t.position[0] - u.position[0]), glm::vec3(1e-6f))) &&
                   glm::all(glm::lessThan(glm::abs(t.position[1] - u.position[1]), glm::vec3(1e-6f))) &&
                   glm::all(glm::lessThan(glm::abs(t.position[2] - u.position[2]), glm::vec3(1e-6f)));
        });
        ASSERT_NE(same, loaded.triangles.end());
        expectNear(t.normal[0], same->normal[0]);
    }
}

// KHR_mesh_quantization: positions as shorts (4 a vertex, as glTF aligns attributes to 4 bytes)
// that the node's scale dequantizes, normals as normalized bytes, texture coordinates as unsigned
// bytes, read as the floats they stand for; without the extension declared, refused naming the
// accessor and the extension.
TEST_F(GltfLoader, QuantizedAttributesReadAsTheFloatsTheyStandFor) {
    auto build = [&](bool declared) {
        GltfBuilder b;
        const int positions = b.accessor(std::vector<std::int16_t>{0, 0, 0, 0, 4, 0, 0, 0, 0, 8, 0, 0}, 5122, "VEC3", 3);
        b.doc()["bufferViews"][positions]["byteStride"] = 8;
        const int normals = b.accessor(std::vector<std::int8_t>{0, 0, 127, 0, 0, 0, 127, 0, 0, 0, 127, 0}, 5120, "VEC3", 3);
        b.doc()["bufferViews"][normals]["byteStride"] = 4;
        b.doc()["accessors"][normals]["normalized"] = true;
        const int uvs = b.accessor(std::vector<std::uint8_t>{0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0}, 5121, "VEC2", 3);
        b.doc()["bufferViews"][uvs]["byteStride"] = 4;
        const json attributes = {{"POSITION", positions}, {"NORMAL", normals}, {"TEXCOORD_0", uvs}};
        b.node({{"mesh", b.mesh({{"attributes", attributes}})}, {"scale", {0.25, 0.25, 0.25}}});
        if (declared) b.doc()["extensionsUsed"] = b.doc()["extensionsRequired"] = {"KHR_mesh_quantization"};
        return b.write(dir_ / (declared ? "quantized.gltf" : "undeclared.gltf"));
    };
    const Scene scene = load(build(true));
    ASSERT_EQ(scene.triangles.size(), 1u);
    const Triangle& t = scene.triangles[0];
    // glTF's (0, 0, 0), (1, 0, 0), (0, 2, 0) in vitrum's z-up; the normal glTF's +z, vitrum's -y;
    // vitrum's v is 1 - glTF's.
    expectNear(t.position[0], {0, 0, 0});
    expectNear(t.position[1], {1, 0, 0});
    expectNear(t.position[2], {0, 0, 2});
    for (const glm::vec3& n : t.normal) expectNear(n, {0, -1, 0});
    EXPECT_EQ(t.uv[1], glm::vec2(1, 1));
    EXPECT_EQ(t.uv[2], glm::vec2(0, 0));
    try {
        load(build(false));
        ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("accessors[0] (meshes[0].primitives[0].attributes.POSITION) has component type 5122"),
                  std::string::npos) << message;
        EXPECT_NE(message.find("KHR_mesh_quantization, which the file does not declare"), std::string::npos) << message;
    }
}

// EXT_meshopt_compression: positions, normals (octahedral, 8 bits) and triangle indices
// compressed by meshoptimizer's encoders into buffer 0, decoded into a fallback buffer that the
// file does not hold (no uri); in a .gltf and a .glb, they read as the uncompressed mesh does.
class MeshoptMesh {
public:
    MeshoptMesh() {
        // A quad of two triangles, its normals tilted differently at each corner.
        positions_ = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
        normals_ = {0, 0, 1, 0.6f, 0, 0.8f, 0, 0.6f, 0.8f, -0.6f, 0, 0.8f};
        indices_ = {0, 1, 2, 0, 2, 3};
    }
    // The uncompressed mesh.
    fs::path plain(const fs::path& file) const {
        GltfBuilder b;
        const int n = b.accessor(normals_, 5126, "VEC3", 4);
        const int i = b.accessor(indices_, 5123, "SCALAR", 6);
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(positions_)}, {"NORMAL", n}}}, {"indices", i}})}});
        return b.write(file);
    }
    // `change` edits the document before it is written; the fallback buffer declares
    // `fallbackBytes` (what the views decode to).
    fs::path compressed(const fs::path& file, bool glb, const std::function<void(json&)>& change = {},
                        std::size_t fallbackBytes = 48 + 16 + 12) const {
        GltfBuilder b;
        // Normals as 8-bit octahedral x, y, and 1 in z (4 bytes a vertex), as meshopt's filter wants.
        std::vector<std::int8_t> octahedral(16);
        std::vector<float> normals4;
        for (int v = 0; v < 4; ++v)
            normals4.insert(normals4.end(), {normals_[3 * v], normals_[3 * v + 1], normals_[3 * v + 2], 0.0f});
        meshopt_encodeFilterOct(octahedral.data(), 4, 4, 8, normals4.data());
        const int fallback = b.buffer({{"byteLength", fallbackBytes}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
        auto view = [&](const void* data, std::size_t count, std::size_t stride, const char* mode, const char* filter,
                        std::size_t at) {
            std::vector<unsigned char> packed;
            if (std::string(mode) == "ATTRIBUTES") {
                packed.resize(meshopt_encodeVertexBufferBound(count, stride));
                packed.resize(meshopt_encodeVertexBuffer(packed.data(), packed.size(), data, count, stride));
            } else {
                packed.resize(meshopt_encodeIndexBufferBound(count, 4));
                packed.resize(meshopt_encodeIndexBuffer(packed.data(), packed.size(),
                                                        static_cast<const unsigned short*>(data), count));
            }
            json extension = {{"buffer", 0}, {"byteOffset", b.append(packed)}, {"byteLength", packed.size()},
                              {"byteStride", stride}, {"count", count}, {"mode", mode}};
            if (filter) extension["filter"] = filter;
            json v = {{"buffer", fallback}, {"byteOffset", at}, {"byteLength", count * stride},
                      {"extensions", {{"EXT_meshopt_compression", extension}}}};
            if (std::string(mode) == "ATTRIBUTES") v["byteStride"] = stride;
            b.doc()["bufferViews"].push_back(v);
            return int(b.doc()["bufferViews"].size() - 1);
        };
        auto accessor = [&](int view, int componentType, const char* type, std::size_t count, bool normalized) {
            b.doc()["accessors"].push_back({{"bufferView", view}, {"componentType", componentType}, {"count", count},
                                            {"type", type}, {"normalized", normalized}});
            return int(b.doc()["accessors"].size() - 1);
        };
        const int p = accessor(view(positions_.data(), 4, 12, "ATTRIBUTES", nullptr, 0), 5126, "VEC3", 4, false);
        const int n = accessor(view(octahedral.data(), 4, 4, "ATTRIBUTES", "OCTAHEDRAL", 48), 5120, "VEC3", 4, true);
        const int i = accessor(view(indices_.data(), 6, 2, "TRIANGLES", nullptr, 64), 5123, "SCALAR", 6, false);
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", p}, {"NORMAL", n}}}, {"indices", i}})}});
        b.doc()["extensionsUsed"] = b.doc()["extensionsRequired"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
        if (change) change(b.doc());
        return glb ? b.writeGlb(file) : b.write(file);
    }

private:
    std::vector<float> positions_, normals_;
    std::vector<std::uint16_t> indices_;
};

TEST_F(GltfLoader, MeshoptCompressedBuffersReadAsTheUncompressedMesh) {
    const MeshoptMesh mesh;
    const Scene plain = load(mesh.plain(dir_ / "plain.gltf"));
    ASSERT_EQ(plain.triangles.size(), 2u);
    for (const bool glb : {false, true}) {
        const Scene scene = load(mesh.compressed(dir_ / (glb ? "meshopt.glb" : "meshopt.gltf"), glb));
        ASSERT_EQ(scene.triangles.size(), 2u) << glb;
        for (std::size_t t = 0; t < 2; ++t)
            for (int c = 0; c < 3; ++c) {
                EXPECT_EQ(scene.triangles[t].position[c], plain.triangles[t].position[c]) << glb;
                // 8-bit octahedral normals: within 0.01 of the float ones.
                EXPECT_LT(glm::length(scene.triangles[t].normal[c] - plain.triangles[t].normal[c]), 0.01f) << glb;
            }
    }
}

TEST_F(GltfLoader, MeshoptBuffersThatDoNotDecodeOrAskForTooMuchAreRefused) {
    const MeshoptMesh mesh;
    auto refusal = [&](const std::string& name, const std::function<void(json&)>& change,
                       std::size_t fallbackBytes = 48 + 16 + 12) -> std::string {
        try {
            load(mesh.compressed(dir_ / name, false, change, fallbackBytes));
        } catch (const InputError& e) {
            return e.what();
        }
        return "no refusal";
    };
    auto expect = [&](const std::string& message, const std::string& part) {
        EXPECT_NE(message.find(part), std::string::npos) << message;
    };
    expect(refusal("short.gltf", [](json& doc) { doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 5; }),
           "bufferViews[0]: EXT_meshopt_compression: its bytes do not decode");
    expect(refusal("huge.gltf", [](json&) {}, std::size_t(1e12)),
           "buffers[1]: its byteLength of 1000000000000 is more than its compressed views decode to");
    expect(refusal("many.gltf",
                   [](json& doc) {
                       doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = std::uint64_t(1e9);
                       doc["bufferViews"][0]["byteLength"] = std::uint64_t(12e9);
                   }),
           "bufferViews[0]: EXT_meshopt_compression decodes 1000000000 elements");
    expect(refusal("mode.gltf", [](json& doc) { doc["bufferViews"][2]["extensions"]["EXT_meshopt_compression"]["mode"] = "LINES"; }),
           "has the mode \"LINES\"");
    expect(refusal("stride.gltf", [](json& doc) { doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 6; }),
           "has a byteStride of 6");
    expect(refusal("beyond.gltf", [](json& doc) { doc["bufferViews"][2]["byteOffset"] = 68; }),
           "bufferViews[2] reaches beyond its buffer");
}

// KHR_draco_mesh_compression: a quad's positions, normals and texture coordinates encoded by
// Draco's own encoder, without quantization (lossless) in a .gltf and a .glb, read as the
// uncompressed quad is (Draco may reorder the triangles and start each at another corner:
// compared from each triangle's least corner), and quantized as exporters write it, within its
// steps; data that does not decode is refused naming the primitive.
TEST_F(GltfLoader, DracoCompressedPrimitivesReadAsTheUncompressedOnes) {
    const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const std::vector<float> normals = {0, 0, 1, 0.6f, 0, 0.8f, 0, 0.6f, 0.8f, -0.6f, 0, 0.8f};
    const std::vector<float> uvs = {0, 0, 1, 0, 1, 1, 0, 1};
    const std::vector<std::uint16_t> indices = {0, 1, 2, 0, 2, 3};
    GltfBuilder plain;
    plain.node({{"mesh", plain.mesh({{"attributes",
                                      {{"POSITION", plain.positions(positions)},
                                       {"NORMAL", plain.accessor(normals, 5126, "VEC3", 4)},
                                       {"TEXCOORD_0", plain.accessor(uvs, 5126, "VEC2", 4)}}},
                                     {"indices", plain.accessor(indices, 5123, "SCALAR", 6)}})}});
    const Scene expected = load(plain.write(dir_ / "plain.gltf"));

    draco::TriangleSoupMeshBuilder builder;
    builder.Start(2);
    const int p = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int n = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
    const int t = builder.AddAttribute(draco::GeometryAttribute::TEX_COORD, 2, draco::DT_FLOAT32);
    for (int f = 0; f < 2; ++f) {
        const std::uint16_t* c = &indices[std::size_t(3 * f)];
        builder.SetAttributeValuesForFace(p, draco::FaceIndex(f), &positions[3 * c[0]], &positions[3 * c[1]], &positions[3 * c[2]]);
        builder.SetAttributeValuesForFace(n, draco::FaceIndex(f), &normals[3 * c[0]], &normals[3 * c[1]], &normals[3 * c[2]]);
        builder.SetAttributeValuesForFace(t, draco::FaceIndex(f), &uvs[2 * c[0]], &uvs[2 * c[1]], &uvs[2 * c[2]]);
    }
    const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    ASSERT_TRUE(mesh);
    draco::Encoder encoder;
    draco::EncoderBuffer encoded, quantized;
    ASSERT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &encoded).ok());
    // As exporters write it: 14-bit positions, 10-bit normals, 12-bit texture coordinates.
    encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
    encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
    ASSERT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &quantized).ok());
    auto compressed = [&](const fs::path& file, bool glb, bool corrupt, const draco::EncoderBuffer& data) {
        GltfBuilder b;
        std::vector<unsigned char> bytes(data.data(), data.data() + data.size());
        if (corrupt) bytes.resize(bytes.size() / 2);
        const std::size_t offset = b.append(bytes);
        b.doc()["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes.size()}});
        auto accessor = [&](int componentType, const char* type, std::size_t count) {
            b.doc()["accessors"].push_back({{"componentType", componentType}, {"count", count}, {"type", type}});
            return int(b.doc()["accessors"].size() - 1);
        };
        const std::size_t points = mesh->num_points();
        const json draco = {{"bufferView", b.doc()["bufferViews"].size() - 1},
                            {"attributes",
                             {{"POSITION", mesh->attribute(p)->unique_id()},
                              {"NORMAL", mesh->attribute(n)->unique_id()},
                              {"TEXCOORD_0", mesh->attribute(t)->unique_id()}}}};
        b.node({{"mesh", b.mesh({{"attributes",
                                  {{"POSITION", accessor(5126, "VEC3", points)},
                                   {"NORMAL", accessor(5126, "VEC3", points)},
                                   {"TEXCOORD_0", accessor(5126, "VEC2", points)}}},
                                 {"indices", accessor(5123, "SCALAR", 6)},
                                 {"extensions", {{"KHR_draco_mesh_compression", draco}}}})}});
        b.doc()["extensionsUsed"] = b.doc()["extensionsRequired"] = {"KHR_draco_mesh_compression"};
        return glb ? b.writeGlb(file) : b.write(file);
    };
    auto byLeastCorner = [](const Scene& scene) {
        std::multiset<std::vector<float>> set;
        for (const Triangle& tri : scene.triangles) {
            auto corner = [&](int c) {
                const glm::vec3 &q = tri.position[c], &m = tri.normal[c];
                return std::vector<float>{q.x, q.y, q.z, m.x, m.y, m.z, tri.uv[c].x, tri.uv[c].y};
            };
            const std::vector<float> corners[3] = {corner(0), corner(1), corner(2)};
            const int first = int(std::min_element(corners, corners + 3) - corners);
            std::vector<float> key;
            for (int c = 0; c < 3; ++c) key.insert(key.end(), corners[(first + c) % 3].begin(), corners[(first + c) % 3].end());
            set.insert(key);
        }
        return set;
    };
    for (const bool glb : {false, true}) {
        const Scene scene = load(compressed(dir_ / (glb ? "draco.glb" : "draco.gltf"), glb, false, encoded));
        EXPECT_EQ(byLeastCorner(scene), byLeastCorner(expected)) << glb;
    }
    // Quantized: every corner within the quantization's step of one of the quad's, with its normal
    // and texture coordinate.
    const Scene scene = load(compressed(dir_ / "quantized.glb", true, false, quantized));
    ASSERT_EQ(scene.triangles.size(), 2u);
    for (const Triangle& tri : scene.triangles)
        for (int c = 0; c < 3; ++c) {
            int matches = 0;
            for (const Triangle& e : expected.triangles)
                for (int k = 0; k < 3; ++k)
                    if (glm::length(tri.position[c] - e.position[k]) < 1e-3f) {
                        EXPECT_LT(glm::length(tri.normal[c] - e.normal[k]), 0.01f);
                        EXPECT_LT(glm::length(tri.uv[c] - e.uv[k]), 1e-3f);
                        ++matches;
                    }
            EXPECT_GT(matches, 0);
        }
    try {
        load(compressed(dir_ / "corrupt.gltf", false, true, encoded));
        ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("meshes[0].primitives[0]: KHR_draco_mesh_compression: its data does not decode"),
                  std::string::npos)
            << e.what();
    }
}

// An attribute the Draco data does not hold is stored uncompressed, in its accessor, in the order
// of the decoded vertices (KHR_draco_mesh_compression's attributes): texture coordinates (x, y) of
// each decoded vertex's position, beside Draco-compressed positions.
TEST_F(GltfLoader, AnAttributeOutsideTheDracoDataComesFromItsAccessor) {
    draco::TriangleSoupMeshBuilder builder;
    builder.Start(2);
    const int p = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const float corners[2][3][3] = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, {{0, 0, 0}, {1, 1, 0}, {0, 1, 0}}};
    for (int f = 0; f < 2; ++f)
        builder.SetAttributeValuesForFace(p, draco::FaceIndex(f), corners[f][0], corners[f][1], corners[f][2]);
    const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    draco::Encoder encoder;
    draco::EncoderBuffer encoded;
    ASSERT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &encoded).ok());
    // The vertices in the order a decoder gives them, and their texture coordinates.
    draco::DecoderBuffer input;
    input.Init(encoded.data(), encoded.size());
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&input);
    ASSERT_TRUE(decoded.ok());
    const std::unique_ptr<draco::Mesh> order = std::move(decoded).value();
    const draco::PointAttribute* position = order->GetNamedAttribute(draco::GeometryAttribute::POSITION);
    std::vector<float> uvs;
    for (draco::PointIndex i(0); i < order->num_points(); ++i) {
        float xyz[3];
        position->ConvertValue<float>(position->mapped_index(i), 3, xyz);
        uvs.insert(uvs.end(), {xyz[0], xyz[1]});
    }
    GltfBuilder b;
    const int uvAccessor = b.accessor(uvs, 5126, "VEC2", order->num_points());
    const std::size_t offset = b.append(std::vector<unsigned char>(encoded.data(), encoded.data() + encoded.size()));
    b.doc()["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", encoded.size()}});
    b.doc()["accessors"].push_back({{"componentType", 5126}, {"count", order->num_points()}, {"type", "VEC3"}});
    b.doc()["accessors"].push_back({{"componentType", 5125}, {"count", 6}, {"type", "SCALAR"}});
    const json draco = {{"bufferView", b.doc()["bufferViews"].size() - 1},
                        {"attributes", {{"POSITION", mesh->attribute(p)->unique_id()}}}};
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", 1}, {"TEXCOORD_0", uvAccessor}}},
                             {"indices", 2},
                             {"extensions", {{"KHR_draco_mesh_compression", draco}}}})}});
    b.doc()["extensionsUsed"] = b.doc()["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    const Scene scene = load(b.write(dir_ / "mixed.gltf"));
    ASSERT_EQ(scene.triangles.size(), 2u);
    // glTF's (x, y, z) is vitrum's (x, -z, y), and vitrum's v is 1 - glTF's.
    for (const Triangle& t : scene.triangles)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(t.uv[c], glm::vec2(t.position[c].x, 1.0f - t.position[c].z));
}

// Every index component type the spec allows (unsigned byte, short, int) and no indices at all
// give the same triangles.
TEST_F(GltfLoader, IndexTypesAndNonIndexedGiveTheSameTriangles) {
    const std::vector<float> quad = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const std::vector<int> corners = {0, 1, 2, 0, 2, 3};
    std::vector<float> unrolled;
    for (int c : corners) unrolled.insert(unrolled.end(), quad.begin() + 3 * c, quad.begin() + 3 * c + 3);
    GltfBuilder b;
    const int vertices = b.positions(quad);
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", vertices}}},
                              {"indices", b.accessor(std::vector<std::uint8_t>(corners.begin(), corners.end()), 5121, "SCALAR", 6)}})}});
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", vertices}}},
                              {"indices", b.accessor(std::vector<std::uint16_t>(corners.begin(), corners.end()), 5123, "SCALAR", 6)}})}});
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", vertices}}},
                              {"indices", b.accessor(std::vector<std::uint32_t>(corners.begin(), corners.end()), 5125, "SCALAR", 6)}})}});
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(unrolled)}}}})}});
    Scene scene = load(b.write(dir_ / "indices.gltf"));
    ASSERT_EQ(scene.triangles.size(), 8u);
    for (std::size_t i = 2; i < 8; ++i)
        for (int k = 0; k < 3; ++k) EXPECT_EQ(scene.triangles[i].position[k], scene.triangles[i % 2].position[k]);
}

// A cube as exporters write it: 24 vertices, split at the edges for their normals. The medium's
// closed-mesh check works on positions, so the cube is closed glass.
TEST_F(GltfLoader, CubeSplitAtItsNormalSeamsIsClosedGlass) {
    std::vector<float> positions, normals;
    std::vector<std::uint16_t> indices;
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = -1; side <= 1; side += 2) {
            glm::vec3 n(0.0f);
            n[axis] = float(side);
            const glm::vec3 u = glm::vec3(n.y, n.z, n.x), v = glm::cross(n, u);
            const auto first = std::uint16_t(positions.size() / 3);
            for (const auto& [a, c] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
                const glm::vec3 p = n + float(a) * u + float(c) * v;
                positions.insert(positions.end(), {p.x, p.y, p.z});
                normals.insert(normals.end(), {n.x, n.y, n.z});
            }
            for (int k : {0, 1, 2, 0, 2, 3}) indices.push_back(std::uint16_t(first + k));
        }
    }
    GltfBuilder b;
    const int glass = b.material({{"extensions",
                                   {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                                    {"KHR_materials_volume", {{"thicknessFactor", 2.0}}}}}});
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(positions)},
                                             {"NORMAL", b.accessor(normals, 5126, "VEC3", normals.size() / 3)}}},
                              {"indices", b.accessor(indices, 5123, "SCALAR", indices.size())},
                              {"material", glass}})}});
    Scene scene = load(b.write(dir_ / "cube.gltf"));
    ASSERT_EQ(scene.triangles.size(), 12u);
    ASSERT_EQ(scene.materials[scene.triangles[0].material].model, MaterialModel::Glass);
    EXPECT_TRUE(openGlassObjects(scene).empty());
    // Each face's normals are its own, turned into z-up and pointing out of the cube.
    for (const Triangle& t : scene.triangles) {
        const glm::vec3 centre = (t.position[0] + t.position[1] + t.position[2]) / 3.0f;
        EXPECT_GT(glm::dot(t.normal[0], centre), 0.0f);
    }
}

// glTF's PBR materials on the render model's (docs/scene-format.md, "glTF materials").
TEST_F(GltfLoader, MaterialsMapOntoTheRenderModel) {
    GltfBuilder b;
    const int positions = b.positions(kTriangle);
    auto instance = [&](json material) {
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", positions}}}, {"material", b.material(std::move(material))}})}});
    };
    instance({{"name", "water"},
              {"extensions",
               {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                {"KHR_materials_ior", {{"ior", 1.33}}},
                {"KHR_materials_volume",
                 {{"thicknessFactor", 1.0}, {"attenuationDistance", 2.0}, {"attenuationColor", {0.5, 1.0, 0.25}}}}}}});
    instance({{"name", "chrome"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.9, 0.8, 0.7, 1}}, {"metallicFactor", 1.0}, {"roughnessFactor", 0.0}}}});
    instance({{"name", "plastic"},
              {"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.4, 0.6, 1}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.5}}}});
    instance({{"name", "default-rough"}});  // the spec's defaults: metallic 1, roughness 1
    instance({{"name", "tinted"},
              {"pbrMetallicRoughness", {{"metallicFactor", 0.0}}},
              {"extensions", {{"KHR_materials_specular", {{"specularFactor", 0.5}, {"specularColorFactor", {2.0, 1.0, 30.0}}}}}}});
    instance({{"name", "matte"},
              {"pbrMetallicRoughness", {{"metallicFactor", 0.0}}},
              {"extensions", {{"KHR_materials_specular", {{"specularFactor", 0.0}}}}}});
    const int before = warningCount();
    Scene scene = load(b.write(dir_ / "materials.gltf"));
    ASSERT_EQ(scene.materials.size(), 6u);
    const Material& water = scene.materials[0];
    EXPECT_EQ(water.model, MaterialModel::Glass);
    EXPECT_FLOAT_EQ(water.ior, 1.33f);
    // mu = -ln(attenuationColor) / attenuationDistance (KHR_materials_volume).
    EXPECT_NEAR(water.attenuation.x, std::log(2.0) / 2.0, 1e-7);
    EXPECT_EQ(water.attenuation.y, 0.0f);
    EXPECT_NEAR(water.attenuation.z, std::log(4.0) / 2.0, 1e-7);
    const Material& chrome = scene.materials[1];
    EXPECT_EQ(chrome.model, MaterialModel::Mirror);
    expectNear(chrome.specular, {0.9f, 0.8f, 0.7f});
    const Material& plastic = scene.materials[2];
    EXPECT_EQ(plastic.model, MaterialModel::Phong);
    expectNear(plastic.diffuse, {0.2f, 0.4f, 0.6f});  // factors are linear already
    expectNear(plastic.specular, glm::vec3(0.04f));   // ((1.5 - 1) / (1.5 + 1))^2
    EXPECT_FLOAT_EQ(plastic.shininess, 30.0f);        // 2 / alpha^2 - 2, alpha = 0.5^2
    EXPECT_FLOAT_EQ(plastic.ior, 1.5f);
    // The default material is a rough metal: a mirror, its roughness named in a warning.
    EXPECT_EQ(scene.materials[3].model, MaterialModel::Mirror);
    EXPECT_EQ(warningCount(), before + 1);
    // KHR_materials_specular: Ks = min(F0 * specularColorFactor, 1) * specularFactor; no specular
    // layer at all is Lambert.
    EXPECT_EQ(scene.materials[4].model, MaterialModel::Phong);
    expectNear(scene.materials[4].specular, {0.04f, 0.02f, 0.5f});
    EXPECT_FLOAT_EQ(scene.materials[4].shininess, 1.0f);  // roughness 1 by default
    EXPECT_EQ(scene.materials[5].model, MaterialModel::Lambert);
}

// A base colour factor multiplies the base colour texture (glTF 2.0, 3.9.2); the render model's
// diffuse is one texel, so the product is made once per image and factor.
TEST_F(GltfLoader, BaseColourFactorMultipliesItsEmbeddedTexture) {
    Image image(2, 1);
    image.pixels = {glm::vec3(srgbToLinear(128.0f / 255.0f)), glm::vec3(1.0f)};
    GltfBuilder b;
    b.embedTexture(image, dir_ / "texture.png");
    const int uvs = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1}, 5126, "VEC2", 3);
    const int positions = b.positions(kTriangle);
    for (double red : {1.0, 0.5}) {
        const int material = b.material(
            {{"pbrMetallicRoughness",
              {{"baseColorFactor", {red, 1, 1, 1}}, {"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.0}}}});
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", positions}, {"TEXCOORD_0", uvs}}}, {"material", material}})}});
    }
    Scene scene = load(b.write(dir_ / "textured.gltf"));
    ASSERT_EQ(scene.textures.size(), 2u);
    const Texture& plain = scene.textures[size_t(scene.materials[0].diffuseTexture)];
    const Texture& reddish = scene.textures[size_t(scene.materials[1].diffuseTexture)];
    EXPECT_FLOAT_EQ(plain.texels[1].x, 1.0f);
    EXPECT_FLOAT_EQ(reddish.texels[1].x, 0.5f);
    EXPECT_FLOAT_EQ(reddish.texels[1].y, 1.0f);
    EXPECT_FLOAT_EQ(reddish.texels[0].x, plain.texels[0].x * 0.5f);
    // glTF's v runs down from the image's top row; vitrum's up from the bottom (render model).
    EXPECT_EQ(scene.triangles[0].uv[0], glm::vec2(0, 1));
    EXPECT_EQ(scene.triangles[0].uv[2], glm::vec2(0, 0));
}

// EXT_texture_webp: a texture whose extension names a WebP image (in an image/webp data URI,
// which tinygltf 2.7 does not decode itself) beside a PNG fallback as its source: the WebP is read.
TEST_F(GltfLoader, AWebpTextureIsReadBeforeItsFallback) {
    Image fallback(1, 1);
    fallback.pixels = {glm::vec3(0.0f)};
    GltfBuilder b;
    b.embedTexture(fallback, dir_ / "fallback.png");
    const std::uint8_t rgb[3] = {255, 128, 0};
    std::uint8_t* encoded = nullptr;
    const std::size_t size = WebPEncodeLosslessRGB(rgb, 1, 1, 3, &encoded);
    ASSERT_GT(size, 0u);
    b.doc()["images"].push_back({{"uri", "data:image/webp;base64," + base64(std::vector<unsigned char>(encoded, encoded + size))}});
    WebPFree(encoded);
    b.doc()["textures"][0]["extensions"] = {{"EXT_texture_webp", {{"source", 1}}}};
    b.doc()["extensionsUsed"] = {"EXT_texture_webp"};
    const int material = b.material({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.0}}}});
    const int uvs = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1}, 5126, "VEC2", 3);
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}, {"TEXCOORD_0", uvs}}}, {"material", material}})}});
    const Scene scene = load(b.write(dir_ / "webp.gltf"));
    ASSERT_EQ(scene.textures.size(), 1u);
    const glm::vec3 texel = scene.textures[std::size_t(scene.materials[0].diffuseTexture)].texels[0];
    EXPECT_EQ(texel, glm::vec3(1.0f, srgbToLinear(128.0f / 255.0f), 0.0f));
}

// KHR_texture_transform on the base colour texture: uv' = T R S uv with the specification's
// matrices, rows (1 0 ox; 0 1 oy), (cos sin 0; -sin cos 0), (sx 0; 0 sy), in glTF's coordinates
// (v down); vitrum's v is then 1 - v'. A material without it keeps its coordinates.
TEST_F(GltfLoader, TextureTransformMovesTheBaseColourCoordinates) {
    GltfBuilder b;
    b.embedTexture(Image(1, 1), dir_ / "texel.png");
    b.doc()["extensionsUsed"] = json::array({"KHR_texture_transform"});
    const std::vector<float> uv = {0.25f, 0.5f, 1.0f, 0.0f, 0.0f, 1.0f};
    const int uvs = b.accessor(uv, 5126, "VEC2", 3);
    const int positions = b.positions(kTriangle);
    const double ox = 0.5, oy = 0.25, angle = 0.3, sx = 2.0, sy = 3.0;
    const json transform = {{"offset", {ox, oy}}, {"rotation", angle}, {"scale", {sx, sy}}};
    for (bool transformed : {false, true}) {
        json texture = {{"index", 0}};
        if (transformed) texture["extensions"] = {{"KHR_texture_transform", transform}};
        const int material =
            b.material({{"pbrMetallicRoughness", {{"baseColorTexture", texture}, {"metallicFactor", 0.0}}}});
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", positions}, {"TEXCOORD_0", uvs}}}, {"material", material}})}});
    }
    ::testing::internal::CaptureStderr();
    Scene scene = load(b.write(dir_ / "transformed.gltf"));
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(warnings.find("KHR_texture_transform"), std::string::npos) << warnings;
    ASSERT_EQ(scene.triangles.size(), 2u);
    const double c = std::cos(angle), s = std::sin(angle);
    for (int i = 0; i < 3; ++i) {
        const double u = uv[std::size_t(2 * i)], v = uv[std::size_t(2 * i + 1)];
        EXPECT_EQ(scene.triangles[0].uv[i], glm::vec2(float(u), 1.0f - float(v)));
        const double u2 = c * sx * u + s * sy * v + ox, v2 = -s * sx * u + c * sy * v + oy;
        EXPECT_NEAR(scene.triangles[1].uv[i].x, u2, 1e-6) << "corner " << i;
        EXPECT_NEAR(scene.triangles[1].uv[i].y, 1.0 - v2, 1e-6) << "corner " << i;
    }
}

// KHR_materials_pbrSpecularGlossiness (what assimp writes) replaces the metallic-roughness model:
// Kd = diffuseFactor, Ks = specularFactor, Ns = 2 / alpha^2 - 2 with alpha = (1 - glossiness)^2,
// Lambert without a specular layer; a glass keeps its transmission.
TEST_F(GltfLoader, SpecularGlossinessMaterialsMapOntoPhongAndLambert) {
    GltfBuilder b;
    const int positions = b.positions(kTriangle);
    const json sg = {{"diffuseFactor", {0.8, 0.2, 0.1, 1.0}}, {"specularFactor", {0.5, 0.25, 0.5}}, {"glossinessFactor", 0.75}};
    const json lambert = {{"diffuseFactor", {0.3, 0.6, 0.9, 1.0}}, {"specularFactor", {0.0, 0.0, 0.0}}, {"glossinessFactor", 0.032}};
    const std::vector<json> materials = {
        // metallic 1 in the fallback: the extension rules, not the mirror.
        {{"pbrMetallicRoughness", {{"metallicFactor", 1.0}}}, {"extensions", {{"KHR_materials_pbrSpecularGlossiness", sg}}}},
        {{"extensions", {{"KHR_materials_pbrSpecularGlossiness", lambert}}}},
        {{"extensions", {{"KHR_materials_pbrSpecularGlossiness", sg},
                         {"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                         {"KHR_materials_volume", {{"thicknessFactor", 1.0}}}}}},
    };
    for (const json& material : materials)
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", positions}}}, {"material", b.material(material)}})}});
    Scene scene = load(b.write(dir_ / "specular_glossiness.gltf"));
    ASSERT_EQ(scene.materials.size(), 3u);
    const Material& phong = scene.materials[0];
    EXPECT_EQ(phong.model, MaterialModel::Phong);
    EXPECT_EQ(phong.diffuse, glm::vec3(0.8f, 0.2f, 0.1f));
    EXPECT_EQ(phong.specular, glm::vec3(0.5f, 0.25f, 0.5f));
    const double alpha = 0.25 * 0.25;
    EXPECT_NEAR(phong.shininess, 2.0 / (alpha * alpha) - 2.0, 1e-3);  // 510
    EXPECT_EQ(scene.materials[1].model, MaterialModel::Lambert);
    EXPECT_EQ(scene.materials[1].diffuse, glm::vec3(0.3f, 0.6f, 0.9f));
    EXPECT_EQ(scene.materials[2].model, MaterialModel::Glass);
}

// Thin-walled transmission (KHR_materials_volume: no extension, or thicknessFactor 0) is thin
// glass, never a solid: its Ni from KHR_materials_ior, what it transmits tinted by the base colour
// (KHR_materials_transmission), factor and texture; a volume's attenuation and a dispersion do
// not apply to a wall of no thickness, the dispersion named in a warning.
TEST_F(GltfLoader, ThinWalledGlassIsThinGlassTintedByItsBaseColour) {
    Image image(1, 1);
    image.pixels = {glm::vec3(srgbToLinear(128.0f / 255.0f))};  // a PNG holds it exactly
    GltfBuilder b;
    b.embedTexture(image, dir_ / "texture.png");
    const int uvs = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1}, 5126, "VEC2", 3);
    const int positions = b.positions(kTriangle);
    const json transmission = {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}};
    json zeroThickness = transmission;
    zeroThickness["KHR_materials_volume"] = {{"thicknessFactor", 0.0}, {"attenuationDistance", 1.0}};
    zeroThickness["KHR_materials_dispersion"] = {{"dispersion", 0.0}};  // none: nothing to warn about
    json tinted = transmission;
    tinted["KHR_materials_ior"] = {{"ior", 1.52}};
    tinted["KHR_materials_dispersion"] = {{"dispersion", 0.5}};
    const json pbr = {{"baseColorFactor", {0.2, 0.8, 0.4, 1.0}}, {"metallicFactor", 0.0}};
    json textured = pbr;
    textured["baseColorTexture"] = {{"index", 0}};
    for (const json& material :
         {json{{"name", "pane"}, {"extensions", transmission}}, json{{"name", "flat"}, {"extensions", zeroThickness}},
          json{{"name", "green"}, {"extensions", tinted}, {"pbrMetallicRoughness", pbr}},
          json{{"name", "stained"}, {"extensions", transmission}, {"pbrMetallicRoughness", textured}}})
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", positions}, {"TEXCOORD_0", uvs}}},
                                 {"material", b.material(material)}})}});
    const int before = warningCount();
    const Scene scene = load(b.write(dir_ / "thin.gltf"));
    EXPECT_EQ(warningCount(), before + 1);  // the dispersion a pane's two faces undo
    ASSERT_EQ(scene.materials.size(), 4u);
    for (const Material& m : scene.materials) {
        SCOPED_TRACE(m.name);
        EXPECT_EQ(m.model, MaterialModel::ThinGlass);
        EXPECT_EQ(m.attenuation, glm::vec3(0.0f));
        EXPECT_EQ(m.abbe, 0.0f);
    }
    EXPECT_EQ(scene.materials[0].diffuse, glm::vec3(1.0f));  // no base colour: clear
    EXPECT_EQ(scene.materials[0].ior, 1.5f);
    EXPECT_EQ(scene.materials[2].diffuse, glm::vec3(0.2f, 0.8f, 0.4f));
    EXPECT_EQ(scene.materials[2].ior, 1.52f);
    ASSERT_GE(scene.materials[3].diffuseTexture, 0);
    // The texture times the factor, as a base colour's (BaseColourFactorMultipliesItsEmbeddedTexture).
    const Texture& texture = scene.textures[std::size_t(scene.materials[3].diffuseTexture)];
    EXPECT_FLOAT_EQ(texture.texels[0].y, 0.8f * srgbToLinear(128.0f / 255.0f));
}

// The base colour of a glass volume tints the light passing through its boundary, at every
// crossing (KHR_materials_volume, "Base Color and Absorption"): Material::tint, as glass of the
// ABeautifulGame pawns and the StainedGlassLamp's beads of Khronos's sample assets have it. A
// factor outside [0, 1] is kept within it (a tint never adds light), a thin glass's too; a base
// colour texture is not read for a volume, and the warning says so.
TEST_F(GltfLoader, VolumeGlassIsTintedByItsBaseColourFactor) {
    Image image(1, 1);
    image.pixels = {glm::vec3(0.5f)};
    GltfBuilder b;
    b.embedTexture(image, dir_ / "texture.png");
    const int uvs = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1}, 5126, "VEC2", 3);
    const int positions = b.positions(kTriangle);
    const json volume = {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                         {"KHR_materials_volume", {{"thicknessFactor", 0.02}}}};
    auto base = [](json factor) { return json{{"baseColorFactor", std::move(factor)}, {"metallicFactor", 0.0}}; };
    json textured = base({0.3, 0.5, 0.45, 1.0});
    textured["baseColorTexture"] = {{"index", 0}};
    for (const json& material :
         {json{{"name", "clear"}, {"extensions", volume}},
          json{{"name", "amber"}, {"extensions", volume}, {"pbrMetallicRoughness", base({1.0, 0.6, 0.2, 1.0})}},
          json{{"name", "beyond"}, {"extensions", volume}, {"pbrMetallicRoughness", base({1.5, -0.5, 0.5, 1.0})}},
          json{{"name", "textured"}, {"extensions", volume}, {"pbrMetallicRoughness", textured}},
          json{{"name", "thin"},
               {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}}},
               {"pbrMetallicRoughness", base({1.5, -0.5, 0.5, 1.0})}}})
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", positions}, {"TEXCOORD_0", uvs}}},
                                 {"material", b.material(material)}})}});
    const int before = warningCount();
    ::testing::internal::CaptureStderr();
    const Scene scene = load(b.write(dir_ / "tinted.gltf"));
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(warningCount(), before + 1) << warnings;
    EXPECT_NE(warnings.find("(\"textured\"): ignored: baseColorTexture (a glass volume is tinted by its "
                            "baseColorFactor alone)"),
              std::string::npos)
        << warnings;
    ASSERT_EQ(scene.materials.size(), 5u);
    for (std::size_t i = 0; i < 4; ++i) {
        SCOPED_TRACE(scene.materials[i].name);
        EXPECT_EQ(scene.materials[i].model, MaterialModel::Glass);
        EXPECT_EQ(scene.materials[i].diffuseTexture, -1);
    }
    EXPECT_EQ(scene.materials[0].tint, glm::vec3(1.0f));
    EXPECT_EQ(scene.materials[1].tint, glm::vec3(1.0f, 0.6f, 0.2f));
    EXPECT_EQ(scene.materials[2].tint, glm::vec3(1.0f, 0.0f, 0.5f));
    EXPECT_EQ(scene.materials[3].tint, glm::vec3(0.3f, 0.5f, 0.45f));
    // A thin glass's tint, its diffuse colour, is kept within [0, 1] the same way.
    EXPECT_EQ(scene.materials[4].model, MaterialModel::ThinGlass);
    EXPECT_EQ(scene.materials[4].diffuse, glm::vec3(1.0f, 0.0f, 0.5f));
}

// An RGBA or grey-and-alpha PNG (stb_image_write: the project's own writer writes RGB only).
std::vector<unsigned char> pngWithAlpha(int width, int height, int channels, const std::vector<unsigned char>& values) {
    std::vector<unsigned char> bytes;
    auto append = [](void* context, void* data, int size) {
        auto* out = static_cast<std::vector<unsigned char>*>(context);
        out->insert(out->end(), static_cast<unsigned char*>(data), static_cast<unsigned char*>(data) + size);
    };
    EXPECT_NE(stbi_write_png_to_func(append, &bytes, width, height, channels, values.data(), width * channels), 0);
    return bytes;
}

// alphaMode MASK (glTF 2.0, "Alpha Coverage" and alphaCutoff): the surface is not there where the base
// colour's alpha, the texture's times the factor's, is below alphaCutoff (0.5 unless given).
// Material::cutout holds that alpha over the cutoff a texel: exactly 2 a / 255 for an 8-bit
// alpha a and the default cutoff, a f / c otherwise. An opaque material's alpha is ignored, a
// factor alone that is below the cutoff cuts the whole surface (one texel), and nothing is cut
// where the alpha cannot fall below the cutoff.
TEST_F(GltfLoader, AMaskedMaterialIsCutOutWhereItsAlphaIsBelowTheCutoff) {
    GltfBuilder b;
    const std::vector<unsigned char> rgba = {255, 0, 0, 0, 0, 255, 0, 127, 0, 0, 255, 128, 9, 9, 9, 255};
    b.doc()["images"] =
        json::array({{{"uri", "data:image/png;base64," + base64(pngWithAlpha(2, 2, 4, rgba))}},
                     {{"uri", "data:image/png;base64," + base64(pngWithAlpha(2, 1, 2, {50, 40, 60, 200}))}},
                     {{"uri", "data:image/png;base64," + base64(pngWithAlpha(1, 1, 3, {1, 2, 3}))}}});
    b.doc()["textures"] = json::array({{{"source", 0}}, {{"source", 1}}, {{"source", 2}}});
    const int uvs = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1}, 5126, "VEC2", 3);
    const int positions = b.positions(kTriangle);
    auto masked = [](std::string name, int texture, double alpha, std::optional<double> cutoff = std::nullopt,
                     std::string mode = "MASK") {
        json pbr = {{"baseColorFactor", {0.5, 0.5, 0.5, alpha}}, {"metallicFactor", 0.0}};
        if (texture >= 0) pbr["baseColorTexture"] = {{"index", texture}};
        json m = {{"name", std::move(name)}, {"alphaMode", std::move(mode)}, {"pbrMetallicRoughness", pbr}};
        if (cutoff) m["alphaCutoff"] = *cutoff;
        return m;
    };
    json mirror = masked("mirror", 0, 1.0);
    mirror["pbrMetallicRoughness"]["metallicFactor"] = 1.0;
    json volume = masked("volume", 0, 1.0);
    volume["extensions"] = {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                            {"KHR_materials_volume", {{"thicknessFactor", 0.1}}}};
    json thin = masked("thin", 0, 1.0);
    thin["extensions"] = {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}};
    // A volume whose alpha is 1 everywhere: its MASK would cut nothing, and goes unmentioned.
    json wholeVolume = masked("whole volume", 1, 1.0, 0.15);
    wholeVolume["extensions"] = volume["extensions"];
    // KHR_materials_pbrSpecularGlossiness's diffuse replaces the base colour, its alpha too.
    json glossy = masked("glossy", 0, 1.0);
    glossy["extensions"] = {{"KHR_materials_pbrSpecularGlossiness", {{"diffuseFactor", {1.0, 1.0, 1.0, 0.3}}}}};
    for (const json& material : {masked("rgba", 0, 1.0), masked("scaled", 0, 0.8, 0.25), masked("grey", 1, 1.0),
                                 masked("opaque", 0, 1.0, 0.5, "OPAQUE"), masked("factor only", -1, 0.3),
                                 masked("factor enough", -1, 0.5), masked("no alpha channel", 2, 0.4, 0.8),
                                 masked("cutoff 0", 0, 1.0, 0.0), mirror, volume, thin, glossy, wholeVolume})
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", positions}, {"TEXCOORD_0", uvs}}},
                                 {"material", b.material(material)}})}});
    ::testing::internal::CaptureStderr();
    const Scene scene = load(b.write(dir_ / "masked.gltf"));
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    ASSERT_EQ(scene.materials.size(), 13u);
    auto cutout = [&](std::size_t material) -> std::vector<float> {
        const Material& m = scene.materials[material];
        if (m.cutout < 0) return {};
        const Texture& t = scene.textures[std::size_t(m.cutout)];
        std::vector<float> values;
        for (const glm::vec3& texel : t.texels) {
            EXPECT_TRUE(texel.x == texel.y && texel.y == texel.z) << m.name << ": a grey texture";
            values.push_back(texel.x);
        }
        EXPECT_EQ(values.size(), std::size_t(t.width) * std::size_t(t.height)) << m.name;
        return values;
    };
    const std::vector<float> rgbaAlpha = {0.0f, float(2.0 * 127 / 255.0), float(2.0 * 128 / 255.0), float(2.0)};
    EXPECT_EQ(cutout(0), rgbaAlpha);
    EXPECT_EQ(scene.textures[std::size_t(scene.materials[0].cutout)].width, 2);
    // The colour keeps its own texture, the alpha left out of it.
    ASSERT_GE(scene.materials[0].diffuseTexture, 0);
    EXPECT_NE(scene.materials[0].diffuseTexture, scene.materials[0].cutout);
    // The alpha as read, a float a / 255, times f / c, rounded once.
    const double scale = 0.8 / 0.25;
    EXPECT_EQ(cutout(1), (std::vector<float>{0.0f, float(double(127 / 255.0f) * scale),
                                             float(double(128 / 255.0f) * scale), float(scale)}));
    EXPECT_EQ(cutout(2), (std::vector<float>{float(2.0 * 40 / 255.0), float(2.0 * 200 / 255.0)}));
    EXPECT_EQ(cutout(3), std::vector<float>{}) << "OPAQUE ignores alpha";
    EXPECT_EQ(cutout(4), std::vector<float>{float(0.3 / 0.5)}) << "a factor below the cutoff cuts everything";
    EXPECT_EQ(cutout(5), std::vector<float>{}) << "alpha 0.5 is not below the cutoff 0.5";
    EXPECT_EQ(cutout(6), std::vector<float>{float(0.4 / 0.8)}) << "an image without alpha is opaque";
    EXPECT_EQ(cutout(7), std::vector<float>{}) << "no alpha is below a cutoff of 0";
    // A metal's colour texture is not read, its alpha is.
    EXPECT_EQ(scene.materials[8].model, MaterialModel::Mirror);
    EXPECT_EQ(cutout(8), rgbaAlpha);
    // A glass volume keeps its closed surface (it bounds the medium), with a warning.
    EXPECT_EQ(scene.materials[9].model, MaterialModel::Glass);
    EXPECT_EQ(scene.materials[9].cutout, -1);
    EXPECT_NE(warnings.find("(\"volume\"): ignored: baseColorTexture (a glass volume is tinted by its baseColorFactor "
                            "alone), alphaMode MASK (a glass volume's surface is closed: it bounds its medium)"),
              std::string::npos)
        << warnings;
    // A thin glass's holes (GlassBrokenWindow's).
    EXPECT_EQ(scene.materials[10].model, MaterialModel::ThinGlass);
    EXPECT_EQ(cutout(10), rgbaAlpha);
    EXPECT_EQ(warnings.find("alphaMode"), warnings.rfind("alphaMode")) << "only the volume's is ignored: " << warnings;
    EXPECT_EQ(cutout(11), std::vector<float>{float(double(0.3f) / 0.5)});
    const SceneFeatures features = analyseScene(scene);
    EXPECT_TRUE(features.cutouts);
}

// alphaMode BLEND (glTF 2.0, "Alpha Coverage"): an opaque surface is partly there, by the base
// colour's alpha (texture times factor); where the alpha is 0 it is cut away (the alpha over half
// an 8-bit step, 1/510, below 1); a glass's BLEND is ignored with a warning
// (render-model-decisions.md, "Partial coverage").
TEST_F(GltfLoader, ABlendedMaterialIsPartlyThereByItsAlpha) {
    GltfBuilder b;
    const std::vector<unsigned char> rgba = {255, 0, 0, 0, 0, 255, 0, 127, 0, 0, 255, 128, 9, 9, 9, 255};
    b.doc()["images"] =
        json::array({{{"uri", "data:image/png;base64," + base64(pngWithAlpha(2, 2, 4, rgba))}},
                     {{"uri", "data:image/png;base64," + base64(pngWithAlpha(2, 1, 4, {1, 2, 3, 255, 4, 5, 6, 255}))}},
                     {{"uri", "data:image/png;base64," + base64(pngWithAlpha(1, 1, 3, {1, 2, 3}))}}});
    b.doc()["textures"] = json::array({{{"source", 0}}, {{"source", 1}}, {{"source", 2}}});
    const int uvs = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1}, 5126, "VEC2", 3);
    const int positions = b.positions(kTriangle);
    auto blended = [](std::string name, int texture, double alpha) {
        json pbr = {{"baseColorFactor", {0.5, 0.5, 0.5, alpha}}, {"metallicFactor", 0.0}};
        if (texture >= 0) pbr["baseColorTexture"] = {{"index", texture}};
        return json{{"name", std::move(name)}, {"alphaMode", "BLEND"}, {"pbrMetallicRoughness", pbr}};
    };
    json mirror = blended("mirror", 0, 0.5);
    mirror["pbrMetallicRoughness"]["metallicFactor"] = 1.0;
    json thin = blended("thin", 0, 1.0);
    thin["extensions"] = {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}};
    // A glass whose alpha is 1 everywhere (what exporters write for glass): its BLEND changes
    // nothing, and goes unmentioned.
    json clear = blended("clear", 1, 1.0);
    clear["extensions"] = thin["extensions"];
    for (const json& material :
         {blended("rgba", 0, 1.0), blended("factor", -1, 0.25), blended("factor 0", -1, 0.0),
          blended("opaque alpha", 1, 1.0), blended("no alpha channel", 2, 0.6), mirror, thin, clear})
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", positions}, {"TEXCOORD_0", uvs}}},
                                 {"material", b.material(material)}})}});
    ::testing::internal::CaptureStderr();
    const Scene scene = load(b.write(dir_ / "blended.gltf"));
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    ASSERT_EQ(scene.materials.size(), 8u);
    auto values = [&](int texture) -> std::vector<float> {
        if (texture < 0) return {};
        std::vector<float> v;
        for (const glm::vec3& texel : scene.textures[std::size_t(texture)].texels) v.push_back(texel.x);
        return v;
    };
    const float a127 = 127 / 255.0f, a128 = 128 / 255.0f;  // the alphas as read
    const double overNone = 510.0;                         // over half an 8-bit step
    // Alpha itself is the share that is there; only its 0 is cut.
    EXPECT_EQ(values(scene.materials[0].coverage), (std::vector<float>{0.0f, a127, a128, 1.0f}));
    EXPECT_EQ(values(scene.materials[0].cutout),
              (std::vector<float>{0.0f, float(double(a127) * overNone), float(double(a128) * overNone), 510.0f}));
    EXPECT_TRUE(hasPartialCoverage(scene.materials[0]) && hasCutouts(scene.materials[0]));
    EXPECT_EQ(values(scene.materials[1].coverage), std::vector<float>{0.25f}) << "the factor alone";
    EXPECT_EQ(scene.materials[1].cutout, -1) << "a quarter is there everywhere";
    EXPECT_EQ(values(scene.materials[2].coverage), std::vector<float>{0.0f});
    EXPECT_EQ(values(scene.materials[2].cutout), std::vector<float>{0.0f}) << "a factor of 0: nothing is there";
    EXPECT_EQ(scene.materials[3].coverage, -1) << "an alpha of 255 everywhere is all there";
    EXPECT_EQ(scene.materials[3].cutout, -1);
    EXPECT_EQ(values(scene.materials[4].coverage), std::vector<float>{0.6f}) << "an image without alpha: the factor";
    EXPECT_EQ(scene.materials[5].model, MaterialModel::Mirror);
    EXPECT_EQ(values(scene.materials[5].coverage),
              (std::vector<float>{0.0f, float(double(a127) * 0.5), float(double(a128) * 0.5), 0.5f}));
    EXPECT_EQ(scene.materials[6].model, MaterialModel::ThinGlass);
    EXPECT_EQ(scene.materials[6].coverage, -1);
    EXPECT_EQ(scene.materials[6].cutout, -1);
    EXPECT_NE(warnings.find("(\"thin\"): ignored: alphaMode BLEND"), std::string::npos) << warnings;
    EXPECT_EQ(warnings.find("alphaMode"), warnings.rfind("alphaMode")) << "only the glass's is ignored: " << warnings;
    const SceneFeatures features = analyseScene(scene);
    EXPECT_TRUE(features.partialCoverage && features.cutouts && features.textures);
}

// KHR_materials_transmission's transmissionTexture (render-model-decisions.md, "Transmission
// textures"): red times transmissionFactor is the share transmitted, and each texel takes the
// nearer model, as the factor does: the glass where it is 1/2 or more, elsewhere the material as it
// would be without transmission (its opaque part). Red is read as stored, not as sRGB.
TEST_F(GltfLoader, ATransmissionTextureMakesAGlassOpaqueWhereItsRedTimesTheFactorIsBelowAHalf) {
    GltfBuilder b;
    b.doc()["images"] =
        json::array({{{"uri", "data:image/png;base64," +
                                  base64(pngWithAlpha(4, 1, 3, {0, 9, 9, 127, 9, 9, 128, 9, 9, 255, 9, 9}))}},
                     {{"uri", "data:image/png;base64," + base64(pngWithAlpha(1, 1, 3, {255, 255, 255}))}}});
    b.doc()["textures"] = json::array({{{"source", 0}}, {{"source", 1}}});
    const int uvs = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1}, 5126, "VEC2", 3);
    const int positions = b.positions(kTriangle);
    auto transmissive = [](std::string name, double factor, int texture, json pbr, bool volume) {
        json extensions = {{"KHR_materials_transmission", {{"transmissionFactor", factor}}}};
        if (texture >= 0) extensions["KHR_materials_transmission"]["transmissionTexture"] = {{"index", texture}};
        if (volume) extensions["KHR_materials_volume"] = {{"thicknessFactor", 0.1}};
        return json{{"name", std::move(name)}, {"pbrMetallicRoughness", std::move(pbr)}, {"extensions", extensions}};
    };
    const json plastic = {{"baseColorFactor", {0.2, 0.4, 0.6, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.5}};
    json moved = transmissive("moved", 1.0, 0, {{"baseColorTexture", {{"index", 1}}}}, false);
    moved["extensions"]["KHR_materials_transmission"]["transmissionTexture"]["extensions"] = {
        {"KHR_texture_transform", {{"offset", {0.5, 0.0}}}}};
    for (const json& material :
         {transmissive("pane", 1.0, 0, plastic, false), transmissive("half", 0.5, 0, plastic, false),
          transmissive("block", 1.0, 0, {{"baseColorFactor", {0.9, 0.8, 0.7, 1.0}}}, true),
          transmissive("clear", 1.0, 1, plastic, false), transmissive("dim", 0.3, 0, plastic, false), moved})
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", positions}, {"TEXCOORD_0", uvs}}},
                                 {"material", b.material(material)}})}});
    ::testing::internal::CaptureStderr();
    const Scene scene = load(b.write(dir_ / "transmission.gltf"));
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    auto named = [&](const std::string& name) -> const Material& {
        for (const Material& m : scene.materials)
            if (m.name == name) return m;
        ADD_FAILURE() << "no material " << name;
        return scene.materials.front();
    };
    auto values = [&](const Material& m) {
        std::vector<float> v;
        if (m.transmissionTexture >= 0)
            for (const glm::vec3& texel : scene.textures[std::size_t(m.transmissionTexture)].texels)
                v.push_back(texel.x);
        return v;
    };
    ASSERT_EQ(scene.materials.size(), 9u) << "six materials and three opaque parts";
    // Red over 1/2: 127 of 255 is just below it, 128 just above.
    const Material& pane = named("pane");
    EXPECT_EQ(pane.model, MaterialModel::ThinGlass);
    EXPECT_EQ(values(pane), (std::vector<float>{0.0f, float(254 / 255.0), float(256 / 255.0), 2.0f}));
    ASSERT_TRUE(hasTransmissionTexture(pane));
    const Material& paneOpaque = scene.materials[std::size_t(pane.opaquePart)];
    EXPECT_EQ(paneOpaque.name, "pane (where not glass)");
    // The opaque dielectric the material is without transmission: Ks = F0(1.5) = 0.04, Ns = 2 /
    // roughness^4 - 2 = 30.
    EXPECT_EQ(paneOpaque.model, MaterialModel::Phong);
    EXPECT_EQ(paneOpaque.diffuse, glm::vec3(0.2f, 0.4f, 0.6f));
    EXPECT_NEAR(paneOpaque.specular.x, 0.04f, 1e-7f);
    EXPECT_NEAR(paneOpaque.shininess, 30.0f, 1e-4f);
    EXPECT_FALSE(hasTransmissionTexture(paneOpaque) || hasCutouts(paneOpaque) || hasPartialCoverage(paneOpaque));
    // A factor of 1/2: red itself over 1/2, so 255 is exactly 1, glass.
    EXPECT_EQ(values(named("half")), (std::vector<float>{0.0f, float(127 / 255.0), float(128 / 255.0), 1.0f}));
    const Material& block = named("block");
    EXPECT_EQ(block.model, MaterialModel::Glass);
    ASSERT_TRUE(hasTransmissionTexture(block));
    EXPECT_EQ(scene.materials[std::size_t(block.opaquePart)].model, MaterialModel::Mirror) << "metallicFactor 1";
    EXPECT_EQ(scene.materials[std::size_t(block.opaquePart)].specular, glm::vec3(0.9f, 0.8f, 0.7f));
    EXPECT_EQ(named("clear").transmissionTexture, -1) << "1/2 or more everywhere is glass everywhere";
    EXPECT_EQ(named("clear").opaquePart, -1);
    EXPECT_EQ(named("dim").model, MaterialModel::Phong) << "below 1/2 everywhere, whatever the texture";
    EXPECT_EQ(named("dim").transmissionTexture, -1);
    EXPECT_EQ(named("moved").transmissionTexture, -1);
    EXPECT_NE(warnings.find("(\"moved\"): ignored: transmissionTexture (its KHR_texture_transform is not the "
                            "baseColorTexture's)"),
              std::string::npos)
        << warnings;
    EXPECT_EQ(warnings.find("transmissionTexture"), warnings.rfind("transmissionTexture (")) << warnings;
    const SceneFeatures features = analyseScene(scene);
    EXPECT_TRUE(features.transmissionTextures && features.textures);
    EXPECT_TRUE(features.uses(MaterialModel::Phong) && features.uses(MaterialModel::Mirror))
        << "the opaque parts' models, which no triangle names";
}

// A blended material's alpha is a texture of its own on the device, beside its colour: with the
// colour's texels held, it must fit what the texel limit leaves, or the file is refused naming
// the limit, as an image too large is.
TEST_F(GltfLoader, ABlendedMaterialsAlphaCountsAgainstTheTexelLimit) {
    GltfBuilder b;
    const std::vector<unsigned char> rgba = {255, 0, 0, 0, 0, 255, 0, 127, 0, 0, 255, 128, 9, 9, 9, 255};
    b.doc()["images"] = json::array({{{"uri", "data:image/png;base64," + base64(pngWithAlpha(2, 2, 4, rgba))}}});
    b.doc()["textures"] = json::array({{{"source", 0}}});
    const int uvs = b.accessor(std::vector<float>{0, 0, 1, 0, 0, 1}, 5126, "VEC2", 3);
    json pbr = {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.0}};
    b.node(
        {{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}, {"TEXCOORD_0", uvs}}},
                          {"material",
                           b.material({{"name", "lace"}, {"alphaMode", "BLEND"}, {"pbrMetallicRoughness", pbr}})}})}});
    const fs::path file = b.write(dir_ / "limit.gltf");
    // Colour, coverage and the cut where alpha is 0: three textures of 4 texels, 16 bytes each.
    SceneLoadOptions enough;
    enough.texelLimit = TexelLimit{3 * 4 * 16, "192 bytes"};
    EXPECT_EQ(loadScene(file, enough).textures.size(), 3u);
    SceneLoadOptions tight;
    tight.texelLimit = TexelLimit{3 * 4 * 16 - 1, "the test's device allows 191 bytes"};
    try {
        loadScene(file, tight);
        ADD_FAILURE() << "loaded beyond the texel limit";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("its alpha of 2x2 pixels does not fit the device"), std::string::npos) << message;
        EXPECT_NE(message.find("the test's device allows 191 bytes"), std::string::npos) << message;
    }
}

// tinygltf passes material extensions' values on unchecked: one of the wrong type is refused,
// naming the material, the extension and the value, never read as absent (a transmissionFactor
// "1" read as 0 would be plastic).
TEST_F(GltfLoader, MaterialExtensionValuesOfTheWrongTypeAreRefused) {
    const json glass = {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                        {"KHR_materials_volume", {{"thicknessFactor", 1.0}, {"attenuationDistance", 2.0}}},
                        {"KHR_materials_ior", {{"ior", 1.5}}}};
    auto refusal = [&](const std::function<void(json&)>& breakIt) -> std::string {
        json extensions = glass;
        breakIt(extensions);
        GltfBuilder b;
        const int material = b.material({{"name", "tumbler"}, {"extensions", extensions}});
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}, {"material", material}})}});
        try {
            load(b.write(dir_ / "glass.gltf"));
        } catch (const InputError& e) {
            return e.what();
        }
        return "loaded";
    };
    EXPECT_EQ(refusal([](json&) {}), "loaded");
    auto expectContains = [](const std::string& message, const std::string& part) {
        EXPECT_NE(message.find(part), std::string::npos) << message << "\nexpected: " << part;
    };
    expectContains(refusal([](json& e) { e["KHR_materials_transmission"]["transmissionFactor"] = "1"; }),
                   "materials[0] (\"tumbler\"): KHR_materials_transmission's transmissionFactor is not a number");
    expectContains(refusal([](json& e) { e["KHR_materials_ior"]["ior"] = "1.5"; }),
                   "materials[0] (\"tumbler\"): KHR_materials_ior's ior is not a number");
    expectContains(refusal([](json& e) { e["KHR_materials_volume"]["attenuationColor"] = {0.5, 0.5}; }),
                   "materials[0] (\"tumbler\"): KHR_materials_volume's attenuationColor is not three numbers");
    expectContains(refusal([](json& e) { e["KHR_materials_volume"]["thicknessFactor"] = true; }),
                   "materials[0] (\"tumbler\"): KHR_materials_volume's thicknessFactor is not a number");
}

// The first perspective camera in node order, or the one named; its node looks down its -z with
// +y up (glTF 2.0, 3.10.1); yfov in radians; the aspect ratio gives the image's height.
// KHR_materials_variants: with --variant NAME each primitive takes the material its mappings give
// that variant, else its default; without it, the defaults, and a warning names the variants. A
// name the file has not is refused, naming those it has.
TEST_F(GltfLoader, AVariantPicksEachPrimitivesMaterialFromItsMappings) {
    GltfBuilder b;
    b.doc()["extensions"] = {
        {"KHR_materials_variants", {{"variants", {{{"name", "Lamp on"}}, {{"name", "Lamp off"}}}}}}};
    auto lambert = [](std::string name, double grey) {
        return json{{"name", std::move(name)},
                    {"pbrMetallicRoughness", {{"baseColorFactor", {grey, grey, grey, 1.0}}, {"metallicFactor", 0.0}}},
                    {"extensions", {{"KHR_materials_specular", {{"specularFactor", 0.0}}}}}};
    };
    const int shade = b.material(lambert("shade", 0.1)), lit = b.material(lambert("lit", 0.9)),
              unlit = b.material(lambert("unlit", 0.3));
    const int positions = b.positions(kTriangle);
    // The shade has a mapping for "Lamp off" only; the bulb one for each variant.
    const json mappings = {
        {"mappings", {{{"material", lit}, {"variants", {0}}}, {{"material", unlit}, {"variants", {1}}}}}};
    b.node({{"mesh",
             b.mesh({{"attributes", {{"POSITION", positions}}},
                     {"material", shade},
                     {"extensions",
                      {{"KHR_materials_variants", {{"mappings", {{{"material", unlit}, {"variants", {1}}}}}}}}}})}});
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", positions}}},
                             {"material", lit},
                             {"extensions", {{"KHR_materials_variants", mappings}}}})}});
    const fs::path file = b.write(dir_ / "variants.gltf");
    auto shown = [](const Scene& scene) {
        std::vector<std::string> names;
        for (const Triangle& t : scene.triangles) names.push_back(scene.materials[t.material].name);
        return names;
    };
    SceneLoadOptions options;
    ::testing::internal::CaptureStderr();
    EXPECT_EQ(shown(loadScene(file, options)), (std::vector<std::string>{"shade", "lit"}));
    const std::string warnings = ::testing::internal::GetCapturedStderr();
    EXPECT_NE(warnings.find("has material variants (\"Lamp on\", \"Lamp off\"): each primitive is rendered with its "
                            "default material; choose a variant with --variant NAME"),
              std::string::npos)
        << warnings;
    options.variant = "Lamp on";
    EXPECT_EQ(shown(loadScene(file, options)), (std::vector<std::string>{"shade", "lit"}));
    options.variant = "Lamp off";
    EXPECT_EQ(shown(loadScene(file, options)), (std::vector<std::string>{"unlit", "unlit"}));
    options.variant = "Lamp broken";
    try {
        loadScene(file, options);
        ADD_FAILURE() << "loaded a variant the file has not";
    } catch (const InputError& e) {
        EXPECT_NE(
            std::string(e.what()).find("has no material variant named \"Lamp broken\"; its variants: \"Lamp on\", "
                                       "\"Lamp off\""),
            std::string::npos)
            << e.what();
    }
}

TEST_F(GltfLoader, CamerasComeFromTheirNodes) {
    GltfBuilder b;
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}})}});
    b.doc()["cameras"] = json::array({{{"name", "front"}, {"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"aspectRatio", 2.0}, {"znear", 0.1}}}},
                                      {{"name", "top"}, {"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}},
                                      {{"name", "plan"}, {"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"zfar", 10}, {"znear", 0.1}}}}});
    b.node({{"camera", 0}, {"translation", {0, 0, 5}}});
    const double s = std::sqrt(0.5);  // a quarter turn about x: looking down glTF's -y
    b.node({{"camera", 1}, {"translation", {0, 5, 0}}, {"rotation", {-s, 0, 0, s}}});
    b.node({{"camera", 2}});
    const fs::path file = b.write(dir_ / "cameras.gltf");

    Scene front = load(file);
    expectNear(front.camera.from, {0, -5, 0});  // glTF +z towards the viewer is vitrum's -y
    expectNear(glm::normalize(front.camera.at - front.camera.from), {0, 1, 0});
    expectNear(front.camera.up, {0, 0, 1});
    EXPECT_NEAR(front.camera.fovY, glm::degrees(0.5f), 1e-4f);
    EXPECT_EQ(front.camera.width, 640u);
    EXPECT_EQ(front.camera.height, 320u);
    ASSERT_EQ(front.lights.size(), 1u);  // no lights in the file: the automatic one

    Scene top = load(file, "top");
    expectNear(top.camera.from, {0, 0, 5});
    expectNear(glm::normalize(top.camera.at - top.camera.from), {0, 0, -1});
    expectNear(top.camera.up, {0, 1, 0});
    EXPECT_EQ(top.camera.height, 480u);

    for (const auto& [name, expected] : {std::pair{"plan", "(\"plan\") is orthographic"},
                                         std::pair{"side", "has no camera named \"side\"; its cameras: \"front\", \"top\", \"plan\""}}) {
        try {
            load(file, name);
            ADD_FAILURE() << name;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
        }
    }
}

// KHR_lights_punctual: a point light is colour times intensity with the inverse-square fall-off;
// a spot light becomes a point light and a directional light is skipped, each with a warning.
TEST_F(GltfLoader, PunctualLightsBecomePointLights) {
    GltfBuilder b;
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}})}});
    b.doc()["extensionsUsed"] = {"KHR_lights_punctual"};
    b.doc()["extensions"] = {{"KHR_lights_punctual",
                              {{"lights", {{{"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 8.0}},
                                           {{"type", "spot"}, {"intensity", 2.0}, {"spot", {{"outerConeAngle", 0.5}}}},
                                           {{"type", "directional"}}}}}}};
    for (int light = 0; light < 3; ++light)
        b.node({{"translation", {1, 2, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", light}}}}}});
    const int before = warningCount();
    Scene scene = load(b.write(dir_ / "lights.gltf"));
    EXPECT_EQ(warningCount(), before + 2);
    ASSERT_EQ(scene.lights.size(), 2u);
    expectNear(scene.lights[0].position, {1, -3, 2});
    expectNear(scene.lights[0].colour, {8, 4, 2});
    EXPECT_TRUE(scene.lights[0].inverseSquare);
    expectNear(scene.lights[1].colour, {2, 2, 2});
}

// Primitives that are not triangles are skipped with one warning each; their mesh's triangles stay.
TEST_F(GltfLoader, PrimitivesOtherThanTrianglesAreSkipped) {
    GltfBuilder b;
    const int positions = b.positions(kTriangle);
    b.doc()["meshes"].push_back({{"primitives", {{{"attributes", {{"POSITION", positions}}}, {"mode", 1}},
                                                 {{"attributes", {{"POSITION", positions}}}},
                                                 {{"attributes", {{"POSITION", positions}}}, {"mode", 5}}}}});
    b.node({{"mesh", 0}});
    const int before = warningCount();
    Scene scene = load(b.write(dir_ / "lines.gltf"));
    EXPECT_EQ(scene.triangles.size(), 1u);
    EXPECT_EQ(warningCount(), before + 2);
}

// What cannot be read is refused naming the file and what is wrong.
TEST_F(GltfLoader, BrokenFilesAreRefusedWithTheirReason) {
    auto expectRefused = [&](GltfBuilder& b, const std::string& expected) {
        const fs::path file = b.write(dir_ / "broken.gltf");
        try {
            load(file);
            ADD_FAILURE() << "loaded; expected: " << expected;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
            EXPECT_EQ(std::string(e.what()).rfind(file.string(), 0), 0u) << e.what();
        }
    };
    {
        GltfBuilder b;
        const int positions = b.positions(kTriangle);
        b.doc()["accessors"][positions]["count"] = 4;  // one vertex more than its view holds
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", positions}}}})}});
        expectRefused(b, "reaches beyond its buffer");
    }
    {
        GltfBuilder b;
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}},
                                  {"indices", b.accessor(std::vector<std::uint16_t>{0, 1, 3}, 5123, "SCALAR", 3)}})}});
        expectRefused(b, "uses vertex 3, but it has 3");
    }
    {
        GltfBuilder b;
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}})}});
        b.doc()["extensionsRequired"] = {"KHR_texture_basisu"};
        b.doc()["extensionsUsed"] = {"KHR_texture_basisu"};
        expectRefused(b, "requires the glTF extension KHR_texture_basisu");
    }
    {
        GltfBuilder b;
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions({0, 0, 0, 1e30f, 0, 0, 0, 1, 0})}}}})}, {"scale", {1e10, 1, 1}}});
        expectRefused(b, "is not finite after its transform");
    }
    {
        GltfBuilder b;
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}})}});
        b.node({{"mesh", 0}, {"translation", {1, 2}}});
        expectRefused(b, "nodes[1]: its translation has 2 numbers; glTF 2.0 gives it 3");
    }
    {
        GltfBuilder b;
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}})},
                {"matrix", std::vector<double>(15, 1.0)}});
        expectRefused(b, "nodes[0]: its matrix has 15 numbers; glTF 2.0 gives it 16");
    }
    {
        GltfBuilder b;
        const int child = b.node({}, false);
        b.doc()["nodes"][child]["children"] = {child};
        b.doc()["scenes"][0]["nodes"].push_back(child);
        expectRefused(b, "is its own ancestor");
    }
}

// tinygltf's own messages name a property, not its element: the loader adds the element's JSON
// path, in .gltf and .glb files alike. Each file has two of the element's kind, the second wrong,
// so that a message naming the first, or none, fails.
TEST_F(GltfLoader, TinygltfsMessagesNameTheElementTheyAreAbout) {
    auto refusal = [&](GltfBuilder& b, bool glb) -> std::string {
        const fs::path file = glb ? b.writeGlb(dir_ / "broken.glb") : b.write(dir_ / "broken.gltf");
        try {
            load(file);
        } catch (const InputError& e) {
            return e.what();
        }
        return "loaded";
    };
    auto expectContains = [](const std::string& message, const std::string& part) {
        EXPECT_NE(message.find(part), std::string::npos) << message << "\nexpected: " << part;
    };
    auto twoTriangles = [](const std::function<void(json& doc)>& breakIt) {
        GltfBuilder b;
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}})}});
        b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}})}});
        breakIt(b.doc());
        return b;
    };
    for (bool glb : {false, true}) {
        SCOPED_TRACE(glb ? ".glb" : ".gltf");
        GltfBuilder countAsText = twoTriangles([](json& doc) { doc["accessors"][1]["count"] = "3"; });
        expectContains(refusal(countAsText, glb), "accessors[1]: 'count' property is not a positive integer");
        GltfBuilder noLength = twoTriangles([](json& doc) { doc["bufferViews"][1].erase("byteLength"); });
        expectContains(refusal(noLength, glb), "bufferViews[1]: 'byteLength' property is missing.");
        GltfBuilder noType = twoTriangles([](json& doc) { doc["accessors"][1].erase("type"); });
        expectContains(refusal(noType, glb), "accessors[1]: 'type' property is missing.");
        GltfBuilder badType = twoTriangles([](json& doc) { doc["accessors"][1]["type"] = "VEC7"; });
        expectContains(refusal(badType, glb), "accessors[1]: Unsupported `type` for accessor object");
        GltfBuilder badStride = twoTriangles([](json& doc) { doc["bufferViews"][1]["byteStride"] = 2; });
        expectContains(refusal(badStride, glb), "bufferViews[1]: Invalid `byteStride' value");
        GltfBuilder noAttributes = twoTriangles([](json& doc) { doc["meshes"][1]["primitives"][0].erase("attributes"); });
        expectContains(refusal(noAttributes, glb), "meshes[1].primitives[0]: 'attributes' property is missing.");
        GltfBuilder indexAsText = twoTriangles([](json& doc) {
            doc["materials"] = json::array({json{{"normalTexture", {{"index", 0}}}}, json{{"normalTexture", {{"index", "0"}}}}});
        });
        expectContains(refusal(indexAsText, glb), "materials[1].normalTexture: 'index' property");
    }
}

// The binary container reads as the text one.
TEST_F(GltfLoader, GlbReadsAsGltf) {
    GltfBuilder b;
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}})}, {"translation", {1, 2, 3}}});
    const Scene text = load(b.write(dir_ / "a.gltf"));
    const Scene binary = load(b.writeGlb(dir_ / "a.glb"));
    ASSERT_EQ(binary.triangles.size(), 1u);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(binary.triangles[0].position[k], text.triangles[0].position[k]);
}

// In a JSON scene a glTF is an object entry with the OBJ entries' transform; its lights join
// the scene's, its cameras are not used.
TEST_F(GltfLoader, JsonSceneEntryTakesTheTransform) {
    GltfBuilder b;
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}})}});
    b.write(dir_ / "part.gltf");
    std::ofstream(dir_ / "scene.json")
        << R"({"objects": [{"gltf": "part.gltf", "transform": {"translate": [0, 0, 7], "scale": 2}}], "lights": []})";
    const Scene scene = loadScene(dir_ / "scene.json");
    ASSERT_EQ(scene.triangles.size(), 1u);
    expectNear(scene.triangles[0].position[1], {2, 0, 7});
    expectNear(scene.triangles[0].position[2], {0, 0, 9});
    std::ofstream(dir_ / "both.json") << R"({"objects": [{"gltf": "part.gltf", "obj": "part.obj"}]})";
    EXPECT_THROW(loadScene(dir_ / "both.json"), InputError);
    std::ofstream(dir_ / "mtl.json") << R"({"objects": [{"gltf": "part.gltf", "mtl": "part.gltf"}]})";
    EXPECT_THROW(loadScene(dir_ / "mtl.json"), InputError);
}

// A glTF file that several entries of a JSON scene name is loaded once (docs/scene-format.md,
// "Instancing"): each of its meshes is stored once and placed by every entry, its lights come once
// an entry, and the copies are the triangles that loading the file once an entry makes.
TEST_F(GltfLoader, AFileThreeEntriesOfAJsonSceneNameIsLoadedOnce) {
    GltfBuilder b;
    const int shared = b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}});
    b.node({{"mesh", shared}, {"name", "plain"}});
    b.node({{"mesh", shared}, {"translation", {0, 0, 2}}, {"scale", {-1, 1, 1}}, {"name", "mirrored"}});
    b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}})}, {"translation", {3, 0, 0}},
            {"name", "once"}});
    b.doc()["extensionsUsed"] = {"KHR_lights_punctual"};
    b.doc()["extensions"] = {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}, {"intensity", 5.0}}}}}}};
    b.node({{"translation", {1, 2, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    b.write(dir_ / "part.gltf");
    const std::string cube = std::string(VITRUM_SOURCE_DIR) + "/scenes/meshes/cube.obj";
    std::ofstream(dir_ / "thrice.json") << R"({"lights": [], "objects": [{"gltf": "part.gltf"}, {"obj": ")" << cube
                                        << R"("}, {"gltf": "part.gltf", "transform": {"translate": [10, 0, 0]}},
        {"gltf": "part.gltf", "transform": {"rotate_deg": [0, 0, 90], "translate": [0, 10, 0]}}]})";
    const Scene scene = loadScene(dir_ / "thrice.json");
    ASSERT_EQ(scene.meshes.size(), 2u);
    EXPECT_EQ(scene.instances.size(), 9u);  // three entries, three mesh nodes each
    EXPECT_EQ(worldTriangleCount(scene), 12u);  // the cube's
    EXPECT_EQ(scene.triangles.size(), 12u + 2u);  // and each glTF mesh once
    // The light at glTF's (1, 2, 3), vitrum's (1, -3, 2), once an entry: in place, moved along x,
    // and turned a quarter about z ((x, y) to (-y, x)) and moved along y.
    ASSERT_EQ(scene.lights.size(), 3u);
    expectNear(scene.lights[0].position, {1, -3, 2});
    expectNear(scene.lights[1].position, {11, -3, 2});
    expectNear(scene.lights[2].position, {3, 11, 2}, 1e-5f);
    // The copies are what the file loaded once an entry makes, object by object.
    const Scene flat = loadScene(dir_ / "thrice.json", {.instancing = false});
    EXPECT_TRUE(flat.instances.empty());
    const Scene placed = flattened(scene);
    ASSERT_EQ(placed.triangles.size(), flat.triangles.size());
    using Corners = std::tuple<std::string, long, long, long, long, long, long, long, long, long>;
    auto corners = [](const Scene& s) {
        std::multiset<Corners> set;
        for (const Triangle& t : s.triangles) {
            auto r = [](float v) { return std::lround(v * 1e4f); };
            const glm::vec3* p = t.position;
            set.insert({s.objectNames[t.object], r(p[0].x), r(p[0].y), r(p[0].z), r(p[1].x), r(p[1].y), r(p[1].z),
                        r(p[2].x), r(p[2].y), r(p[2].z)});
        }
        return set;
    };
    EXPECT_EQ(corners(placed), corners(flat));
    for (std::size_t i = 0; i < flat.lights.size(); ++i) expectNear(scene.lights[i].position, flat.lights[i].position);
}

// A copy that cannot be an instance (a node scaled to nothing: its matrix has no inverse to move
// rays into the mesh) is made in the world, as a mesh placed once is; a copy that an entry moves
// beyond the range of float is refused naming the node and the entry.
TEST_F(GltfLoader, ACopyWithoutAnInverseIsMadeInTheWorldAndOneBeyondFloatIsRefused) {
    GltfBuilder b;
    const int shared = b.mesh({{"attributes", {{"POSITION", b.positions(kTriangle)}}}});
    b.node({{"mesh", shared}});
    b.node({{"mesh", shared}, {"translation", {0, 0, 2}}});
    b.node({{"mesh", shared}, {"scale", {0, 0, 0}}, {"name", "hidden"}});
    const Scene scene = load(b.write(dir_ / "hidden.gltf"));
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.instances.size(), 2u);
    ASSERT_EQ(worldTriangleCount(scene), 1u);
    for (const glm::vec3& p : scene.triangles[0].position) EXPECT_EQ(p, glm::vec3(0.0f));
    EXPECT_EQ(scene.objectNames.size(), 3u);
    std::ofstream(dir_ / "far.json") << R"({"objects": [{"gltf": "hidden.gltf"}, {"gltf": "hidden.gltf",
        "transform": {"scale": 1e38, "translate": [3e38, 0, 0]}}]})";
    try {
        loadScene(dir_ / "far.json");
        ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
        const std::string expected = "nodes[0], placed by /objects/1, moves its mesh's vertices beyond the range of float";
        EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace vitrum

namespace vitrum {
namespace {

// Debian's gltfpack 0.18 wrote scenes/meshes/glass_set.gltf quantized (KHR_mesh_quantization) to
// tests/fuzz/corpus/gltf/glass_set_quantized.glb, and quantized and compressed (`-c`,
// EXT_meshopt_compression) to glass_set_meshopt.glb. The compression is lossless: the two load to
// the same triangles, their corners bit for bit; both hold the original's triangles and objects, within the
// quantization's steps (14 bits over the 6-unit floor for positions).
TEST(GltfAccessors, GltfpacksCompressedFileLoadsAsItsUncompressedOne) {
    const fs::path corpus = fs::path(VITRUM_SOURCE_DIR) / "tests/fuzz/corpus/gltf";
    const Scene quantized = loadScene(corpus / "glass_set_quantized.glb");
    const Scene compressed = loadScene(corpus / "glass_set_meshopt.glb");
    const Scene original = loadScene(fs::path(VITRUM_SOURCE_DIR) / "scenes/meshes/glass_set.gltf");
    ASSERT_EQ(compressed.triangles.size(), quantized.triangles.size());
    EXPECT_EQ(compressed.triangles.size(), original.triangles.size());
    EXPECT_EQ(compressed.objectNames.size(), original.objectNames.size());
    // The same triangles, each of the same object, with the same corners, in the same winding:
    // gltfpack orders a compressed mesh's vertices its own way, and meshoptimizer's index codec may
    // start a triangle at another corner, so each is keyed from its least corner. Normals are
    // the file's or, where it has none (the gem), the corners' cross product, which rounds
    // differently from another first corner.
    auto triangles = [](const Scene& scene) {
        std::multimap<std::vector<float>, std::vector<glm::vec3>> byCorners;
        for (const Triangle& t : scene.triangles) {
            const auto* p = t.position;
            auto less = [](const glm::vec3& u, const glm::vec3& v) { return std::tie(u.x, u.y, u.z) < std::tie(v.x, v.y, v.z); };
            const int first = less(p[1], p[0]) ? (less(p[2], p[1]) ? 2 : 1) : (less(p[2], p[0]) ? 2 : 0);
            std::vector<float> key{float(t.object)};
            std::vector<glm::vec3> normals;
            for (int c = 0; c < 3; ++c) {
                const int k = (first + c) % 3;
                key.insert(key.end(), {p[k].x, p[k].y, p[k].z});
                normals.push_back(t.normal[k]);
            }
            byCorners.emplace(std::move(key), std::move(normals));
        }
        return byCorners;
    };
    const auto a = triangles(compressed), b = triangles(quantized);
    ASSERT_EQ(a.size(), b.size());
    for (auto i = a.begin(), j = b.begin(); i != a.end(); ++i, ++j) {
        ASSERT_EQ(i->first, j->first);
        for (int c = 0; c < 3; ++c) EXPECT_LT(glm::length(i->second[c] - j->second[c]), 1e-6f);
    }
    const FloatBox before = worldBox(original), after = worldBox(compressed);
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_NEAR(before.min[axis], after.min[axis], 1e-3f);
        EXPECT_NEAR(before.max[axis], after.max[axis], 1e-3f);
    }
}

// tests/fuzz/corpus/gltf/sparse_strided.gltf: three vertices 24 bytes apart (a byte stride with
// padding between them), then a sparse accessor that replaces vertex 2, (0, 1, 0), by (0, 2, 0)
// (glTF 2.0, 3.6.2.3 "Sparse accessors").
TEST(GltfAccessors, StridedAndSparseAccessorsReadAsTheSpecSays) {
    const Scene scene = loadScene(fs::path(VITRUM_SOURCE_DIR) / "tests/fuzz/corpus/gltf/sparse_strided.gltf");
    ASSERT_EQ(scene.triangles.size(), 1u);
    EXPECT_EQ(scene.triangles[0].position[0], glm::vec3(0, 0, 0));
    EXPECT_EQ(scene.triangles[0].position[1], glm::vec3(1, 0, 0));
    EXPECT_EQ(scene.triangles[0].position[2], glm::vec3(0, 0, 2));  // glTF's y is vitrum's z
}

}  // namespace
}  // namespace vitrum
