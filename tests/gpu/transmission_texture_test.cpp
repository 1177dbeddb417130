// Transmission textures (glTF's transmissionTexture; docs/render-model-decisions.md, "Transmission
// textures"): a glass is glass only where its texture, read at the hit's uv, is 1 or more, and its
// opaque part elsewhere. So a pixel whose ray meets the surface where it is glass must be the
// pixel of the scene with the surface all glass, and one whose ray meets it elsewhere the pixel of
// the scene with the surface all its opaque part: the expectations are those two scenes, rebuilt.
#include "gpu_test_support.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "../support/scenes_in_code.h"

namespace vitrum::testing {
namespace {

// How a scene's switching surface (its material 0) is made: glass where its texture says, all
// glass, or all its opaque part (material 2).
enum class Surface { Textured, Glass, Opaque };

// Material 0 glass only where `texels` (a row, nearest filtering) are 1 or more, else material 2.
void setSurface(Scene& scene, Surface surface, const std::vector<float>& texels) {
    if (surface == Surface::Opaque) {
        for (Triangle& t : scene.triangles)
            if (t.material == 0) t.material = 2;
        return;
    }
    if (surface == Surface::Textured) {
        scene.textures.push_back(greyRow(texels));
        scene.materials[0].transmissionTexture = int(scene.textures.size()) - 1;
        scene.materials[0].opaquePart = 2;
    }
}

// A tinted thin-glass wall filling the 9 x 9 camera's view, a lit Lambert wall behind the camera
// that it reflects, and a Phong plastic as its opaque part.
Scene paneScene(Surface surface) {
    Scene scene = baseScene();
    scene.settings.filter = TextureFilter::Nearest;
    scene.materials = {makeMaterial(MaterialModel::ThinGlass, {}, glm::vec3(0.8f, 0.9f, 0.5f), {}, 1.0f, 1.5f),
                       makeMaterial(MaterialModel::Lambert, glm::vec3(0.1f), glm::vec3(0.5f, 0.6f, 0.7f)),
                       makeMaterial(MaterialModel::Phong, glm::vec3(0.05f), glm::vec3(0.6f, 0.2f, 0.1f),
                                    glm::vec3(0.4f), 20.0f, 1.5f)};
    scene.objectNames = {"pane", "wall"};
    addSquareY(scene, {0, 0, 0}, 3.0f, true, 0, 0);
    addSquareY(scene, {0, -10, 0}, 30.0f, false, 1, 1);
    scene.lights.push_back({.position = {1.0f, -4.0f, 2.0f}, .colour = glm::vec3(0.9f)});
    setSurface(scene, surface, {0.0f, 2.0f});
    return scene;
}

// Columns 0 to 3 look at u in (0.23, 0.43), where the texture is 0: the opaque part's pixels;
// columns 5 to 8 at u above 1/2, where it is 2: the glass's (column 4 looks at u = 1/2 within
// rounding).
TEST(TransmissionTextures, APaneIsItsOpaquePartWhereItsTextureIsBelowOneAndGlassElsewhere) {
    const Scene scene = paneScene(Surface::Textured);
    const RenderPair textured = renderBoth(scene);
    const RenderPair glass = renderBoth(paneScene(Surface::Glass));
    const RenderPair opaque = renderBoth(paneScene(Surface::Opaque));
    auto expectColumns = [](const Image& image, const Image& expected, std::uint32_t from, std::uint32_t to) {
        for (std::uint32_t y = 0; y < 9; ++y)
            for (std::uint32_t x = from; x <= to; ++x)
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(image.at(x, y)[c], expected.at(x, y)[c], 1e-6) << x << ", " << y;
    };
    expectColumns(textured.gpu, opaque.gpu, 0, 3);
    expectColumns(textured.gpu, glass.gpu, 5, 8);
    expectColumns(textured.cpu, opaque.cpu, 0, 3);
    expectColumns(textured.cpu, glass.cpu, 5, 8);
    // The two halves must look different for the test to say anything.
    for (std::uint32_t x : {0u, 8u}) EXPECT_GT(std::abs(glass.cpu.at(x, 4).x - opaque.cpu.at(x, 4).x), 0.05f) << x;
    // The opaque half sends shadow rays and Phong reflections, the glass half thin-glass rays.
    for (const RenderStats* stats : {&textured.gpuStats, &textured.cpuStats}) {
        EXPECT_GE(stats->shadowRays, 36u);
        EXPECT_LE(stats->shadowRays, 45u + 81u) << "the wall behind the camera is lit too";
    }
    EXPECT_EQ(textured.gpuStats.shadowRays, textured.cpuStats.shadowRays);
    EXPECT_TRUE(textured.gpuStats.kernel && textured.gpuStats.kernel->transmissionTextures);
    EXPECT_FALSE(glass.gpuStats.kernel->transmissionTextures);
    expectTheGeneralKernelAgrees(scene, textured);
}

// A glass block on a lit floor, its texture one texel: 0 makes the whole block its opaque part
// (a mirror), 2 the whole block glass, for every ray that meets it, from outside or inside, so the
// images must be those of the block built of either, on both backends.
Scene blockScene(Surface surface, float texel) {
    Scene scene;
    scene.camera = {.from = {1.5f, -6.0f, 2.5f},
                    .at = {0.0f, 0.0f, 0.3f},
                    .up = {0, 0, 1},
                    .fovY = 40.0f,
                    .width = 32,
                    .height = 24};
    scene.background.colour = glm::vec3(0.3f, 0.5f, 0.8f);
    scene.settings.maxDepth = 8;
    scene.lights.push_back({.position = {2.0f, -3.0f, 5.0f}, .colour = glm::vec3(0.9f)});
    scene.materials = {makeMaterial(MaterialModel::Glass, {}, {}, {}, 1.0f, 1.5f),
                       makeMaterial(MaterialModel::Lambert, glm::vec3(0.1f), glm::vec3(0.7f, 0.6f, 0.5f)),
                       makeMaterial(MaterialModel::Mirror, {}, {}, glm::vec3(0.8f, 0.7f, 0.9f))};
    scene.materials[0].attenuation = glm::vec3(0.3f, 0.1f, 0.05f);
    scene.objectNames = {"block", "floor"};
    addBox(scene, {-1.0f, -1.0f, 0.0f}, {1.0f, 1.0f, 1.2f}, 0, 0);
    scene.triangles.push_back(makeTriangle({-9, -9, 0}, {9, -9, 0}, {9, 9, 0}, 1, 1));
    scene.triangles.push_back(makeTriangle({-9, -9, 0}, {9, 9, 0}, {-9, 9, 0}, 1, 1));
    setSurface(scene, surface, {texel});
    return scene;
}

TEST(TransmissionTextures, AGlassBlockIsAllItsOpaquePartOrAllGlassByItsTexture) {
    for (const auto& [texel, expected] : {std::pair{0.0f, Surface::Opaque}, std::pair{2.0f, Surface::Glass}}) {
        SCOPED_TRACE("texel " + std::to_string(texel));
        const Scene scene = blockScene(Surface::Textured, texel);
        const RenderPair textured = renderBoth(scene);
        const RenderPair built = renderBoth(blockScene(expected, texel));
        for (const auto& [image, reference] :
             {std::pair{&textured.gpu, &built.gpu}, std::pair{&textured.cpu, &built.cpu}})
            for (std::size_t i = 0; i < image->pixels.size(); ++i)
                for (int c = 0; c < 3; ++c) ASSERT_NEAR(image->pixels[i][c], reference->pixels[i][c], 1e-6) << i;
        EXPECT_EQ(textured.gpuStats.refractionRays, built.gpuStats.refractionRays);
        EXPECT_EQ(textured.gpuStats.reflectionRays, built.gpuStats.reflectionRays);
        if (expected == Surface::Glass) {
            EXPECT_GT(textured.gpuStats.refractionRays, 100u);
        } else {
            EXPECT_EQ(textured.gpuStats.refractionRays, 0u);
        }
        expectTheGeneralKernelAgrees(scene, textured);
    }
}

// The same pane at an angle before a lit room, glass where u > 1/2: every pixel is the all-glass
// scene's or the all-opaque scene's (the switch is decided once a hit, at its uv; shadow rays are
// blocked by any surface, so the room's lighting is the same in both), and many are each.
TEST(TransmissionTextures, EveryPixelOfAMixedPaneIsTheGlassSceneOrTheOpaqueScenes) {
    auto room = [](Surface surface) {
        Scene scene;
        scene.camera = {.from = {1.5f, -7.0f, 2.0f},
                        .at = {0.0f, 2.0f, 0.3f},
                        .up = {0, 0, 1},
                        .fovY = 40.0f,
                        .width = 32,
                        .height = 24};
        scene.settings.filter = TextureFilter::Nearest;
        scene.background.colour = glm::vec3(0.3f, 0.5f, 0.8f);
        scene.lights.push_back({.position = {2.0f, 6.0f, 5.0f}, .colour = glm::vec3(0.9f)});
        scene.materials = {makeMaterial(MaterialModel::ThinGlass, {}, glm::vec3(0.9f, 0.7f, 0.6f), {}, 1.0f, 1.5f),
                           makeMaterial(MaterialModel::Lambert, glm::vec3(0.1f), glm::vec3(0.7f, 0.6f, 0.5f)),
                           makeMaterial(MaterialModel::Lambert, glm::vec3(0.05f), glm::vec3(0.2f, 0.3f, 0.8f))};
        scene.objectNames = {"pane", "floor", "box"};
        scene.triangles.push_back(makeTriangle({-9, 0.5f, -1}, {9, 0.5f, -1}, {9, 9, -1}, 1, 1));
        scene.triangles.push_back(makeTriangle({-9, 0.5f, -1}, {9, 9, -1}, {-9, 9, -1}, 1, 1));
        addBox(scene, {-1.0f, 2.0f, -1.0f}, {0.5f, 3.0f, 0.5f}, 1, 2);
        addSquareY(scene, {0.0f, 0.0f, 0.5f}, 2.5f, true, 0, 0);
        setSurface(scene, surface, {0.0f, 2.0f});
        return scene;
    };
    const Scene scene = room(Surface::Textured);
    const RenderPair textured = renderBoth(scene);
    const RenderPair glass = renderBoth(room(Surface::Glass));
    const RenderPair opaque = renderBoth(room(Surface::Opaque));
    auto near = [](const glm::vec3& a, const glm::vec3& b) {
        return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(1e-6f)));
    };
    // Each pixel's kind: 1 where it is only the glass scene's, 2 only the opaque scene's, 3 both.
    auto kinds = [&](const Image& image, const Image& all, const Image& none) {
        std::vector<int> kind(image.pixels.size());
        for (std::size_t i = 0; i < image.pixels.size(); ++i) {
            kind[i] = (near(image.pixels[i], all.pixels[i]) ? 1 : 0) + (near(image.pixels[i], none.pixels[i]) ? 2 : 0);
            EXPECT_NE(kind[i], 0) << "pixel " << i << " is neither scene's";
        }
        EXPECT_GE(std::count(kind.begin(), kind.end(), 1), 100);
        EXPECT_GE(std::count(kind.begin(), kind.end(), 2), 100);
        return kind;
    };
    const std::vector<int> gpu = kinds(textured.gpu, glass.gpu, opaque.gpu);
    const std::vector<int> cpu = kinds(textured.cpu, glass.cpu, opaque.cpu);
    // Both backends decide alike at every hit but those at the texture's edge, u = 1/2 within rounding.
    std::size_t decidedApart = 0;
    for (std::size_t i = 0; i < gpu.size(); ++i)
        decidedApart += (gpu[i] == 1 && cpu[i] == 2) || (gpu[i] == 2 && cpu[i] == 1);
    EXPECT_LE(decidedApart, 2u);
    expectTheGeneralKernelAgrees(scene, textured);
}

}  // namespace
}  // namespace vitrum::testing
