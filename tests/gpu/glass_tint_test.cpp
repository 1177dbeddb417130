// Glass whose surface tints the light crossing it (docs/render-model-decisions.md, "Glass tint";
// glTF's base colour of a volume): every refraction and every index-matched crossing through a
// real surface is multiplied by the surface's tint, reflections are not, and a false surface
// (overlapping media) tints nothing. The expected values are the slab's Fresnel series and
// products of tints, worked out here, on both backends and both kernels.
#include "gpu_test_support.h"

#include <cmath>

#include "../support/scenes_in_code.h"

namespace vitrum::testing {
namespace {

Material tintedGlass(glm::vec3 tint, float ior = 1.5f) {
    Material m = makeMaterial(MaterialModel::Glass, {}, {}, {}, 1.0f, ior);
    m.tint = tint;
    return m;
}

// A slab 0.1 thick seen head-on (baseScene's centre ray) under a white background, exact
// Fresnel: the front reflects R; the light leaving after k inner reflections, T^2 R^k, crossed
// two surfaces, so a tint t takes t^2 of it (the reflections inside take nothing): R + t^2 T^2
// (1 + R + ... + R^(maxDepth - 3)) per channel, the untinted series (hard_cases_test.cpp's
// slabSeries) with its exits times t^2. One surface's tint (t) or none would miss it by 0.08 in red.
TEST(GlassTint, ASlabTintsEachExitTwiceAndNoReflection) {
    const glm::dvec3 tint(0.5, 0.8, 1.0);
    const double r = 0.04, t = 1.0 - r;  // ((1.5 - 1) / (1.5 + 1))^2 head-on
    for (unsigned maxDepth : {3u, 10u}) {
        SCOPED_TRACE("max_depth " + std::to_string(maxDepth));
        Scene scene = baseScene();
        scene.background.colour = glm::vec3(1.0f);
        scene.settings.fresnel = FresnelModel::Exact;
        scene.settings.maxDepth = maxDepth;
        scene.materials.push_back(tintedGlass(glm::vec3(tint)));
        scene.objectNames = {"slab"};
        addBox(scene, {-2, 0, -2}, {2, 0.1f, 2}, 0, 0);
        const RenderPair p = renderBoth(scene);
        double exits = 0.0;
        for (unsigned k = 0; k + 2 < maxDepth; ++k) exits += t * t * std::pow(r, double(k));
        for (const Image* image : {&p.gpu, &p.cpu})
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(image->at(4, 4)[c], r + tint[c] * tint[c] * exits, 2e-6)
                    << (image == &p.gpu ? "GPU" : "CPU") << ", channel " << c;
        EXPECT_TRUE(p.gpuStats.kernel && p.gpuStats.kernel->glassTints);
        expectTheGeneralKernelAgrees(scene, p);
    }
}

// A tinted glass of the air's index is no optical interface: the same ray goes on through both
// surfaces at its depth, so max_depth 1 sees through it, and each pixel through it is the
// background times t^2 exactly (no Fresnel), with no reflected or refracted ray.
TEST(GlassTint, AGlassOfTheAirsIndexOnlyTints) {
    const glm::vec3 tint(0.25f, 0.5f, 0.75f);
    Scene scene = baseScene();
    scene.background.colour = glm::vec3(0.8f, 0.6f, 0.4f);
    scene.settings.maxDepth = 1;
    scene.materials.push_back(tintedGlass(tint, 1.0f));
    scene.objectNames = {"box"};
    addBox(scene, {-1, -1, -1}, {1, 1, 1}, 0, 0);
    const RenderPair p = renderBoth(scene);
    const glm::vec3 expected = scene.background.colour * tint * tint;
    for (const Image* image : {&p.gpu, &p.cpu})
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(image->at(4, 4)[c], expected[c], 1e-7) << c;
    for (const RenderStats* stats : {&p.gpuStats, &p.cpuStats}) {
        EXPECT_EQ(stats->reflectionRays, 0u);
        EXPECT_EQ(stats->refractionRays, 0u);
    }
    expectTheGeneralKernelAgrees(scene, p);
}

// Two tinted boxes of the air's index touching face to face: the centre ray crosses the first's
// front (t1), their common face, where it leaves one and enters the other at once (t1 t2, one
// touching interface), and the second's back (t2): t1^2 t2^2. Dropping the touching object's tint
// at the common face would give t1^2 t2.
TEST(GlassTint, ATouchingInterfaceTintsByEverySurfaceItCrosses) {
    const glm::vec3 front(0.9f, 0.5f, 0.8f), back(0.6f, 0.9f, 0.5f);
    Scene scene = baseScene();
    scene.background.colour = glm::vec3(1.0f);
    scene.materials.push_back(tintedGlass(front, 1.0f));
    scene.materials.push_back(tintedGlass(back, 1.0f));
    scene.objectNames = {"front", "back"};
    addBox(scene, {-1, -1, -1}, {1, 0, 1}, 0, 0);
    addBox(scene, {-1, 0, -1}, {1, 1, 1}, 1, 1);
    const RenderPair p = renderBoth(scene);
    const glm::vec3 expected = front * front * back * back;
    for (const Image* image : {&p.gpu, &p.cpu})
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(image->at(4, 4)[c], expected[c], 1e-6) << c;
    EXPECT_GT(p.gpuStats.touchingInterfaces, 0u);
    EXPECT_GT(p.cpuStats.touchingInterfaces, 0u);
    expectTheGeneralKernelAgrees(scene, p);
}

// Overlapping media by priority: inside a block of glass of priority 1, the surfaces of a smaller
// tinted glass of priority 0 within it are false hits, no surfaces at all: the image is the one
// without the inner glass.
TEST(GlassTint, AFalseSurfaceTintsNothing) {
    Scene without = baseScene();
    without.background.colour = glm::vec3(1.0f);
    Material block = tintedGlass(glm::vec3(1.0f));
    block.priority = 1;
    without.materials = {block, tintedGlass(glm::vec3(0.2f, 0.4f, 0.6f), 1.33f)};
    without.objectNames = {"block", "inner"};
    addBox(without, {-2, -1, -2}, {2, 1, 2}, 0, 0);
    Scene with = without;
    addBox(with, {-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}, 1, 1);
    const RenderPair a = renderBoth(with);
    const RenderPair b = renderBoth(without);
    EXPECT_GT(a.gpuStats.falseHits, 0u);
    EXPECT_GT(a.cpuStats.falseHits, 0u);
    for (std::size_t i = 0; i < a.gpu.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            ASSERT_NEAR(a.gpu.pixels[i][c], b.gpu.pixels[i][c], 1e-5) << "GPU pixel " << i;
            ASSERT_NEAR(a.cpu.pixels[i][c], b.cpu.pixels[i][c], 1e-5) << "CPU pixel " << i;
        }
}

}  // namespace
}  // namespace vitrum::testing
