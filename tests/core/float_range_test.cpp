// Which cameras can be rendered (scene/float_range.h), judged in double.
#include "scene/float_range.h"

#include <gtest/gtest.h>

namespace vitrum {
namespace {

Camera camera(glm::vec3 from, glm::vec3 at, glm::vec3 up = {0.0f, 0.0f, 1.0f}) {
    Camera c;
    c.from = from;
    c.at = at;
    c.up = up;
    return c;
}

TEST(FloatRange, AnOrdinaryCameraPasses) { EXPECT_EQ(cameraProblem(camera({0, -5, 0}, {0, 0, 0})), ""); }

// 1e20 squared is beyond float range: in float, from - at normalized to 0 and up looked parallel.
TEST(FloatRange, FarCamerasAreJudgedByTheirGeometry) {
    EXPECT_EQ(cameraProblem(camera({1e18f, 1, 1}, {0, 0, 0})), "");
    EXPECT_NE(cameraProblem(camera({1e20f, 1, 1}, {0, 0, 0})).find("\"from\" and \"at\" are apart by 1e+20"),
              std::string::npos);
    EXPECT_NE(cameraProblem(camera({3e38f, 0, 0}, {-3e38f, 0, 1})).find("overflows"), std::string::npos);
    EXPECT_NE(cameraProblem(camera({0, -5, 0}, {0, 0, 0}, {0, 0, 1e20f})).find("\"up\" is as long as 1e+20"),
              std::string::npos);
}

TEST(FloatRange, DegenerateCamerasNameWhatIsWrong) {
    EXPECT_EQ(cameraProblem(camera({1, 2, 3}, {1, 2, 3})), "\"at\" must differ from \"from\"");
    EXPECT_EQ(cameraProblem(camera({0, -5, 0}, {0, 0, 0}, {0, 0, 0})), "\"up\" must not be zero");
    EXPECT_EQ(cameraProblem(camera({0, 0, 5}, {0, 0, 0})), "\"up\" must not be parallel to from - at");
    EXPECT_EQ(cameraProblem(camera({0, 0, 1e-30f}, {0, 0, 0}, {1e-30f, 0, 0})), "");  // tiny, not degenerate
}

// A light 3e38 away lit nothing: its direction from a surface normalized to NaN.
TEST(FloatRange, LightsAreJudgedByTheirDistanceFromTheScene) {
    Scene scene;
    Triangle t{};
    t.position[0] = {0, 0, 0};
    t.position[1] = {1, 0, 0};
    t.position[2] = {0, 1, 0};
    scene.triangles.push_back(t);
    scene.lights.push_back({.position = {3, 0, 5}});
    scene.lights.push_back({.position = {1e18f, 0, 0}});
    EXPECT_FALSE(lightProblem(scene).has_value());
    scene.lights.push_back({.position = {3e38f, 0, 5}});
    const auto problem = lightProblem(scene);
    ASSERT_TRUE(problem.has_value());
    EXPECT_EQ(problem->light, 2u);
    EXPECT_NE(problem->message.find("as far from the scene's triangles as 3e+38"), std::string::npos);
}

}  // namespace
}  // namespace vitrum
