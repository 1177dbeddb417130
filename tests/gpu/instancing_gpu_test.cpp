// Instancing on both backends (issue 50; docs/gpu-design.md, "Instancing"): placed copies render
// as their flattened scene (of glass, tinted glass, thin glass and cut-out surfaces), a mirroring copy's surfaces face
// out, two copies of a cube placed face to face are one box, scaling keeps the image, and a pixel suspended inside an
// instance resumes there.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "gpu_test_support.h"
#include "scene/instances.h"
#include "scene/scene_loader.h"

#include "../support/instanced_scene.h"

namespace vitrum {
namespace {

using namespace vitrum::testing;

// The copies are traced in their meshes' space and the flattened copies in the world: rounding
// differs, so a ray within an ulp of an edge may pick the other triangle (as between the two
// backends), and the image is otherwise the same.
void expectSameImage(const Image& a, const Image& b, double maxShareOver005 = 0.01, double maxMean = 3e-3) {
    const ImageDiff d = diffImages(a, b);
    EXPECT_LE(d.shareOver005, maxShareOver005) << "psnr " << d.psnr;
    EXPECT_LE(d.meanAbsError, maxMean);
}

struct InstancedAndFlat {
    RenderPair instanced;
    RenderPair flat;  // every copy in the world
};

// The scene rendered as placed and flattened, on both backends: the GPU's image within the
// thresholds of the CPU's, and each backend's copies as its flattened ones.
InstancedAndFlat renderInstancedAndFlat(const Scene& scene) {
    InstancedAndFlat r{renderBoth(scene), renderBoth(flattened(scene))};
    expectImagesMatch(r.instanced);
    expectSameImage(r.instanced.gpu, r.flat.gpu);
    expectSameImage(r.instanced.cpu, r.flat.cpu);
    return r;
}

TEST(Instancing, PlacedCopiesRenderAsTheirFlattenedSceneOnBothBackends) {
    const Scene scene = instancedScene();
    const auto [instanced, flat] = renderInstancedAndFlat(scene);
    EXPECT_EQ(instanced.gpuStats.primaryRays, flat.gpuStats.primaryRays);
    // Refraction through the glass copies, the mirrored one included (a copy whose winding were
    // inward would make its rays leave a medium they never entered), as often as flattened.
    EXPECT_GT(instanced.gpuStats.refractionRays, 0u);
    EXPECT_EQ(instanced.gpuStats.inconsistentMedia, 0u);
    EXPECT_EQ(instanced.cpuStats.inconsistentMedia, 0u);
    EXPECT_EQ(instanced.gpuStats.traversalStackOverflows, 0u);
    EXPECT_EQ(instanced.gpuStats.refractionRays, flat.gpuStats.refractionRays);
}

// The copies of thin glass (render-model-decisions.md, "Thin-walled glass"), tinted, as their
// flattened scene: a copy's normals, moved to the world, face the ray as the flattened triangles'
// do, and no copy is a medium.
TEST(Instancing, ThinGlassCopiesRenderAsTheirFlattenedScene) {
    Scene scene = instancedScene();
    scene.materials[1] = makeMaterial(MaterialModel::ThinGlass, glm::vec3(0.0f), glm::vec3(0.9f, 0.5f, 0.3f), {},
                                      1.0f, 1.7f);
    const auto [instanced, flat] = renderInstancedAndFlat(scene);
    EXPECT_GT(instanced.gpuStats.refractionRays, 0u);
    EXPECT_EQ(instanced.gpuStats.refractionRays, flat.gpuStats.refractionRays);
    EXPECT_EQ(instanced.gpuStats.maxMediumDepth, 0u);
    EXPECT_EQ(instanced.cpuStats.maxMediumDepth, 0u);
}

// Tinted glass copies (render-model-decisions.md, "Glass tint") as their flattened scene: each
// copy is an object of its own whose surface takes its mesh's glass's tint, and the tint shows
// (the centre of the image is not the untinted one's).
TEST(Instancing, TintedGlassCopiesRenderAsTheirFlattenedScene) {
    Scene scene = instancedScene();
    ASSERT_EQ(scene.materials[1].model, MaterialModel::Glass);
    const RenderPair untinted = renderBoth(scene);
    scene.materials[1].tint = glm::vec3(0.6f, 0.9f, 0.4f);
    const auto [instanced, flat] = renderInstancedAndFlat(scene);
    EXPECT_TRUE(instanced.gpuStats.kernel && instanced.gpuStats.kernel->glassTints);
    EXPECT_GT(diffImages(instanced.gpu, untinted.gpu).shareOver005, 0.01);
}

// instancedScene with its tetrahedron mesh made of a red plastic whose texture `texture` (a 3x3
// grey texture alternating `even` and `odd`) is its cutout or coverage, at uvs that repeat it a few
// times across the mesh; returns the plastic's material index.
std::size_t texturedTetrahedra(Scene& scene, int Material::*texture, float even, float odd) {
    Material plastic =
        makeMaterial(MaterialModel::Phong, glm::vec3(0.05f), glm::vec3(0.8f, 0.3f, 0.2f), glm::vec3(0.3f), 40.0f, 1.5f);
    plastic.*texture = int(scene.textures.size());
    scene.textures.push_back(Texture{"grey", 3, 3, {}});
    for (int i = 0; i < 9; ++i) scene.textures.back().texels.push_back(glm::vec3(i % 2 == 0 ? even : odd));
    scene.materials.push_back(plastic);
    const Mesh& tetrahedron = scene.meshes[1];
    for (std::uint32_t i = tetrahedron.first; i < tetrahedron.first + tetrahedron.count; ++i) {
        Triangle& t = scene.triangles[i];
        t.material = std::uint32_t(scene.materials.size() - 1);
        for (int k = 0; k < 3; ++k) t.uv[k] = 4.0f * glm::vec2(t.position[k].x + t.position[k].z, t.position[k].y);
    }
    return scene.materials.size() - 1;
}

// Copies of a mesh with cut-out parts (Material::cutout): each copy's hits are tested against
// the texture at the mesh's uvs, in the mesh's space, as the flattened copies' are in the world.
TEST(Instancing, CutOutCopiesRenderAsTheirFlattenedScene) {
    Scene scene = instancedScene();
    const std::size_t plastic = texturedTetrahedra(scene, &Material::cutout, 0.2f, 1.5f);
    const auto [instanced, flat] = renderInstancedAndFlat(scene);
    EXPECT_TRUE(instanced.gpuStats.kernel && instanced.gpuStats.kernel->cutouts);
    scene.materials[plastic].cutout = -1;
    EXPECT_GT(diffImages(instanced.gpu, renderBoth(scene).gpu).shareOver005, 0.01) << "the holes show";
}

// Copies of a partly covered mesh (Material::coverage): each copy's coverage is read at the
// mesh's uvs and its rays pass on through it from the hit moved to the world, as the flattened
// copies' do.
TEST(Instancing, PartlyCoveredCopiesRenderAsTheirFlattenedScene) {
    Scene scene = instancedScene();
    const std::size_t plastic = texturedTetrahedra(scene, &Material::coverage, 0.2f, 0.7f);
    const auto [instanced, flat] = renderInstancedAndFlat(scene);
    EXPECT_GT(instanced.gpuStats.passThroughRays, 0u);
    EXPECT_EQ(instanced.gpuStats.passThroughRays, flat.gpuStats.passThroughRays);
    scene.materials[plastic].coverage = -1;
    EXPECT_GT(diffImages(instanced.gpu, renderBoth(scene).gpu).shareOver005, 0.01) << "what lies beyond shows";
}

// Copies of a mesh of glass in parts (Material::transmissionTexture): each copy's hit reads the
// texture at the mesh's uvs and shows the glass or its opaque part, as the flattened copies' do.
TEST(Instancing, CopiesOfGlassInPartsRenderAsTheirFlattenedScene) {
    Scene scene = instancedScene();
    const std::size_t glass = texturedTetrahedra(scene, &Material::transmissionTexture, 0.2f, 1.5f);
    Material opaque = scene.materials[glass];
    opaque.transmissionTexture = -1;
    scene.materials[glass].model = MaterialModel::Glass;
    scene.materials[glass].opaquePart = int(scene.materials.size());
    scene.materials.push_back(opaque);
    const auto [instanced, flat] = renderInstancedAndFlat(scene);
    EXPECT_TRUE(instanced.gpuStats.kernel && instanced.gpuStats.kernel->transmissionTextures);
    scene.materials[glass].transmissionTexture = -1;
    EXPECT_GT(diffImages(instanced.gpu, renderBoth(scene).gpu).shareOver005, 0.01) << "the opaque parts show";
}

// A mirroring instance's triangles face out as its flattened copy's do (the loaders reverse the
// winding of a mirrored mesh): seen from inside, the mirrored tetrahedron's medium is entered and
// left as often as the plain one's.
TEST(Instancing, AMirroredCopyIsTheMirrorImageOfThePlainOne) {
    Scene scene = instancedScene(48, 48);
    // Only the two tetrahedra, side by side, mirrored about the plane x = 0 between them.
    scene.instances.clear();
    const glm::mat4 identity(1.0f);
    scene.objectNames.resize(1);
    testing::place(scene, 1, glm::translate(identity, {0.15f, 0.0f, 0.0f}), "plain");
    testing::place(scene, 1, glm::scale(glm::translate(identity, {-0.15f, 0.0f, 0.0f}), {-1.0f, 1.0f, 1.0f}), "mirrored");
    scene.camera = {.from = {0.0f, -5.0f, 1.5f}, .at = {0.0f, 0.3f, 0.3f}, .up = {0, 0, 1}, .fovY = 30.0f,
                    .width = 48, .height = 48};
    scene.lights[0].position = {0.0f, -4.0f, 6.0f};  // on the mirror plane: the image is symmetric
    RenderPair r = renderBoth(scene);
    expectImagesMatch(r);
    // The image is its own mirror image about the middle column (an even width: columns x and
    // 47 - x), but where rounding picks another triangle at an edge.
    for (const Image* image : {&r.gpu, &r.cpu}) {
        std::uint32_t differing = 0;
        for (std::uint32_t y = 0; y < 48; ++y)
            for (std::uint32_t x = 0; x < 24; ++x) {
                const glm::vec3 d = glm::abs(image->at(x, y) - image->at(47 - x, y));
                if (std::max(d.x, std::max(d.y, d.z)) > 0.05f) ++differing;
            }
        EXPECT_LE(differing, 12u);  // 1% of the pairs
    }
    EXPECT_EQ(r.gpuStats.inconsistentMedia, 0u);
}

// Lecture, "Problematic Cases": two cubes touching face to face are one glass -> glass interface
// at the shared face, so they render as one box of their outer shape: so too when they are two
// copies of one cube (scenes/meshes/cube.obj placed by two entries of a JSON scene).
TEST(Instancing, TwoCopiesOfACubeFaceToFaceRenderAsOneBox) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "vitrum_instancing_gpu_test";
    std::filesystem::create_directories(dir);
    const std::filesystem::path file = dir / "face_to_face.json";
    const std::string root = VITRUM_SOURCE_DIR;
    std::ifstream in(root + "/scenes/one_box.json");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string box = R"({
      "obj": "meshes/one_box.obj",
      "mtl": "materials/clear_glass.mtl"
    })";
    const std::size_t at = text.find(R"("obj": "meshes/one_box.obj")");
    ASSERT_NE(at, std::string::npos);
    const std::size_t begin = text.rfind('{', at), end = text.find('}', at) + 1;
    auto cube = [&](const char* x) {
        return R"({"obj": ")" + root + R"(/scenes/meshes/cube.obj", "mtl": ")" + root +
               R"(/scenes/materials/clear_glass.mtl", "transform": {"translate": [)" + x + ", 0, 0]}}";
    };
    text.replace(begin, end - begin, cube("-0.5") + ", " + cube("0.5"));
    text = std::regex_replace(text, std::regex(R"("meshes/checker_floor.obj")"),
                              "\"" + root + "/scenes/meshes/checker_floor.obj\"");
    std::ofstream(file) << text;
    Scene twoCubes = loadScene(file);
    ASSERT_EQ(twoCubes.instances.size(), 2u);
    Scene oneBox = loadScene(sourcePath("scenes/one_box.json"));
    for (Scene* s : {&twoCubes, &oneBox}) {
        s->camera.width = 160;
        s->camera.height = 120;
        s->settings.fresnel = FresnelModel::Exact;
    }
    RenderPair touching = renderBoth(twoCubes);
    RenderPair one = renderBoth(oneBox);
    expectImagesMatch(touching);
    // TouchingMedia.TouchingGlassCubesMatchOneBoxOnBothBackends' allowance: rounding where the ray
    // restarts beyond the shared face.
    for (auto [a, b] : {std::pair{&touching.gpu, &one.gpu}, std::pair{&touching.cpu, &one.cpu}}) {
        const ImageDiff d = diffImages(*a, *b);
        EXPECT_LE(d.shareOver1of255, 0.001) << "psnr " << d.psnr;
        EXPECT_LE(d.maxAbsError, 0.02);
    }
    EXPECT_GT(touching.gpuStats.touchingInterfaces, 0u);
    EXPECT_EQ(touching.gpuStats.maxMediumDepth, 1u);  // one cube's medium at a time, never both
    EXPECT_EQ(touching.gpuStats.mediumStackOverflows, 0u);
}

