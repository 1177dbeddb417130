#include "gpu/gpu_buffer.h"

#include <cstdlib>
#include <optional>
#include <string>

#include "common/error.h"
#include "gpu/vulkan_error.h"

namespace vitrum {
namespace {

// For tests only: VITRUM_MAX_BUFFER_BYTES=N lowers the storage buffer limit to N bytes (never
// raises it), so that "does not fit the device" can be tested with a small scene
// (tests/cli/bad_input_test.cpp).
std::optional<VkDeviceSize> testBufferLimit() {
    const char* text = std::getenv("VITRUM_MAX_BUFFER_BYTES");
    if (!text || !*text) return std::nullopt;
    char* end = nullptr;
    unsigned long long value = std::strtoull(text, &end, 10);
    if (*end != '\0') return std::nullopt;
    return VkDeviceSize(value);
}

}  // namespace

std::string describeBytes(VkDeviceSize bytes) {
    if (bytes < (VkDeviceSize(1) << 20)) return std::to_string(bytes) + " bytes";
    return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB";
}

BufferLimit bufferLimit(const VulkanDevice& device, BufferKind kind) {
    const VkPhysicalDeviceLimits& limits = device.properties().limits;
    BufferLimit limit = kind == BufferKind::Storage
                            ? BufferLimit{limits.maxStorageBufferRange, "maxStorageBufferRange"}
                            : BufferLimit{VkDeviceSize(limits.maxTexelBufferElements) * 16, "maxTexelBufferElements"};
    if (auto test = testBufferLimit(); test && *test < limit.bytes) limit = {*test, "VITRUM_MAX_BUFFER_BYTES"};
    return limit;
}

InputError bufferTooLarge(const VulkanDevice& device, const std::string& what, VkDeviceSize size, BufferKind kind) {
    const BufferLimit limit = bufferLimit(device, kind);
    return InputError("the scene does not fit the device: " + what + " needs " + describeBytes(size) + ", but " +
                      device.name() + " allows " + describeBytes(limit.bytes) +
                      (kind == BufferKind::Storage ? " per storage buffer (" : " per texel buffer of 16-byte texels (") +
                      limit.source + ")");
}

GpuBuffer::GpuBuffer(const VulkanDevice& device, VkDeviceSize size, VkBufferUsageFlags usage, const std::string& what)
    : device_(device.device()), size_(size) {
    if ((usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) && size > bufferLimit(device, BufferKind::Storage).bytes)
        throw bufferTooLarge(device, what, size, BufferKind::Storage);
    if ((usage & (VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT)) &&
        size > bufferLimit(device, BufferKind::Texel).bytes)
        throw bufferTooLarge(device, what, size, BufferKind::Texel);
    VkBufferCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
        .size = size,
        .usage = usage,
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
    };
    VkBuffer buffer = VK_NULL_HANDLE;
    VK_CHECK(vkCreateBuffer(device_, &info, nullptr, &buffer));
    buffer_ = UniqueBuffer(device_, buffer);

    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(device_, buffer, &requirements);
    VkMemoryAllocateInfo allocate{
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .allocationSize = requirements.size,
        .memoryTypeIndex = device.findMemoryType(
            requirements.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
            VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT),
    };
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkResult result = vkAllocateMemory(device_, &allocate, nullptr, &memory);
    if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
        throw InputError("the scene does not fit the device: " + what + " needs " + describeBytes(size) +
                         " and allocating it failed with " + vkResultName(result));
    VK_CHECK(result);
    memory_ = UniqueMemory(device_, memory);
    VK_CHECK(vkBindBufferMemory(device_, buffer, memory, 0));
    VK_CHECK(vkMapMemory(device_, memory, 0, VK_WHOLE_SIZE, 0, &mapped_));
}

void GpuBuffer::makeTexelView() {
    VkBufferViewCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO,
        .buffer = buffer_.get(),
        .format = VK_FORMAT_R32G32B32A32_UINT,  // Vulkan requires its uniform and storage texel buffer support
        .offset = 0,
        .range = VK_WHOLE_SIZE,
    };
    VkBufferView view = VK_NULL_HANDLE;
    VK_CHECK(vkCreateBufferView(device_, &info, nullptr, &view));
    view_ = UniqueBufferView(device_, view);
}

GpuBuffer::~GpuBuffer() {
    if (mapped_ && memory_.get()) vkUnmapMemory(device_, memory_.get());
}

}  // namespace vitrum
