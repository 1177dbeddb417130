// Overlapping media by priority (render-model-decisions.md, "Overlapping media by priority";
// Schmidt and Budge, JGT 2002), on both backends: priorities change nothing where media do not
// overlap, and water modelled a little larger than its glass's cavity, cutting into the wall,
// renders as the exactly fitted water when the glass has the higher priority.
#include "gpu_test_support.h"

#include "analysis/scene_features.h"
#include "../support/scenes_in_code.h"

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

// On each backend: the overlapping scene with priorities within the image-diff thresholds of the
// exactly fitted one, and without them beyond the thresholds.
void expectOnlyPrioritiesMatchTheFittedScene(const RenderPair& fitted, const RenderPair& ranked,
                                             const RenderPair& unranked) {
    for (const bool gpu : {true, false}) {
        SCOPED_TRACE(gpu ? "GPU" : "CPU");
        const ImageDiff withPriorities = diffImages(gpu ? ranked.gpu : ranked.cpu, gpu ? fitted.gpu : fitted.cpu);
        EXPECT_LE(withPriorities.shareOver005, 0.005) << "rmse " << withPriorities.rmse;
        EXPECT_LE(withPriorities.meanAbsError, 2e-3) << "rmse " << withPriorities.rmse;
        const ImageDiff without = diffImages(gpu ? unranked.gpu : unranked.cpu, gpu ? fitted.gpu : fitted.cpu);
        EXPECT_GT(without.shareOver005, 0.005) << "rmse " << without.rmse;
    }
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
    // Without priorities the overlap is the wrong media: the glass wall then holds the water's IOR
    // between the two surfaces, and the image fails the same thresholds (8.3% of the pixels over
    // 0.05 here).
    expectOnlyPrioritiesMatchTheFittedScene(fitted, ranked, unranked);
}

// A glass marble floating in a box of water, half under its surface, built here twice: with the
// water exactly fitted around the marble (its top face holed by the marble's equator, the
// marble's lower hemisphere, wound the other way, as the water's surface there: the two touch)
// and with a plain box of water whose top face cuts through the marble.
struct MarbleInWater {
    static constexpr float kRadius = 0.35f, kSurface = 1.0f;
    static constexpr int kSegments = 32, kBands = 16;  // 32: the square's corners are ring angles

    // Adds a triangle whose geometric normal points along `outward`.
    static void add(Scene& scene, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 outward, std::uint32_t material,
                    std::uint32_t object) {
        if (glm::dot(glm::cross(b - a, c - a), outward) < 0.0f) std::swap(b, c);
        scene.triangles.push_back(makeTriangle(a, b, c, material, object));
    }

