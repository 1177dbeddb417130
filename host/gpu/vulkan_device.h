// The chosen physical device of a Vulkan instance (gpu/vulkan_instance.h, which validates with
// VITRUM_VALIDATION=1), its logical device and one compute queue.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/vulkan_handle.h"
#include "gpu/vulkan_instance.h"

namespace vitrum {

// What a device's subgroups can do for trace.comp (shaders/lanes.glsl, shaders/statistics.glsl).
struct SubgroupSupport {
    std::uint32_t size = 0;  // VkPhysicalDeviceSubgroupProperties::subgroupSize (lavapipe: 8)
    // Compute shaders may use subgroup arithmetic and ballots (subgroupAdd, subgroupBallot), as
    // trace.comp's statistics do: not a Vulkan 1.2 requirement, though lavapipe and desktop GPUs
    // have both.
    bool arithmeticAndBallot = false;
    // A compute pipeline may require full subgroups (VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT:
    // VK_EXT_subgroup_size_control's computeFullSubgroups) and shuffle within them; implies
    // arithmeticAndBallot. Such a kernel's workgroup width must be a multiple of maxSize.
    bool fullSubgroups = false;
    std::uint32_t maxSize = 0;  // the largest subgroup size a pipeline may get; 0 without size control
};

struct DeviceDescription {
    std::uint32_t index = 0;
    std::string name;
    std::string type;  // "discrete GPU", "integrated GPU", "CPU", ...
    bool cpu = false;  // VK_PHYSICAL_DEVICE_TYPE_CPU: lavapipe
    std::uint32_t apiVersion = 0;
    // The driver and its version (VkPhysicalDeviceDriverProperties, Vulkan 1.2): "llvmpipe",
    // "Mesa 25.0.7-2~bpo12+1 (LLVM 15.0.6)". Two builds of one driver can differ in what they
    // do beyond the spec (docs/gpu-design.md, "Two drivers").
    std::string driverName;
    std::string driverInfo;
    SubgroupSupport subgroups;
    std::uint64_t maxStorageBufferRange = 0;  // bytes a storage buffer binding may span
    std::uint32_t maxTexelBufferElements = 0;
    // Kernels may keep IEEE infinities, NaNs and signed zeros (VkPhysicalDeviceFloatControlsProperties::
    // shaderSignedZeroInfNanPreserveFloat32); vitrum asks for it wherever it can (gpu/spirv_float_semantics.h).
    bool preservesInfNan = false;
    // The largest device-local memory heap, and the largest one that also has a host-visible
    // memory type (a discrete GPU's mappable window into its memory: 256 MiB without resizable
    // BAR, all of it with; the whole heap where the device's memory is the host's).
    std::uint64_t deviceLocalBytes = 0;
    std::uint64_t mappableDeviceLocalBytes = 0;
};

class VulkanDevice {
public:
    // `selector`: "" picks the first discrete GPU, else the first integrated one, else the first
    // device (lavapipe on a machine without a GPU); a number picks by index; anything else picks
    // the first device whose name contains it (case-insensitive). Throws InputError if none fits.
    explicit VulkanDevice(const std::string& selector = "");
    ~VulkanDevice();
    VulkanDevice(const VulkanDevice&) = delete;
    VulkanDevice& operator=(const VulkanDevice&) = delete;

    static std::vector<DeviceDescription> listDevices();

    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    std::string name() const { return properties_.deviceName; }
    // What listDevices says of this device.
    const DeviceDescription& description() const { return description_; }
    // SubgroupSupport says what these mean; full subgroups are enabled on this device where it
    // has them.
    const SubgroupSupport& subgroups() const { return description_.subgroups; }
    bool hasSubgroupArithmeticAndBallot() const { return subgroups().arithmeticAndBallot; }
    bool hasFullSubgroups() const { return subgroups().fullSubgroups; }
    // DeviceDescription::preservesInfNan.
    bool preservesInfNan() const { return description_.preservesInfNan; }
    // Which trace kernel this device gets, and why (gpu/subgroup_self_check.h): "fast: ..." where
    // full subgroups passed the self-check, else "safe: ..." with the reason.
    const std::string& kernelPath() const { return kernelPath_; }
    // Messages the validation layer sent so far, to any device of the process (0 when validation is off).
    std::uint32_t validationMessages() const { return VulkanInstance::validationMessages(); }

    const VkPhysicalDeviceMemoryProperties& memoryProperties() const { return memoryProperties_; }

    // Records commands with `record`, submits them and waits for them to finish. The command
    // buffer goes back to the pool on every way out, a `record` that throws included.
    template <class Record>
    void submitAndWait(Record&& record);
    // Command buffers taken from the pool and not yet freed: 0 between submitAndWait calls
    // (the pool would grow with each one left behind, unseen by the driver and the validation layer).
    std::uint32_t commandBuffersInUse() const { return commandBuffersInUse_; }

private:
    // A command buffer of the device's pool, freed when it goes out of scope.
    class PooledCommands {
    public:
        explicit PooledCommands(VulkanDevice& device);
        ~PooledCommands();
        PooledCommands(const PooledCommands&) = delete;
        PooledCommands& operator=(const PooledCommands&) = delete;
        VkCommandBuffer get() const { return commands_; }

    private:
        VulkanDevice& device_;
        VkCommandBuffer commands_ = VK_NULL_HANDLE;
    };

    void release();
    void chooseKernelPath();
    void beginCommands(VkCommandBuffer commands);
    void endSubmitWait(VkCommandBuffer commands);

    VulkanInstance instance_;  // first: destroyed after the device
    DeviceDescription description_;
    std::string kernelPath_;
    VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memoryProperties_{};
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    std::uint32_t queueFamily_ = 0;
    UniqueCommandPool commandPool_;
    UniqueFence fence_;
    std::uint32_t commandBuffersInUse_ = 0;
};

template <class Record>
void VulkanDevice::submitAndWait(Record&& record) {
    const PooledCommands commands(*this);
    beginCommands(commands.get());
    record(commands.get());
    endSubmitWait(commands.get());
}

}  // namespace vitrum
