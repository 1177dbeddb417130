#include "gpu/vulkan_instance.h"

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <iostream>

#include "gpu/vulkan_error.h"

namespace vitrum {
namespace {

std::atomic<std::uint32_t> gValidationMessages{0};

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data, void* program) {
    ++gValidationMessages;
    std::cerr << static_cast<const char*>(program)
              << ": Vulkan validation: " << (data && data->pMessage ? data->pMessage : "(no message)") << "\n";
    return VK_FALSE;
}

}  // namespace

bool VulkanInstance::validationRequested() {
    const char* value = std::getenv("VITRUM_VALIDATION");
    return value && std::strcmp(value, "0") != 0;
}

std::uint32_t VulkanInstance::validationMessages() { return gValidationMessages.load(); }

VulkanInstance::VulkanInstance(const char* program, bool validation) : program_(program) {
    const VkApplicationInfo app{
        .sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
        .pApplicationName = program,
        .applicationVersion = VK_MAKE_VERSION(0, 1, 0),
        .pEngineName = "vitrum",
        .engineVersion = VK_MAKE_VERSION(0, 1, 0),
        .apiVersion = VK_API_VERSION_1_2,
    };
    const char* layer = "VK_LAYER_KHRONOS_validation";
    const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    const VkInstanceCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
        .pApplicationInfo = &app,
        .enabledLayerCount = validation ? 1u : 0u,
        .ppEnabledLayerNames = validation ? &layer : nullptr,
        .enabledExtensionCount = validation ? 1u : 0u,
        .ppEnabledExtensionNames = validation ? &extension : nullptr,
    };
    const VkResult result = vkCreateInstance(&info, nullptr, &instance_);
    if (result == VK_ERROR_LAYER_NOT_PRESENT)
        throw VulkanError(result,
                          "VITRUM_VALIDATION is set but the Khronos validation layer is not installed "
                          "(Debian package vulkan-validationlayers)");
    VK_CHECK(result);
    if (!validation) return;
    try {
        const VkDebugUtilsMessengerCreateInfoEXT messengerInfo{
            .sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT,
            .messageSeverity =
                VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT,
            .messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT,
            .pfnUserCallback = onValidationMessage,
            .pUserData = const_cast<char*>(program_),
        };
        auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
        if (!create) throw VulkanError(VK_ERROR_EXTENSION_NOT_PRESENT, "vkCreateDebugUtilsMessengerEXT missing");
        VK_CHECK(create(instance_, &messengerInfo, nullptr, &messenger_));
    } catch (...) {
        release();
        throw;
    }
}

VulkanInstance::~VulkanInstance() { release(); }

void VulkanInstance::release() {
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
        messenger_ = VK_NULL_HANDLE;
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
    instance_ = VK_NULL_HANDLE;
}

std::vector<VkPhysicalDevice> VulkanInstance::physicalDevices() const {
    std::uint32_t count = 0;
    VK_CHECK(vkEnumeratePhysicalDevices(instance_, &count, nullptr));
    std::vector<VkPhysicalDevice> devices(count);
    VK_CHECK(vkEnumeratePhysicalDevices(instance_, &count, devices.data()));
    return devices;
}

}  // namespace vitrum
