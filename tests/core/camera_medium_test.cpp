// The media around the camera (host/analysis/camera_medium.h): the winding number that decides
// inside from outside, and the stack it gives primary rays.
#include <cmath>

#include <gtest/gtest.h>

#include "common/error.h"
#include "glass_scenes.h"
#include "analysis/camera_medium.h"
#include "analysis/scene_features.h"

#include "../support/test_meshes.h"

namespace vitrum {
namespace {

std::vector<const Triangle*> pointers(const std::vector<Triangle>& triangles) {
    std::vector<const Triangle*> result;
    for (const Triangle& t : triangles) result.push_back(&t);
    return result;
}

// A closed mesh wound counterclockwise seen from outside winds once around a point inside it and
// not at all around one outside; the same mesh wound the other way, -1.
TEST(CameraMedium, WindingNumberIsOneInsideZeroOutside) {
    const testing::IndexedMesh sphere = testing::icosphere(2, 1.0f, glm::vec3(3.0f, -2.0f, 0.5f));
    std::vector<Triangle> outward, inward;
    for (const glm::uvec3& f : sphere.faces) {
        Triangle t;
        for (int i = 0; i < 3; ++i) t.position[i] = sphere.vertices[f[i]];
        outward.push_back(t);
        std::swap(t.position[1], t.position[2]);
        inward.push_back(t);
    }
    for (const glm::dvec3 inside :
         {glm::dvec3(3.0, -2.0, 0.5), glm::dvec3(3.9, -2.0, 0.5), glm::dvec3(3.0, -2.0, -0.45)}) {
        EXPECT_NEAR(windingNumber(pointers(outward), inside), 1.0, 1e-9);
        EXPECT_NEAR(windingNumber(pointers(inward), inside), -1.0, 1e-9);
    }
    for (const glm::dvec3 outside : {glm::dvec3(0.0), glm::dvec3(4.1, -2.0, 0.5), glm::dvec3(3.0, -2.0, 1e6)})
        EXPECT_NEAR(windingNumber(pointers(outward), outside), 0.0, 1e-9);
}

// Nested boxes (a bubble in a block in a tank) around the camera, outermost first; a box beside
// the camera and an open box around it hold no medium of the camera's.
TEST(CameraMedium, NestedBoxesAroundTheCameraInnermostLast) {
    Scene scene = glassScene();
    addGlassBox(scene, glm::vec3(-1.0f), glm::vec3(1.0f));  // object 0: the block
    addGlassBox(scene, glm::vec3(3.0f), glm::vec3(4.0f));   // object 1: beside the camera
    addGlassBox(scene, glm::vec3(-0.2f), glm::vec3(0.2f));  // object 2: the bubble
    addGlassBox(scene, glm::vec3(-5.0f), glm::vec3(5.0f));  // object 3: the tank
    addGlassBox(scene, glm::vec3(-0.5f), glm::vec3(0.5f));  // object 4: open, one face missing
    scene.triangles.pop_back();
    scene.camera.from = glm::vec3(0.05f, -0.1f, 0.0f);
    EXPECT_EQ(analyseScene(scene).cameraMedia, (std::vector<std::uint32_t>{3, 0, 2}));
    scene.camera.from = glm::vec3(0.5f, 0.0f, 0.0f);  // in the block, beside the bubble
    EXPECT_EQ(analyseScene(scene).cameraMedia, (std::vector<std::uint32_t>{3, 0}));
    scene.camera.from = glm::vec3(6.0f, 0.0f, 0.0f);  // in air
    EXPECT_TRUE(analyseScene(scene).cameraMedia.empty());
}

// The GPU's stack holds four media: a camera inside five nested boxes starts inside the four
// innermost (on both backends), and the user is told.
TEST(CameraMedium, MoreMediaThanTheStackHoldsKeepsTheInnermostWithAWarning) {
    Scene scene = glassScene();
    for (int i = 0; i < 5; ++i) addGlassBox(scene, glm::vec3(-1.0f - float(i)), glm::vec3(1.0f + float(i)));
    scene.camera.from = glm::vec3(0.0f);
    const int warnings = warningCount();
    EXPECT_EQ(analyseScene(scene).cameraMedia, (std::vector<std::uint32_t>{3, 2, 1, 0}));
    EXPECT_EQ(warningCount(), warnings + 1);
}

// The camera lies on a triangle when it is closer to it than the offset a ray starting there gets
// along its normal (analysis/camera_surface.h): 32 float ulps of the coordinates here. Primary rays
// then start off it, with the media of their side: above the top face of a glass box, air; below
// it, the box.
TEST(CameraSurface, TheCameraLiesOnATriangleWithinItsRayOffset) {
    Scene scene = glassScene();
    addGlassBox(scene, glm::vec3(-1.0f), glm::vec3(1.0f));
    auto ulpsAbove = [](int n) {
        float z = 1.0f;
        for (int i = 0; i < n; ++i) z = std::nextafter(z, 2.0f);
        return z;
    };
    for (int ulps : {0, 8, 31}) {
        SCOPED_TRACE(ulps);
        scene.camera.from = glm::vec3(0.3f, 0.2f, ulpsAbove(ulps));
        const SceneFeatures f = analyseScene(scene);
        EXPECT_EQ(f.cameraSurface.triangles, 1u);
        EXPECT_EQ(f.cameraSurface.normal, glm::vec3(0.0f, 0.0f, 1.0f));
        EXPECT_FALSE(f.cameraSurface.otherPlanes);
        EXPECT_TRUE(f.cameraMedia.empty());
        EXPECT_EQ(f.cameraMediaBehind, std::vector<std::uint32_t>{0});
    }
    for (float z : {ulpsAbove(33), 1.001f, 0.999f}) {
        SCOPED_TRACE(z);
        scene.camera.from = glm::vec3(0.3f, 0.2f, z);
        const SceneFeatures f = analyseScene(scene);
        EXPECT_EQ(f.cameraSurface.triangles, 0u);
        EXPECT_EQ(f.cameraSurface.normal, glm::vec3(0.0f));
        EXPECT_EQ(f.cameraMedia, f.cameraMediaBehind);
        EXPECT_EQ(f.cameraMedia.size(), z < 1.0f ? 1u : 0u);
    }
    // On the diagonal the top face's two triangles share: one plane.
    scene.camera.from = glm::vec3(0.5f, 0.5f, 1.0f);
    EXPECT_EQ(analyseScene(scene).cameraSurface.triangles, 2u);
    EXPECT_FALSE(analyseScene(scene).cameraSurface.otherPlanes);
    // On an edge, where the top face meets a side at a right angle: the user is told.
    scene.camera.from = glm::vec3(1.0f, 0.2f, 1.0f);
    const int warnings = warningCount();
    const SceneFeatures edge = analyseScene(scene);
    EXPECT_TRUE(edge.cameraSurface.otherPlanes);
    EXPECT_EQ(warningCount(), warnings + 1);
}

}  // namespace
}  // namespace vitrum