    static Scene build(bool fitted) {
        Scene scene;
        scene.camera.from = {0.0f, -3.2f, 2.2f};
        scene.camera.at = {0.0f, 0.0f, 0.6f};
        scene.camera.fovY = 38.0f;
        scene.camera.width = 160;
        scene.camera.height = 120;
        scene.background.colour = glm::vec3(0.55f, 0.65f, 0.8f);
        scene.lights = {PointLight{{2.0f, -3.0f, 4.0f}, glm::vec3(1.0f), false}};
        scene.materials = {makeMaterial(MaterialModel::Lambert, glm::vec3(0.05f), {0.8f, 0.75f, 0.6f}),
                           makeMaterial(MaterialModel::Lambert, glm::vec3(0.05f), {0.15f, 0.2f, 0.3f})};
        Material water = makeMaterial(MaterialModel::Glass, glm::vec3(0), glm::vec3(0), glm::vec3(0), 1.0f, 1.33f);
        water.attenuation = {0.3f, 0.05f, 0.02f};
        water.priority = 1;
        Material marble = makeMaterial(MaterialModel::Glass, glm::vec3(0), glm::vec3(0), glm::vec3(0), 1.0f, 1.5f);
        marble.attenuation = {0.0f, 0.4f, 0.6f};
        marble.priority = 2;
        scene.materials.push_back(water);   // 2
        scene.materials.push_back(marble);  // 3
        scene.objectNames = {"floor", "water", "marble"};
        // A checkered floor a little below the water's bottom.
        for (int i = 0; i < 8; ++i)
            for (int j = 0; j < 8; ++j) {
                const glm::vec3 p(-2.0f + 0.5f * float(i), -2.0f + 0.5f * float(j), -0.01f);
                const std::uint32_t m = std::uint32_t((i + j) % 2);
                add(scene, p, p + glm::vec3(0.5f, 0, 0), p + glm::vec3(0.5f, 0.5f, 0), {0, 0, 1}, m, 0);
                add(scene, p, p + glm::vec3(0.5f, 0.5f, 0), p + glm::vec3(0, 0.5f, 0), {0, 0, 1}, m, 0);
            }
        // The marble: a UV sphere around (0, 0, kSurface) whose equator lies in the water's surface.
        const glm::vec3 centre(0.0f, 0.0f, kSurface);
        auto vertex = [&](int band, int segment) {
            if (band == 0) return centre + glm::vec3(0, 0, kRadius);
            if (band == kBands) return centre - glm::vec3(0, 0, kRadius);
            const double theta = M_PI * band / kBands, phi = 2.0 * M_PI * (segment % kSegments) / kSegments;
            const double z = band == kBands / 2 ? 0.0 : kRadius * std::cos(theta);
            return centre + glm::vec3(float(kRadius * std::sin(theta) * std::cos(phi)),
                                      float(kRadius * std::sin(theta) * std::sin(phi)), float(z));
        };
        for (int band = 0; band < kBands; ++band)
            for (int s = 0; s < kSegments; ++s) {
                const glm::vec3 a = vertex(band, s), b = vertex(band + 1, s), c = vertex(band + 1, s + 1),
                                d = vertex(band, s + 1);
                const bool lower = band >= kBands / 2;
                auto both = [&](glm::vec3 x, glm::vec3 y, glm::vec3 z) {
                    const glm::vec3 out = (x + y + z) / 3.0f - centre;
                    add(scene, x, y, z, out, 3, 2);
                    if (fitted && lower) add(scene, x, y, z, -out, 2, 1);  // the water's dent
                };
                if (band != kBands - 1) both(a, b, c);
                if (band != 0) both(a, c, d);
            }
        // The water: a box over [-1, 1]^2 x [0, kSurface]. Its top, sides and bottom share the
        // points where rays from the centre through the marble's equator meet the square's edge.
        auto rim = [&](int s) {
            glm::vec2 d = glm::vec2(vertex(kBands / 2, s)) / kRadius;
            d /= std::max(std::abs(d.x), std::abs(d.y));
            // Onto the edge exactly (both coordinates at a corner), so that top, sides and bottom
            // share these points bit for bit.
            if (std::abs(d.x) > 1.0f - 1e-5f) d.x = glm::sign(d.x);
            if (std::abs(d.y) > 1.0f - 1e-5f) d.y = glm::sign(d.y);
            return d;
        };
        for (int s = 0; s < kSegments; ++s) {
            const glm::vec2 q0 = rim(s), q1 = rim(s + 1);
            const glm::vec3 top0(q0, kSurface), top1(q1, kSurface), bottom0(q0, 0.0f), bottom1(q1, 0.0f);
            const glm::vec3 ring0 = vertex(kBands / 2, s), ring1 = vertex(kBands / 2, s + 1);
            add(scene, ring0, top0, top1, {0, 0, 1}, 2, 1);
            add(scene, ring0, top1, ring1, {0, 0, 1}, 2, 1);
            if (!fitted) add(scene, glm::vec3(0, 0, kSurface), ring0, ring1, {0, 0, 1}, 2, 1);
            const glm::vec3 side = q0.x == q1.x ? glm::vec3(q0.x, 0, 0) : glm::vec3(0, q0.y, 0);
            add(scene, top0, bottom0, bottom1, side, 2, 1);
            add(scene, top0, bottom1, top1, side, 2, 1);
            add(scene, glm::vec3(0), bottom0, bottom1, {0, 0, -1}, 2, 1);
        }
        return scene;
    }
};

// A marble of higher priority than the water it floats in, cut by the water's surface, renders as
// the marble in exactly fitted water: inside the marble the water's top face is a false hit, and
// where the ray leaves the marble under the surface it enters the water (1.5 to 1.33), as at the
// fitted scene's touching surfaces.
TEST(MediumPriorities, MarbleCuttingIntoTheWaterSurfaceRendersAsTheFittedMarble) {
    const Scene fittedScene = MarbleInWater::build(true);
    ASSERT_TRUE(openGlassObjects(fittedScene).empty());  // both closed: the construction is right
    Scene overlapping = MarbleInWater::build(false);
    ASSERT_TRUE(openGlassObjects(overlapping).empty());
    const RenderPair fitted = renderBoth(fittedScene);
    const RenderPair ranked = renderBoth(overlapping);
    expectImagesMatch(fitted);
    expectImagesMatch(ranked);
    EXPECT_GT(ranked.gpuStats.falseHits, 100u);
    EXPECT_GT(fitted.gpuStats.refractionRays, 10000u);
    for (Material& m : overlapping.materials) m.priority = 0;
    const RenderPair unranked = renderBoth(overlapping);
    // Without priorities the marble's lower half holds the water's medium and the disk of the
    // water's surface inside the marble refracts: the image fails the thresholds.
    expectOnlyPrioritiesMatchTheFittedScene(fitted, ranked, unranked);
}

}  // namespace
}  // namespace vitrum::testing
