// Every Vulkan call goes through VK_CHECK: a failure becomes a VulkanError that names the
// VkResult, the call and the source line.
#pragma once

#include <stdexcept>
#include <string>

#include <vulkan/vulkan.h>

namespace vitrum {

class VulkanError : public std::runtime_error {
public:
    VulkanError(VkResult result, const std::string& message) : std::runtime_error(message), result_(result) {}
    VkResult result() const { return result_; }

private:
    VkResult result_;
};

const char* vkResultName(VkResult result);

void throwVulkanError(VkResult result, const char* call, const char* file, int line);

inline void checkVk(VkResult result, const char* call, const char* file, int line) {
    if (result != VK_SUCCESS) throwVulkanError(result, call, file, line);
}

}  // namespace vitrum

#define VK_CHECK(call) ::vitrum::checkVk((call), #call, __FILE__, __LINE__)
