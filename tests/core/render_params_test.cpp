// The parameters the GPU reads (shaders/shared/render_params.h), made from a scene: each lane
// read back through its accessor holds what the scene and its analysis say.
#include <gtest/gtest.h>

#include <cmath>

#include "../support/scenes_in_code.h"
#include "gpu_input/render_params.h"
#include "shared/gpu_types.h"
#include "analysis/scene_features.h"

namespace vitrum {
namespace {

using testing::addBox;
using testing::makeMaterial;

TEST(RenderParams, EveryLaneHoldsWhatTheSceneSays) {
    Scene scene;
    scene.camera.from = glm::vec3(0.0f, -4.0f, 0.0f);
    scene.camera.width = 40;
    scene.camera.height = 30;
    scene.camera.fovY = 60.0f;
    scene.settings.samplesPerPixel = 8;
    scene.settings.maxDepth = 7;
    scene.settings.minWeight = 0.25f;
    scene.settings.fresnel = FresnelModel::Exact;
    scene.settings.filter = TextureFilter::Nearest;
    scene.background.colour = glm::vec3(0.1f, 0.2f, 0.3f);
    scene.airIor = 1.25f;
    scene.lights.resize(2);
    scene.materials.push_back(makeMaterial(MaterialModel::Glass, glm::vec3(0), glm::vec3(0)));
    scene.objectNames = {"a", "b"};
    // Two glass boxes, the camera inside the first.
    addBox(scene, glm::vec3(-5.0f), glm::vec3(5.0f), 0, 0);
    addBox(scene, glm::vec3(1.0f), glm::vec3(2.0f), 0, 1);
    const SceneFeatures features = analyseScene(scene);
    const gpu::RenderParams p = makeRenderParams(scene, features, 123u, 4567u);

    EXPECT_EQ(gpu::cameraPosition(p), scene.camera.from);
    EXPECT_FLOAT_EQ(gpu::focalLength(p), 30.0f / (2.0f * std::tan(glm::radians(30.0f))));
    EXPECT_EQ(gpu::cameraAxisZ(p), glm::vec3(0.0f, -1.0f, 0.0f));  // from the target back to the camera
    EXPECT_EQ(gpu::cameraAxisX(p), glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(gpu::cameraAxisY(p), glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(gpu::backgroundColour(p), scene.background.colour);
    EXPECT_EQ(gpu::airIor(p), 1.25f);
    EXPECT_EQ(gpu::imageWidth(p), 40u);
    EXPECT_EQ(gpu::imageHeight(p), 30u);
    EXPECT_EQ(gpu::samplesPerPixel(p), 8u);
    EXPECT_EQ(gpu::sampleGridColumns(p), 2u);  // 8 samples: 2 columns x 4 rows
    EXPECT_EQ(gpu::maxDepth(p), 7u);
    EXPECT_EQ(gpu::iterationBudget(p), 4567u);
    EXPECT_EQ(gpu::lightCount(p), 2u);
    EXPECT_EQ(gpu::textureCount(p), 0u);
    EXPECT_EQ(gpu::fresnelModelOf(p), gpu::kFresnelExact);
    EXPECT_EQ(gpu::backgroundKindOf(p), gpu::kBackgroundConstant);
    EXPECT_EQ(gpu::textureFilterOf(p), gpu::kFilterNearest);
    EXPECT_EQ(gpu::minWeight(p), 0.25f);
    EXPECT_EQ(gpu::touchingDistance(p), float(features.touchingDistance));
    EXPECT_TRUE(gpu::touchingProbeOn(p));  // two glass objects
    EXPECT_EQ(gpu::opaqueContactOn(p), features.opaqueContactPossible);
    EXPECT_EQ(gpu::coincidentOpaqueOn(p), features.coincidentOpaquePossible);
    EXPECT_EQ(gpu::bvhRoot(p), 123u);
    ASSERT_EQ(features.cameraMedia, std::vector<std::uint32_t>{0u});
    EXPECT_EQ(gpu::cameraMediaCount(p), 1u);
    EXPECT_EQ(p.cameraMedia.x, 0u);
    // The camera lies on no surface: the media behind are the same.
    EXPECT_EQ(gpu::cameraSurfaceNormal(p), glm::vec3(0.0f));
    EXPECT_EQ(gpu::cameraMediaBehindCount(p), 1u);
    EXPECT_EQ(p.cameraMediaBehind.x, 0u);
}

}  // namespace
}  // namespace vitrum
