// The device self-check of the fast kernel's subgroup machinery (gpu/subgroup_self_check.h), the
// fallback it decides, and the Mesa 25 lavapipe defect that made the fast kernel wrong there
// (docs/gpu-design.md, "Two drivers").
#include "gpu_test_support.h"

#include <span>

#include "common/error.h"
#include "gpu/subgroup_self_check.h"
#include "gpu/trace_pipeline.h"

namespace vitrum::testing {
namespace {

bool isLavapipe() { return testDevice().name().find("llvmpipe") != std::string::npos; }

// Whether SPIR-V `code` has an instruction with `opcode` (after the 5-word header, each
// instruction's first word holds its word count above its opcode).
bool hasInstruction(std::span<const std::uint32_t> code, std::uint32_t opcode) {
    for (std::size_t i = 5; i < code.size();) {
        const std::uint32_t words = code[i] >> 16;
        if ((code[i] & 0xFFFFu) == opcode) return true;
        if (words == 0) break;
        i += words;
    }
    return false;
}

TEST(SubgroupSelfCheck, LavapipePassesItAndGetsTheFastKernel) {
    if (!isLavapipe()) GTEST_SKIP() << "what other devices get is theirs to say (vitrum devices)";
    ASSERT_TRUE(testDevice().hasFullSubgroups());
    const SubgroupSelfCheck check = checkSubgroupMachinery(testDevice());
    EXPECT_TRUE(check.passed) << check.failure;
    EXPECT_EQ(testDevice().kernelPath().rfind("fast:", 0), 0u) << testDevice().kernelPath();
}

// The fault makes one lane of one unit leave its loop at once, as a lost invocation: the check
// must name it, and a device opened with it must take the safe kernel, warn once, and render the
// image the fast kernel renders, bit for bit.
TEST(SubgroupSelfCheck, AFailedCheckGivesTheSafeKernelAndTheSameImage) {
    if (!testDevice().hasFullSubgroups()) GTEST_SKIP() << "the device has no fast kernel to fall back from";
    const SubgroupSelfCheck injected = checkSubgroupMachinery(testDevice(), false, true);
    EXPECT_FALSE(injected.passed);
    EXPECT_NE(injected.failure.find("unit 0"), std::string::npos) << injected.failure;

    Scene scene = loadScene(sourcePath("scenes/demo.json"));
    scene.camera.width = 64;
    scene.camera.height = 48;
    const Bvh bvh = buildSceneBvh(scene);
    RenderStats fastStats, safeStats;
    const Image fast = renderVulkan(testDevice(), scene, bvh, VulkanRenderOptions{}, fastStats);

    const int warningsBefore = warningCount();
    const std::uint32_t messagesBefore = testDevice().validationMessages();
    ::setenv("VITRUM_SELF_CHECK_FAULT", "1", 1);
    VulkanDevice failing(std::to_string(testDevice().description().index));
    ::unsetenv("VITRUM_SELF_CHECK_FAULT");
    EXPECT_FALSE(failing.hasFullSubgroups());
    EXPECT_EQ(failing.kernelPath().rfind("safe:", 0), 0u) << failing.kernelPath();
    EXPECT_NE(failing.kernelPath().find("self-check"), std::string::npos) << failing.kernelPath();
    EXPECT_EQ(warningCount(), warningsBefore + 1);
    EXPECT_EQ(statisticsSumsFor(failing, StatisticsSums::shuffles), StatisticsSums::subgroupAdd);
    const Image safe = renderVulkan(failing, scene, bvh, VulkanRenderOptions{}, safeStats);
    EXPECT_EQ(failing.validationMessages(), messagesBefore);  // the process's count (gpu/vulkan_instance.h)
    EXPECT_EQ(fast.pixels, safe.pixels);
    EXPECT_EQ(fastStats.primaryRays, std::uint64_t(64 * 48));
    EXPECT_EQ(countersWithoutTimes(fastStats, {"group_loop_steps", "dispatches"}),
              countersWithoutTimes(safeStats, {"group_loop_steps", "dispatches"}));
}

// The minimal kernel of the Mesa 25 lavapipe defect: the self-check with a subgroup barrier every
// round. The subgroups of a workgroup run different numbers of rounds; Mesa 25.0's lavapipe runs
// the subgroup barrier as the workgroup's, and invocations of subgroups waiting there never
// finish. trace.comp's ray sharing once ordered the donor's write before the taker's read so; it
// now hands the ray over by shuffles, and no kernel of vitrum's has a control barrier.
TEST(DriverDefects, SubgroupBarrierInSubgroupsThatRunDifferentRounds) {
    constexpr std::uint32_t kOpControlBarrier = 224;
    EXPECT_FALSE(hasInstruction(traceKernelCode(StatisticsSums::shuffles), kOpControlBarrier));
    EXPECT_FALSE(hasInstruction(traceKernelCode(StatisticsSums::atomics), kOpControlBarrier));
    if (!testDevice().hasFullSubgroups()) GTEST_SKIP() << "the device cannot run the minimal kernel";
    const SubgroupSelfCheck check = checkSubgroupMachinery(testDevice(), true);
    const std::string& driver = testDevice().description().driverInfo;
    ::testing::Test::RecordProperty("driver", driver);
    ::testing::Test::RecordProperty("subgroup_barrier", check.passed ? "right" : check.failure);
    std::printf("%s: a subgroup barrier in subgroups that run different rounds: %s\n", driver.c_str(),
                check.passed ? "every invocation finished" : check.failure.c_str());
    // Known: Mesa 22.3 runs it right, Mesa 25.0 does not. Another build says which it is.
    if (driver.rfind("Mesa 22.3", 0) == 0) {
        EXPECT_TRUE(check.passed) << check.failure;
    }
    if (driver.rfind("Mesa 25.0", 0) == 0) {
        EXPECT_FALSE(check.passed) << "the defect is gone: docs/gpu-design.md";
    }
}

}  // namespace
}  // namespace vitrum::testing
