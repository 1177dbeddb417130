#include "gpu/gpu_buffer.h"

#include <cstdlib>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "common/error.h"
#include "common/huge_pages.h"
#include "gpu/vulkan_error.h"

namespace vitrum {
namespace {

// VITRUM_MAX_BUFFER_BYTES=N lowers the buffer limits to N bytes, never raises them: a device with
// smaller buffers (docs/environment.md).
std::optional<VkDeviceSize> environmentBufferLimit() {
    const char* text = std::getenv("VITRUM_MAX_BUFFER_BYTES");
    if (!text || !*text) return std::nullopt;
    char* end = nullptr;
    unsigned long long value = std::strtoull(text, &end, 10);
    if (*end != '\0') return std::nullopt;
    return VkDeviceSize(value);
}

}  // namespace

std::vector<std::uint32_t> memoryTypesFor(const VkPhysicalDeviceMemoryProperties& memory, std::uint32_t typeBits,
                                          MemoryUse use) {
    constexpr VkMemoryPropertyFlags kMappable = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    // What each use requires, and what it prefers on top where the device has it. Vulkan lists a
    // device's memory types so that, of two equally fast ones, the one with fewer properties comes
    // first: the first device-local type is a discrete GPU's own memory, before the part of it the
    // host can map, and the first mappable type is host memory.
    VkMemoryPropertyFlags required = kMappable, preferred = 0;
    switch (use) {
        case MemoryUse::HostShared: preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT; break;
        case MemoryUse::Readback: preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT; break;
        case MemoryUse::Upload:
        case MemoryUse::DeviceOnly: required = 0, preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT; break;
        case MemoryUse::Staging: break;
    }
    auto has = [&](std::uint32_t i, VkMemoryPropertyFlags flags) {
        return (typeBits & (1u << i)) && (memory.memoryTypes[i].propertyFlags & flags) == flags;
    };
    std::vector<std::uint32_t> types;
    for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i)
        if (has(i, required | preferred)) types.push_back(i);
    for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i)
        if (has(i, required) && !has(i, required | preferred)) types.push_back(i);
    return types;
}

std::optional<std::uint32_t> firstTypeWithRoom(std::span<const std::uint32_t> types,
                                               const std::function<VkResult(std::uint32_t)>& allocate) {
    for (std::uint32_t type : types) {
        const VkResult result = allocate(type);
        if (result == VK_SUCCESS) return type;
        if (result != VK_ERROR_OUT_OF_DEVICE_MEMORY && result != VK_ERROR_OUT_OF_HOST_MEMORY)
            throwVulkanError(result, "vkAllocateMemory", __FILE__, __LINE__);
    }
    return std::nullopt;
}

bool stagedUploadsForced() {
    const char* text = std::getenv("VITRUM_STAGED_UPLOADS");
    return text && std::string_view(text) == "1";
}

BufferLimit bufferLimit(const VulkanDevice& device, BufferKind kind) {
    const VkPhysicalDeviceLimits& limits = device.properties().limits;
    BufferLimit limit = kind == BufferKind::Storage
                            ? BufferLimit{limits.maxStorageBufferRange, "maxStorageBufferRange"}
                            : BufferLimit{VkDeviceSize(limits.maxTexelBufferElements) * 16, "maxTexelBufferElements"};
    if (auto test = environmentBufferLimit(); test && *test < limit.bytes) limit = {*test, "VITRUM_MAX_BUFFER_BYTES"};
    return limit;
}

std::string describeBufferLimit(const VulkanDevice& device, BufferKind kind) {
    const BufferLimit limit = bufferLimit(device, kind);
    return device.name() + " allows " + describeBytes(limit.bytes) +
           (kind == BufferKind::Storage ? " per storage buffer (" : " per texel buffer of 16-byte texels (") +
           limit.source + ")";
}

InputError bufferTooLarge(const VulkanDevice& device, const std::string& what, VkDeviceSize size, BufferKind kind) {
    return InputError("the scene does not fit the device: " + what + " needs " + describeBytes(size) + ", but " +
                      describeBufferLimit(device, kind));
}

