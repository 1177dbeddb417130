// The Vulkan instance a program's devices come from. With VITRUM_VALIDATION=1 in the environment
// (docs/environment.md) it enables the Khronos validation layer, and every message the layer
// sends is printed and counted: the tests fail on any.
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

namespace vitrum {

class VulkanInstance {
public:
    // `program` names the instance to the driver and heads each validation message it prints
    // ("vitrum: Vulkan validation: ..."); it must outlive the instance (a string literal).
    explicit VulkanInstance(const char* program, bool validation = validationRequested());
    ~VulkanInstance();
    VulkanInstance(const VulkanInstance&) = delete;
    VulkanInstance& operator=(const VulkanInstance&) = delete;

    VkInstance get() const { return instance_; }
    std::vector<VkPhysicalDevice> physicalDevices() const;

    // Whether VITRUM_VALIDATION asks for the validation layer (set and not "0").
    static bool validationRequested();
    // Messages the validation layer sent so far, to every instance of the process.
    static std::uint32_t validationMessages();

private:
    void release();

    const char* program_;
    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
};

}  // namespace vitrum
