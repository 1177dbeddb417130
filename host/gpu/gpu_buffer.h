// A storage or uniform buffer in host-visible memory, mapped for its whole life (on lavapipe all
// memory is host memory; on a discrete GPU this prefers memory that is both device-local and
// mappable where the device has it).
#pragma once

#include <cstring>
#include <span>
#include <string>

#include "common/error.h"
#include "gpu/vulkan_device.h"
#include "gpu/vulkan_handle.h"

namespace vitrum {

class GpuBuffer {
public:
    GpuBuffer() = default;
    // `what` names the buffer in errors ("BVH nodes needs 300 MiB, the device allows 128 MiB").
    GpuBuffer(const VulkanDevice& device, VkDeviceSize size, VkBufferUsageFlags usage, const std::string& what);
    ~GpuBuffer();
    GpuBuffer(GpuBuffer&&) noexcept = default;
    GpuBuffer& operator=(GpuBuffer&&) noexcept = default;

    VkBuffer buffer() const { return buffer_.get(); }
    // The uvec4 texel view of a buffer made by makeTexelBuffer (VK_NULL_HANDLE otherwise).
    VkBufferView texelView() const { return view_.get(); }
    VkDeviceSize size() const { return size_; }
    void* mapped() const { return mapped_; }

    template <class T>
    void upload(std::span<const T> data) {
        if (data.empty()) return;  // an empty vector's data() may be null: memcpy must not see it
        std::memcpy(mapped_, data.data(), data.size_bytes());
    }
    template <class T>
    T* as() const {
        return static_cast<T*>(mapped_);
    }

private:
    template <class T>
    friend GpuBuffer makeTexelBuffer(const VulkanDevice&, std::span<const T>, const std::string&);
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
// VITRUM_MAX_BUFFER_BYTES (for tests only) asks for less.
struct BufferLimit {
    VkDeviceSize bytes;
    const char* source;  // "maxStorageBufferRange", "maxTexelBufferElements" or "VITRUM_MAX_BUFFER_BYTES"
};
BufferLimit bufferLimit(const VulkanDevice& device, BufferKind kind);
// "N bytes" below 1 MiB, else "N MiB" (rounded up).
std::string describeBytes(VkDeviceSize bytes);
// "the scene does not fit the device: WHAT needs N MiB, but DEVICE allows M MiB per storage buffer (...)"
InputError bufferTooLarge(const VulkanDevice& device, const std::string& what, VkDeviceSize size, BufferKind kind);

// A texel buffer of R32G32B32A32_UINT texels holding `data`, whose size must be a multiple of 16
// bytes, for reading as a storage texel buffer (a readonly uimageBuffer, how trace.comp reads the
// scene: shaders/bindings.glsl) or as a uniform texel buffer (a usamplerBuffer, as the plain
// baseline of bench/baseline does). Checks the size against the device's maxTexelBufferElements
// first.
template <class T>
GpuBuffer makeTexelBuffer(const VulkanDevice& device, std::span<const T> data, const std::string& what) {
    static_assert(sizeof(T) % 16 == 0, "texel buffers hold whole uvec4 texels");
    VkDeviceSize size = std::max<VkDeviceSize>(data.size_bytes(), 16);
    GpuBuffer buffer(device, size, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT,
                     what);
    buffer.upload(data);
    buffer.makeTexelView();
    return buffer;
}

// A storage buffer holding `data` (at least 16 bytes: Vulkan has no empty buffers). Checks the
// size against the device's maxStorageBufferRange first.
template <class T>
GpuBuffer makeStorageBuffer(const VulkanDevice& device, std::span<const T> data, const std::string& what) {
    VkDeviceSize size = std::max<VkDeviceSize>(data.size_bytes(), 16);
    GpuBuffer buffer(device, size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, what);
    buffer.upload(data);
    return buffer;
}

}  // namespace vitrum
