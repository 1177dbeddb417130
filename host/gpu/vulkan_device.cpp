#include "gpu/vulkan_device.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>

#include "common/error.h"
#include "gpu/subgroup_self_check.h"
#include "gpu/trace_pipeline.h"
#include "gpu/vulkan_error.h"

namespace vitrum {
namespace {

const char* deviceTypeName(VkPhysicalDeviceType type) {
    switch (type) {
        case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
        case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
        case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
        case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
        default: return "other";
    }
}

std::string lowercase(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

// Index into `devices` per the selector rules in the header.
std::size_t selectDevice(const std::vector<VkPhysicalDevice>& devices, const std::string& selector) {
    std::vector<VkPhysicalDeviceProperties> props(devices.size());
    for (std::size_t i = 0; i < devices.size(); ++i) vkGetPhysicalDeviceProperties(devices[i], &props[i]);
    std::string known;
    for (std::size_t i = 0; i < devices.size(); ++i)
        known += (i ? ", " : "") + std::to_string(i) + ": " + props[i].deviceName;
    if (devices.empty())
        throw InputError("no Vulkan device found (install Debian's mesa-vulkan-drivers for lavapipe)");
    if (selector.empty()) {
        for (auto wanted : {VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU})
            for (std::size_t i = 0; i < devices.size(); ++i)
                if (props[i].deviceType == wanted && props[i].apiVersion >= VK_API_VERSION_1_2) return i;
        return 0;
    }
    if (std::all_of(selector.begin(), selector.end(), [](unsigned char c) { return std::isdigit(c); })) {
        std::size_t index = std::stoul(selector);
        if (index >= devices.size())
            throw InputError("--device " + selector + ": there are only " + std::to_string(devices.size()) +
                             " Vulkan devices (" + known + ")");
        return index;
    }
    for (std::size_t i = 0; i < devices.size(); ++i)
        if (lowercase(props[i].deviceName).find(lowercase(selector)) != std::string::npos) return i;
    throw InputError("--device " + selector + ": no Vulkan device has that in its name (" + known + ")");
}

// Whether the device can promise that a compute kernel runs in full subgroups
// (VK_EXT_subgroup_size_control's computeFullSubgroups, core in Vulkan 1.3), and its largest
// subgroup size.
bool canRequireFullSubgroups(VkPhysicalDevice device, std::uint32_t& maxSubgroupSize) {
    std::uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
    if (std::none_of(extensions.begin(), extensions.end(), [](const VkExtensionProperties& e) {
            return std::strcmp(e.extensionName, VK_EXT_SUBGROUP_SIZE_CONTROL_EXTENSION_NAME) == 0;
        }))
        return false;
    VkPhysicalDeviceSubgroupSizeControlFeaturesEXT features{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_SIZE_CONTROL_FEATURES_EXT};
    VkPhysicalDeviceFeatures2 features2{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &features};
    vkGetPhysicalDeviceFeatures2(device, &features2);
    VkPhysicalDeviceSubgroupSizeControlPropertiesEXT sizes{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_SIZE_CONTROL_PROPERTIES_EXT};
    VkPhysicalDeviceProperties2 properties2{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &sizes};
    vkGetPhysicalDeviceProperties2(device, &properties2);
    maxSubgroupSize = sizes.maxSubgroupSize;
    return features.subgroupSizeControl && features.computeFullSubgroups && maxSubgroupSize > 0;
}

bool keepsInfNan(VkPhysicalDevice device) {
    VkPhysicalDeviceFloatControlsProperties controls{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FLOAT_CONTROLS_PROPERTIES};
    VkPhysicalDeviceProperties2 properties2{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &controls};
    vkGetPhysicalDeviceProperties2(device, &properties2);
    return controls.shaderSignedZeroInfNanPreserveFloat32;
}

SubgroupSupport subgroupSupportOf(VkPhysicalDevice device) {
    VkPhysicalDeviceSubgroupProperties subgroup{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceProperties2 properties2{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &subgroup};
    vkGetPhysicalDeviceProperties2(device, &properties2);
    SubgroupSupport support;
    support.size = subgroup.subgroupSize;
    const VkSubgroupFeatureFlags statisticsOperations = VK_SUBGROUP_FEATURE_ARITHMETIC_BIT | VK_SUBGROUP_FEATURE_BALLOT_BIT;
    support.arithmeticAndBallot = (subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) &&
                                  (subgroup.supportedOperations & statisticsOperations) == statisticsOperations;
    support.fullSubgroups = support.arithmeticAndBallot && (subgroup.supportedOperations & VK_SUBGROUP_FEATURE_SHUFFLE_BIT) &&
                            canRequireFullSubgroups(device, support.maxSize);
    return support;
}

// DeviceDescription's deviceLocalBytes and mappableDeviceLocalBytes.
void describeMemory(VkPhysicalDevice device, DeviceDescription& description) {
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(device, &memory);
    for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
        const VkMemoryType& type = memory.memoryTypes[i];
        if (!(type.propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)) continue;
        const std::uint64_t heap = memory.memoryHeaps[type.heapIndex].size;
        description.deviceLocalBytes = std::max(description.deviceLocalBytes, heap);
        if (type.propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT)
            description.mappableDeviceLocalBytes = std::max(description.mappableDeviceLocalBytes, heap);
    }
}

DeviceDescription describeDevice(VkPhysicalDevice device, std::uint32_t index) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(device, &p);
    DeviceDescription d{.index = index,
                        .name = p.deviceName,
                        .type = deviceTypeName(p.deviceType),
                        .cpu = p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU,
                        .apiVersion = p.apiVersion,
                        .maxStorageBufferRange = p.limits.maxStorageBufferRange,
                        .maxTexelBufferElements = p.limits.maxTexelBufferElements};
    // Subgroup properties are Vulkan 1.1, float controls 1.2; vitrum refuses devices below 1.2.
    if (p.apiVersion >= VK_API_VERSION_1_1) d.subgroups = subgroupSupportOf(device);
    d.preservesInfNan = p.apiVersion >= VK_API_VERSION_1_2 && keepsInfNan(device);
    if (p.apiVersion >= VK_API_VERSION_1_2) {
        VkPhysicalDeviceDriverProperties driver{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
        VkPhysicalDeviceProperties2 properties2{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &driver};
        vkGetPhysicalDeviceProperties2(device, &properties2);
        d.driverName = driver.driverName;
        d.driverInfo = driver.driverInfo;
    }
    describeMemory(device, d);
    return d;
}

}  // namespace

std::vector<DeviceDescription> VulkanDevice::listDevices() {
    const VulkanInstance instance("vitrum", false);
    const std::vector<VkPhysicalDevice> devices = instance.physicalDevices();
    std::vector<DeviceDescription> result;
    for (std::uint32_t i = 0; i < devices.size(); ++i) result.push_back(describeDevice(devices[i], i));
    return result;
}

VulkanDevice::VulkanDevice(const std::string& selector) : instance_("vitrum") {
    try {
        const std::vector<VkPhysicalDevice> devices = instance_.physicalDevices();
        const std::size_t index = selectDevice(devices, selector);
        physicalDevice_ = devices[index];
        vkGetPhysicalDeviceProperties(physicalDevice_, &properties_);
        vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memoryProperties_);
        if (properties_.apiVersion < VK_API_VERSION_1_2)
            throw InputError(std::string("Vulkan device ") + properties_.deviceName + " supports only Vulkan " +
                             std::to_string(VK_API_VERSION_MAJOR(properties_.apiVersion)) + "." +
                             std::to_string(VK_API_VERSION_MINOR(properties_.apiVersion)) + "; vitrum needs 1.2");
        description_ = describeDevice(physicalDevice_, std::uint32_t(index));

        // The scene's buffers are read as storage texel buffers of R32G32B32A32_UINT texels
        // (shaders/bindings.glsl), which Vulkan requires every device to support.
        VkFormatProperties texelFormat;
        vkGetPhysicalDeviceFormatProperties(physicalDevice_, VK_FORMAT_R32G32B32A32_UINT, &texelFormat);
        if (!(texelFormat.bufferFeatures & VK_FORMAT_FEATURE_STORAGE_TEXEL_BUFFER_BIT))
            throw InputError(std::string("Vulkan device ") + properties_.deviceName +
                             " cannot read R32G32B32A32_UINT storage texel buffers, which Vulkan requires");

        std::uint32_t familyCount = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, nullptr);
        std::vector<VkQueueFamilyProperties> families(familyCount);
        vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, families.data());
        queueFamily_ = familyCount;
        for (std::uint32_t i = 0; i < familyCount; ++i)
            if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) {
                queueFamily_ = i;
                break;
            }
        if (queueFamily_ == familyCount)
            throw InputError(std::string("Vulkan device ") + properties_.deviceName + " has no compute queue");

        float priority = 1.0f;
        VkDeviceQueueCreateInfo queueInfo{
            .sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
            .queueFamilyIndex = queueFamily_,
            .queueCount = 1,
            .pQueuePriorities = &priority,
        };
        VkPhysicalDeviceSubgroupSizeControlFeaturesEXT fullSubgroupFeatures{
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_SIZE_CONTROL_FEATURES_EXT,
            .subgroupSizeControl = VK_TRUE,
            .computeFullSubgroups = VK_TRUE,
        };
        const char* fullSubgroupExtension = VK_EXT_SUBGROUP_SIZE_CONTROL_EXTENSION_NAME;
        VkDeviceCreateInfo deviceInfo{
            .sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
            .pNext = subgroups().fullSubgroups ? &fullSubgroupFeatures : nullptr,
            .queueCreateInfoCount = 1,
            .pQueueCreateInfos = &queueInfo,
            .enabledExtensionCount = subgroups().fullSubgroups ? 1u : 0u,
            .ppEnabledExtensionNames = subgroups().fullSubgroups ? &fullSubgroupExtension : nullptr,
        };
        VK_CHECK(vkCreateDevice(physicalDevice_, &deviceInfo, nullptr, &device_));
        vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);

        VkCommandPoolCreateInfo poolInfo{
            .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
            .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
            .queueFamilyIndex = queueFamily_,
        };
        VkCommandPool pool = VK_NULL_HANDLE;
        VK_CHECK(vkCreateCommandPool(device_, &poolInfo, nullptr, &pool));
        commandPool_ = UniqueCommandPool(device_, pool);
        VkFenceCreateInfo fenceInfo{.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        VkFence fence = VK_NULL_HANDLE;
        VK_CHECK(vkCreateFence(device_, &fenceInfo, nullptr, &fence));
        fence_ = UniqueFence(device_, fence);
        chooseKernelPath();
    } catch (...) {
        release();
        throw;
    }
}

