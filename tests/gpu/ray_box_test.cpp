// The traversal's ray/box test (shaders/ray_box.glsl) on lavapipe through tests/gpu/kernels/box_test.comp,
// on the cases where its arithmetic is degenerate: a ray in the plane of a face (0 * inf is NaN,
// and the axis must not constrain the segment), flat boxes of axis-aligned triangles, and
// segments that end on a face. Each expectation is the slab test worked out by hand for the
// unit box [0, 1]^3.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "test_kernels.h"
#include "gpu_test_support.h"

namespace vitrum::testing {
namespace {

using glm::vec3;

struct Case {
    const char* what;
    vec3 boxMin, boxMax, origin, direction;
    float tMin, tMax;
    bool hit;
};

constexpr float kFar = 3.0e38f;

const std::vector<Case> kCases = {
    {"straight through the middle", vec3(0), vec3(1), vec3(0.5f, 0.5f, -1), vec3(0, 0, 1), 0, kFar, true},
    {"the segment ends before the box", vec3(0), vec3(1), vec3(0.5f, 0.5f, -1), vec3(0, 0, 1), 0, 0.5f, false},
    {"the segment starts beyond the box", vec3(0), vec3(1), vec3(0.5f, 0.5f, -1), vec3(0, 0, 1), 3, kFar, false},
    {"the segment ends on the near face", vec3(0), vec3(1), vec3(0.5f, 0.5f, -1), vec3(0, 0, 1), 0, 1, true},
    {"pointing away", vec3(0), vec3(1), vec3(0.5f, 0.5f, -1), vec3(0, 0, -1), 0, kFar, false},
    // d.x = 0 and the origin on the face x = 1: (1 - 1) * inf is NaN, the axis is skipped.
    {"in the plane of the face x = 1", vec3(0), vec3(1), vec3(1, 0.5f, -1), vec3(0, 0, 1), 0, kFar, true},
    {"in the plane of the face x = 0", vec3(0), vec3(1), vec3(0, 0.5f, -1), vec3(0, 0, 1), 0, kFar, true},
    {"in a face plane, with d.x = -0", vec3(0), vec3(1), vec3(1, 0.5f, -1), vec3(-0.0f, 0, 1), 0, kFar, true},
    {"along an edge (two NaN axes)", vec3(0), vec3(1), vec3(1, 1, -1), vec3(0, 0, 1), 0, kFar, true},
    {"parallel to a face, outside the slab", vec3(0), vec3(1), vec3(1.5f, 0.5f, -1), vec3(0, 0, 1), 0, kFar, false},
    {"in a face plane, but past the box", vec3(0), vec3(1), vec3(1, 2, -1), vec3(0, 0, 1), 0, kFar, false},
    // A NaN axis next to one that misses: the NaN must not hide the miss, whichever its place.
    {"in the face plane y = 0, before the slab in x", vec3(0), vec3(1), vec3(-0.5f, 0, -1), vec3(0, 0, 1), 0, kFar,
     false},
    {"in the face plane y = 1, past the slab in x", vec3(0), vec3(1), vec3(1.5f, 1, -1), vec3(0, 0, 1), 0, kFar, false},
    {"in the face plane x = 1, past the slab in y", vec3(0), vec3(1), vec3(1, 1.5f, -1), vec3(0, 0, 1), 0, kFar, false},
    {"in the face plane x = 0, before the slab in y", vec3(0), vec3(1), vec3(0, -0.5f, -1), vec3(0, 0, 1), 0, kFar,
     false},
    // The box of an axis-aligned triangle has no thickness.
    {"a flat box, in its plane", vec3(0, 0, 0), vec3(1, 1, 0), vec3(-1, 0.5f, 0), vec3(1, 0, 0), 0, kFar, true},
    {"a flat box, head on", vec3(0, 0, 0), vec3(1, 1, 0), vec3(0.5f, 0.5f, -1), vec3(0, 0, 1), 0, kFar, true},
    {"a flat box, just beside it", vec3(0, 0, 0), vec3(1, 1, 0), vec3(0.5f, 0.5f, 0.001f), vec3(1, 0, 0), 0, kFar,
     false},
    {"the origin inside, every direction component 0 but one", vec3(0), vec3(1), vec3(0.5f), vec3(0, 1, 0), 0, kFar,
     true},
};

TEST(GlslRayBox, DegenerateSlabsFollowTheSlabTest) {
    std::vector<BoxCase> cases;
    for (const Case& c : kCases)
        cases.push_back({glm::vec4(c.boxMin, c.tMin), glm::vec4(c.boxMax, c.tMax), glm::vec4(c.origin, 0.0f),
                         glm::vec4(c.direction, 0.0f)});
    const std::uint32_t before = testDevice().validationMessages();
    const std::vector<BoxResult> results = evaluateBoxTestsOnGpu(testDevice(), cases);
    EXPECT_EQ(testDevice().validationMessages(), before) << "Vulkan validation messages in box_test.comp";
    ASSERT_EQ(results.size(), kCases.size());
    for (std::size_t i = 0; i < kCases.size(); ++i)
        EXPECT_EQ(results[i].hit.x != 0u, kCases[i].hit) << kCases[i].what;
}

}  // namespace
}  // namespace vitrum::testing
