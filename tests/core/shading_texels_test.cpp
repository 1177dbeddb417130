// The shading texels (gpu_input/shading_texels.h, gpu_types.h's ShadingTexel): every triangle's
// normals and uvs come back with their exact bits from the texels as bindings.glsl reads them, a
// flat untextured triangle in one texel, each distinct normal stored once.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <set>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "gpu_input/scene_geometry_bytes.h"
#include "gpu_input/shading_texels.h"

#include "../support/scenes_in_code.h"

namespace vitrum {
namespace {

using namespace vitrum::testing;

glm::vec3 floats(const glm::uvec4& bits) {
    return {std::bit_cast<float>(bits.x), std::bit_cast<float>(bits.y), std::bit_cast<float>(bits.z)};
}

glm::uvec3 bitsOf(const glm::vec3& v) {
    return {std::bit_cast<std::uint32_t>(v.x), std::bit_cast<std::uint32_t>(v.y), std::bit_cast<std::uint32_t>(v.z)};
}

// bindings.glsl's loadVertexNormals and interpolatedUv's reads, on the host.
struct Decoded {
    glm::vec3 normal[3];
    glm::vec2 uv[3];
};
Decoded decode(const std::vector<gpu::ShadingTexel>& texels, std::size_t i) {
    const glm::uvec4 t = texels[i].bits;
    Decoded d{};
    for (int k = 0; k < 3; ++k) d.normal[k] = t.w == gpu::kFlatTriangle ? floats(t) : floats(texels[t[k]].bits);
    if (t.w != gpu::kFlatTriangle && t.w != gpu::kNoCornerUvs) {
        const glm::vec3 a = floats(texels[t.w].bits);
        const float a3 = std::bit_cast<float>(texels[t.w].bits.w);
        const glm::vec3 b = floats(texels[t.w + 1].bits);
        d.uv[0] = {a.x, a.y};
        d.uv[1] = {a.z, a3};
        d.uv[2] = {b.x, b.y};
    }
    return d;
}

// Five triangles far apart along x (so that the BVH reorders them): flat; smooth; smooth, sharing
// two normals with the one before; flat and textured; "flat" but for a zero's sign.
Scene mixedShading() {
    Scene scene;
    scene.materials = {makeMaterial(MaterialModel::Lambert, glm::vec3(0), glm::vec3(0.5f)),
                       makeMaterial(MaterialModel::Lambert, glm::vec3(0), glm::vec3(0.5f))};
    scene.materials[1].diffuseTexture = 0;
    const glm::vec3 up(0, 0, 1), a(0.6f, 0, 0.8f), b(0, 0.6f, 0.8f), c(-0.6f, 0, 0.8f), d(0, -0.6f, 0.8f);
    const std::vector<std::array<glm::vec3, 3>> normals = {
        {up, up, up}, {a, b, c}, {b, c, d}, {a, a, a}, {up, glm::vec3(-0.0f, 0, 1), up}};
    float x = 0.0f;
    for (std::size_t i = 0; i < normals.size(); ++i) {
        Triangle t = makeTriangle(glm::vec3(x, 0, 0), glm::vec3(x + 1, 0, 0), glm::vec3(x, 1, 0), i == 3 ? 1 : 0, 0);
        for (int k = 0; k < 3; ++k) {
            t.normal[k] = normals[i][std::size_t(k)];
            t.uv[k] = glm::vec2(0.25f * float(k) + float(i), 1.0f / float(k + 3));
        }
        scene.triangles.push_back(t);
        x -= 10.0f;
    }
    return scene;
}

TEST(ShadingTexels, EveryTriangleGetsItsNormalsAndUvsBackBitForBit) {
    const Scene scene = mixedShading();
    const Bvh bvh = buildSceneBvh(scene);
    const ShadingPlan plan = planShading(scene, bvh);
    // Distinct normals of the triangles not flat and untextured: a, b, c, d; a (the textured
    // one's); up and -0 up. Uvs for the one textured triangle.
    EXPECT_EQ(plan.normals.size(), 6u);
    EXPECT_EQ(plan.texturedTriangles, 1u);
    EXPECT_EQ(plan.texels(), 5u + 6u + 2u);
    std::vector<gpu::ShadingTexel> texels(plan.texels());
    writeShading(scene, bvh, plan, texels);
    for (std::size_t i = 0; i < bvh.triangleOrder.size(); ++i) {
        const std::uint32_t original = bvh.triangleOrder[i];
        const Triangle& t = scene.triangles[original];
        const Decoded decoded = decode(texels, i);
        EXPECT_EQ(texels[i].bits.w == gpu::kFlatTriangle, original == 0) << "triangle " << original;
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(bitsOf(decoded.normal[k]), bitsOf(t.normal[k])) << "triangle " << original << " corner " << k;
            if (original == 3) {
                EXPECT_EQ(decoded.uv[k], t.uv[k]) << "corner " << k;
            }
        }
    }
}

// The traversal reads a cut-out triangle's uvs (shaders/cutout.glsl), shading a partly covered
// one's (coverSurface in shading.glsl): a material with either and no map_Kd stores them as a
// textured one's, bit for bit; a glass volume's (which nothing reads) stores none.
TEST(ShadingTexels, ACutOutPartlyCoveredOrTransmissionTexturedTriangleGetsItsUvs) {
    for (const std::string kind : {"cut out", "partly covered", "transmission textured"}) {
        SCOPED_TRACE(kind);
        Scene scene = mixedShading();
        for (Material& m : scene.materials) m.diffuseTexture = -1;
        if (kind == "cut out") scene.materials[0].cutout = 0;
        if (kind == "partly covered") scene.materials[0].coverage = 0;
        if (kind == "transmission textured") {
            // A thin glass whose opaque part no triangle names: the glass's triangles carry the uvs.
            scene.materials.push_back(scene.materials[0]);
            scene.materials[0].model = MaterialModel::ThinGlass;
            scene.materials[0].transmissionTexture = 0;
            scene.materials[0].opaquePart = int(scene.materials.size()) - 1;
        }
        const Bvh bvh = buildSceneBvh(scene);
        const ShadingPlan plan = planShading(scene, bvh);
        std::size_t cut = 0;
        for (const Triangle& t : scene.triangles) cut += t.material == 0 ? 1 : 0;
        EXPECT_EQ(plan.texturedTriangles, cut);
        std::vector<gpu::ShadingTexel> texels(plan.texels());
        writeShading(scene, bvh, plan, texels);
        for (std::size_t i = 0; i < bvh.triangleOrder.size(); ++i) {
            const Triangle& t = scene.triangles[bvh.triangleOrder[i]];
            if (t.material != 0) continue;
            const Decoded decoded = decode(texels, i);
            for (int k = 0; k < 3; ++k) EXPECT_EQ(decoded.uv[k], t.uv[k]) << "corner " << k;
        }
        scene.materials[0].model = kind == "transmission textured" ? MaterialModel::Phong : MaterialModel::Glass;
        EXPECT_EQ(planShading(scene, bvh).texturedTriangles, 0u);
    }
}

TEST(ShadingTexels, AFlatUntexturedModelTakesOneTexelATriangle) {
    Scene scene = mixedShading();
    scene.triangles.resize(1);
    for (int i = 1; i < 100; ++i) {
        Triangle t = scene.triangles[0];
        for (glm::vec3& p : t.position) p.y += float(i);
        scene.triangles.push_back(t);
    }
    const Bvh bvh = buildSceneBvh(scene);
    const ShadingPlan plan = planShading(scene, bvh);
    EXPECT_TRUE(plan.normals.empty());
    EXPECT_TRUE(plan.cornerNormals.empty());
    EXPECT_EQ(plan.texels(), 100u);
    EXPECT_EQ(sceneGeometry(bvh, plan).shading, 100u * 16u);
    // The least any layout takes is this one's shading; its BVH is no smaller than the least.
    EXPECT_EQ(sceneGeometryAtLeast(100).shading, 100u * 16u);
    EXPECT_LE(sceneGeometryAtLeast(100).nodes, sceneGeometry(bvh, plan).nodes);
    EXPECT_EQ(sceneGeometryAtLeast(100).nodes, (13u - 1u) * 64u);
}

// A big smooth mesh, every third quad textured: each distinct normal once, in the order of first
// use in the scene, every corner pointing at its own normal and uv.
TEST(ShadingTexels, ABigSmoothMeshHasEachNormalOnceInTheOrderOfFirstUse) {
    Scene scene = mixedShading();
    scene.triangles.clear();
    constexpr int kSide = 320;  // 2 x 319 x 319 = 203,522 triangles
    auto normalAt = [](int x, int y) { return glm::normalize(glm::vec3(float(x) - 160.0f, float(y) - 160.0f, 100.0f)); };
    for (int y = 0; y + 1 < kSide; ++y)
        for (int x = 0; x + 1 < kSide; ++x) {
            const glm::vec3 a(x, y, 0), b(x + 1, y, 0), c(x, y + 1, 0), d(x + 1, y + 1, 0);
            Triangle t1 = makeTriangle(a, b, d, 0, 0), t2 = makeTriangle(a, d, c, 0, 0);
            t1.normal[0] = t2.normal[0] = normalAt(x, y);
            t1.normal[1] = normalAt(x + 1, y);
            t1.normal[2] = t2.normal[1] = normalAt(x + 1, y + 1);
            t2.normal[2] = normalAt(x, y + 1);
            // Every third quad textured (material 1), its corners' uvs its own.
            if ((x + y) % 3 == 0)
                for (Triangle* t : {&t1, &t2}) {
                    t->material = 1;
                    for (int k = 0; k < 3; ++k) t->uv[k] = glm::vec2(float(x) + 0.25f * float(k), float(y));
                }
            scene.triangles.push_back(t1);
            scene.triangles.push_back(t2);
        }
    const Bvh bvh = buildSceneBvh(scene);
    const ShadingPlan plan = planShading(scene, bvh);
    // The order of first use, worked out here.
    std::vector<glm::uvec3> firstUse;
    std::set<std::array<std::uint32_t, 3>> seen;
    for (const Triangle& t : scene.triangles)
        for (const glm::vec3& n : t.normal) {
            const glm::uvec3 bits = bitsOf(n);
            if (seen.insert({bits.x, bits.y, bits.z}).second) firstUse.push_back(bits);
        }
    ASSERT_EQ(plan.normals.size(), firstUse.size());
    for (std::size_t k = 0; k < firstUse.size(); ++k) ASSERT_EQ(bitsOf(plan.normals[k]), firstUse[k]) << k;
    std::vector<gpu::ShadingTexel> texels(plan.texels());
    writeShading(scene, bvh, plan, texels);
    for (std::size_t i = 0; i < bvh.triangleOrder.size(); ++i) {
        const Decoded decoded = decode(texels, i);
        const Triangle& t = scene.triangles[bvh.triangleOrder[i]];
        for (int k = 0; k < 3; ++k) {
            ASSERT_EQ(bitsOf(decoded.normal[k]), bitsOf(t.normal[k])) << i << " " << k;
            if (t.material == 1) {
                ASSERT_EQ(decoded.uv[k], t.uv[k]) << i << " " << k;
            }
        }
    }
}

}  // namespace
}  // namespace vitrum
