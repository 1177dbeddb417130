// Lanes that take pending rays from the other lanes of their SIMD group (shaders/ray_sharing.glsl)
// change how many steps the groups run and nothing else. The kernel shares where subgroups are
// full (StatisticsSums::shuffles, lavapipe's default); the build that sums by subgroupAdd runs the
// same loops and subgroup counts without sharing, so it is the reference.
#include "gpu_test_support.h"

#include <nlohmann/json.hpp>

namespace vitrum::testing {
namespace {

Scene diamond(std::uint32_t width, std::uint32_t height, std::uint32_t maxDepth) {
    Scene scene = loadScene(sourcePath("scenes/diamond.json"));
    scene.camera.width = width;
    scene.camera.height = height;
    scene.settings.maxDepth = maxDepth;
    return scene;
}

struct Render {
    Image image;
    RenderStats stats;
};

Render render(const Scene& scene, StatisticsSums sums, std::uint32_t budget = VulkanRenderOptions{}.iterationBudget) {
    Render r;
    r.image = renderVulkan(testDevice(), scene, buildSceneBvh(scene),
                           VulkanRenderOptions{.iterationBudget = budget, .statisticsSums = sums}, r.stats);
    return r;
}

// Every counter but the time and the groups' steps.
nlohmann::json counters(const RenderStats& stats) { return countersWithoutTimes(stats, {"group_loop_steps"}); }

// Whether the device's kernel shares rays; lavapipe's must. (A test skips itself with GTEST_SKIP
// in its own body: in a helper it would only return from the helper.)
bool sharesRays() {
    if (testDevice().name().find("llvmpipe") != std::string::npos) {
        EXPECT_TRUE(testDevice().hasFullSubgroups());
    }
    return statisticsSumsFor(testDevice(), StatisticsSums::shuffles) == StatisticsSums::shuffles;
}
constexpr const char* kNoSharing = "the device cannot require full subgroups: its kernel does not share rays";

// The diamond's deep trees of internal reflections at depth 24 leave pixels with long queues of
// pending rays beside pixels that are long done; its pending-ray stack (16 rays) overflows, so
// the refractions it drops must be the same too (a taken ray's tree starts at its index in its
// owner's stack, not at the bottom of the taker's: that drops 82 instead of 110 here). The
// image must be the same bit for bit (the colour is a sum in fixed point), and so must every
// counter: the rays, the limits, each pixel's steps (a taken tree's steps go back to its pixel:
// max_pixel_loop_steps) and their sum. The budget is one that gives up no pixel without sharing
// either.
TEST(RaySharing, TakenRaysChangeNothingButTheGroupsSteps) {
    if (!sharesRays()) GTEST_SKIP() << kNoSharing;
    const Scene scene = diamond(8, 6, 24);
    const Render shared = render(scene, StatisticsSums::shuffles, 65400);
    const Render alone = render(scene, StatisticsSums::subgroupAdd, 65400);
    EXPECT_EQ(shared.image.pixels, alone.image.pixels);
    EXPECT_EQ(counters(shared.stats), counters(alone.stats));
    EXPECT_GT(shared.stats.rayStackOverflows, 0u) << "the scene no longer overflows the pending-ray stack";
    EXPECT_EQ(alone.stats.restartedPixels, 0u);
    // The point of it: idle lanes worked, so the groups ran fewer steps; never fewer than the
    // lanes' steps spread evenly over all lanes.
    EXPECT_LT(shared.stats.groupLoopSteps, alone.stats.groupLoopSteps);
    EXPECT_GE(shared.stats.groupLoopSteps * shared.stats.lanesPerGroup, shared.stats.loopSteps);
}

// With 4 samples a pixel, a pixel's lane goes on to its next sample while other lanes trace the
// trees its last one left pending. Without sharing, some groups here need more than one dispatch
// (and the pixels they give up are traced again by the resumable kernel, which never shares):
// the dispatches and restarts differ, and a pixel suspended there counts a step or two more
// where it resumes; what is traced does not differ.
TEST(RaySharing, TakenRaysOfEarlierSamplesChangeNothingThatIsTraced) {
    if (!sharesRays()) GTEST_SKIP() << kNoSharing;
    Scene scene = diamond(8, 6, 20);
    scene.settings.samplesPerPixel = 4;
    const Render shared = render(scene, StatisticsSums::shuffles, 65400);
    const Render alone = render(scene, StatisticsSums::subgroupAdd, 65400);
    EXPECT_EQ(shared.image.pixels, alone.image.pixels);
    nlohmann::json a = counters(shared.stats), b = counters(alone.stats);
    for (const char* differs :
         {"dispatches", "restarted_pixels", "restarted_steps", "loop_steps", "max_pixel_loop_steps"}) {
        a.erase(differs);
        b.erase(differs);
    }
    EXPECT_EQ(a, b);
    EXPECT_GT(shared.stats.rayStackOverflows, 0u) << "the scene no longer overflows the pending-ray stack";
    EXPECT_LT(shared.stats.groupLoopSteps, alone.stats.groupLoopSteps);
}

// A group cut by the step budget after one of its lanes took a ray gives up all its pixels, also
// the finished ones (their rays may be in another lane's counters, a taken tree unfinished); the
// resumable kernel traces them again, and the image and the rays are still those of one
// dispatch. A 4x2 image is one SIMD group on lavapipe: with a budget one step short of what the
// sharing group needs, all 8 pixels are given up, while without sharing only those still
// unfinished at that step are.
TEST(RaySharing, AGroupCutAfterATakeGivesUpAllItsPixels) {
    if (!sharesRays()) GTEST_SKIP() << kNoSharing;
    if (testDevice().subgroups().size < 8) GTEST_SKIP() << "a 4x2 image is more than one subgroup";
    const Scene scene = diamond(4, 2, 10);
    const Render whole = render(scene, StatisticsSums::shuffles);
    const Render wholeAlone = render(scene, StatisticsSums::subgroupAdd);
    ASSERT_EQ(whole.stats.dispatches, 1u);
    ASSERT_LT(whole.stats.groupLoopSteps, wholeAlone.stats.groupLoopSteps) << "no lane took a ray";
    const auto budget = std::uint32_t(whole.stats.groupLoopSteps - 1);
    ASSERT_GE(budget, kMinIterationBudget);

    const Render cut = render(scene, StatisticsSums::shuffles, budget);
    const Render cutAlone = render(scene, StatisticsSums::subgroupAdd, budget);
    EXPECT_EQ(cut.stats.restartedPixels, 8u);
    EXPECT_GT(cutAlone.stats.restartedPixels, 0u);
    EXPECT_LT(cutAlone.stats.restartedPixels, 8u);
    for (const Render* r : {&cut, &cutAlone}) {
        EXPECT_EQ(r->image.pixels, whole.image.pixels);
        EXPECT_EQ(toJson(r->stats)["rays"], toJson(whole.stats)["rays"]);
        EXPECT_EQ(r->stats.nodeVisits, whole.stats.nodeVisits);
        EXPECT_EQ(r->stats.loopLimitSuspected, 0u);
    }
}

}  // namespace
}  // namespace vitrum::testing
