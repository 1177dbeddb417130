// VulkanInstance's validation: every message of the Khronos layer is counted and printed under the
// program's name. Every device test relies on the count ("any validation message fails the test").
#include "gpu_test_support.h"

#include "gpu/vulkan_instance.h"

namespace vitrum::testing {
namespace {

// A call the layer must report: VkPhysicalDeviceProperties2 with the wrong sType
// (VUID-VkPhysicalDeviceProperties2-sType-sType). Harmless if a driver saw it: pNext is null.
void makeOneMistake(VkPhysicalDevice device) {
    VkPhysicalDeviceProperties2 properties{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    vkGetPhysicalDeviceProperties2(device, &properties);
}

TEST(VulkanInstance, CountsAndNamesEveryValidationMessage) {
    const VulkanInstance instance("vitrum_instance_test", true);
    const std::vector<VkPhysicalDevice> devices = instance.physicalDevices();
    ASSERT_FALSE(devices.empty());
    const std::uint32_t before = VulkanInstance::validationMessages();
    ::testing::internal::CaptureStderr();
    makeOneMistake(devices.front());
    const std::string printed = ::testing::internal::GetCapturedStderr();
    EXPECT_GE(VulkanInstance::validationMessages(), before + 1u);
    EXPECT_NE(printed.find("vitrum_instance_test: Vulkan validation: "), std::string::npos) << printed;
    EXPECT_NE(printed.find("VUID-VkPhysicalDeviceProperties2-sType-sType"), std::string::npos) << printed;
}

TEST(VulkanInstance, WithoutTheLayerNothingIsCounted) {
    const VulkanInstance instance("vitrum_instance_test", false);
    const std::vector<VkPhysicalDevice> devices = instance.physicalDevices();
    ASSERT_FALSE(devices.empty());
    const std::uint32_t before = VulkanInstance::validationMessages();
    makeOneMistake(devices.front());
    EXPECT_EQ(VulkanInstance::validationMessages(), before);
}

}  // namespace
}  // namespace vitrum::testing
