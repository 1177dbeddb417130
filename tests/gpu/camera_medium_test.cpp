// A camera inside glass (render model: "Primary rays start with the camera's medium"): primary
// rays start with the media around the camera on both backends (host/analysis/camera_medium.h).
#include "gpu_test_support.h"

#include <cmath>

namespace vitrum::testing {
namespace {

// Inside one_box.json's box (x in [-1, 1], IOR 1.5), given absorption mu, looking head-on at its
// face x = 1 from x = -0.5. The centre pixel's primary ray travels 1.5 through the glass (Beer-
// Lambert exp(-1.5 mu)) and leaves it at normal incidence, where Fresnel gives R0 = ((1.5 - 1) /
// (1.5 + 1))^2 = 0.04 with either model: (1 - R0) of the white background comes through. Its
// reflection (depth 1) can start no traced child at max_depth 2, so it adds nothing. A camera
// taken to be in air would see 0.96 unattenuated, and its ray would leave a box it never entered.
TEST(CameraMedium, LookingOutOfAnAbsorbingBoxIsBeerLambertTimesFresnel) {
    const glm::vec3 mu(0.5f, 1.0f, 2.0f);
    for (FresnelModel fresnel : {FresnelModel::Exact, FresnelModel::Schlick}) {
        Scene scene = loadScene(sourcePath("scenes/one_box.json"));
        for (Material& m : scene.materials)
            if (m.model == MaterialModel::Glass) m.attenuation = mu;
        scene.camera = {.from = {-0.5f, 0, 0}, .at = {1, 0, 0}, .up = {0, 0, 1}, .fovY = 10, .width = 9, .height = 9};
        scene.lights.clear();
        scene.background.colour = glm::vec3(1.0f);
        scene.settings.maxDepth = 2;
        scene.settings.fresnel = fresnel;
        RenderPair r = renderBoth(scene);
        for (const Image* image : {&r.gpu, &r.cpu}) {
            const glm::vec3 centre = image->at(4, 4);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(centre[c], std::exp(-1.5 * mu[c]) * 0.96, 1e-5) << c;
        }
        EXPECT_EQ(r.gpuStats.inconsistentMedia, 0u);
        EXPECT_EQ(r.cpuStats.inconsistentMedia, 0u);
    }
}

// bubble.json's air bubble (radius 0.35 around (0, 0, 1)) sits in a tinted glass block: a camera
// at its centre starts two media deep, block then bubble, and every ray finds the stack it
// expects when it leaves an object: none leaves one it is not inside.
TEST(CameraMedium, CameraInTheBubbleStartsInsideBlockAndBubble) {
    Scene scene = loadScene(sourcePath("scenes/bubble.json"));
    scene.camera = {.from = {0, 0, 1}, .at = {0.3f, -1, 0.6f}, .up = {0, 0, 1}, .fovY = 70, .width = 64, .height = 48};
    scene.settings.fresnel = FresnelModel::Exact;
    RenderPair r = renderBoth(scene);
    expectImagesMatch(r);
    EXPECT_EQ(r.gpuStats.inconsistentMedia, 0u);
    EXPECT_EQ(r.cpuStats.inconsistentMedia, 0u);
    EXPECT_EQ(r.gpuStats.maxMediumDepth, 2u);
    EXPECT_EQ(r.gpuStats.mediumStackOverflows, 0u);
    EXPECT_GT(imageSpread(r.gpu), 0.01);  // the floor and the block's walls, not one flat colour
}

}  // namespace
}  // namespace vitrum::testing
