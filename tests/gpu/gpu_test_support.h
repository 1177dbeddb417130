// Rendering one scene on lavapipe and with the CPU reference, for the image-diff tests.
// The Vulkan device is created once per test process with the validation layer on
// (VITRUM_VALIDATION=1 from tests/CMakeLists.txt); any validation message fails the test.
#pragma once

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bvh/bvh.h"
#include "cpu/reference_renderer.h"
#include "test_kernels.h"
#include "gpu/vulkan_device.h"
#include "gpu/vulkan_renderer.h"
#include "image/image.h"
#include "image/image_diff.h"
#include "stats/render_stats.h"
#include "scene/scene_loader.h"

namespace vitrum::testing {

inline std::string sourcePath(const std::string& relative) { return std::string(VITRUM_SOURCE_DIR) + "/" + relative; }
inline std::string sharedPath(const std::string& relative) { return std::string(VITRUM_SHARED_DIR) + "/" + relative; }

// A render's statistics as `--stats` writes them, without the phases' seconds (which change from
// run to run) and without the keys in `without`: what two renders of the same work must agree on.
inline nlohmann::json countersWithoutTimes(const RenderStats& stats, std::initializer_list<const char*> without = {}) {
    nlohmann::json json = toJson(stats);
    json.erase("seconds");
    for (const char* key : without) json.erase(key);
    return json;
}

// The JSON scenes of scenes/ and scenes/course/, as paths relative to the source folder, sorted.
inline std::vector<std::string> projectScenes() {
    std::vector<std::string> scenes;
    for (const char* folder : {"scenes", "scenes/course"})
        for (const auto& entry : std::filesystem::directory_iterator(sourcePath(folder)))
            if (entry.path().extension() == ".json")
                scenes.push_back(std::string(folder) + "/" + entry.path().filename().string());
    std::sort(scenes.begin(), scenes.end());
    return scenes;
}

inline VulkanDevice& testDevice() {
    static VulkanDevice device("");
    return device;
}

// Runs optics_test.comp over `cases` on the test device; any validation message fails the test.
inline std::vector<OpticsResult> evaluateOptics(const std::vector<OpticsCase>& cases) {
    const std::uint32_t before = testDevice().validationMessages();
    std::vector<OpticsResult> results = evaluateOpticsOnGpu(testDevice(), cases);
    EXPECT_EQ(testDevice().validationMessages(), before) << "Vulkan validation messages in optics_test.comp";
    EXPECT_EQ(results.size(), cases.size());
    return results;
}

struct RenderPair {
    Image gpu;
    Image cpu;
    RenderStats gpuStats;
    RenderStats cpuStats;
    ImageDiff diff;
};

inline RenderPair renderBoth(const Scene& scene, const VulkanRenderOptions& gpuOptions = {}) {
    RenderPair result;
    Bvh bvh = buildSceneBvh(scene);
    std::uint32_t before = testDevice().validationMessages();
    result.gpu = renderVulkan(testDevice(), scene, bvh, gpuOptions, result.gpuStats);
    EXPECT_EQ(testDevice().validationMessages(), before) << "Vulkan validation messages while rendering";
    result.cpu = renderReference(scene, bvh, ReferenceOptions{}, result.cpuStats);
    result.diff = diffImages(result.gpu, result.cpu);
    return result;
}

// The pixels of two images of one size that differ in any bit.
inline std::size_t differingPixels(const Image& a, const Image& b) {
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i)
        if (std::memcmp(&a.pixels[i], &b.pixels[i], sizeof(glm::vec3)) != 0) ++differing;
    return differing;
}

// The pixels of two images of one size with a channel more than `tolerance` apart (or not a number).
inline std::size_t pixelsApart(const Image& a, const Image& b, float tolerance) {
    std::size_t apart = 0;
    for (std::size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i)
        if (!glm::all(glm::lessThanEqual(glm::abs(a.pixels[i] - b.pixels[i]), glm::vec3(tolerance)))) ++apart;
    return apart;
}

// Two renders of the same rays (the specialized kernel and the general one, say) counted the same
// work and met the same limits.
inline void expectSameWork(const RenderStats& a, const RenderStats& b) {
    EXPECT_EQ(a.primaryRays, b.primaryRays);
    EXPECT_EQ(a.shadowRays, b.shadowRays);
    EXPECT_EQ(a.reflectionRays, b.reflectionRays);
    EXPECT_EQ(a.refractionRays, b.refractionRays);
    EXPECT_EQ(a.passThroughRays, b.passThroughRays);
    EXPECT_EQ(a.depthLimitHits, b.depthLimitHits);
    EXPECT_EQ(a.rayStackOverflows, b.rayStackOverflows);
    EXPECT_EQ(a.mediumStackOverflows, b.mediumStackOverflows);
    EXPECT_EQ(a.inconsistentMedia, b.inconsistentMedia);
    EXPECT_EQ(a.weightCuts, b.weightCuts);
    EXPECT_EQ(a.totalInternalReflections, b.totalInternalReflections);
    EXPECT_EQ(a.touchingInterfaces, b.touchingInterfaces);
    EXPECT_EQ(a.maxRayDepth, b.maxRayDepth);
    EXPECT_EQ(a.maxMediumDepth, b.maxMediumDepth);
}

