// The persistent kernel (trace.comp's main, on a device that runs on the CPU with full subgroups):
// its subgroups take units of work until none is left, so which subgroup traces which unit, and
// how many units one traces, depend on the threads' timing. What is traced must not: each unit
// runs with the same budget whichever subgroup takes it, so the image and every counter but the
// dispatches are those of the kernel that traces one unit a subgroup.
#include "gpu_test_support.h"

namespace vitrum::testing {
namespace {

struct Render {
    Image image;
    RenderStats stats;
};

Render render(const std::string& file, std::uint32_t width, std::uint32_t height, bool persistent,
              std::uint32_t budget = VulkanRenderOptions{}.iterationBudget) {
    Scene scene = loadScene(sourcePath(file));
    scene.camera.width = width;
    scene.camera.height = height;
    Render r;
    const std::uint32_t before = testDevice().validationMessages();
    r.image = renderVulkan(testDevice(), scene, buildSceneBvh(scene),
                           VulkanRenderOptions{.iterationBudget = budget, .persistentSubgroups = persistent}, r.stats);
    EXPECT_EQ(testDevice().validationMessages(), before) << "Vulkan validation messages while rendering " << file;
    return r;
}

// Whether the renderer runs the persistent kernel on the test device. On lavapipe, where the
// tests run, it must: else every comparison here would be of one kernel with itself.
bool persistentHere() {
    const bool here = testDevice().description().cpu &&
                      statisticsSumsFor(testDevice(), StatisticsSums::shuffles) == StatisticsSums::shuffles;
    if (testDevice().name().find("llvmpipe") != std::string::npos) {
        EXPECT_TRUE(here) << "lavapipe no longer gets the persistent kernel";
    }
    return here;
}

void expectSameWork(const Render& persistent, const Render& oneUnit, const std::string& what) {
    EXPECT_EQ(persistent.image.pixels, oneUnit.image.pixels) << what;
    EXPECT_EQ(countersWithoutTimes(persistent.stats, {"dispatches"}),
              countersWithoutTimes(oneUnit.stats, {"dispatches"}))
        << what;
}

// Scenes with every kind of work: glass trees deep enough that lanes share pending rays
// (diamond), touching probes (water_glass), textures and several lights (demo), absorption
// (plastics_green_glass), on a tile that the image's edge cuts to 70x38 pixels: 9x5 blocks of 8x8,
// the last column and row of them partly outside the image.
TEST(PersistentSubgroups, TraceWhatOneUnitASubgroupTraces) {
    persistentHere();
    for (const char* file :
         {"scenes/diamond.json", "scenes/water_glass.json", "scenes/demo.json", "scenes/plastics_green_glass.json"}) {
        const Render persistent = render(file, 70, 38, true);
        const Render oneUnit = render(file, 70, 38, false);
        expectSameWork(persistent, oneUnit, file);
        EXPECT_GT(persistent.stats.totalRays(), 70u * 38u) << file;
    }
}

// A budget so close to lavapipe's limit that a subgroup has room for one unit only (65,200 steps
// and the 64 a unit is counted beyond its steps leave less than 64 of the kernel's 65,279): the
// persistent kernel then traces an eighth of the units a dispatch (it dispatches a subgroup for
// eight), and the host dispatches it again, the work cursor kept, until every unit is traced.
TEST(PersistentSubgroups, DispatchAgainWhileUnitsAreLeft) {
    const Render persistent = render("scenes/demo.json", 64, 48, true, 65200);
    const Render oneUnit = render("scenes/demo.json", 64, 48, false, 65200);
    expectSameWork(persistent, oneUnit, "demo at a budget of 65,200");
    EXPECT_EQ(oneUnit.stats.dispatches, 1u);
    if (persistentHere()) {
        EXPECT_EQ(persistent.stats.dispatches, 8u);
    }
    EXPECT_EQ(persistent.stats.loopLimitSuspected, 0u);
}

// A small budget gives up pixels in the first dispatch, which the resumable kernel (never
// persistent) restarts: a unit gives up the same pixels whichever subgroup took it and whatever
// that subgroup traced before, so the restarts and their steps are the same too.
TEST(PersistentSubgroups, GiveUpThePixelsOneUnitASubgroupGivesUp) {
    const Render persistent = render("scenes/diamond.json", 48, 32, true, 400);
    const Render oneUnit = render("scenes/diamond.json", 48, 32, false, 400);
    expectSameWork(persistent, oneUnit, "diamond at a budget of 400");
    EXPECT_GT(oneUnit.stats.restartedPixels, 0u) << "the budget no longer gives up pixels";
}

}  // namespace
}  // namespace vitrum::testing
