// Where buffers live (gpu/gpu_buffer.h's MemoryUse): the memory type each use takes on the kinds
// of device there are, and scenes uploaded through staging buffers as on a discrete GPU.
#include "gpu/gpu_buffer.h"

#include <cstdlib>

#include "gpu_test_support.h"

namespace vitrum::testing {
namespace {

constexpr VkMemoryPropertyFlags kLocal = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
constexpr VkMemoryPropertyFlags kVisible = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
constexpr VkMemoryPropertyFlags kCoherent = VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
constexpr VkMemoryPropertyFlags kCached = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;

VkPhysicalDeviceMemoryProperties memoryOf(std::initializer_list<VkMemoryPropertyFlags> types) {
    VkPhysicalDeviceMemoryProperties memory{};
    memory.memoryHeapCount = 1;
    for (VkMemoryPropertyFlags flags : types) memory.memoryTypes[memory.memoryTypeCount++] = {flags, 0};
    return memory;
}

std::uint32_t typeFor(const VkPhysicalDeviceMemoryProperties& memory, MemoryUse use, std::uint32_t bits = ~0u) {
    const std::optional<std::uint32_t> type = memoryTypeFor(memory, bits, use);
    EXPECT_TRUE(type.has_value());
    return type.value_or(~0u);
}

// A discrete GPU as NVIDIA's drivers list its memory: its own memory, host memory, host memory
// the CPU caches, and the 256 MiB window of its memory the host can map (or all of it, with
// resizable BAR). The scene and the kernels' buffers go to its memory, the parameters and
// statistics the host rewrites every dispatch to the window, the image to cached host memory
// (reads from the window are uncached), staging buffers to host memory.
TEST(GpuBuffer, ADiscreteGpuKeepsTheKernelsBuffersInItsOwnMemory) {
    const auto memory = memoryOf({kLocal, kVisible | kCoherent, kVisible | kCoherent | kCached, kLocal | kVisible | kCoherent});
    EXPECT_EQ(typeFor(memory, MemoryUse::DeviceOnly), 0u);
    EXPECT_EQ(typeFor(memory, MemoryUse::Upload), 0u);
    EXPECT_EQ(typeFor(memory, MemoryUse::HostShared), 3u);
    EXPECT_EQ(typeFor(memory, MemoryUse::Readback), 2u);
    EXPECT_EQ(typeFor(memory, MemoryUse::Staging), 1u);
    // A buffer that may not live in the GPU's memory takes the next best.
    EXPECT_EQ(typeFor(memory, MemoryUse::Upload, 0b0110), 1u);
    EXPECT_EQ(typeFor(memory, MemoryUse::HostShared, 0b0111), 1u);
    EXPECT_FALSE(memoryTypeFor(memory, 0b0001, MemoryUse::Readback).has_value()) << "the host cannot map type 0";
}

// lavapipe has one memory type with every property, and an integrated GPU's memory is the host's:
// every use takes the first type, and nothing needs a staging copy.
TEST(GpuBuffer, OnSharedMemoryEveryUseTakesTheSameType) {
    const auto lavapipe = memoryOf({kLocal | kVisible | kCoherent | kCached});
    const auto integrated = memoryOf({kLocal, kLocal | kVisible | kCoherent, kLocal | kVisible | kCoherent | kCached});
    for (MemoryUse use : {MemoryUse::DeviceOnly, MemoryUse::Upload, MemoryUse::HostShared, MemoryUse::Readback,
                          MemoryUse::Staging})
        EXPECT_EQ(typeFor(lavapipe, use), 0u);
    EXPECT_EQ(typeFor(integrated, MemoryUse::HostShared), 1u);
    EXPECT_EQ(typeFor(integrated, MemoryUse::Readback), 2u);
}

TEST(GpuBuffer, OnlyBuffersTheHostUsesAreMapped) {
    VulkanDevice& device = testDevice();
    EXPECT_EQ(GpuBuffer(device, 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "kernel's own", MemoryUse::DeviceOnly).mapped(),
              nullptr);
    EXPECT_NE(GpuBuffer(device, 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "results", MemoryUse::Readback).mapped(), nullptr);
    EXPECT_NE(GpuBuffer(device, 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "counters").mapped(), nullptr);
}

// Sets VITRUM_STAGED_UPLOADS for the life of the object.
struct StagedUploads {
    StagedUploads() { setenv("VITRUM_STAGED_UPLOADS", "1", 1); }
    ~StagedUploads() { unsetenv("VITRUM_STAGED_UPLOADS"); }
};

// The scene's buffers filled by copies from staging buffers, as on a GPU whose memory the host
// cannot map, render the image that buffers written directly render, bit for bit. Without the
// copies (or with them in the wrong place) the kernel reads no scene: the image would be the
// background's.
TEST(GpuBuffer, AStagedSceneRendersTheSameImage) {
    Scene scene = loadScene(sourcePath("scenes/demo.json"));
    scene.camera.width = 48;
    scene.camera.height = 32;
    const Bvh bvh = buildBvh(scene.triangles);
    const std::uint32_t before = testDevice().validationMessages();
    RenderStats directStats, stagedStats;
    const Image direct = renderVulkan(testDevice(), scene, bvh, VulkanRenderOptions{}, directStats);
    Image staged;
    {
        const StagedUploads forced;
        ASSERT_TRUE(stagedUploadsForced());
        const std::vector<glm::vec4> data(4, glm::vec4(1.0f));
        EXPECT_EQ(makeStorageBuffer(testDevice(), std::span<const glm::vec4>(data), "staged").mapped(), nullptr);
        staged = renderVulkan(testDevice(), scene, bvh, VulkanRenderOptions{}, stagedStats);
    }
    EXPECT_FALSE(stagedUploadsForced());
    EXPECT_EQ(testDevice().validationMessages(), before) << "Vulkan validation messages while rendering";
    EXPECT_EQ(differingPixels(direct, staged), 0u);
    EXPECT_EQ(countersWithoutTimes(directStats, {"dispatches"}), countersWithoutTimes(stagedStats, {"dispatches"}));
    EXPECT_GT(imageSpread(direct), 0.05) << "the demo shows more than its background";
}

}  // namespace
}  // namespace vitrum::testing
