// The Vulkan instance, the chosen physical device, its logical device and one compute queue.
// With VITRUM_VALIDATION=1 in the environment the Khronos validation layer is enabled and every
// message it sends is printed and counted (tests fail on any).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/vulkan_handle.h"

namespace vitrum {

struct DeviceDescription {
    std::uint32_t index = 0;
    std::string name;
    std::string type;  // "discrete GPU", "integrated GPU", "CPU", ...
    std::uint32_t apiVersion = 0;
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
    VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
    VkQueue queue() const { return queue_; }
    std::uint32_t queueFamily() const { return queueFamily_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    std::string name() const { return properties_.deviceName; }
    // Whether compute shaders may use subgroup arithmetic and ballots (subgroupAdd,
    // subgroupBallot), as trace.comp's statistics do: not a Vulkan 1.2 requirement, though
    // lavapipe and desktop GPUs have both.
    bool hasSubgroupArithmeticAndBallot() const { return subgroupArithmeticAndBallot_; }
    // Whether a compute pipeline may require full subgroups
    // (VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT: VK_EXT_subgroup_size_control's
    // computeFullSubgroups, enabled on this device) and shuffle within them; implies
    // hasSubgroupArithmeticAndBallot. Such a kernel's workgroup width must be a multiple of
    // maxSubgroupSize.
    bool hasFullSubgroups() const { return fullSubgroups_; }
    std::uint32_t maxSubgroupSize() const { return maxSubgroupSize_; }
    // Messages the validation layer sent so far (0 when validation is off).
    std::uint32_t validationMessages() const;

    // A memory type with all of `required` among `typeBits`; throws if there is none.
    std::uint32_t findMemoryType(std::uint32_t typeBits, VkMemoryPropertyFlags required) const;
    // Prefers `preferred` on top of `required` where the device has it.
    std::uint32_t findMemoryType(std::uint32_t typeBits, VkMemoryPropertyFlags required,
                                 VkMemoryPropertyFlags preferred) const;

    // Records commands with `record`, submits them and waits for them to finish.
    template <class Record>
    void submitAndWait(Record&& record);

private:
    void release();
    VkCommandBuffer beginCommands();
    void endSubmitWait(VkCommandBuffer commands);

    VkInstance instance_ = VK_NULL_HANDLE;
    bool subgroupArithmeticAndBallot_ = false;
    bool fullSubgroups_ = false;
    std::uint32_t maxSubgroupSize_ = 0;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memoryProperties_{};
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    std::uint32_t queueFamily_ = 0;
    UniqueCommandPool commandPool_;
    UniqueFence fence_;
};

template <class Record>
void VulkanDevice::submitAndWait(Record&& record) {
    VkCommandBuffer commands = beginCommands();
    record(commands);
    endSubmitWait(commands);
}

}  // namespace vitrum
