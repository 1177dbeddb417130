// Scene analysis: what each project scene can need, checked against what the scene contains.
#include <gtest/gtest.h>

#include "render/scene_features.h"
#include "scene/scene_loader.h"

namespace vitrum {
namespace {

SceneFeatures featuresOf(const std::string& scene) {
    return analyseScene(loadScene(std::string(VITRUM_SOURCE_DIR) + "/" + scene));
}

TEST(SceneFeatures, OpaqueLambertSceneNeedsNoGlassAndNoSecondaryRays) {
    SceneFeatures f = featuresOf("scenes/course/cornell_box2.json");
    // cornell_box2 has a clear_glass sphere: glass, one object.
    EXPECT_TRUE(f.glass);
    EXPECT_EQ(f.glassObjects, 1u);
    EXPECT_FALSE(f.touchingMediaPossible);
    SceneFeatures g = featuresOf("scenes/course/geospheres_5x5.json");  // shader 5: Lambert only
    EXPECT_FALSE(g.glass);
    EXPECT_FALSE(g.reflection);
    EXPECT_TRUE(g.shadowRays);
    EXPECT_EQ(g.usefulDepth, 1u);
}

TEST(SceneFeatures, GlassScenesReportTheirMedia) {
    SceneFeatures touching = featuresOf("scenes/touching_cubes.json");
    EXPECT_TRUE(touching.glass);
    EXPECT_EQ(touching.glassObjects, 2u);
    EXPECT_TRUE(touching.touchingMediaPossible);
    EXPECT_EQ(touching.usefulDepth, 10u);
    SceneFeatures green = featuresOf("scenes/plastics_green_glass.json");
    EXPECT_TRUE(green.absorbingMedia);  // Tf 0.4 0.001 0.4
    SceneFeatures demo = featuresOf("scenes/demo.json");
    EXPECT_TRUE(demo.absorbingMedia);
    EXPECT_EQ(featuresOf("scenes/glass_sphere_cube.json").background, BackgroundKind::Cube);
    EXPECT_EQ(featuresOf("scenes/glass_sphere_spherical.json").background, BackgroundKind::Spherical);
}

}  // namespace
}  // namespace vitrum
