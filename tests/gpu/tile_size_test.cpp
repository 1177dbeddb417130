// The default tile (gpu/tile_size.h): 256 pixels a side on a CPU device, and on a GPU the largest
// multiple of 8 whose per-tile buffers fit both a storage buffer binding and an eighth of the
// device's memory.
#include "gpu/tile_buffers.h"
#include "gpu/tile_size.h"

#include <cmath>
#include <vector>
#include <utility>
#include <string>

#include "gpu_test_support.h"

namespace vitrum::testing {
namespace {

constexpr std::uint64_t kMiB = 1ull << 20, kGiB = 1ull << 30;

DeviceDescription gpu(std::uint64_t storageRange, std::uint64_t deviceLocal) {
    return DeviceDescription{.name = "a GPU", .type = "discrete GPU", .maxStorageBufferRange = storageRange,
                             .deviceLocalBytes = deviceLocal};
}

// The largest multiple of 8 whose square is at most `pixels`, worked out with a square root.
std::uint32_t largestSideFor(double pixels) { return std::uint32_t(std::floor(std::sqrt(pixels) / 8.0)) * 8u; }

TEST(TileSize, CpuDevicesTake256PixelTilesWhateverTheirMemory) {
    DeviceDescription cpu = gpu(128 * kMiB, 2 * kGiB);
    cpu.cpu = true;
    EXPECT_EQ(defaultTileSize(cpu), 256u);
    cpu.deviceLocalBytes = 512 * kGiB;
    EXPECT_EQ(defaultTileSize(cpu), 256u);
    if (testDevice().description().cpu) {  // lavapipe
        EXPECT_EQ(defaultTileSize(testDevice().description()), 256u);
    }
}

// The worst case a pixel: a vec4 pixel, a 256-byte trace state, 16 pending rays of 64 bytes and
// 64 stack entries of 4 bytes (shaders/shared/gpu_types.h): 1552 bytes, the pending rays the most.
TEST(TileSize, APixelsBuffersAreTheGeneralKernels) {
    std::uint64_t all = 0, largest = 0;
    for (const TileBuffer& buffer : kTileBuffers) all += buffer.bytesPerPixel, largest = std::max(largest, buffer.bytesPerPixel);
    EXPECT_EQ(all, 16u + 256u + 16u * 64u + 64u * 4u);
    EXPECT_EQ(largest, 16u * 64u);
}

// An NVIDIA H200 (4095 MiB a binding, 141 GiB): the binding bounds the pending rays to
// sqrt(4095 MiB / 1024 bytes) = 2047.7 pixels a side, 2040 as a multiple of 8, which holds a
// 1920x1080 image in one tile.
TEST(TileSize, ALargeGpuIsBoundByItsStorageBufferRange) {
    const DeviceDescription h200 = gpu(4095 * kMiB, 141 * kGiB);
    EXPECT_EQ(defaultTileSize(h200), 2040u);
    EXPECT_EQ(largestSideFor(4095.0 * kMiB / 1024.0), 2040u);
}

// An 8 GiB GPU: an eighth of it is 1 GiB, sqrt(1 GiB / 1552 bytes) = 831.8 -> 824 a side.
TEST(TileSize, ASmallGpuIsBoundByAnEighthOfItsMemory) {
    EXPECT_EQ(defaultTileSize(gpu(4 * kGiB, 8 * kGiB)), 824u);
    EXPECT_EQ(defaultTileSize(gpu(4 * kGiB, 64 * kMiB)), largestSideFor(8.0 * kMiB / 1552.0));  // 72
}

// Whatever the device, the default tile's buffers fit, and 8 pixels more a side would not
// (or it is the largest tile or the smallest).
TEST(TileSize, TheDefaultIsTheLargestThatFits) {
    for (std::uint64_t range : {16 * kMiB, 128 * kMiB, 1 * kGiB, 4 * kGiB - 1, 16 * kGiB})
        for (std::uint64_t memory : {std::uint64_t(0), 1 * kMiB, 256 * kMiB, 3 * kGiB, 24 * kGiB, 1024 * kGiB}) {
            const std::uint32_t side = defaultTileSize(gpu(range, memory));
            SCOPED_TRACE(std::to_string(range) + " bytes a binding, " + std::to_string(memory) + " bytes: " +
                         std::to_string(side));
            ASSERT_GE(side, kMinTileSize);
            ASSERT_LE(side, kMaxTileSize);
            EXPECT_EQ(side % 8, 0u);
            auto fits = [&](std::uint64_t s) {
                for (const TileBuffer& buffer : kTileBuffers)
                    if (s * s * buffer.bytesPerPixel > range) return false;
                std::uint64_t all = 0;
                for (const TileBuffer& buffer : kTileBuffers) all += s * s * buffer.bytesPerPixel;
                return all <= memory / 8;
            };
            if (side > kMinTileSize) {
                EXPECT_TRUE(fits(side));
            }
            if (side < kMaxTileSize) {
                EXPECT_FALSE(fits(side + 8));
            }
        }
}

TEST(TileSize, ARequestedTileIsKeptAboveTheSmallest) {
    const DeviceDescription h200 = gpu(4095 * kMiB, 141 * kGiB);
    EXPECT_EQ(tileSizeFor(h200, 19), 19u);
    EXPECT_EQ(tileSizeFor(h200, 3), kMinTileSize);
    EXPECT_EQ(tileSizeFor(h200, 0), 2040u);
}

// A render with the default options uses the device's default tile (256 on lavapipe) and says so.
TEST(TileSize, ARenderReportsItsTile) {
    Scene scene = loadScene(sourcePath("scenes/prism.json"));
    scene.camera.width = 24;
    scene.camera.height = 16;
    RenderStats stats;
    renderVulkan(testDevice(), scene, buildSceneBvh(scene), VulkanRenderOptions{}, stats);
    const std::uint32_t expected = defaultTileSize(testDevice().description());
    EXPECT_EQ(stats.tileSize, expected);
    EXPECT_EQ(toJson(stats)["kernel"]["tile_size"], expected);
    renderVulkan(testDevice(), scene, buildSceneBvh(scene), VulkanRenderOptions{.tileSize = 16}, stats);
    EXPECT_EQ(stats.tileSize, 16u);
}

// Progress in phases: the scene's analysis, its upload by its three per-triangle buffers, then
// the render from 0 by tiles (six tiles of 8 x 8 here), each phase in order.
TEST(TileSize, ARenderReportsItsUploadThenItsTiles) {
    Scene scene = loadScene(sourcePath("scenes/prism.json"));
    scene.camera.width = 24;
    scene.camera.height = 16;
    std::vector<std::pair<std::string, double>> calls;
    VulkanRenderOptions options{.tileSize = 8};
    options.progress = [&](const std::string& phase, double fraction) { calls.emplace_back(phase, fraction); };
    RenderStats stats;
    renderVulkan(testDevice(), scene, buildSceneBvh(scene), options, stats);
    const std::vector<std::pair<std::string, double>> expected = {
        {"analysing the scene", 0.0},       {"analysing the scene", 1.0},
        {"uploading the scene", 0.0},       {"uploading the scene", 1.0 / 3.0}, {"uploading the scene", 2.0 / 3.0},
        {"uploading the scene", 1.0},       {"rendering", 0.0},                 {"rendering", 1.0 / 6.0},
        {"rendering", 2.0 / 6.0},           {"rendering", 3.0 / 6.0},           {"rendering", 4.0 / 6.0},
        {"rendering", 5.0 / 6.0},           {"rendering", 1.0}};
    EXPECT_EQ(calls, expected);
}

}  // namespace
}  // namespace vitrum::testing

namespace vitrum {
namespace {

// A tile's buffers as the renderer makes them: a pixel's worth each for the tile's pixels, but the
// pending rays, which the first dispatch keeps by invocation of whole 8x8 workgroups.
TEST(TileBuffers, PendingRaysCoverTheTilesWholeWorkgroups) {
    const glm::uvec2 tile(10, 17);  // 2 x 3 workgroups: 384 invocations
    for (const TileBuffer& buffer : kTileBuffers) {
        const std::uint64_t bytes = tileBufferBytes(buffer, tile, 9);
        if (buffer.perPendingRay) EXPECT_EQ(bytes, 384u * 9u * sizeof(gpu::PendingRay)) << buffer.what;
        else EXPECT_EQ(bytes, 170u * buffer.bytesPerPixel) << buffer.what;
    }
    // The general kernel's capacity gives the table's bytes a pixel over whole workgroups.
    for (const TileBuffer& buffer : kTileBuffers)
        EXPECT_EQ(tileBufferBytes(buffer, glm::uvec2(16, 24), gpu::kRayStackSize), 384u * buffer.bytesPerPixel);
}

}  // namespace
}  // namespace vitrum
