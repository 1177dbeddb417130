// A Vulkan buffer with its own memory, placed by how it is used (MemoryUse). On lavapipe every
// memory type is host memory and every use gets the same one; on a discrete GPU the kernels' own
// buffers and the scene live in the GPU's memory, which the host may not be able to map, and the
// image comes back through memory the host reads fast (docs/gpu-design.md, "Memory").
#pragma once

#include <cstddef>
#include <cstring>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/byte_size.h"
#include "common/error.h"
#include "gpu/vulkan_device.h"
#include "gpu/vulkan_handle.h"

namespace vitrum {

// Who reads and writes a buffer, which decides its memory type.
enum class MemoryUse {
    // Written and read by the host between dispatches, and by kernels (render parameters,
    // statistics): host-visible and coherent, device-local where such memory exists. Mapped.
    HostShared,
    // Written by kernels, read by the host (the image, test results): host-visible and coherent,
    // host-cached where such memory exists, since reads from uncached memory (a discrete GPU's
    // mappable memory) crawl. Mapped.
    Readback,
    // Filled once by the host (makeTexelBuffer, makeStorageBuffer), then only read by kernels:
    // device-local, mapped and written directly where that memory is host-visible, else filled
    // by a copy from a staging buffer.
    Upload,
    // Used by kernels alone (trace state, pending rays, stacks): device-local, never mapped.
    DeviceOnly,
    // Written by the host, copied from by the device (fill's staging buffers): host-visible and
    // coherent, the first such type (host memory on a discrete GPU). Mapped.
    Staging,
};

class GpuBuffer;
template <class T>
GpuBuffer makeTexelBuffer(VulkanDevice& device, std::span<const T> data, const std::string& what,
                          MemoryUse use = MemoryUse::Upload);
template <class T, class Write>
GpuBuffer makeTexelBufferWritten(VulkanDevice& device, std::size_t count, const std::string& what, Write write);

class GpuBuffer {
public:
    GpuBuffer() = default;
    // `what` names the buffer in errors ("BVH nodes needs 300 MiB, the device allows 128 MiB").
    GpuBuffer(const VulkanDevice& device, VkDeviceSize size, VkBufferUsageFlags usage, const std::string& what,
              MemoryUse use = MemoryUse::HostShared);
    ~GpuBuffer();
    GpuBuffer(GpuBuffer&&) noexcept = default;
    GpuBuffer& operator=(GpuBuffer&&) noexcept = default;

    VkBuffer buffer() const { return buffer_.get(); }
    // The uvec4 texel view of a buffer made by makeTexelBuffer (VK_NULL_HANDLE otherwise).
    VkBufferView texelView() const { return view_.get(); }
    VkDeviceSize size() const { return size_; }
    // Null for a buffer the host cannot map (DeviceOnly, or Upload in memory that is not host-visible).
    void* mapped() const { return mapped_; }

    // Writes `bytes` at the buffer's start: directly where it is mapped, else through a staging
    // buffer and a copy on `device`'s queue, after which kernels may read it.
    void fill(VulkanDevice& device, std::span<const std::byte> bytes);
    // The same for `size` bytes that `writer` writes at the pointer it is given: the buffer's own
    // memory where it is mapped, else the staging buffer's (no copy of them in between).
    void write(VulkanDevice& device, VkDeviceSize size, const std::function<void(void*)>& writer);
    template <class T>
    T* as() const {
        return static_cast<T*>(mapped_);
    }

private:
    template <class T>
    friend GpuBuffer makeTexelBuffer(VulkanDevice&, std::span<const T>, const std::string&, MemoryUse);
    template <class T, class Write>
    friend GpuBuffer makeTexelBufferWritten(VulkanDevice&, std::size_t, const std::string&, Write);
    void makeTexelView();

