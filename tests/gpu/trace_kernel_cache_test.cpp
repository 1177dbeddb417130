// Kernels kept across renders (gpu/trace_kernel_cache.h): a render that takes its kernel from the
// cache binds its own scene's buffers to it, so it must give what a render with a kernel of its
// own gives, and the cache must create a kernel exactly when no kept one is built for the render.
#include "gpu/trace_kernel_cache.h"

#include "gpu_test_support.h"

namespace vitrum::testing {
namespace {

struct Render {
    Image image;
    RenderStats stats;
};

Scene smallScene(const std::string& file) {
    Scene scene = loadScene(sourcePath(file));
    scene.camera.width = 40;
    scene.camera.height = 24;
    return scene;
}

Render render(const Scene& scene, TraceKernelCache* kernels,
              std::uint32_t budget = VulkanRenderOptions{}.iterationBudget,
              std::uint32_t tileSize = VulkanRenderOptions{}.tileSize) {
    Render r;
    const std::uint32_t before = testDevice().validationMessages();
    r.image = renderVulkan(testDevice(), scene, buildSceneBvh(scene),
                           VulkanRenderOptions{.iterationBudget = budget, .tileSize = tileSize, .kernels = kernels},
                           r.stats);
    EXPECT_EQ(testDevice().validationMessages(), before) << "Vulkan validation messages while rendering";
    return r;
}

// The persistent kernel's dispatches depend on the threads' timing (persistent_subgroups_test.cpp).
void expectSameRender(const Render& kept, const Render& own, const std::string& what) {
    EXPECT_EQ(kept.image.pixels, own.image.pixels) << what;
    EXPECT_EQ(countersWithoutTimes(kept.stats, {"dispatches"}), countersWithoutTimes(own.stats, {"dispatches"}))
        << what;
}

// Two scenes in turns, the second with a budget so small that its first dispatches give up pixels
// and the resumable kernel restarts them: three kernels, each created once, and every render the
// same as one with kernels of its own, though a kept kernel was last bound to the other scene's
// buffers. A kept kernel is not compiled again: its compile phase is 0 exactly.
TEST(TraceKernelCache, RendersWithKeptKernelsAreTheRendersWithTheirOwn) {
    const Scene demo = smallScene("scenes/demo.json");
    const Scene diamond = smallScene("scenes/diamond.json");
    const Render demoOwn = render(demo, nullptr);
    const Render diamondOwn = render(diamond, nullptr, 400);
    ASSERT_GT(diamondOwn.stats.restartedPixels, 0u) << "the budget no longer gives up pixels";

    TraceKernelCache kernels;
    for (int round = 0; round < 2; ++round) {
        SCOPED_TRACE("round " + std::to_string(round));
        const Render demoKept = render(demo, &kernels);
        expectSameRender(demoKept, demoOwn, "demo");
        const Render diamondKept = render(diamond, &kernels, 400);
        expectSameRender(diamondKept, diamondOwn, "diamond at a budget of 400");
        EXPECT_EQ(kernels.created(), 3u);
        if (round == 1) {
            EXPECT_EQ(demoKept.stats.seconds("compile"), 0.0);
            EXPECT_EQ(diamondKept.stats.seconds("compile"), 0.0);
        }
    }
    EXPECT_GT(demoOwn.stats.seconds("compile"), 0.0);
}

// A setting compiled into the kernel (the Fresnel model) takes a kernel of its own; one that the
// kernel reads at run time (the image's size, the weight cut-off) takes the kept one.
TEST(TraceKernelCache, AKernelForEachSpecialization) {
    Scene scene = smallScene("scenes/prism.json");
    TraceKernelCache kernels;
    render(scene, &kernels);
    scene.camera.width = 48;
    scene.settings.minWeight = 0.01f;
    render(scene, &kernels);
    EXPECT_EQ(kernels.created(), 1u);
    scene.settings.fresnel = FresnelModel::Exact;
    const Render exact = render(scene, &kernels);
    EXPECT_EQ(kernels.created(), 2u);
    expectSameRender(exact, render(scene, nullptr), "prism with exact Fresnel");
}

// Full, the cache drops the kernel used least recently.
TEST(TraceKernelCache, DropsTheKernelUsedLeastRecently) {
    const Scene demo = smallScene("scenes/demo.json");
    const Scene diamond = smallScene("scenes/diamond.json");
    const Scene bubble = smallScene("scenes/bubble.json");
    TraceKernelCache kernels(2);
    render(demo, &kernels);
    render(diamond, &kernels);
    render(demo, &kernels);  // kept: diamond is now the least recent
    EXPECT_EQ(kernels.created(), 2u);
    render(bubble, &kernels);  // drops diamond
    EXPECT_EQ(kernels.size(), 2u);
    render(demo, &kernels);
    EXPECT_EQ(kernels.created(), 3u);
    const Render diamondAgain = render(diamond, &kernels);
    EXPECT_EQ(kernels.created(), 4u);
    EXPECT_GT(diamondAgain.stats.seconds("compile"), 0.0);
}

// A render that takes two kernels from a full cache of two: its resumable kernel drops the other
// scene's kernel, never the first-dispatch kernel that the render's later tiles still dispatch
// (tiles of 8 pixels: a dropped kernel in use would be a destroyed pipeline, validation errors or
// a crash, and another image).
TEST(TraceKernelCache, HoldsTheTwoKernelsOfARender) {
    EXPECT_THROW(TraceKernelCache(1), std::logic_error);
    const Scene demo = smallScene("scenes/demo.json");
    const Scene diamond = smallScene("scenes/diamond.json");
    const Render diamondOwn = render(diamond, nullptr, 400, 8);
    ASSERT_GT(diamondOwn.stats.restartedPixels, 0u) << "the budget no longer gives up pixels";
    TraceKernelCache kernels(2);
    render(demo, &kernels);
    const Render diamondKept = render(diamond, &kernels, 400, 8);
    EXPECT_EQ(kernels.created(), 3u);
    EXPECT_EQ(kernels.size(), 2u);
    expectSameRender(diamondKept, diamondOwn, "diamond at a budget of 400, two kernels in a cache of two");
}

}  // namespace
}  // namespace vitrum::testing