VulkanDevice::~VulkanDevice() { release(); }

// The fast kernel relies on full subgroups doing what the self-check does; a device that fails it
// is treated as one without them, so every kernel it gets is the safe one, with one warning.
void VulkanDevice::chooseKernelPath() {
    switch (statisticsSumsFor(subgroups(), StatisticsSums::shuffles)) {
        case StatisticsSums::atomics:
            kernelPath_ = "safe: one atomic a counter and lane (the device has no subgroup arithmetic and ballots)";
            return;
        case StatisticsSums::subgroupAdd:
            kernelPath_ = "safe: statistics summed by subgroupAdd (full subgroups need the device to require them, "
                          "of at most " + std::to_string(kTraceGroupSize) + " lanes: the kernel's workgroup width)";
            return;
        case StatisticsSums::shuffles:
            break;
    }
    const char* fault = std::getenv("VITRUM_SELF_CHECK_FAULT");
    const SubgroupSelfCheck check = checkSubgroupMachinery(*this, false, fault && std::string(fault) == "1");
    if (check.passed) {
        kernelPath_ = "fast: full subgroups (shuffles, ray sharing, persistent subgroups on a CPU), self-check passed";
        return;
    }
    description_.subgroups.fullSubgroups = false;
    kernelPath_ = "safe: statistics summed by subgroupAdd (the self-check of full subgroups failed: " + check.failure + ")";
    warn(name() + " failed the self-check of full subgroups (" + check.failure +
         "): it gets the kernel without them (the same image, slower)");
}