GpuBuffer::GpuBuffer(const VulkanDevice& device, VkDeviceSize size, VkBufferUsageFlags usage, const std::string& what,
                     MemoryUse use)
    : device_(device.device()), size_(size) {
    if ((usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) && size > bufferLimit(device, BufferKind::Storage).bytes)
        throw bufferTooLarge(device, what, size, BufferKind::Storage);
    if ((usage & (VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT)) &&
        size > bufferLimit(device, BufferKind::Texel).bytes)
        throw bufferTooLarge(device, what, size, BufferKind::Texel);
    VkBufferCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
        .size = size,
        .usage = usage | (use == MemoryUse::Upload ? VkBufferUsageFlags(VK_BUFFER_USAGE_TRANSFER_DST_BIT) : 0u),
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
    };
    VkBuffer buffer = VK_NULL_HANDLE;
    VK_CHECK(vkCreateBuffer(device_, &info, nullptr, &buffer));
    buffer_ = UniqueBuffer(device_, buffer);

    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(device_, buffer, &requirements);
    const std::vector<std::uint32_t> types = memoryTypesFor(device.memoryProperties(), requirements.memoryTypeBits, use);
    if (types.empty()) throw VulkanError(VK_ERROR_FEATURE_NOT_PRESENT, "no memory type of " + device.name() + " fits " + what);
    VkDeviceMemory memory = VK_NULL_HANDLE;
    const std::optional<std::uint32_t> type = firstTypeWithRoom(types, [&](std::uint32_t candidate) {
        const VkMemoryAllocateInfo allocate{
            .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
            .allocationSize = requirements.size,
            .memoryTypeIndex = candidate,
        };
        return vkAllocateMemory(device_, &allocate, nullptr, &memory);
    });
    if (!type)
        throw InputError("the scene does not fit the device: " + what + " needs " + describeBytes(size) +
                         " and no memory of " + device.name() + " that could hold it has room");
    const VkMemoryType* memoryTypes = device.memoryProperties().memoryTypes;
    auto deviceLocal = [&](std::uint32_t t) { return (memoryTypes[t].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT) != 0; };
    if (deviceLocal(types.front()) && !deviceLocal(*type))
        warn(what + " did not fit " + device.name() + "'s own memory: the kernels read it from host memory, more slowly");
    memory_ = UniqueMemory(device_, memory);
    VK_CHECK(vkBindBufferMemory(device_, buffer, memory, 0));
    const VkMemoryPropertyFlags mappable = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    const bool map = use == MemoryUse::Upload ? !stagedUploadsForced() : use != MemoryUse::DeviceOnly;
    if (map && (memoryTypes[*type].propertyFlags & mappable) == mappable) {
        VK_CHECK(vkMapMemory(device_, memory, 0, VK_WHOLE_SIZE, 0, &mapped_));
        // A device on the CPU (lavapipe) maps its memory as the process's own: huge pages spare
        // a big model's upload a page fault every 4 KiB.
        if (device.description().cpu) adviseHugePages(mapped_, size);
    }
}

void GpuBuffer::fill(VulkanDevice& device, std::span<const std::byte> bytes) {
    if (bytes.empty()) return;  // an empty vector's data() may be null: memcpy must not see it
    write(device, bytes.size(), [&](void* into) { std::memcpy(into, bytes.data(), bytes.size()); });
}

void GpuBuffer::write(VulkanDevice& device, VkDeviceSize size, const std::function<void(void*)>& writer) {
    if (size == 0) return;
    if (size > size_) throw std::logic_error("GpuBuffer::write: more bytes than the buffer holds");
    if (mapped_) {
        writer(mapped_);
        return;
    }
    GpuBuffer staging(device, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, "staging buffer", MemoryUse::Staging);
    writer(staging.mapped());
    device.submitAndWait([&](VkCommandBuffer commands) {
        const VkBufferCopy region{.srcOffset = 0, .dstOffset = 0, .size = size};
        vkCmdCopyBuffer(commands, staging.buffer(), buffer(), 1, &region);
        // The copy's writes made visible to the kernels that read the buffer in later submissions.
        const VkMemoryBarrier barrier{
            .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
            .srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT,
            .dstAccessMask = VK_ACCESS_SHADER_READ_BIT,
        };
        vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1,
                             &barrier, 0, nullptr, 0, nullptr);
    });
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
