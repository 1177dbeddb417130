// Which cameras can be rendered (scene/camera_check.h), judged in double.
#include "scene/camera_check.h"

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

TEST(CameraCheck, AnOrdinaryCameraPasses) { EXPECT_EQ(cameraProblem(camera({0, -5, 0}, {0, 0, 0})), ""); }

// 1e20 squared is beyond float range: in float, from - at normalized to 0 and up looked parallel.
TEST(CameraCheck, FarCamerasAreJudgedByTheirGeometry) {
    EXPECT_EQ(cameraProblem(camera({1e18f, 1, 1}, {0, 0, 0})), "");
    EXPECT_NE(cameraProblem(camera({1e20f, 1, 1}, {0, 0, 0})).find("\"from\" and \"at\" are 1e+20 apart"),
              std::string::npos);
    EXPECT_NE(cameraProblem(camera({3e38f, 0, 0}, {-3e38f, 0, 1})).find("overflows"), std::string::npos);
    EXPECT_NE(cameraProblem(camera({0, -5, 0}, {0, 0, 0}, {0, 0, 1e20f})).find("\"up\" is 1e+20 long"),
              std::string::npos);
}

TEST(CameraCheck, DegenerateCamerasNameWhatIsWrong) {
    EXPECT_EQ(cameraProblem(camera({1, 2, 3}, {1, 2, 3})), "\"at\" must differ from \"from\"");
    EXPECT_EQ(cameraProblem(camera({0, -5, 0}, {0, 0, 0}, {0, 0, 0})), "\"up\" must not be zero");
    EXPECT_EQ(cameraProblem(camera({0, 0, 5}, {0, 0, 0})), "\"up\" must not be parallel to from - at");
    EXPECT_EQ(cameraProblem(camera({0, 0, 1e-30f}, {0, 0, 0}, {1e-30f, 0, 0})), "");  // tiny, not degenerate
}

}  // namespace
}  // namespace vitrum