    UniqueBuffer buffer_;
    UniqueBufferView view_;
    UniqueMemory memory_;
    VkDevice device_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;
};

// What a buffer is bound as: its size limit differs.
enum class BufferKind { Storage, Texel };

// The largest buffer of a kind the checks allow: the device's maxStorageBufferRange, or
// maxTexelBufferElements texels of 16 bytes, or less where the environment variable
// VITRUM_MAX_BUFFER_BYTES asks for less (docs/environment.md).
struct BufferLimit {
    VkDeviceSize bytes;
    const char* source;  // "maxStorageBufferRange", "maxTexelBufferElements" or "VITRUM_MAX_BUFFER_BYTES"
};
BufferLimit bufferLimit(const VulkanDevice& device, BufferKind kind);
// "DEVICE allows M MiB per storage buffer (maxStorageBufferRange)"
std::string describeBufferLimit(const VulkanDevice& device, BufferKind kind);
// "the scene does not fit the device: WHAT needs N MiB, but DEVICE allows M MiB per storage buffer (...)"
InputError bufferTooLarge(const VulkanDevice& device, const std::string& what, VkDeviceSize size, BufferKind kind);

// The memory types of `memory` for a buffer of that use that may be bound to the types in
// `typeBits` (VkMemoryRequirements::memoryTypeBits), best first: those with what the use prefers,
// then those with only what it requires; empty where no type has what the use requires. A buffer
// takes the first that has room (a GPU's own memory may be full: then the host's).
std::vector<std::uint32_t> memoryTypesFor(const VkPhysicalDeviceMemoryProperties& memory, std::uint32_t typeBits,
                                          MemoryUse use);

// The first of `types` that `allocate` gets memory of (`allocate(type)` is the driver's answer);
// none where each is out of device or host memory. Any other failure throws a VulkanError.
std::optional<std::uint32_t> firstTypeWithRoom(std::span<const std::uint32_t> types,
                                               const std::function<VkResult(std::uint32_t)>& allocate);

// VITRUM_STAGED_UPLOADS=1 fills every Upload buffer through a staging buffer, as on a discrete
// GPU, also where its memory is mappable (lavapipe's always is; docs/environment.md).
bool stagedUploadsForced();

// A texel buffer of R32G32B32A32_UINT texels holding `data`, whose size must be a multiple of 16
// bytes, for reading as a storage texel buffer (a readonly uimageBuffer, how trace.comp reads the
// scene: shaders/bindings.glsl) or as a uniform texel buffer (a usamplerBuffer, as the plain
// baseline of bench/baseline does). Checks the size against the device's maxTexelBufferElements
// first. `use`: Upload, or HostShared for one the host writes again between dispatches.
template <class T>
GpuBuffer makeTexelBuffer(VulkanDevice& device, std::span<const T> data, const std::string& what, MemoryUse use) {
    static_assert(sizeof(T) % 16 == 0, "texel buffers hold whole uvec4 texels");
    VkDeviceSize size = std::max<VkDeviceSize>(data.size_bytes(), 16);
    GpuBuffer buffer(device, size, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT,
                     what, use);
    buffer.fill(device, std::as_bytes(data));
    buffer.makeTexelView();
    return buffer;
}

// A texel buffer of `count` elements that `write(std::span<T>)` writes where they are to live:
// straight into the buffer where the host can map it, else into the staging buffer it is copied
// from (GpuBuffer::write): no second copy of a big model's array either way. MemoryUse::Upload.
template <class T, class Write>
GpuBuffer makeTexelBufferWritten(VulkanDevice& device, std::size_t count, const std::string& what, Write write) {
    static_assert(sizeof(T) % 16 == 0, "texel buffers hold whole uvec4 texels");
    const VkDeviceSize size = std::max<VkDeviceSize>(count * sizeof(T), 16);
    GpuBuffer buffer(device, size, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT,
                     what, MemoryUse::Upload);
    buffer.write(device, count * sizeof(T), [&](void* into) { write(std::span<T>(static_cast<T*>(into), count)); });
    buffer.makeTexelView();
    return buffer;
}

// A storage buffer holding `data` (at least 16 bytes: Vulkan has no empty buffers). Checks the
// size against the device's maxStorageBufferRange first. MemoryUse::Upload.
template <class T>
GpuBuffer makeStorageBuffer(VulkanDevice& device, std::span<const T> data, const std::string& what) {
    VkDeviceSize size = std::max<VkDeviceSize>(data.size_bytes(), 16);
    GpuBuffer buffer(device, size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, what, MemoryUse::Upload);
    buffer.fill(device, std::as_bytes(data));
    return buffer;
}

}  // namespace vitrum
