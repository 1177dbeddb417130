// Scene analysis: what each scene can need, checked against what the scene contains, and the
// kernel specialization made from it.
#include <gtest/gtest.h>

#include <set>

#include "../support/scenes_in_code.h"
#include "analysis/scene_features.h"
#include "glass_scenes.h"
#include "gpu_input/trace_specialization.h"
#include "scene/scene_loader.h"
#include "shared/gpu_types.h"

namespace vitrum {
namespace {

Scene loadProjectScene(const std::string& scene) { return loadScene(std::string(VITRUM_SOURCE_DIR) + "/" + scene); }
SceneFeatures featuresOf(const std::string& scene) { return analyseScene(loadProjectScene(scene)); }

TEST(SceneFeatures, LambertOnlySceneNeedsNoSecondaryRaysAndNoStacks) {
    SceneFeatures g = featuresOf("scenes/course/geospheres_5x5.json");  // shader 5: Lambert only
    EXPECT_EQ(g.materialModels, 1u << std::uint32_t(MaterialModel::Lambert));
    EXPECT_FALSE(g.glass);
    EXPECT_FALSE(g.reflection);
    EXPECT_TRUE(g.shadowRays);
    EXPECT_EQ(g.usefulDepth, 1u);
    EXPECT_EQ(g.mediumStackDepth, 0u);
    EXPECT_EQ(g.rayStackDepth, 0u);
    EXPECT_EQ(g.background, BackgroundKind::Constant);
}

TEST(SceneFeatures, SeparateGlassObjectsNeedAMediumStackOfOne) {
    // 25 glass spheres on a grid, none touching another: a ray is inside at most one of them.
    SceneFeatures f = featuresOf("scenes/course/geospheres_5x5_glass.json");
    EXPECT_TRUE(f.glass);
    EXPECT_EQ(f.glassObjects, 25u);
    EXPECT_FALSE(f.touchingMediaPossible);
    EXPECT_EQ(f.mediumStackDepth, 1u);
    EXPECT_EQ(f.rayStackDepth, 9u);  // max_depth 10
    SceneFeatures cornell = featuresOf("scenes/course/cornell_box2.json");  // one clear_glass sphere
    EXPECT_EQ(cornell.glassObjects, 1u);
    EXPECT_FALSE(cornell.touchingMediaPossible);
    EXPECT_EQ(cornell.mediumStackDepth, 1u);
}

TEST(SceneFeatures, TouchingAndNestedGlassNeedsTheProbeAndADeeperStack) {
    SceneFeatures touching = featuresOf("scenes/touching_cubes.json");
    EXPECT_EQ(touching.glassObjects, 2u);
    EXPECT_TRUE(touching.touchingMediaPossible);
    EXPECT_EQ(touching.mediumStackDepth, 2u);
    EXPECT_EQ(touching.usefulDepth, 10u);
    // An air bubble inside a glass block: nested (a stack of 2), but its surface is far from the
    // block's, so no touching probe.
    SceneFeatures bubble = featuresOf("scenes/bubble.json");
    EXPECT_FALSE(bubble.touchingMediaPossible);
    EXPECT_EQ(bubble.mediumStackDepth, 2u);
    SceneFeatures green = featuresOf("scenes/plastics_green_glass.json");
    EXPECT_TRUE(green.absorbingMedia);  // Tf 0.4 0.001 0.4
    EXPECT_TRUE(featuresOf("scenes/demo.json").absorbingMedia);
    EXPECT_EQ(featuresOf("scenes/glass_sphere_cube.json").background, BackgroundKind::Cube);
    EXPECT_EQ(featuresOf("scenes/glass_sphere_spherical.json").background, BackgroundKind::Spherical);
}

// Priorities matter only where glass media differ in them: equal ones, or one on an opaque
// material, leave the kernel without the priority code.
TEST(SceneFeatures, OnlyGlassOfDifferentPrioritiesNeedsThePriorityRule) {
    Scene scene = loadProjectScene("scenes/water_glass.json");
    EXPECT_FALSE(analyseScene(scene).mediumPriorities);
    EXPECT_FALSE(TraceSpecialization::forScene(scene, analyseScene(scene)).mediumPriorities);
    for (Material& m : scene.materials) m.priority = m.model == MaterialModel::Glass ? 4 : 9;
    EXPECT_FALSE(analyseScene(scene).mediumPriorities);
    for (Material& m : scene.materials)
        if (m.name == "water") m.priority = 3;
    const SceneFeatures f = analyseScene(scene);
    EXPECT_TRUE(f.mediumPriorities);
    EXPECT_TRUE(TraceSpecialization::forScene(scene, f).mediumPriorities);
    EXPECT_TRUE(TraceSpecialization::general().mediumPriorities);  // decided by the data at run time
}

// Only a glass that tints what crosses it calls for the tint: a tint on an opaque material (never
// read) or a white one leaves the kernel without it.
TEST(SceneFeatures, OnlyTintedGlassNeedsTheTint) {
    Scene scene = loadProjectScene("scenes/water_glass.json");
    EXPECT_FALSE(analyseScene(scene).glassTints);
    for (Material& m : scene.materials)
        if (m.model != MaterialModel::Glass) m.tint = glm::vec3(0.5f);
    EXPECT_FALSE(analyseScene(scene).glassTints);
    for (Material& m : scene.materials)
        if (m.name == "water") m.tint = glm::vec3(1.0f, 1.0f, 0.9f);
    const SceneFeatures f = analyseScene(scene);
    EXPECT_TRUE(f.glassTints);
    EXPECT_TRUE(TraceSpecialization::forScene(scene, f).glassTints);
    EXPECT_TRUE(TraceSpecialization::general().glassTints);
}

// Only a material with cut-outs that is not a glass volume (whose closed surface bounds its
// medium) calls for the test of cut-outs in the traversal; a material no triangle uses does not.
TEST(SceneFeatures, OnlyCutOutSurfacesNeedTheCutoutTest) {
    Scene scene = loadProjectScene("scenes/water_glass.json");
    EXPECT_FALSE(analyseScene(scene).cutouts);
    scene.textures.push_back(Texture{"cutout", 1, 1, {glm::vec3(0.5f)}});
    for (Material& m : scene.materials)
        if (m.model == MaterialModel::Glass) m.cutout = int(scene.textures.size() - 1);
    EXPECT_FALSE(analyseScene(scene).cutouts);
    scene.materials.push_back(scene.materials[0]);
    scene.materials.back().model = MaterialModel::Phong;
    EXPECT_FALSE(analyseScene(scene).cutouts) << "a material no triangle uses";
    for (Material& m : scene.materials)
        if (m.model != MaterialModel::Glass) m.cutout = int(scene.textures.size() - 1);
    const SceneFeatures f = analyseScene(scene);
    EXPECT_TRUE(f.cutouts);
    EXPECT_TRUE(TraceSpecialization::forScene(scene, f).cutouts);
    EXPECT_TRUE(TraceSpecialization::general().cutouts);
    EXPECT_FALSE(
        TraceSpecialization::forScene(scene, analyseScene(loadProjectScene("scenes/water_glass.json"))).cutouts);
}

// A partly covered surface (Material::coverage) of a Lambert, Phong or mirror material calls for
// the coverage test, its uvs and pending rays (its pass-through waits as a refraction does) and
// makes max_depth matter; a glass's or thin glass's coverage is not read.
TEST(SceneFeatures, PartlyCoveredSurfacesNeedPendingRaysAndTheirUvs) {
    Scene scene = loadProjectScene("scenes/lambert_spheres.json");
    for (Material& m : scene.materials) m.model = MaterialModel::Lambert;
    const SceneFeatures before = analyseScene(scene);
    ASSERT_FALSE(before.partialCoverage || before.textures || before.reflection);
    ASSERT_EQ(before.rayStackDepth, 0u);
    ASSERT_EQ(before.usefulDepth, 1u);
    scene.textures.push_back(Texture{"coverage", 1, 1, {glm::vec3(0.5f)}});
    for (Material& m : scene.materials) m.coverage = 0;
    const SceneFeatures f = analyseScene(scene);
    EXPECT_TRUE(f.partialCoverage && f.textures && f.reflection);
    EXPECT_EQ(f.rayStackDepth, scene.settings.maxDepth - 1);
    EXPECT_EQ(f.usefulDepth, scene.settings.maxDepth);
    EXPECT_TRUE(TraceSpecialization::forScene(scene, f).partialCoverage);
    EXPECT_TRUE(TraceSpecialization::general().partialCoverage);
    EXPECT_FALSE(TraceSpecialization::forScene(scene, before).partialCoverage);
    for (Material& m : scene.materials) m.model = MaterialModel::ThinGlass;
    EXPECT_FALSE(analyseScene(scene).partialCoverage) << "a thin glass's coverage";
}

// A glass that is glass only where its transmission texture says (Material::transmissionTexture)
// calls for the switch and the uvs to read it, and for its opaque part's model and what that needs
// (a lit Phong surface: shadow rays), though no triangle names the opaque part; a material no hit
// can show needs nothing.
TEST(SceneFeatures, AGlassWithATransmissionTextureNeedsItsOpaquePartsModel) {
    Scene scene = loadProjectScene("scenes/lambert_spheres.json");
    ASSERT_FALSE(scene.lights.empty());
    for (Material& m : scene.materials) m = testing::makeMaterial(MaterialModel::ThinGlass, {}, glm::vec3(0.9f));
    scene.materials.push_back(
        testing::makeMaterial(MaterialModel::Phong, glm::vec3(0.1f), glm::vec3(0.5f), glm::vec3(0.3f), 20.0f));
    scene.textures.push_back(Texture{"transmission", 2, 1, {glm::vec3(0.0f), glm::vec3(2.0f)}});
    const SceneFeatures before = analyseScene(scene);
    ASSERT_FALSE(before.transmissionTextures || before.textures || before.shadowRays);
    ASSERT_FALSE(before.uses(MaterialModel::Phong)) << "a material no triangle names";
    for (std::size_t i = 0; i + 1 < scene.materials.size(); ++i) {
        scene.materials[i].transmissionTexture = 0;
        scene.materials[i].opaquePart = int(scene.materials.size()) - 1;
    }
    const SceneFeatures f = analyseScene(scene);
    EXPECT_TRUE(f.transmissionTextures && f.textures && f.shadowRays);
    EXPECT_TRUE(f.uses(MaterialModel::Phong) && f.uses(MaterialModel::ThinGlass));
    EXPECT_TRUE(TraceSpecialization::forScene(scene, f).transmissionTextures);
    EXPECT_FALSE(TraceSpecialization::forScene(scene, before).transmissionTextures);
    EXPECT_TRUE(TraceSpecialization::general().transmissionTextures);
    for (std::size_t i = 0; i + 1 < scene.materials.size(); ++i) scene.materials[i].model = MaterialModel::Lambert;
    EXPECT_FALSE(analyseScene(scene).transmissionTextures) << "an opaque material's transmission texture";
}

TEST(SceneFeatures, GlassRestingOnAnOpaqueSurfaceNeedsTheContactCheck) {
    // A glass box on an opaque slab: standing on it, or a gap far below the touching distance
    // (1e-5 of the diagonal, here ~9e-5; the analysis looks twice as far), calls for the check;
    // a gap of 1e-3 does not, nor do opaque surfaces touching each other or glass alone.
    for (const auto& [gap, contact] : {std::pair{0.0f, true}, std::pair{1e-6f, true}, std::pair{1e-3f, false}}) {
        Scene scene = glassScene();
        addGlassBox(scene, {0, 0, gap}, {2, 2, 2});
        Material lambert;
        lambert.model = MaterialModel::Lambert;
        scene.materials.push_back(lambert);
        const std::size_t first = scene.triangles.size();
        addGlassBox(scene, {-3, -3, -1}, {3, 3, 0});
        for (std::size_t i = first; i < scene.triangles.size(); ++i) scene.triangles[i].material = 1;
        EXPECT_EQ(analyseScene(scene).opaqueContactPossible, contact) << "gap " << gap;
        EXPECT_FALSE(analyseScene(scene).touchingMediaPossible) << "gap " << gap;  // one glass object
        // The same slab in glass: two glass objects touch, and nothing is opaque.
        for (std::size_t i = first; i < scene.triangles.size(); ++i) scene.triangles[i].material = 0;
        EXPECT_FALSE(analyseScene(scene).opaqueContactPossible) << "gap " << gap;
        EXPECT_EQ(analyseScene(scene).touchingMediaPossible, contact) << "gap " << gap;
    }
    // The project's scenes: water_glass's glass stands 0.01 above its floor; the demo's glass
    // touches its floor.
    EXPECT_FALSE(featuresOf("scenes/water_glass.json").opaqueContactPossible);
    EXPECT_TRUE(featuresOf("scenes/demo.json").opaqueContactPossible);
}

TEST(SceneFeatures, OpaqueObjectsStandingOnEachOtherNeedTheCoincidenceCheckWhereARayCanComeFromBehind) {
    // An opaque box standing on another, with a glass top that lets rays in: on it, or with a gap
    // far below the touching distance (here ~6e-5; the analysis looks twice as far), a ray inside
    // the upper box can meet its bottom from behind where the lower box's top coincides; with a
    // gap of 1e-3 it cannot.
    Material lambert;
    lambert.model = MaterialModel::Lambert;
    auto stacked = [&](float gap) {
        Scene scene = glassScene();
        scene.materials.push_back(lambert);
        scene.camera.from = {1, 1, 10};
        addGlassBox(scene, {0, 0, gap}, {2, 2, 2});
        addGlassBox(scene, {-1, -1, -1}, {3, 3, 0});
        for (Triangle& t : scene.triangles) t.material = t.object == 0u && t.position[0].z == 2.0f ? 0u : 1u;
        return scene;
    };
    for (const auto& [gap, coincident] : {std::pair{0.0f, true}, std::pair{1e-6f, true}, std::pair{1e-3f, false}}) {
        Scene scene = stacked(gap);
        EXPECT_EQ(analyseScene(scene).coincidentOpaquePossible, coincident) << "gap " << gap;
        EXPECT_EQ(opaqueObjectsMetFromBehind(scene, {glm::dvec3(1, 1, 10)}), (std::set<std::uint32_t>{0u}));
        // Faces of one object never count: every mesh's neighbouring triangles touch.
        for (Triangle& t : scene.triangles) t.object = 0;
        EXPECT_FALSE(analyseScene(scene).coincidentOpaquePossible) << "one object, gap " << gap;
    }
    // Both boxes wholly opaque, closed and wound outward: no ray meets either from behind, so
    // nothing is looked for; but a camera inside one of them, or the upper box turned inside out,
    // lets rays meet it from behind.
    Scene closed = stacked(0.0f);
    for (Triangle& t : closed.triangles) t.material = 1;
    EXPECT_TRUE(opaqueObjectsMetFromBehind(closed, {glm::dvec3(1, 1, 10)}).empty());
    EXPECT_FALSE(analyseScene(closed).coincidentOpaquePossible);
    EXPECT_EQ(opaqueObjectsMetFromBehind(closed, {glm::dvec3(1, 1, 1)}), (std::set<std::uint32_t>{0u}));
    closed.camera.from = {1, 1, 1};
    EXPECT_TRUE(analyseScene(closed).coincidentOpaquePossible);
    closed.camera.from = {1, 1, 10};
    for (Triangle& t : closed.triangles)
        if (t.object == 0u) std::swap(t.position[1], t.position[2]);
    EXPECT_EQ(opaqueObjectsMetFromBehind(closed, {glm::dvec3(1, 1, 10)}), (std::set<std::uint32_t>{0u}));
    EXPECT_TRUE(analyseScene(closed).coincidentOpaquePossible);
    // The upper box open (no top): a ray can come in.
    Scene open = stacked(0.0f);
    std::erase_if(open.triangles, [](const Triangle& t) { return t.object == 0u && t.position[0].z == 2.0f; });
    EXPECT_EQ(opaqueObjectsMetFromBehind(open, {glm::dvec3(1, 1, 10)}), (std::set<std::uint32_t>{0u}));
    EXPECT_TRUE(analyseScene(open).coincidentOpaquePossible);

    // The project's scenes: the demo's plastic sphere rests on its floor, both closed; the
    // course's Cornell box has walls that are open sheets meeting one another.
    EXPECT_FALSE(featuresOf("scenes/demo.json").coincidentOpaquePossible);
    EXPECT_TRUE(featuresOf("scenes/course/cornell_box2.json").coincidentOpaquePossible);
}

TEST(SceneFeatures, MediumStackDepthCountsOverlappingBoxes) {
    Scene apart = glassScene();
    for (int i = 0; i < 5; ++i) addGlassBox(apart, {3.0f * i, 0, 0}, {3.0f * i + 2, 2, 2});  // gaps of 1
    EXPECT_EQ(analyseScene(apart).openGlassObjects, 0u);
    EXPECT_FALSE(analyseScene(apart).touchingMediaPossible);
    EXPECT_EQ(analyseScene(apart).mediumStackDepth, 1u);

    // A gap far below the touching tolerance (1e-5 of the diagonal, here ~1.2e-4) is touching;
    // one of 1e-3 is not.
    for (const auto& [gap, touching] : {std::pair{1e-6f, true}, std::pair{1e-3f, false}}) {
        Scene close = glassScene();
        addGlassBox(close, {0, 0, 0}, {2, 2, 2});
        addGlassBox(close, {2 + gap, 0, 0}, {4, 2, 2});
        addGlassBox(close, {10, 0, 0}, {12, 2, 2});
        EXPECT_EQ(analyseScene(close).touchingMediaPossible, touching) << "gap " << gap;
        EXPECT_EQ(analyseScene(close).mediumStackDepth, touching ? 2u : 1u) << "gap " << gap;
    }

    // Boxes nested three deep need 3; six deep are capped at the GPU's stack.
    Scene nested = glassScene();
    for (int i = 0; i < 3; ++i) addGlassBox(nested, glm::vec3(float(i)), glm::vec3(10.0f - i));
    EXPECT_EQ(analyseScene(nested).mediumStackDepth, 3u);
    for (int i = 3; i < 6; ++i) addGlassBox(nested, glm::vec3(float(i)), glm::vec3(10.0f - i));
    EXPECT_EQ(analyseScene(nested).mediumStackDepth, gpu::kMaxMediumDepth);
}

TEST(SceneFeatures, OpenOrBadlyWoundGlassGetsTheWholeMediumStack) {
    // A ray can leave an open mesh without having entered it, or enter one twice: its nesting
    // says nothing, so the stack keeps the general size (the same image as the general kernel).
    Scene open = glassScene();
    addGlassBox(open, {0, 0, 0}, {1, 1, 1});
    addGlassBox(open, {3, 0, 0}, {4, 1, 1});
    open.triangles.pop_back();
    EXPECT_EQ(analyseScene(open).openGlassObjects, 1u);
    EXPECT_EQ(analyseScene(open).mediumStackDepth, gpu::kMaxMediumDepth);
    Scene inverted = glassScene();
    addGlassBox(inverted, {0, 0, 0}, {1, 1, 1});
    std::swap(inverted.triangles[0].position[1], inverted.triangles[0].position[2]);  // one triangle inside out
    EXPECT_EQ(analyseScene(inverted).openGlassObjects, 1u);
    Scene duplicated = glassScene();
    addGlassBox(duplicated, {0, 0, 0}, {1, 1, 1});
    duplicated.triangles.push_back(duplicated.triangles[0]);
    EXPECT_EQ(analyseScene(duplicated).openGlassObjects, 1u);
    Scene degenerate = glassScene();  // a triangle with an edge from a point to itself
    addGlassBox(degenerate, {0, 0, 0}, {1, 1, 1});
    Triangle sliver = degenerate.triangles[0];
    sliver.position[1] = sliver.position[0];
    degenerate.triangles.push_back(sliver);
    EXPECT_EQ(analyseScene(degenerate).openGlassObjects, 1u);
    // Two closed boxes whose triangles come interleaved, not object by object: both closed.
    Scene interleaved = glassScene();
    addGlassBox(interleaved, {0, 0, 0}, {1, 1, 1});
    addGlassBox(interleaved, {3, 0, 0}, {4, 1, 1});
    const std::size_t half = interleaved.triangles.size() / 2;
    for (std::size_t i = 1; i < half; i += 2) std::swap(interleaved.triangles[i], interleaved.triangles[half + i]);
    EXPECT_EQ(analyseScene(interleaved).openGlassObjects, 0u);
    interleaved.triangles.erase(interleaved.triangles.begin() + 1);  // a triangle of the second box
    EXPECT_EQ(analyseScene(interleaved).openGlassObjects, 1u);
}

TEST(SceneFeatures, PendingRayStackFollowsMaxDepthUpToTheGpuStackWithGlassOnly) {
    Scene scene = glassScene();
    addGlassBox(scene, {0, 0, 0}, {1, 1, 1});
    for (std::uint32_t depth : {1u, 2u, 10u, 17u}) {
        scene.settings.maxDepth = depth;
        EXPECT_EQ(analyseScene(scene).rayStackDepth, depth - 1);
    }
    scene.settings.maxDepth = 0;
    EXPECT_EQ(analyseScene(scene).rayStackDepth, 0u);
    scene.settings.maxDepth = 40;
    EXPECT_EQ(analyseScene(scene).rayStackDepth, gpu::kRayStackSize);
    // Mirrors and Phong surfaces reflect, but their one child is traced at once: without glass
    // no ray ever waits, whatever the depth.
    for (MaterialModel model : {MaterialModel::Mirror, MaterialModel::Phong}) {
        scene.materials[0].model = model;
        SceneFeatures f = analyseScene(scene);
        EXPECT_TRUE(f.reflection);
        EXPECT_EQ(f.rayStackDepth, 0u);
    }
}

// Thin glass (render-model-decisions.md, "Thin-walled glass") transmits as glass refracts: its
// transmitted ray waits while the reflection is traced, so it needs the pending rays glass needs,
// but no medium stack, no touching probe and no glass-on-opaque check; its texture is read.
TEST(SceneFeatures, ThinGlassNeedsPendingRaysButNoMedium) {
    Scene scene = glassScene();
    addGlassBox(scene, {0, 0, 0}, {1, 1, 1});
    addGlassBox(scene, {1, 0, 0}, {2, 1, 1});  // touching the first
    for (Material& m : scene.materials) m.model = MaterialModel::ThinGlass;
    scene.settings.maxDepth = 10;
    SceneFeatures f = analyseScene(scene);
    EXPECT_TRUE(f.uses(MaterialModel::ThinGlass));
    EXPECT_FALSE(f.glass);
    EXPECT_TRUE(f.reflection);
    EXPECT_EQ(f.rayStackDepth, 9u);
    EXPECT_EQ(f.mediumStackDepth, 0u);
    EXPECT_FALSE(f.touchingMediaPossible);
    EXPECT_FALSE(f.opaqueContactPossible);
    EXPECT_FALSE(f.textures);
    scene.materials[0].diffuseTexture = 0;
    scene.textures.push_back(Texture{"tint", 1, 1, {glm::vec3(0.5f)}});
    EXPECT_TRUE(analyseScene(scene).textures);
    // Rays pass through its walls, so a closed, outward-wound thin-glass box is met from behind.
    EXPECT_EQ(opaqueObjectsMetFromBehind(scene, {glm::dvec3(5, 5, 5)}), (std::set<std::uint32_t>{0u, 1u}));
    // Two such boxes sharing a face: a ray in one meets the shared face from behind.
    EXPECT_TRUE(f.coincidentOpaquePossible);
}

TEST(TraceSpecialization, LambertSceneGetsAKernelWithoutGlassOrStacks) {
    Scene scene = loadProjectScene("scenes/course/geospheres_5x5.json");
    TraceSpecialization s = TraceSpecialization::forScene(scene, analyseScene(scene));
    EXPECT_TRUE(s.specialized);
    EXPECT_EQ(s.materialModels, 1u << std::uint32_t(MaterialModel::Lambert));
    EXPECT_TRUE(s.shadowRays);
    EXPECT_FALSE(s.absorption);
    EXPECT_FALSE(s.touchingProbe);
    EXPECT_FALSE(s.textures);
    EXPECT_EQ(s.backgroundKind, std::uint32_t(BackgroundKind::Constant));
    EXPECT_EQ(s.pendingRayCapacity, 0u);
    EXPECT_EQ(s.mediumStackDepth, 1u);  // never used without glass; 1 keeps the code well-formed

    TraceSpecialization general = TraceSpecialization::general();
    EXPECT_FALSE(general.specialized);
    EXPECT_EQ(general.materialModels, 0xFFFFFFFFu);
    EXPECT_EQ(general.mediumStackDepth, gpu::kMaxMediumDepth);
    EXPECT_EQ(general.pendingRayCapacity, gpu::kRayStackSize);
    EXPECT_EQ(general.backgroundKind, TraceSpecialization::kAnyKind);
    // The constants by id (shaders/shared/trace_constants.h).
    const auto c = s.constants();
    EXPECT_EQ(c[gpu::kConstantMaterialModels], s.materialModels);
    EXPECT_EQ(c[gpu::kConstantShadowRays], 1u);
    EXPECT_EQ(c[gpu::kConstantTouchingProbe], 0u);
    EXPECT_EQ(c[gpu::kConstantMediumStackDepth], 1u);
    EXPECT_EQ(c[gpu::kConstantPendingRayCapacity], 0u);
    EXPECT_EQ(c[gpu::kConstantOpaqueContact], 0u);
    EXPECT_EQ(c[gpu::kConstantCoincidentOpaque], 0u);
    EXPECT_EQ(c[gpu::kConstantResumable], 0u);  // the kernel's role: set by the pipeline, not the scene
}

}  // namespace
}  // namespace vitrum
