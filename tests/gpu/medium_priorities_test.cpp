// Overlapping media by priority (render-model-decisions.md, "Overlapping media by priority";
// Schmidt and Budge, JGT 2002), on both backends: priorities change nothing where media do not
// overlap, and water modelled a little larger than its glass's cavity, cutting into the wall,
// renders as the exactly fitted water when the glass has the higher priority.
#include "gpu_test_support.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace vitrum::testing {
namespace {

Scene sized(const std::string& path) {
    Scene scene = loadScene(sourcePath(path));
    scene.camera.width = 160;
    scene.camera.height = 120;
    return scene;
}

bool isShape(const Scene& scene, const Triangle& t, const std::string& shape) {
    return scene.objectNames[t.object].ends_with("/" + shape);  // "water_glass.obj/water"
}

// Gives every glass material of the OBJ shape `shape` the priority.
void setPriority(Scene& scene, const std::string& shape, int priority) {
    for (const Triangle& t : scene.triangles)
        if (isShape(scene, t, shape) && scene.materials[t.material].model == MaterialModel::Glass)
            scene.materials[t.material].priority = priority;
}

void expectSameImages(const RenderPair& a, const RenderPair& b) {
    EXPECT_EQ(differingPixels(a.gpu, b.gpu), 0u);
    EXPECT_EQ(differingPixels(a.cpu, b.cpu), 0u);
}

// A glass of higher priority than its water, or a bubble of higher priority than its block:
// media that touch or nest without overlapping render bit for bit as without priorities, with
// the kernel that has the priorities compiled in.
TEST(MediumPriorities, ChangeNothingWhereMediaTouchOrNest) {
    for (const auto& [path, inner, outer] : {std::tuple{"scenes/water_glass.json", "water", "tumbler"},
                                             std::tuple{"scenes/bubble.json", "sphere", "block"}}) {
        SCOPED_TRACE(path);
        const Scene plain = sized(path);
        Scene ranked = plain;
        setPriority(ranked, outer, 1);
        // The water below its glass (they touch), the bubble above its block (it nests in it).
        setPriority(ranked, inner, std::string(inner) == "water" ? 0 : 2);
        const RenderPair before = renderBoth(plain), after = renderBoth(ranked);
        ASSERT_FALSE(before.gpuStats.kernel->mediumPriorities);
        ASSERT_TRUE(after.gpuStats.kernel->mediumPriorities);
        expectSameImages(before, after);
        EXPECT_EQ(after.gpuStats.falseHits, 0u);
        EXPECT_EQ(after.cpuStats.falseHits, 0u);
        EXPECT_GT(after.gpuStats.refractionRays, 0u);
    }
}

// water_glass's water (scenes/generate/make_scenes.py: the tumbler's inner radius 0.92, its wall
// 0.08 thick, its bottom at z = 0.2, the water's surface at 1.6) grown into the glass by 1% of the
// wall's thickness at its side and its bottom; its surface stays where it was.
Scene waterCuttingIntoItsGlass() {
    Scene scene = sized("scenes/water_glass.json");
    constexpr float kInner = 0.92f, kCut = 0.0008f, kLift = 0.01f, kBottom = 0.2f + kLift;
    for (Triangle& t : scene.triangles) {
        if (!isShape(scene, t, "water")) continue;
        for (glm::vec3& p : t.position) {
            p.x *= (kInner + kCut) / kInner;
            p.y *= (kInner + kCut) / kInner;
            if (std::abs(p.z - kBottom) < 1e-4f) p.z -= kCut;
        }
    }
    return scene;
}

TEST(MediumPriorities, WaterCuttingIntoItsGlassRendersAsTheFittedWater) {
    const RenderPair fitted = renderBoth(sized("scenes/water_glass.json"));
    Scene overlapping = waterCuttingIntoItsGlass();
    const RenderPair unranked = renderBoth(overlapping);
    setPriority(overlapping, "tumbler", 2);
    setPriority(overlapping, "water", 1);
    const RenderPair ranked = renderBoth(overlapping);
    expectImagesMatch(ranked);  // the GPU against the CPU
    // Inside the wall, the glass is the medium: the water's surfaces there are passed, as many
    // times on both backends (to rounding: 234,569 both here).
    EXPECT_GT(ranked.gpuStats.falseHits, 1000u);
    EXPECT_NEAR(double(ranked.gpuStats.falseHits), double(ranked.cpuStats.falseHits), 1e-3 * double(ranked.cpuStats.falseHits));
    // The stacks stay consistent: as rarely not as in the fitted scene (a grazing ray or two).
    EXPECT_LE(ranked.gpuStats.inconsistentMedia, fitted.gpuStats.inconsistentMedia + 2);
    EXPECT_LE(ranked.cpuStats.inconsistentMedia, fitted.cpuStats.inconsistentMedia + 2);
    for (const bool gpu : {true, false}) {
        SCOPED_TRACE(gpu ? "GPU" : "CPU");
        const ImageDiff withPriorities = diffImages(gpu ? ranked.gpu : ranked.cpu, gpu ? fitted.gpu : fitted.cpu);
        EXPECT_LE(withPriorities.shareOver005, 0.005) << "rmse " << withPriorities.rmse;
        EXPECT_LE(withPriorities.meanAbsError, 2e-3) << "rmse " << withPriorities.rmse;
        // Without priorities the overlap is the wrong media: the glass wall then holds the water's
        // IOR between the two surfaces, and the image fails the same thresholds (8.3% of the
        // pixels over 0.05 here).
        const ImageDiff without = diffImages(gpu ? unranked.gpu : unranked.cpu, gpu ? fitted.gpu : fitted.cpu);
        EXPECT_GT(without.shareOver005, 0.005) << "rmse " << without.rmse;
    }
}

}  // namespace
}  // namespace vitrum::testing
