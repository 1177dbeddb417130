// The driver's own traversal, for bench/ray_query_bench.cpp: a Vulkan device opened with
// VK_KHR_acceleration_structure and VK_KHR_ray_query, the acceleration structures the driver
// builds from a scene's triangles (one bottom level, and a top level that holds it once, at the
// identity), and bench/ray_query/trace_rays_query.comp tracing a list of rays through them, one
// ray an invocation: what a renderer that left traversal to the driver would trace with.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include <vulkan/vulkan.h>
#include <glm/glm.hpp>

#include "cpu/reference_renderer.h"
#include "gpu/vulkan_handle.h"
#include "gpu/vulkan_instance.h"

namespace vitrum::bench {

class RayQueryDevice;

// A buffer with its own memory and its device address; mapped where the host writes or reads it.
class RayQueryBuffer {
public:
    RayQueryBuffer() = default;
    RayQueryBuffer(const RayQueryDevice& device, VkDeviceSize size, VkBufferUsageFlags usage, bool mapped);
    VkBuffer buffer() const { return buffer_.get(); }
    VkDeviceAddress address() const { return address_; }
    void* mapped() const { return mapped_; }

private:
    UniqueMemory memory_;  // freed after the buffer bound to it
    UniqueBuffer buffer_;
    VkDeviceAddress address_ = 0;
    void* mapped_ = nullptr;
};

// An acceleration structure and the buffer that holds it; vkDestroyAccelerationStructureKHR is an
// extension's function, so DeviceHandle cannot hold it.
class AccelerationStructure {
public:
    AccelerationStructure() = default;
    AccelerationStructure(const RayQueryDevice& device, VkAccelerationStructureTypeKHR type, VkDeviceSize size);
    ~AccelerationStructure() { reset(); }
    AccelerationStructure(AccelerationStructure&& other) noexcept;
    AccelerationStructure& operator=(AccelerationStructure&& other) noexcept;
    AccelerationStructure(const AccelerationStructure&) = delete;
    AccelerationStructure& operator=(const AccelerationStructure&) = delete;

    VkAccelerationStructureKHR get() const { return handle_; }
    VkDeviceAddress address() const { return address_; }

private:
    void reset();
    const RayQueryDevice* device_ = nullptr;
    RayQueryBuffer storage_;
    VkAccelerationStructureKHR handle_ = VK_NULL_HANDLE;
    VkDeviceAddress address_ = 0;
};

// The first device of a Vulkan instance (gpu/vulkan_instance.h, which validates with
// VITRUM_VALIDATION=1, as VulkanDevice's) that offers ray queries, one compute queue and the
// ray-query kernel's pipeline.
class RayQueryDevice {
public:
    // Throws std::runtime_error, naming every device's driver, where none offers ray queries.
    RayQueryDevice();
    ~RayQueryDevice();
    RayQueryDevice(const RayQueryDevice&) = delete;
    RayQueryDevice& operator=(const RayQueryDevice&) = delete;

    // One line a device: its driver ("Mesa 22.3.6 (LLVM 15.0.6)") and "ray queries", or what it
    // lacks of them ("no VK_KHR_acceleration_structure, no VK_KHR_ray_query, ...").
    static std::string describeDevices();

    // Its index among the instance's devices: VulkanDevice(std::to_string(index())) opens the same one.
    std::uint32_t index() const { return index_; }
    const std::string& name() const { return name_; }
    const std::string& driverInfo() const { return driverInfo_; }

    VkDevice device() const { return device_; }
    std::uint32_t memoryType(std::uint32_t allowed, bool mapped) const;
    VkDeviceSize scratchAlignment() const { return scratchAlignment_; }

    // Records commands with `record`, submits them and waits for them to finish.
    template <class Record>
    void submitAndWait(Record&& record) const {
        VkCommandBuffer commands = begin();
        try {
            record(commands);
        } catch (...) {
            vkFreeCommandBuffers(device_, pool_.get(), 1, &commands);
            throw;
        }
        endSubmitWait(commands);
    }

    // The extension's functions, from vkGetDeviceProcAddr.
    PFN_vkCreateAccelerationStructureKHR createAccelerationStructure = nullptr;
    PFN_vkDestroyAccelerationStructureKHR destroyAccelerationStructure = nullptr;
    PFN_vkGetAccelerationStructureBuildSizesKHR getBuildSizes = nullptr;
    PFN_vkCmdBuildAccelerationStructuresKHR cmdBuild = nullptr;
    PFN_vkGetAccelerationStructureDeviceAddressKHR getAddress = nullptr;

    // The kernel: set 0 = (the top-level structure, the rays' texels, the hits), a push constant
    // the ray count.
    VkDescriptorSetLayout setLayout() const { return setLayout_.get(); }
    VkPipelineLayout pipelineLayout() const { return pipelineLayout_.get(); }
    VkPipeline pipeline() const { return pipeline_.get(); }

private:
    VkCommandBuffer begin() const;
    void endSubmitWait(VkCommandBuffer commands) const;
    void createPipeline();
    void release();

    VulkanInstance instance_;  // first: destroyed after the device
    VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
    VkPhysicalDeviceMemoryProperties memory_{};
    std::uint32_t index_ = 0;
    std::string name_, driverInfo_;
    VkDeviceSize scratchAlignment_ = 1;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    UniqueCommandPool pool_;
    UniqueFence fence_;
    UniqueDescriptorSetLayout setLayout_;
    UniquePipelineLayout pipelineLayout_;
    UniquePipeline pipeline_;
};

// The driver's acceleration structures over a list of triangles: a bottom level of one opaque
// triangle geometry (three corners a triangle, no index buffer, so that a hit's primitive is the
// triangle's place in the list), built for fast tracing, and a top level of one identity instance.
class RayQueryScene {
public:
    // `corners`: three a triangle. Builds both structures once.
    RayQueryScene(const RayQueryDevice& device, std::span<const glm::vec3> corners);
    // Builds both again, on the device (lavapipe offers no host builds); returns the seconds from
    // recording to the end of the build.
    double build(const RayQueryDevice& device) const;
    const AccelerationStructure& topLevel() const { return topLevel_; }
    // Bytes of the bottom level, as the driver sized it.
    VkDeviceSize bottomLevelBytes() const { return bottomSize_; }

private:
    std::uint32_t triangleCount_ = 0;
    RayQueryBuffer vertices_, instance_, bottomScratch_, topScratch_;
    AccelerationStructure bottomLevel_, topLevel_;
    VkDeviceSize bottomSize_ = 0;
};

// A list of rays traced through a RayQueryScene by trace_rays_query.comp.
class RayQueryTrace {
public:
    struct Hit {
        float t;  // the committed hit's, or -1
        std::uint32_t primitive;
    };

    // `order`: the rays to trace, in the order the kernel's invocations take them.
    RayQueryTrace(const RayQueryDevice& device, const RayQueryScene& scene, std::span<const TracedRay> rays,
                  std::span<const std::size_t> order);
    // Seconds to trace every ray once (the first call includes lavapipe's compile).
    double trace(const RayQueryDevice& device) const;
    const Hit& hit(std::size_t k) const { return static_cast<const Hit*>(hits_.mapped())[k]; }

private:
    std::uint32_t count_ = 0;
    RayQueryBuffer rays_, hits_;
    UniqueBufferView raysView_;
    UniqueDescriptorPool pool_;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace vitrum::bench
