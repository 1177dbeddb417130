// The GPU (lavapipe) against the CPU reference, scene by scene, with the thresholds of
// gpu_test_support.h.
#include "gpu_test_support.h"

namespace vitrum::testing {
namespace {

Scene loadSmall(const std::string& path, std::uint32_t width, std::uint32_t height) {
    Scene scene = loadScene(path);
    scene.camera.width = width;
    scene.camera.height = height;
    return scene;
}

TEST(ImageDiff, GeosphereFromCommandLineCameraMatchesReference) {
    // The "done when" case: the bare course OBJ with camera and light given by hand.
    Scene scene = loadScene(sharedPath("scenes/course/geosphere/geosphere.obj"));
    scene.camera.from = {3, -3, 1};
    scene.camera.at = {0, 0, 0};
    scene.camera.width = 160;
    scene.camera.height = 120;
    scene.lights = {{.position = {4, -6, 5}, .colour = glm::vec3(1.0f)}};
    expectImagesMatch(renderBoth(scene));
}

TEST(ImageDiff, CornellBox2MatchesReference) {
    expectImagesMatch(renderBoth(loadSmall(sourcePath("scenes/course/cornell_box2.json"), 160, 120)));
}

TEST(ImageDiff, Geospheres5x5MatchesReference) {
    expectImagesMatch(renderBoth(loadSmall(sourcePath("scenes/course/geospheres_5x5.json"), 160, 120)));
}

TEST(ImageDiff, Geospheres5x5WithFourSamplesMatchesReference) {
    Scene scene = loadSmall(sourcePath("scenes/course/geospheres_5x5.json"), 96, 72);
    scene.settings.samplesPerPixel = 4;
    expectImagesMatch(renderBoth(scene));
}

TEST(ImageDiff, DemoSceneMatchesReference) {
    expectImagesMatch(renderBoth(loadSmall(sourcePath("scenes/demo.json"), 160, 120)));
}

TEST(ImageDiff, LambertSpheresMatchReference) {
    expectImagesMatch(renderBoth(loadSmall(sourcePath("scenes/lambert_spheres.json"), 160, 120)));
}

}  // namespace
}  // namespace vitrum::testing
