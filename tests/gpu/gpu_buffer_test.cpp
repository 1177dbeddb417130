// Where buffers live (gpu/gpu_buffer.h's MemoryUse): the memory type each use takes on the kinds
// of device there are, and scenes uploaded through staging buffers as on a discrete GPU.
#include "gpu/gpu_buffer.h"
#include "gpu/vulkan_error.h"

#include <cstdlib>
#include <optional>
#include <vector>

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

// The type a buffer takes where memory has room: the first of memoryTypesFor's.
std::uint32_t typeFor(const VkPhysicalDeviceMemoryProperties& memory, MemoryUse use, std::uint32_t bits = ~0u) {
    const std::vector<std::uint32_t> types = memoryTypesFor(memory, bits, use);
    EXPECT_FALSE(types.empty());
    return types.empty() ? ~0u : types.front();
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
    EXPECT_TRUE(memoryTypesFor(memory, 0b0001, MemoryUse::Readback).empty()) << "the host cannot map type 0";
}

// Where the GPU's memory is full (other programs hold it, or the scene is larger than it), a
// buffer takes the next type that has room: the kernels' buffers and the scene the mappable
// window, then host memory; what the host must map never an unmappable type.
TEST(GpuBuffer, BuffersFallBackToSlowerMemoryWhereTheGpusIsFull) {
    const auto memory = memoryOf({kLocal, kVisible | kCoherent, kVisible | kCoherent | kCached, kLocal | kVisible | kCoherent});
    using Types = std::vector<std::uint32_t>;
    EXPECT_EQ(memoryTypesFor(memory, ~0u, MemoryUse::DeviceOnly), (Types{0, 3, 1, 2}));
    EXPECT_EQ(memoryTypesFor(memory, ~0u, MemoryUse::Upload), (Types{0, 3, 1, 2}));
    EXPECT_EQ(memoryTypesFor(memory, ~0u, MemoryUse::HostShared), (Types{3, 1, 2}));
    EXPECT_EQ(memoryTypesFor(memory, ~0u, MemoryUse::Readback), (Types{2, 1, 3}));
    EXPECT_EQ(memoryTypesFor(memory, ~0u, MemoryUse::Staging), (Types{1, 2, 3}));
    EXPECT_EQ(memoryTypesFor(memory, 0b1001, MemoryUse::Upload), (Types{0, 3}));

    // The allocation goes down the list past the types that are out of memory ...
    std::vector<std::uint32_t> tried;
    auto fullUntil = [&](std::uint32_t roomy) {
        return [&tried, roomy](std::uint32_t type) {
            tried.push_back(type);
            return type == roomy ? VK_SUCCESS
                                 : (type == 0 ? VK_ERROR_OUT_OF_DEVICE_MEMORY : VK_ERROR_OUT_OF_HOST_MEMORY);
        };
    };
    const Types deviceOnly = memoryTypesFor(memory, ~0u, MemoryUse::DeviceOnly);
    EXPECT_EQ(firstTypeWithRoom(deviceOnly, fullUntil(1)), std::optional<std::uint32_t>(1));
    EXPECT_EQ(tried, (Types{0, 3, 1}));
    // ... to none where every type is full ...
    tried.clear();
    EXPECT_EQ(firstTypeWithRoom(deviceOnly, fullUntil(7)), std::nullopt);
    EXPECT_EQ(tried, deviceOnly);
    // ... and stops at any other failure.
    EXPECT_THROW(firstTypeWithRoom(deviceOnly, [](std::uint32_t) { return VK_ERROR_DEVICE_LOST; }), VulkanError);
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
    const Bvh bvh = buildSceneBvh(scene);
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