// A feature the general kernel decides at run time (a glass tint, a cut-out): its image must be
// the specialized kernel's, bit for bit, with the same work counted.
inline void expectTheGeneralKernelAgrees(const Scene& scene, const RenderPair& specialized) {
    VulkanRenderOptions general;
    general.specialize = false;
    RenderStats stats;
    const Image image = renderVulkan(testDevice(), scene, buildSceneBvh(scene), general, stats);
    EXPECT_EQ(differingPixels(image, specialized.gpu), 0u);
    expectSameWork(stats, specialized.gpuStats);
}

// Standard deviation of the luminance-ish channel mean: 0 for a constant image.
inline double imageSpread(const Image& image) {
    double sum = 0, sumSquares = 0;
    for (const glm::vec3& p : image.pixels) {
        double v = (double(p.x) + p.y + p.z) / 3.0;
        sum += v;
        sumSquares += v * v;
    }
    double n = double(image.pixels.size());
    return std::sqrt(std::max(0.0, sumSquares / n - (sum / n) * (sum / n)));
}

// No NaN, Inf or negative channel; but dispersion's may be negative (render-model-decisions.md,
// "Dispersion": a narrow spectrum outside sRGB's gamut).
inline bool allFinite(const Image& image, bool negativeAllowed = false) {
    for (const glm::vec3& p : image.pixels)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) ||
            (!negativeAllowed && (p.x < 0 || p.y < 0 || p.z < 0)))
            return false;
    return true;
}

// The thresholds every GPU-against-CPU test holds. Both backends compute in float without FMA
// contraction, so pixels agree to a few ulps except where a ray passes within an ulp of a
// triangle edge: there lavapipe and the CPU may pick different triangles (a silhouette or a
// different branch of a glass ray tree). Such pixels are isolated, so we allow at most 0.5% of
// pixels over 0.05 (measured: under 0.1% on every scene) while the mean error must stay below
// 2e-3 (a few 8-bit steps would already be 8e-3; a wrong formula gives errors of 1e-2 and more).
// These thresholds alone, for images that may rightly be constant (random scenes).
inline void expectImagesAgree(const RenderPair& r, double maxShareOver005 = 0.005, double maxMeanError = 2e-3) {
    const bool dispersion = r.gpuStats.kernel && r.gpuStats.kernel->dispersion;
    EXPECT_TRUE(allFinite(r.gpu, dispersion)) << "GPU image has NaN, Inf or negative pixels";
    EXPECT_TRUE(allFinite(r.cpu, dispersion)) << "CPU image has NaN, Inf or negative pixels";
    EXPECT_LE(r.diff.shareOver005, maxShareOver005) << "rmse " << r.diff.rmse << " psnr " << r.diff.psnr;
    EXPECT_LE(r.diff.meanAbsError, maxMeanError) << "rmse " << r.diff.rmse << " psnr " << r.diff.psnr;
    // VITRUM_FAILED_IMAGES=DIR keeps both images of a failing test there, for `vitrum diff`
    // (a failure on another machine's device is otherwise hard to see).
    const char* dir = std::getenv("VITRUM_FAILED_IMAGES");
    if (dir && ::testing::Test::HasFailure()) {
        static int kept = 0;
        const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string stem = std::string(test->test_suite_name()) + "." + test->name() + "." + std::to_string(kept++);
        for (char& c : stem) c = std::isalnum(static_cast<unsigned char>(c)) || c == '.' ? c : '_';
        std::filesystem::create_directories(dir);
        writeImage(r.gpu, std::filesystem::path(dir) / (stem + ".gpu.pfm"));
        writeImage(r.cpu, std::filesystem::path(dir) / (stem + ".cpu.pfm"));
    }
}

inline void expectImagesMatch(const RenderPair& r, double maxShareOver005 = 0.005, double maxMeanError = 2e-3) {
    expectImagesAgree(r, maxShareOver005, maxMeanError);
    // A blank or constant image would match a blank reference: refuse it.
    EXPECT_GT(imageSpread(r.gpu), 0.01) << "GPU image is (nearly) constant";
    EXPECT_GT(imageSpread(r.cpu), 0.01) << "CPU image is (nearly) constant";
}

}  // namespace vitrum::testing