void VulkanDevice::release() {
    fence_.reset();
    commandPool_.reset();
    if (device_) vkDestroyDevice(device_, nullptr);
    device_ = VK_NULL_HANDLE;
}

VulkanDevice::PooledCommands::PooledCommands(VulkanDevice& device) : device_(device) {
    VkCommandBufferAllocateInfo info{
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = device_.commandPool_.get(),
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
        .commandBufferCount = 1,
    };
    VK_CHECK(vkAllocateCommandBuffers(device_.device_, &info, &commands_));
    ++device_.commandBuffersInUse_;
}

VulkanDevice::PooledCommands::~PooledCommands() {
    vkFreeCommandBuffers(device_.device_, device_.commandPool_.get(), 1, &commands_);
    --device_.commandBuffersInUse_;
}

void VulkanDevice::beginCommands(VkCommandBuffer commands) {
    VkCommandBufferBeginInfo begin{
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
        .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT,
    };
    VK_CHECK(vkBeginCommandBuffer(commands, &begin));
}

void VulkanDevice::endSubmitWait(VkCommandBuffer commands) {
    VK_CHECK(vkEndCommandBuffer(commands));
    VkSubmitInfo submit{
        .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
        .commandBufferCount = 1,
        .pCommandBuffers = &commands,
    };
    VkFence fence = fence_.get();
    VK_CHECK(vkResetFences(device_, 1, &fence));
    VK_CHECK(vkQueueSubmit(queue_, 1, &submit, fence));
    VK_CHECK(vkWaitForFences(device_, 1, &fence, VK_TRUE, UINT64_MAX));
}

}  // namespace vitrum
