#include "gpu/vulkan_error.h"

#include <filesystem>

namespace vitrum {

const char* vkResultName(VkResult result) {
    switch (result) {
#define VITRUM_RESULT(name) \
    case name:              \
        return #name;
        VITRUM_RESULT(VK_SUCCESS)
        VITRUM_RESULT(VK_NOT_READY)
        VITRUM_RESULT(VK_TIMEOUT)
        VITRUM_RESULT(VK_INCOMPLETE)
        VITRUM_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
        VITRUM_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
        VITRUM_RESULT(VK_ERROR_INITIALIZATION_FAILED)
        VITRUM_RESULT(VK_ERROR_DEVICE_LOST)
        VITRUM_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
        VITRUM_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
        VITRUM_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
        VITRUM_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
        VITRUM_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
        VITRUM_RESULT(VK_ERROR_TOO_MANY_OBJECTS)
        VITRUM_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
        VITRUM_RESULT(VK_ERROR_FRAGMENTED_POOL)
        VITRUM_RESULT(VK_ERROR_UNKNOWN)
        VITRUM_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY)
        VITRUM_RESULT(VK_ERROR_INVALID_EXTERNAL_HANDLE)
        VITRUM_RESULT(VK_ERROR_FRAGMENTATION)
#undef VITRUM_RESULT
        default:
            return "VkResult(unknown)";
    }
}

void throwVulkanError(VkResult result, const char* call, const char* file, int line) {
    std::string where = std::filesystem::path(file).filename().string() + ":" + std::to_string(line);
    std::string hint;
    if (result == VK_ERROR_INCOMPATIBLE_DRIVER || result == VK_ERROR_INITIALIZATION_FAILED)
        hint = " (is a Vulkan driver installed? lavapipe comes with Debian's mesa-vulkan-drivers)";
    if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
        hint = " (the scene or image does not fit in the device's memory)";
    throw VulkanError(result, std::string("Vulkan call failed with ") + vkResultName(result) + ": " + call + " at " +
                                  where + hint);
}

}  // namespace vitrum