// The hard cases' scale test (HardCaseScale) for instances: scaled by a power of two, every
// product of the moved ray is scaled exactly, so the image is the same bit for bit; by 1e3, 1e-3
// and moved 1e4 away, within the thresholds that test allows.
TEST(Instancing, TheImageIsTheSameScaledAndMovedFarAway) {
    const Scene base = instancedScene(48, 36);
    RenderPair reference = renderBoth(base);
    struct Variant {
        const char* name;
        float scale;
        glm::vec3 shift;
        double maxShare, maxMean;
    };
    const Variant variants[] = {{"x 2^-10", 0x1p-10f, glm::vec3(0.0f), 0.0, 1e-7},
                                {"x 2^10", 0x1p10f, glm::vec3(0.0f), 0.0, 1e-7},
                                {"x 1e-3", 1e-3f, glm::vec3(0.0f), 0.015, 3e-3},
                                {"x 1e3", 1e3f, glm::vec3(0.0f), 0.015, 3e-3},
                                {"+ 1e4", 1.0f, glm::vec3(1e4f, -1e4f, 1e4f), 0.02, 5e-3}};
    for (const Variant& v : variants) {
        SCOPED_TRACE(v.name);
        RenderPair moved = renderBoth(movedInstancedScene(base, v.scale, v.shift));
        expectImagesMatch(moved, 0.01);
        for (auto [a, b] : {std::pair{&moved.gpu, &reference.gpu}, std::pair{&moved.cpu, &reference.cpu}}) {
            const ImageDiff d = diffImages(*a, *b);
            EXPECT_LE(d.shareOver005, v.maxShare);
            EXPECT_LE(d.meanAbsError, v.maxMean);
            if (v.maxShare == 0.0) {
                EXPECT_EQ(differingPixels(*a, *b), 0u);
            }
        }
    }
}

// A pixel whose budget runs out inside an instance's mesh resumes there (its instance in the
// saved state, the entry that leaves it on the saved stack): the same image and work as with one
// dispatch's budget.
TEST(Instancing, APixelSuspendedInsideAnInstanceResumesThere) {
    const Scene scene = instancedScene(32, 24);
    const Bvh bvh = buildSceneBvh(scene);
    RenderStats small, large;
    const Image a = renderVulkan(testDevice(), scene, bvh, VulkanRenderOptions{.iterationBudget = 16}, small);
    const Image b = renderVulkan(testDevice(), scene, bvh, VulkanRenderOptions{.iterationBudget = 1u << 20}, large);
    EXPECT_EQ(differingPixels(a, b), 0u);
    expectSameWork(small, large);
    EXPECT_GT(small.dispatches, large.dispatches);
}

}  // namespace
}  // namespace vitrum
