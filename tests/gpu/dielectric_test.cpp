// Glass, water and plastic: the ray tree with its medium stack, GPU against CPU on every
// dielectric scene at depth 10 with both Fresnel models, touching media, and the loop limit.
#include "gpu_test_support.h"
#include "common/error.h"

#include <nlohmann/json.hpp>

namespace vitrum::testing {
namespace {

Scene loadSized(const std::string& scene, std::uint32_t width, std::uint32_t height, FresnelModel fresnel) {
    Scene s = loadScene(sourcePath(scene));
    s.camera.width = width;
    s.camera.height = height;
    s.settings.maxDepth = 10;
    s.settings.fresnel = fresnel;
    return s;
}

struct DielectricCase {
    const char* scene;
    FresnelModel fresnel;
};

class DielectricScene : public ::testing::TestWithParam<DielectricCase> {};

TEST_P(DielectricScene, GpuMatchesReferenceAtDepth10) {
    RenderPair r = renderBoth(loadSized(GetParam().scene, 96, 72, GetParam().fresnel));
    expectImagesMatch(r);
    EXPECT_EQ(r.gpuStats.loopLimitSuspected, 0u);
    EXPECT_GT(r.gpuStats.refractionRays, 0u);
    EXPECT_GT(r.gpuStats.reflectionRays, 0u);
}

std::string caseName(const ::testing::TestParamInfo<DielectricCase>& info) {
    std::string name = std::filesystem::path(info.param.scene).stem().string();
    name += info.param.fresnel == FresnelModel::Exact ? "_exact" : "_schlick";
    std::erase_if(name, [](char c) { return !std::isalnum(static_cast<unsigned char>(c)) && c != '_'; });
    return name;
}

const char* kDielectricScenes[] = {"scenes/demo.json",           "scenes/touching_cubes.json",
                                   "scenes/one_box.json",        "scenes/water_glass.json",
                                   "scenes/prism.json",          "scenes/plastics_green_glass.json",
                                   "scenes/bubble.json",         "scenes/thin_glass.json",
                                   "scenes/course/geospheres_5x5_glass.json"};

std::vector<DielectricCase> allCases() {
    std::vector<DielectricCase> cases;
    for (const char* scene : kDielectricScenes)
        for (FresnelModel f : {FresnelModel::Schlick, FresnelModel::Exact}) cases.push_back({scene, f});
    return cases;
}

INSTANTIATE_TEST_SUITE_P(Scenes, DielectricScene, ::testing::ValuesIn(allCases()), caseName);

// Lecture, "Problematic Cases": touching glass cubes are one interface glass -> glass at the
// shared face (P2: 1.5 to 1.5), so they render like one box of the same outer shape. The only
// difference allowed is rounding where the ray restarts beyond the shared face.
TEST(TouchingMedia, TouchingGlassCubesMatchOneBoxOnBothBackends) {
    RenderPair touching = renderBoth(loadSized("scenes/touching_cubes.json", 160, 120, FresnelModel::Exact));
    RenderPair oneBox = renderBoth(loadSized("scenes/one_box.json", 160, 120, FresnelModel::Exact));
    for (auto [a, b] : {std::pair{&touching.gpu, &oneBox.gpu}, std::pair{&touching.cpu, &oneBox.cpu}}) {
        ImageDiff d = diffImages(*a, *b);
        EXPECT_LE(d.shareOver1of255, 0.001) << "psnr " << d.psnr;
        EXPECT_LE(d.maxAbsError, 0.02);
    }
    EXPECT_GT(touching.gpuStats.touchingInterfaces, 0u);
    EXPECT_EQ(oneBox.gpuStats.touchingInterfaces, 0u);
    // Leaving one cube and entering the other never stacks both: one medium at a time.
    EXPECT_EQ(touching.gpuStats.maxMediumDepth, 1u);
    EXPECT_EQ(touching.gpuStats.mediumStackOverflows, 0u);
}

// Without the merged interface the shared face would be glass -> air -> glass: two extra
// Fresnel reflections (R = 0.04 at normal incidence each way) that one box does not have. Seen
// head-on through both cubes, the centre pixel must therefore be the one box's value, not
// (1 - 0.04)^2 = 0.92 of it.
TEST(TouchingMedia, SharedFaceAddsNoReflectionHeadOn) {
    Scene touching = loadScene(sourcePath("scenes/touching_cubes.json"));
    Scene oneBox = loadScene(sourcePath("scenes/one_box.json"));
    for (Scene* s : {&touching, &oneBox}) {
        s->camera = {.from = {-6, 0, 0.51f}, .at = {0, 0, 0.51f}, .up = {0, 0, 1}, .fovY = 10, .width = 9, .height = 9};
        s->lights.clear();
        s->background.colour = glm::vec3(1.0f);
        s->settings.fresnel = FresnelModel::Exact;
    }
    RenderPair a = renderBoth(touching);
    RenderPair b = renderBoth(oneBox);
    glm::vec3 ta = a.gpu.at(4, 4), tb = b.gpu.at(4, 4);
    EXPECT_NEAR(ta.x, tb.x, 1e-4);
    EXPECT_GT(tb.x, 0.5f);
    EXPECT_NEAR(a.cpu.at(4, 4).x, b.cpu.at(4, 4).x, 1e-4);
}

TEST(NestedMedia, AirBubbleInGlassBlockIsTwoMediaDeep) {
    RenderPair r = renderBoth(loadSized("scenes/bubble.json", 96, 72, FresnelModel::Exact));
    expectImagesMatch(r);
    EXPECT_EQ(r.gpuStats.maxMediumDepth, 2u);  // block, then bubble inside it
    EXPECT_EQ(r.gpuStats.inconsistentMedia, 0u);
}

// min_weight (render model): a branch whose path weight is below it in every channel is skipped
// and counted; both backends skip the same branches.
TEST(MinWeight, CutOffSkipsBranchesOnBothBackends) {
    Scene exact = loadSized("scenes/demo.json", 96, 72, FresnelModel::Schlick);
    Scene cut = exact;
    cut.settings.minWeight = 0.05f;
    RenderPair full = renderBoth(exact);
    RenderPair pruned = renderBoth(cut);
    expectImagesMatch(pruned);
    EXPECT_GT(pruned.gpuStats.weightCuts, 0u);
    EXPECT_GT(pruned.cpuStats.weightCuts, 0u);
    EXPECT_EQ(full.gpuStats.weightCuts, 0u);
    EXPECT_LT(pruned.gpuStats.totalRays(), full.gpuStats.totalRays());
    // What is skipped carried less than 5% of the light along each branch: the image barely moves.
    EXPECT_LT(diffImages(pruned.gpu, full.gpu).meanAbsError, 0.01);
}

// Render model: a ray is traced only while its depth is below max_depth, so max_depth 0 traces
// nothing at all and every pixel is black.
TEST(DepthLimit, MaxDepthZeroTracesNothingOnBothBackends) {
    Scene scene = loadSized("scenes/demo.json", 16, 12, FresnelModel::Schlick);
    scene.settings.maxDepth = 0;
    RenderPair r = renderBoth(scene);
    for (const Image* image : {&r.gpu, &r.cpu})
        for (const glm::vec3& p : image->pixels) ASSERT_EQ(p, glm::vec3(0.0f));
    EXPECT_EQ(r.gpuStats.totalRays(), 0u);
    EXPECT_EQ(r.cpuStats.totalRays(), 0u);
    EXPECT_EQ(r.gpuStats.depthLimitHits, 16u * 12u);
}

TEST(TotalInternalReflection, PrismShowsTirOnBothBackends) {
    RenderPair r = renderBoth(loadSized("scenes/prism.json", 96, 72, FresnelModel::Schlick));
    expectImagesMatch(r);
    EXPECT_GT(r.gpuStats.totalInternalReflections, 0u);
    EXPECT_GT(r.cpuStats.totalInternalReflections, 0u);
}

TEST(NestedMedia, WaterInGlassKeepsTheStackConsistent) {
    RenderPair r = renderBoth(loadSized("scenes/water_glass.json", 64, 48, FresnelModel::Exact));
    expectImagesMatch(r);
    EXPECT_EQ(r.gpuStats.mediumStackOverflows, 0u);
    EXPECT_GE(r.gpuStats.maxMediumDepth, 1u);
    EXPECT_GT(r.gpuStats.touchingInterfaces, 0u);  // water meets the glass's inner wall
}

// DEVELOPERS.md: lavapipe silently ends loops after 65,535 iterations per invocation. The
// loop-limit scene needs far more per pixel; the renderer splits the work over dispatches.
TEST(LoopLimit, SceneNeedingMoreThan65535IterationsMatchesReference) {
    Scene scene = loadScene(sourcePath("scenes/loop_limit.json"));
    RenderPair r = renderBoth(scene);
    EXPECT_GT(r.gpuStats.maxPixelLoopSteps, 65535u) << "the scene no longer needs more than the driver's limit";
    EXPECT_GT(r.gpuStats.dispatches, 1u);
    EXPECT_GT(r.gpuStats.restartedPixels, 0u);  // the first dispatch gave them up; the resumable kernel finished them
    EXPECT_EQ(r.gpuStats.loopLimitSuspected, 0u);
    expectImagesMatch(r);
    std::cout << "loop-limit scene: " << r.gpuStats.dispatches << " dispatches, at most "
              << r.gpuStats.maxPixelLoopSteps << " loop steps for one pixel\n";
}

// A loop of this many iterations shows whether the driver ends loops early (Mesa 22.3's lavapipe
// after 65,535; Mesa 25.0's never): the two tests below check what holds on either kind.
constexpr std::uint32_t kLoopProbeIterations = 200000;

// With a budget above the driver's limit, a driver that has one cuts loops: the kernel notices
// (the loop ended with work left and budget left), counts it, and the next dispatch resumes the
// pixel, so the image is still right. A driver without a limit runs the budget whole: nothing is
// suspected, and the image is as right.
TEST(LoopLimit, DriverLimitIsDetectedAndRecovered) {
    const std::optional<std::uint32_t> limit = probeLoopLimit(testDevice(), kLoopProbeIterations);
    std::printf("%s: a loop of %u iterations %s\n", testDevice().description().driverInfo.c_str(),
                kLoopProbeIterations,
                limit ? ("was ended after " + std::to_string(*limit)).c_str() : "ran whole: the driver has no loop limit");
    Scene scene = loadScene(sourcePath("scenes/loop_limit.json"));
    RenderPair r = renderBoth(scene, VulkanRenderOptions{.iterationBudget = 1u << 20});
    if (limit) {
        EXPECT_GT(r.gpuStats.loopLimitSuspected, 0u);
    } else {
        EXPECT_EQ(r.gpuStats.loopLimitSuspected, 0u);
    }
    expectImagesMatch(r);
}

// lavapipe 22.3 counts its 65,535 iterations for the SIMD group, and lanes that finish a loop
// early wait for the others, so a group runs far more iterations than any of its lanes: counting
// a lane's steps, the loop-limit scene was cut from a budget of 20,000 on (measured). The kernel
// counts the group's iterations, all but the few after its last counted step, so a budget 135
// under the limit is never cut (measured: first cut at 65,520); the build without subgroup
// arithmetic, which can only count its lane's, shows what that prevents. Where the driver has no
// limit, neither build is cut.
TEST(LoopLimit, BudgetsCountTheGroupsIterationsSoTheDriverNeverCutsThem) {
    if (!testDevice().hasSubgroupArithmeticAndBallot()) GTEST_SKIP() << "the device has no subgroup arithmetic";
    const std::optional<std::uint32_t> limit = probeLoopLimit(testDevice(), kLoopProbeIterations);
    // Mesa 22.3's lavapipe runs a loop's body once and repeats it 65,535 times.
    if (limit) {
        EXPECT_EQ(*limit, 65536u) << "a loop limit other than Mesa 22.3 lavapipe's";
    }
    Scene scene = loadScene(sourcePath("scenes/loop_limit.json"));
    const Bvh bvh = buildSceneBvh(scene);
    RenderStats group, lane;
    renderVulkan(testDevice(), scene, bvh, VulkanRenderOptions{.iterationBudget = 65400}, group);
    renderVulkan(testDevice(), scene, bvh,
                 VulkanRenderOptions{.iterationBudget = 65400, .statisticsSums = StatisticsSums::atomics}, lane);
    EXPECT_GT(group.restartedPixels, 0u);  // the budget was reached
    EXPECT_EQ(group.loopLimitSuspected, 0u);
    if (limit) {
        EXPECT_GT(lane.loopLimitSuspected, 0u);
    } else {
        EXPECT_EQ(lane.loopLimitSuspected, 0u);
    }
}

// A budget of a few steps gives up nearly every pixel in the first dispatch and suspends it again
// and again in the resumable kernel, at every kind of step: in the middle of traversals (whose
// stacks are then saved and restored), between shading phases, with pending rays queued. The
// image and the rays traced must be exactly those of one dispatch: nothing a given-up attempt
// counted may count.
TEST(LoopLimit, TinyBudgetGivesTheImageOfOneDispatch) {
    Scene scene = loadSized("scenes/demo.json", 24, 18, FresnelModel::Exact);
    const Bvh bvh = buildSceneBvh(scene);
    RenderStats whole, split;
    const std::uint32_t before = testDevice().validationMessages();
    const Image a = renderVulkan(testDevice(), scene, bvh, VulkanRenderOptions{}, whole);
    const Image b = renderVulkan(testDevice(), scene, bvh, VulkanRenderOptions{.iterationBudget = 7}, split);
    EXPECT_EQ(testDevice().validationMessages(), before);
    EXPECT_EQ(whole.dispatches, 1u);
    EXPECT_EQ(whole.restartedPixels, 0u);
    EXPECT_GT(split.dispatches, 50u);
    EXPECT_GT(split.restartedPixels, 24u * 18u / 2u);
    EXPECT_LE(split.restartedPixels, 24u * 18u);
    // A given-up attempt ran while its SIMD group had run fewer than the budget's steps, and a
    // lane runs at most its group's steps; a group whose lanes shared rays gives up all its
    // pixels (shaders/ray_sharing.glsl), so its lanes' steps are spread over as many pixels.
    EXPECT_LE(split.restartedSteps, 7u * split.restartedPixels);
    EXPECT_GE(split.restartedSteps, split.restartedPixels);
    EXPECT_EQ(a.pixels, b.pixels);
    EXPECT_EQ(whole.totalRays(), split.totalRays());
    EXPECT_EQ(whole.nodeVisits, split.nodeVisits);
    EXPECT_EQ(split.loopLimitSuspected, 0u);
}

// Below kMinIterationBudget a traversal resumed inside a leaf could stop before its first
// triangle test in every dispatch, and the host would dispatch the tile forever: such a budget is
// refused. At the minimum every pixel still finishes, with the image and rays of one dispatch.
TEST(LoopLimit, TheSmallestBudgetStillFinishesEveryPixel) {
    Scene scene = loadSized("scenes/demo.json", 8, 4, FresnelModel::Exact);
    const Bvh bvh = buildSceneBvh(scene);
    RenderStats refused, whole, smallest;
    EXPECT_THROW(renderVulkan(testDevice(), scene, bvh, VulkanRenderOptions{.iterationBudget = kMinIterationBudget - 1},
                              refused),
                 InputError);
    const Image a = renderVulkan(testDevice(), scene, bvh, VulkanRenderOptions{}, whole);
    const Image b =
        renderVulkan(testDevice(), scene, bvh, VulkanRenderOptions{.iterationBudget = kMinIterationBudget}, smallest);
    EXPECT_GT(smallest.dispatches, 100u);
    EXPECT_EQ(a.pixels, b.pixels);
    EXPECT_EQ(whole.totalRays(), smallest.totalRays());
}

// The kernel's count of its SIMD groups' steps (group_loop_steps) against the budget, which it is
// the count of: a dispatch that leaves a pixel unfinished ran its group to the budget, and no
// group runs past it by more than two steps (a traversal at the budget still runs its node and
// triangle loops once each, masked, shaders/bvh.glsl). A 4x2 image is one SIMD group on lavapipe, and on any device with subgroups
// of 8 or more lanes. And a group runs every step any of its lanes runs: the lanes' own steps are
// at most the group's, times its lanes. (Not so a pixel's: lanes that take its pending rays run
// its steps beside it, shaders/ray_sharing.glsl.)
TEST(LoopLimit, AGroupRunsToItsBudgetAndNoFurther) {
    if (!testDevice().hasSubgroupArithmeticAndBallot()) GTEST_SKIP() << "the device has no subgroup arithmetic";
    if (testDevice().subgroups().size < 8) GTEST_SKIP() << "a 4x2 image is more than one subgroup";
    Scene scene = loadSized("scenes/demo.json", 4, 2, FresnelModel::Exact);
    const Bvh bvh = buildSceneBvh(scene);
    constexpr std::uint32_t kBudget = 25;
    RenderStats stats;
    renderVulkan(testDevice(), scene, bvh, VulkanRenderOptions{.iterationBudget = kBudget}, stats);
    ASSERT_GT(stats.dispatches, 3u) << "the pixels no longer need several dispatches at this budget";
    EXPECT_GE(stats.groupLoopSteps, (stats.dispatches - 1) * kBudget);
    EXPECT_LE(stats.groupLoopSteps, stats.dispatches * (kBudget + 2));
    EXPECT_EQ(stats.lanesPerGroup, testDevice().subgroups().size);
    EXPECT_LE(stats.loopSteps + stats.restartedSteps, stats.groupLoopSteps * stats.lanesPerGroup);
}

// The statistics summed over subgroups before the atomics (by shuffles in full subgroups, the
// default where the device can require them, or by subgroupAdd) are the numbers one atomic per
// invocation gives, with the budget small enough that pixels are given up, restarted and
// suspended too. The image and the tiles are no multiples of 8, so that some subgroups have
// lanes without a pixel: with subgroupAdd they return at once and the lanes left share out the
// counters among themselves; with shuffles they take part with zeros (statistics.glsl).
TEST(Statistics, SubgroupSumsCountWhatPlainAtomicsCount) {
    if (testDevice().name().find("llvmpipe") != std::string::npos) {
        ASSERT_TRUE(testDevice().hasSubgroupArithmeticAndBallot());
        ASSERT_TRUE(testDevice().hasFullSubgroups());
        ASSERT_EQ(statisticsSumsFor(testDevice(), StatisticsSums::shuffles), StatisticsSums::shuffles);
    }
    if (!testDevice().hasSubgroupArithmeticAndBallot()) GTEST_SKIP() << "the device has no subgroup arithmetic and ballots";
    Scene scene = loadSized("scenes/demo.json", 37, 29, FresnelModel::Exact);
    const Bvh bvh = buildSceneBvh(scene);
    auto render = [&](StatisticsSums sums, std::uint32_t budget, Image& image) {
        RenderStats stats;
        image = renderVulkan(testDevice(), scene, bvh,
                             VulkanRenderOptions{.iterationBudget = budget, .tileSize = 19, .statisticsSums = sums}, stats);
        return stats;
    };
    Image plainImage;
    const RenderStats plain = render(StatisticsSums::atomics, 300, plainImage);
    for (StatisticsSums way : {StatisticsSums::subgroupAdd, StatisticsSums::shuffles}) {
        SCOPED_TRACE(way == StatisticsSums::shuffles ? "shuffles" : "subgroupAdd");
        Image image;
        const RenderStats summed = render(way, 300, image);
        EXPECT_EQ(image.pixels, plainImage.pixels);
        EXPECT_GT(summed.restartedPixels, 0u);
        EXPECT_GT(summed.dispatches, 2u);
        EXPECT_EQ(toJson(summed)["rays"], toJson(plain)["rays"]);
        EXPECT_EQ(toJson(summed)["limits"], toJson(plain)["limits"]);
        // The build without subgroup arithmetic counts a lane's loop steps against the budget, not
        // its group's (trace.comp), so it gives up other pixels: the restarts and dispatches differ,
        // what is traced does not.
        for (const char* counter : {"node_visits", "max_ray_depth", "max_medium_depth", "total_internal_reflections",
                                    "touching_probes", "touching_interfaces"})
            EXPECT_EQ(toJson(summed)[counter], toJson(plain)[counter]) << counter;
        EXPECT_GT(summed.nodeVisits, 0u);
        // With a budget that gives up nothing, the steps are those of the pixels alone, the same in both.
        const RenderStats whole = render(way, 49152, image);
        const RenderStats wholePlain = render(StatisticsSums::atomics, 49152, image);
        EXPECT_EQ(whole.restartedPixels, 0u);
        EXPECT_EQ(wholePlain.restartedPixels, 0u);
        for (const char* counter : {"loop_steps", "max_pixel_loop_steps", "dispatches", "node_visits"})
            EXPECT_EQ(toJson(whole)[counter], toJson(wholePlain)[counter]) << counter;
    }
}

// Each subgroup takes the dispatch's next unit of pixels from a counter (trace.comp's tilePixel),
// so which invocation traces which pixels changes from run to run with the timing of lavapipe's
// threads. A unit is always the same pixels, so nothing may change with it: every statistic and
// the image are the same in every run, with a budget small enough that pixels are given up,
// restarted and suspended too.
TEST(Statistics, AreTheSameWhicheverInvocationTakesWhichPixels) {
    Scene scene = loadSized("scenes/demo.json", 45, 30, FresnelModel::Exact);
    const Bvh bvh = buildSceneBvh(scene);
    const VulkanRenderOptions options{.iterationBudget = 300, .tileSize = 24};
    RenderStats firstStats;
    const Image first = renderVulkan(testDevice(), scene, bvh, options, firstStats);
    EXPECT_GT(firstStats.restartedPixels, 0u);
    for (int run = 0; run < 4; ++run) {
        RenderStats stats;
        const Image image = renderVulkan(testDevice(), scene, bvh, options, stats);
        EXPECT_EQ(image.pixels, first.pixels);
        EXPECT_EQ(countersWithoutTimes(stats), countersWithoutTimes(firstStats));
    }
}

}  // namespace
}  // namespace vitrum::testing
