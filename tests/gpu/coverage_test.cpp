// Partial coverage (glTF's alphaMode BLEND; docs/render-model-decisions.md, "Partial coverage"):
// alpha of an opaque surface is there. Its shading takes alpha of the ray's weight, and the ray
// goes on through it, undeviated, with 1 - alpha, at depth + 1. The expectations are sums worked
// out by hand and the linear blend of the scene with the surface and without it.
#include "gpu_test_support.h"

#include <vector>

#include "../support/scenes_in_code.h"

namespace vitrum::testing {
namespace {

constexpr glm::vec3 kAmbient{0.2f, 0.1f, 0.05f};
constexpr glm::vec3 kLightColour{0.9f, 0.8f, 0.7f};

// A Lambert wall lit only by its ambient term (the light is behind it, so n.l < 0 and no shadow
// ray is sent): Ka times the light's colour where it is all there.
Scene ambientWall() {
    Scene scene = wallOf(makeMaterial(MaterialModel::Lambert, kAmbient, glm::vec3(0.5f)));
    scene.lights.push_back({.position = {0.0f, 20.0f, 0.0f}, .colour = kLightColour});
    return scene;
}

// A quarter of the wall is there where u < 1/2 (columns 0 to 3 look at u in (0.23, 0.43)), all of
// it where u > 1/2 (columns 5 to 8): 0.25 Ka l_c + 0.75 background, and Ka l_c.
TEST(Coverage, AWallShowsAlphaOfItselfAndOneMinusAlphaOfWhatLiesBeyond) {
    Scene scene = ambientWall();
    scene.settings.filter = TextureFilter::Nearest;
    scene.textures.push_back(greyRow({0.25f, 1.0f}));
    scene.materials[0].coverage = 0;
    const RenderPair p = renderBoth(scene);
    const glm::vec3 wall = kLightColour * kAmbient;
    const glm::vec3 blended = 0.25f * wall + 0.75f * scene.background.colour;
    for (const Image* image : {&p.gpu, &p.cpu})
        for (std::uint32_t y = 0; y < 9; ++y) {
            for (std::uint32_t x = 0; x < 4; ++x)
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(image->at(x, y)[c], blended[c], 1e-6) << x << ", " << y;
            for (std::uint32_t x = 5; x < 9; ++x)
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(image->at(x, y)[c], wall[c], 1e-6) << x << ", " << y;
        }
    for (const RenderStats* stats : {&p.gpuStats, &p.cpuStats}) {
        EXPECT_EQ(stats->primaryRays, 81u);
        EXPECT_GE(stats->passThroughRays, 36u);  // column 4 looks at u = 1/2 within rounding
        EXPECT_LE(stats->passThroughRays, 45u);
        EXPECT_EQ(stats->shadowRays + stats->reflectionRays + stats->refractionRays, 0u);
    }
    EXPECT_EQ(p.gpuStats.passThroughRays, p.cpuStats.passThroughRays);
    EXPECT_TRUE(p.gpuStats.kernel && p.gpuStats.kernel->partialCoverage);
    expectTheGeneralKernelAgrees(scene, p);
}

// Twelve such walls one behind the other, each half there: the ray meeting wall k has depth k and
// weight 2^-k, so at max_depth 10 the pixel is sum_{k<10} 2^-k (1/2) Ka l_c = (1 - 2^-10) Ka l_c
// and the background is never reached; nine rays pass through (walls 0 to 8), the tenth is
// stopped by the depth limit. Nothing is dropped from the pending-ray stack.
TEST(Coverage, RaysPassingThroughWallsAfterWallsAddAGeometricSeriesUpToTheDepthLimit) {
    Scene scene = baseScene();
    scene.camera.fovY = 5.0f;
    scene.camera.width = scene.camera.height = 3;
    scene.materials.push_back(makeMaterial(MaterialModel::Lambert, kAmbient, glm::vec3(0.5f)));
    scene.lights.push_back({.position = {0.0f, 50.0f, 0.0f}, .colour = kLightColour});
    for (std::uint32_t k = 0; k < 12; ++k) {
        scene.objectNames.push_back("wall " + std::to_string(k));
        addSquareY(scene, {0.0f, float(k), 0.0f}, 3.0f, true, 0, k);
    }
    scene.textures.push_back(greyRow({0.5f}));
    scene.materials[0].coverage = 0;
    const RenderPair p = renderBoth(scene);
    const glm::vec3 expected = (1.0f - 1.0f / 1024.0f) * kLightColour * kAmbient;
    for (const Image* image : {&p.gpu, &p.cpu})
        for (const glm::vec3& pixel : image->pixels)
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(pixel[c], expected[c], 1e-6);
    for (const RenderStats* stats : {&p.gpuStats, &p.cpuStats}) {
        EXPECT_EQ(stats->passThroughRays, 9u * 9u);
        EXPECT_EQ(stats->depthLimitHits, 9u);
        EXPECT_EQ(stats->maxRayDepth, 9u);
        EXPECT_EQ(stats->rayStackOverflows, 0u);
    }
    expectTheGeneralKernelAgrees(scene, p);
}

// A lit room behind a wall that is alpha there everywhere: it must render as alpha times the room
// with the wall built plus 1 - alpha times the room without it, pixel by pixel (linear in the
// paths; the wall faces away from the light, so no shadow ray crosses it, and only Lambert
// surfaces lie behind it, so no ray comes back to it). Phong and mirror walls also reflect.
Scene roomBehindWall(const Material& wall, int mode /* 0: no wall, 1: all there, 2: partly */) {
    Scene scene;
    scene.camera = {.from = {0.5f, -7.0f, 2.0f},
                    .at = {0.0f, 2.0f, 0.3f},
                    .up = {0, 0, 1},
                    .fovY = 40.0f,
                    .width = 32,
                    .height = 24};
    scene.background.colour = glm::vec3(0.3f, 0.5f, 0.8f);
    scene.lights.push_back({.position = {2.0f, 6.0f, 5.0f}, .colour = glm::vec3(0.9f)});
    scene.materials = {makeMaterial(MaterialModel::Lambert, glm::vec3(0.1f), glm::vec3(0.7f, 0.6f, 0.5f)),
                       makeMaterial(MaterialModel::Lambert, glm::vec3(0.05f), glm::vec3(0.2f, 0.3f, 0.8f)), wall};
    scene.objectNames = {"floor", "box", "wall"};
    scene.triangles.push_back(makeTriangle({-9, 0.5f, -1}, {9, 0.5f, -1}, {9, 9, -1}, 0, 0));
    scene.triangles.push_back(makeTriangle({-9, 0.5f, -1}, {9, 9, -1}, {-9, 9, -1}, 0, 0));
    addBox(scene, {-1.0f, 2.0f, -1.0f}, {0.5f, 3.0f, 0.5f}, 1, 1);
    if (mode > 0) addSquareY(scene, {0.0f, 0.0f, 0.5f}, 2.5f, true, 2, 2);
    if (mode == 2) {
        scene.textures.push_back(greyRow({0.3f}));
        scene.materials[2].coverage = 0;
    }
    return scene;
}

TEST(Coverage, APartlyThereWallRendersAsTheBlendOfTheRoomWithAndWithoutIt) {
    const Material walls[] = {
        makeMaterial(MaterialModel::Phong, glm::vec3(0.05f), glm::vec3(0.2f, 0.5f, 0.3f), glm::vec3(0.4f), 30.0f, 1.5f),
        makeMaterial(MaterialModel::Lambert, glm::vec3(0.05f), glm::vec3(0.2f, 0.5f, 0.3f)),
        makeMaterial(MaterialModel::Mirror, {}, {}, glm::vec3(0.8f)),
    };
    for (const Material& wall : walls) {
        SCOPED_TRACE("model " + std::to_string(int(wall.model)));
        const Scene scene = roomBehindWall(wall, 2);
        const RenderPair partly = renderBoth(scene);
        const RenderPair none = renderBoth(roomBehindWall(wall, 0));
        const RenderPair all = renderBoth(roomBehindWall(wall, 1));
        expectImagesMatch(partly);
        for (auto [image, without, with] :
             {std::tuple{&partly.gpu, &none.gpu, &all.gpu}, std::tuple{&partly.cpu, &none.cpu, &all.cpu}}) {
            std::size_t far = 0;
            for (std::size_t i = 0; i < image->pixels.size(); ++i) {
                const glm::vec3 blend = 0.3f * with->pixels[i] + 0.7f * without->pixels[i];
                if (glm::any(glm::greaterThan(glm::abs(image->pixels[i] - blend), glm::vec3(1e-5f)))) ++far;
            }
            EXPECT_EQ(far, 0u) << (image == &partly.gpu ? "GPU" : "CPU");
        }
        // The wall matters: the blend is neither image.
        EXPECT_GT(diffImages(partly.gpu, none.gpu).shareOver005, 0.1);
        EXPECT_GT(diffImages(partly.gpu, all.gpu).shareOver005, 0.1);
        EXPECT_GT(partly.gpuStats.passThroughRays, 0u);
        EXPECT_GT(partly.gpuStats.shadowRays, 0u);
        expectTheGeneralKernelAgrees(scene, partly);
    }
}

// Shadows stay binary (render model, "Lights and shadows": a shadow ray is blocked by any
// surface): a floor behind a wall half there, seen where the camera does not see the wall, is
// the floor behind the whole wall, bit for bit; without the wall it is lit.
TEST(Coverage, APartlyThereSurfaceCastsAWholeShadow) {
    auto scene = [](int mode) {
        Scene s;
        s.camera = {.from = {0.0f, -6.0f, 4.0f},
                    .at = {0.0f, 0.0f, -1.0f},
                    .up = {0, 0, 1},
                    .fovY = 40.0f,
                    .width = 24,
                    .height = 18};
        s.lights.push_back({.position = {0.0f, 0.0f, 8.0f}, .colour = glm::vec3(0.9f)});
        s.materials = {makeMaterial(MaterialModel::Lambert, glm::vec3(0.1f), glm::vec3(0.7f, 0.6f, 0.5f)),
                       makeMaterial(MaterialModel::Lambert, glm::vec3(0.1f), glm::vec3(0.5f))};
        s.objectNames = {"floor", "shade"};
        s.triangles.push_back(makeTriangle({-9, -9, -1}, {9, -9, -1}, {9, 9, -1}, 0, 0));
        s.triangles.push_back(makeTriangle({-9, -9, -1}, {9, 9, -1}, {-9, 9, -1}, 0, 0));
        // A square shade above the camera's view, between the light and the floor's middle.
        if (mode > 0) {
            s.triangles.push_back(makeTriangle({-1, -1, 6}, {1, -1, 6}, {1, 1, 6}, 1, 1));
            s.triangles.push_back(makeTriangle({-1, -1, 6}, {1, 1, 6}, {-1, 1, 6}, 1, 1));
        }
        if (mode == 2) {
            s.textures.push_back(greyRow({0.5f}));
            s.materials[1].coverage = 0;
        }
        return s;
    };
    const RenderPair partly = renderBoth(scene(2));
    const RenderPair whole = renderBoth(scene(1));
    const RenderPair none = renderBoth(scene(0));
    EXPECT_EQ(differingPixels(partly.gpu, whole.gpu), 0u);
    EXPECT_EQ(differingPixels(partly.cpu, whole.cpu), 0u);
    EXPECT_GT(differingPixels(partly.gpu, none.gpu), 20u) << "the shade's shadow";
    EXPECT_EQ(partly.gpuStats.passThroughRays, 0u) << "the camera never meets the shade";
}

// A box half there standing on a floor (an open sheet): its bottom face and the floor's top
// coincide. A ray that goes on through the bottom must meet the floor there, as it does beyond
// the bottom of a box lifted 1e-3 (beyond the touching distance, 1.5e-4 here); a ray started
// beyond the bottom (offset off the surface as a refraction is) would start beyond the floor too
// and see the background under it. Both backends, and in double.
Scene coveredBoxOnFloor(float lift) {
    Scene scene;
    scene.camera = {.from = {1.5f, -4.0f, 3.0f},
                    .at = {0.0f, 0.0f, 0.3f},
                    .up = {0, 0, 1},
                    .fovY = 35.0f,
                    .width = 40,
                    .height = 30};
    scene.background.colour = glm::vec3(0.9f, 0.9f, 1.0f);
    scene.lights.push_back({.position = {3.0f, -2.0f, 6.0f}, .colour = glm::vec3(0.9f)});
    scene.materials = {makeMaterial(MaterialModel::Lambert, glm::vec3(0.2f), glm::vec3(0.7f, 0.6f, 0.5f)),
                       makeMaterial(MaterialModel::Lambert, glm::vec3(0.1f), glm::vec3(0.2f, 0.3f, 0.8f))};
    scene.objectNames = {"floor", "box"};
    scene.triangles.push_back(makeTriangle({-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, 0, 0));
    scene.triangles.push_back(makeTriangle({-5, -5, 0}, {5, 5, 0}, {-5, 5, 0}, 0, 0));
    addBox(scene, {-0.6f, -0.6f, lift}, {0.6f, 0.6f, 1.0f}, 1, 1);
    scene.textures.push_back(greyRow({0.5f}));
    scene.materials[1].coverage = 0;
    return scene;
}

TEST(Coverage, ABoxHalfThereStandingOnAFloorShowsTheFloorThroughItsBottom) {
    const Scene scene = coveredBoxOnFloor(0.0f);
    EXPECT_TRUE(analyseScene(scene).coincidentOpaquePossible);
    const RenderPair standing = renderBoth(scene);
    const RenderPair lifted = renderBoth(coveredBoxOnFloor(1e-3f));
    expectImagesMatch(standing);
    EXPECT_GT(standing.gpuStats.passThroughRays, 0u);
    // Pixels more than 1e-4 apart: a ray passing within 1e-3 of the box's bottom edge sees
    // another picture of the lifted box, so an edge pixel or two may differ.
    EXPECT_LE(pixelsApart(standing.gpu, lifted.gpu, 1e-4f), 2u);
    EXPECT_LE(pixelsApart(standing.cpu, lifted.cpu, 1e-4f), 2u);
    RenderStats doubleStats;
    const Image inDouble = renderReference(scene, buildSceneBvh(scene), {.doublePrecision = true}, doubleStats);
    EXPECT_EQ(pixelsApart(standing.cpu, inDouble, 1e-4f), 0u);
    expectTheGeneralKernelAgrees(scene, standing);
}

// A surface all there (a coverage of 1 everywhere) is the surface without coverage, bit for bit.
TEST(Coverage, ASurfaceAllThereRendersAsOneWithoutCoverage) {
    const Scene plain = roomBehindWall(
        makeMaterial(MaterialModel::Phong, glm::vec3(0.05f), glm::vec3(0.2f, 0.5f, 0.3f), glm::vec3(0.4f), 30.0f, 1.5f),
        1);
    Scene covered = plain;
    covered.textures.push_back(greyRow({1.0f, 1.0f}));
    covered.materials[2].coverage = 0;
    const RenderPair a = renderBoth(plain);
    const RenderPair b = renderBoth(covered);
    EXPECT_EQ(differingPixels(a.gpu, b.gpu), 0u);
    EXPECT_EQ(differingPixels(a.cpu, b.cpu), 0u);
    EXPECT_EQ(b.gpuStats.passThroughRays, 0u);
    expectSameWork(a.gpuStats, b.gpuStats);
}

}  // namespace
}  // namespace vitrum::testing
