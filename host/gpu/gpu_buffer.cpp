#include "gpu/gpu_buffer.h"

#include "common/error.h"
#include "gpu/vulkan_error.h"

namespace vitrum {
namespace {
std::string mebibytes(VkDeviceSize bytes) {
    return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB";
}
}  // namespace

GpuBuffer::GpuBuffer(const VulkanDevice& device, VkDeviceSize size, VkBufferUsageFlags usage, const std::string& what)
    : device_(device.device()), size_(size) {
    const auto& limits = device.properties().limits;
    if ((usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) && size > limits.maxStorageBufferRange)
        throw InputError("the scene does not fit the device: " + what + " needs " + mebibytes(size) + ", but " +
                         device.name() + " allows " + mebibytes(limits.maxStorageBufferRange) +
                         " per storage buffer (maxStorageBufferRange)");
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
        throw InputError("the scene does not fit the device: " + what + " needs " + mebibytes(size) +
                         " and allocating it failed with " + vkResultName(result));
    VK_CHECK(result);
    memory_ = UniqueMemory(device_, memory);
    VK_CHECK(vkBindBufferMemory(device_, buffer, memory, 0));
    VK_CHECK(vkMapMemory(device_, memory, 0, VK_WHOLE_SIZE, 0, &mapped_));
}

GpuBuffer::~GpuBuffer() {
    if (mapped_ && memory_.get()) vkUnmapMemory(device_, memory_.get());
}

}  // namespace vitrum
