#include "ray_query_tracer.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <iterator>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include "gpu/vulkan_error.h"
#include "trace_rays_query.spv.h"

namespace vitrum::bench {
namespace {

constexpr const char* kProgram = "vitrum_bench_ray_query";

// VK_KHR_acceleration_structure needs VK_KHR_deferred_host_operations enabled with it (the
// extension's dependencies; buffer device addresses and descriptor indexing are core in 1.2).
constexpr const char* kExtensions[] = {
    VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
    VK_KHR_RAY_QUERY_EXTENSION_NAME,
    VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME,
};

// What `device` lacks of what the baseline needs (Vulkan 1.2, the extensions, and the features
// accelerationStructure, rayQuery and bufferDeviceAddress): "" where it has everything, else
// "no VK_KHR_ray_query, ...".
std::string lacksForRayQueries(VkPhysicalDevice device) {
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(device, &properties);
    if (properties.apiVersion < VK_API_VERSION_1_2) return "no Vulkan 1.2";
    std::uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> offered(count);
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, offered.data());
    std::string lacks;
    for (const char* wanted : kExtensions)
        if (std::none_of(offered.begin(), offered.end(),
                         [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, wanted) == 0; }))
            lacks += std::string(lacks.empty() ? "" : ", ") + "no " + wanted;
    if (!lacks.empty()) return lacks;
    VkPhysicalDeviceRayQueryFeaturesKHR rayQuery{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
    VkPhysicalDeviceAccelerationStructureFeaturesKHR structures{
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR, .pNext = &rayQuery};
    VkPhysicalDeviceVulkan12Features vulkan12{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
                                              .pNext = &structures};
    VkPhysicalDeviceFeatures2 features{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, .pNext = &vulkan12};
    vkGetPhysicalDeviceFeatures2(device, &features);
    if (!rayQuery.rayQuery) lacks += "no rayQuery feature";
    if (!structures.accelerationStructure)
        lacks += std::string(lacks.empty() ? "" : ", ") + "no accelerationStructure feature";
    if (!vulkan12.bufferDeviceAddress)
        lacks += std::string(lacks.empty() ? "" : ", ") + "no bufferDeviceAddress feature";
    return lacks;
}

std::string driverInfoOf(VkPhysicalDevice device) {
    VkPhysicalDeviceDriverProperties driver{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 properties{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, .pNext = &driver};
    vkGetPhysicalDeviceProperties2(device, &properties);
    return driver.driverInfo;
}

VkDeviceSize alignUp(VkDeviceSize value, VkDeviceSize alignment) {
    return (value + alignment - 1) / alignment * alignment;
}

// An execution and memory dependency from one stage's accesses to another's, for the whole device.
void memoryBarrier(VkCommandBuffer commands, VkPipelineStageFlags srcStage, VkAccessFlags srcAccess,
                   VkPipelineStageFlags dstStage, VkAccessFlags dstAccess) {
    VkMemoryBarrier barrier{
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = srcAccess,
        .dstAccessMask = dstAccess,
    };
    vkCmdPipelineBarrier(commands, srcStage, dstStage, 0, 1, &barrier, 0, nullptr, 0, nullptr);
}

}  // namespace

// ---- RayQueryBuffer ----------------------------------------------------------------------------

RayQueryBuffer::RayQueryBuffer(const RayQueryDevice& device, VkDeviceSize size, VkBufferUsageFlags usage, bool mapped) {
    VkBufferCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
        .size = size,
        .usage = usage | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
        .sharingMode = VK_SHARING_MODE_EXCLUSIVE,
    };
    VkBuffer buffer = VK_NULL_HANDLE;
    VK_CHECK(vkCreateBuffer(device.device(), &info, nullptr, &buffer));
    buffer_ = UniqueBuffer(device.device(), buffer);
    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(device.device(), buffer, &requirements);
    VkMemoryAllocateFlagsInfo flags{
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO,
        .flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT,
    };
    VkMemoryAllocateInfo allocate{
        .sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
        .pNext = &flags,
        .allocationSize = requirements.size,
        .memoryTypeIndex = device.memoryType(requirements.memoryTypeBits, mapped),
    };
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VK_CHECK(vkAllocateMemory(device.device(), &allocate, nullptr, &memory));
    memory_ = UniqueMemory(device.device(), memory);
    VK_CHECK(vkBindBufferMemory(device.device(), buffer, memory, 0));
    const VkBufferDeviceAddressInfo addressInfo{.sType = VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO,
                                                .buffer = buffer};
    address_ = vkGetBufferDeviceAddress(device.device(), &addressInfo);
    if (mapped) VK_CHECK(vkMapMemory(device.device(), memory, 0, VK_WHOLE_SIZE, 0, &mapped_));
}

// ---- AccelerationStructure ---------------------------------------------------------------------

AccelerationStructure::AccelerationStructure(const RayQueryDevice& device, VkAccelerationStructureTypeKHR type,
                                             VkDeviceSize size)
    : device_(&device), storage_(device, size, VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR, false) {
    VkAccelerationStructureCreateInfoKHR info{
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR,
        .buffer = storage_.buffer(),
        .offset = 0,
        .size = size,
        .type = type,
    };
    VK_CHECK(device.createAccelerationStructure(device.device(), &info, nullptr, &handle_));
    const VkAccelerationStructureDeviceAddressInfoKHR addressInfo{
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR,
        .accelerationStructure = handle_,
    };
    address_ = device.getAddress(device.device(), &addressInfo);
}

AccelerationStructure::AccelerationStructure(AccelerationStructure&& other) noexcept
    : device_(other.device_),
      storage_(std::move(other.storage_)),
      handle_(std::exchange(other.handle_, VK_NULL_HANDLE)),
      address_(other.address_) {}

AccelerationStructure& AccelerationStructure::operator=(AccelerationStructure&& other) noexcept {
    if (this != &other) {
        reset();
        device_ = other.device_;
        storage_ = std::move(other.storage_);
        handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
        address_ = other.address_;
    }
    return *this;
}

void AccelerationStructure::reset() {
    if (handle_ != VK_NULL_HANDLE) device_->destroyAccelerationStructure(device_->device(), handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
}

// ---- RayQueryDevice ----------------------------------------------------------------------------

std::string RayQueryDevice::describeDevices() {
    const VulkanInstance instance(kProgram, false);
    std::string lines;
    for (VkPhysicalDevice device : instance.physicalDevices()) {
        VkPhysicalDeviceProperties properties;
        vkGetPhysicalDeviceProperties(device, &properties);
        const std::string lacks = lacksForRayQueries(device);
        lines += std::string(properties.deviceName) + ", " +
                 (properties.apiVersion >= VK_API_VERSION_1_2 ? driverInfoOf(device) : std::string("Vulkan 1.1 or older")) +
                 ": " + (lacks.empty() ? "ray queries (VK_KHR_ray_query, VK_KHR_acceleration_structure)" : lacks) + "\n";
    }
    return lines;
}

RayQueryDevice::RayQueryDevice() : instance_(kProgram) {
    try {
        const std::vector<VkPhysicalDevice> devices = instance_.physicalDevices();
        index_ = std::uint32_t(devices.size());
        for (std::uint32_t i = 0; i < devices.size() && index_ == devices.size(); ++i)
            if (lacksForRayQueries(devices[i]).empty()) index_ = i;
        if (index_ == devices.size())
            throw std::runtime_error(
                "no Vulkan device offers ray queries (Mesa 25's lavapipe does, Mesa 22.3's "
                "does not):\n" +
                describeDevices());
        physicalDevice_ = devices[index_];
        VkPhysicalDeviceProperties properties;
        vkGetPhysicalDeviceProperties(physicalDevice_, &properties);
        name_ = properties.deviceName;
        driverInfo_ = driverInfoOf(physicalDevice_);
        vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memory_);
        VkPhysicalDeviceAccelerationStructurePropertiesKHR structureProperties{
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
        VkPhysicalDeviceProperties2 properties2{.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2,
                                                .pNext = &structureProperties};
        vkGetPhysicalDeviceProperties2(physicalDevice_, &properties2);
        scratchAlignment_ =
            std::max<VkDeviceSize>(1, structureProperties.minAccelerationStructureScratchOffsetAlignment);

        std::uint32_t familyCount = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, nullptr);
        std::vector<VkQueueFamilyProperties> families(familyCount);
        vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice_, &familyCount, families.data());
        std::uint32_t family = 0;
        while (family < familyCount && !(families[family].queueFlags & VK_QUEUE_COMPUTE_BIT)) ++family;
        if (family == familyCount) throw std::runtime_error(name_ + " has no compute queue");

        const float priority = 1.0f;
        const VkDeviceQueueCreateInfo queueInfo{
            .sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
            .queueFamilyIndex = family,
            .queueCount = 1,
            .pQueuePriorities = &priority,
        };
        VkPhysicalDeviceRayQueryFeaturesKHR rayQuery{
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR,
            .rayQuery = VK_TRUE,
        };
        VkPhysicalDeviceAccelerationStructureFeaturesKHR structures{
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR,
            .pNext = &rayQuery,
            .accelerationStructure = VK_TRUE,
        };
        VkPhysicalDeviceVulkan12Features vulkan12{
            .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
            .pNext = &structures,
            .bufferDeviceAddress = VK_TRUE,
        };
        const VkDeviceCreateInfo deviceInfo{
            .sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
            .pNext = &vulkan12,
            .queueCreateInfoCount = 1,
            .pQueueCreateInfos = &queueInfo,
            .enabledExtensionCount = std::uint32_t(std::size(kExtensions)),
            .ppEnabledExtensionNames = kExtensions,
        };
        VK_CHECK(vkCreateDevice(physicalDevice_, &deviceInfo, nullptr, &device_));
        vkGetDeviceQueue(device_, family, 0, &queue_);

        auto load = [&](auto& function, const char* name) {
            function =
                reinterpret_cast<std::remove_reference_t<decltype(function)>>(vkGetDeviceProcAddr(device_, name));
            if (!function) throw VulkanError(VK_ERROR_EXTENSION_NOT_PRESENT, std::string(name) + " missing");
        };
        load(createAccelerationStructure, "vkCreateAccelerationStructureKHR");
        load(destroyAccelerationStructure, "vkDestroyAccelerationStructureKHR");
        load(getBuildSizes, "vkGetAccelerationStructureBuildSizesKHR");
        load(cmdBuild, "vkCmdBuildAccelerationStructuresKHR");
        load(getAddress, "vkGetAccelerationStructureDeviceAddressKHR");

        const VkCommandPoolCreateInfo poolInfo{
            .sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
            .queueFamilyIndex = family,
        };
        VkCommandPool pool = VK_NULL_HANDLE;
        VK_CHECK(vkCreateCommandPool(device_, &poolInfo, nullptr, &pool));
        pool_ = UniqueCommandPool(device_, pool);
        const VkFenceCreateInfo fenceInfo{.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        VkFence fence = VK_NULL_HANDLE;
        VK_CHECK(vkCreateFence(device_, &fenceInfo, nullptr, &fence));
        fence_ = UniqueFence(device_, fence);
        createPipeline();
    } catch (...) {
        release();
        throw;
    }
}

RayQueryDevice::~RayQueryDevice() { release(); }

void RayQueryDevice::createPipeline() {
    const VkDescriptorSetLayoutBinding bindings[] = {
        {.binding = 0,
         .descriptorType = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR,
         .descriptorCount = 1,
         .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT},
        {.binding = 1,
         .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER,
         .descriptorCount = 1,
         .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT},
        {.binding = 2,
         .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
         .descriptorCount = 1,
         .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT},
    };
    const VkDescriptorSetLayoutCreateInfo setInfo{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .bindingCount = std::uint32_t(std::size(bindings)),
        .pBindings = bindings,
    };
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VK_CHECK(vkCreateDescriptorSetLayout(device_, &setInfo, nullptr, &setLayout));
    setLayout_ = UniqueDescriptorSetLayout(device_, setLayout);
    const VkPushConstantRange rayCount{.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT, .offset = 0, .size = 4};
    const VkPipelineLayoutCreateInfo layoutInfo{
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 1,
        .pSetLayouts = &setLayout,
        .pushConstantRangeCount = 1,
        .pPushConstantRanges = &rayCount,
    };
    VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
    VK_CHECK(vkCreatePipelineLayout(device_, &layoutInfo, nullptr, &pipelineLayout));
    pipelineLayout_ = UniquePipelineLayout(device_, pipelineLayout);
    // The kernel as glslang wrote it, without the float semantics vitrum asks of its own kernels
    // (gpu/spirv_float_semantics.h): the traversal and triangle test are the driver's, compiled as
    // the driver sees fit.
    const VkShaderModuleCreateInfo moduleInfo{
        .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
        .codeSize = sizeof trace_rays_query_spv,
        .pCode = trace_rays_query_spv,
    };
    VkShaderModule module = VK_NULL_HANDLE;
    VK_CHECK(vkCreateShaderModule(device_, &moduleInfo, nullptr, &module));
    const UniqueShaderModule shaderModule(device_, module);
    const VkComputePipelineCreateInfo pipelineInfo{
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage =
            {
                .sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                .module = module,
                .pName = "main",
            },
        .layout = pipelineLayout,
    };
    VkPipeline pipeline = VK_NULL_HANDLE;
    VK_CHECK(vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &pipeline));
    pipeline_ = UniquePipeline(device_, pipeline);
}

void RayQueryDevice::release() {
    pipeline_.reset();
    pipelineLayout_.reset();
    setLayout_.reset();
    fence_.reset();
    pool_.reset();
    if (device_) vkDestroyDevice(device_, nullptr);
    device_ = VK_NULL_HANDLE;
}

// Mapped buffers: host-visible, coherent memory. The others: device-local where the device has
// such memory (on lavapipe every type is the host's memory, and device-local).
std::uint32_t RayQueryDevice::memoryType(std::uint32_t allowed, bool mapped) const {
    const VkMemoryPropertyFlags wanted =
        mapped ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
               : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    for (std::uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
        if ((allowed & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
    if (!mapped)
        for (std::uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
            if (allowed & (1u << i)) return i;
    throw std::runtime_error(name_ + " has no memory type for a " + (mapped ? "mapped" : "device") + " buffer");
}

VkCommandBuffer RayQueryDevice::begin() const {
    const VkCommandBufferAllocateInfo info{
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
        .commandPool = pool_.get(),
        .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
        .commandBufferCount = 1,
    };
    VkCommandBuffer commands = VK_NULL_HANDLE;
    VK_CHECK(vkAllocateCommandBuffers(device_, &info, &commands));
    const VkCommandBufferBeginInfo beginInfo{
        .sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
        .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT,
    };
    const VkResult result = vkBeginCommandBuffer(commands, &beginInfo);
    if (result != VK_SUCCESS) {
        vkFreeCommandBuffers(device_, pool_.get(), 1, &commands);
        VK_CHECK(result);
    }
    return commands;
}

void RayQueryDevice::endSubmitWait(VkCommandBuffer commands) const {
    VkResult result = vkEndCommandBuffer(commands);
    if (result == VK_SUCCESS) {
        const VkSubmitInfo submit{
            .sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
            .commandBufferCount = 1,
            .pCommandBuffers = &commands,
        };
        VkFence fence = fence_.get();
        result = vkResetFences(device_, 1, &fence);
        if (result == VK_SUCCESS) result = vkQueueSubmit(queue_, 1, &submit, fence);
        if (result == VK_SUCCESS) result = vkWaitForFences(device_, 1, &fence, VK_TRUE, UINT64_MAX);
    }
    vkFreeCommandBuffers(device_, pool_.get(), 1, &commands);
    VK_CHECK(result);
}

// ---- RayQueryScene -----------------------------------------------------------------------------

namespace {

// What a build of the bottom level reads: the triangles' corners, three a triangle, no indices.
VkAccelerationStructureGeometryKHR triangleGeometry(VkDeviceAddress vertices, std::uint32_t triangleCount) {
    return {
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR,
        .geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR,
        .geometry = {.triangles =
                         {
                             .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR,
                             .vertexFormat = VK_FORMAT_R32G32B32_SFLOAT,
                             .vertexData = {.deviceAddress = vertices},
                             .vertexStride = sizeof(glm::vec3),
                             .maxVertex = 3 * std::max(triangleCount, 1u) - 1,
                             .indexType = VK_INDEX_TYPE_NONE_KHR,
                         }},
        // Opaque: the query never hands a candidate to the shader (no any-hit work), as vitrum's
        // triangles have none.
        .flags = VK_GEOMETRY_OPAQUE_BIT_KHR,
    };
}

VkAccelerationStructureGeometryKHR instanceGeometry(VkDeviceAddress instances) {
    return {
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR,
        .geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR,
        .geometry = {.instances =
                         {
                             .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR,
                             .arrayOfPointers = VK_FALSE,
                             .data = {.deviceAddress = instances},
                         }},
    };
}

VkAccelerationStructureBuildGeometryInfoKHR buildInfo(VkAccelerationStructureTypeKHR type,
                                                      const VkAccelerationStructureGeometryKHR& geometry) {
    return {
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR,
        .type = type,
        .flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR,
        .mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR,
        .geometryCount = 1,
        .pGeometries = &geometry,
    };
}

VkAccelerationStructureBuildSizesInfoKHR buildSizes(const RayQueryDevice& device,
                                                    const VkAccelerationStructureBuildGeometryInfoKHR& info,
                                                    std::uint32_t primitives) {
    VkAccelerationStructureBuildSizesInfoKHR sizes{.sType =
                                                       VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    device.getBuildSizes(device.device(), VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &info, &primitives, &sizes);
    return sizes;
}

}  // namespace

RayQueryScene::RayQueryScene(const RayQueryDevice& device, std::span<const glm::vec3> corners)
    : triangleCount_(std::uint32_t(corners.size() / 3)) {
    const VkBufferUsageFlags input = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR;
    vertices_ = RayQueryBuffer(device, std::max<VkDeviceSize>(sizeof(glm::vec3), corners.size_bytes()), input, true);
    std::memcpy(vertices_.mapped(), corners.data(), corners.size_bytes());

    const VkAccelerationStructureGeometryKHR triangles = triangleGeometry(vertices_.address(), triangleCount_);
    const VkAccelerationStructureBuildSizesInfoKHR bottomSizes =
        buildSizes(device, buildInfo(VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, triangles), triangleCount_);
    bottomSize_ = bottomSizes.accelerationStructureSize;
    bottomLevel_ = AccelerationStructure(device, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, bottomSize_);
    // Scratch addresses must be multiples of minAccelerationStructureScratchOffsetAlignment: room
    // for rounding up.
    bottomScratch_ = RayQueryBuffer(device, bottomSizes.buildScratchSize + device.scratchAlignment(),
                                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);

    const VkAccelerationStructureInstanceKHR identity{
        .transform = {.matrix = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}},
        .instanceCustomIndex = 0,
        .mask = 0xFF,
        .instanceShaderBindingTableRecordOffset = 0,
        .flags = 0,
        .accelerationStructureReference = bottomLevel_.address(),
    };
    instance_ = RayQueryBuffer(device, sizeof identity, input, true);
    std::memcpy(instance_.mapped(), &identity, sizeof identity);
    const VkAccelerationStructureGeometryKHR instances = instanceGeometry(instance_.address());
    const VkAccelerationStructureBuildSizesInfoKHR topSizes =
        buildSizes(device, buildInfo(VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, instances), 1);
    topLevel_ =
        AccelerationStructure(device, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, topSizes.accelerationStructureSize);
    topScratch_ = RayQueryBuffer(device, topSizes.buildScratchSize + device.scratchAlignment(),
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
    build(device);
}

double RayQueryScene::build(const RayQueryDevice& device) const {
    const VkAccelerationStructureGeometryKHR triangles = triangleGeometry(vertices_.address(), triangleCount_);
    VkAccelerationStructureBuildGeometryInfoKHR bottom =
        buildInfo(VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, triangles);
    bottom.dstAccelerationStructure = bottomLevel_.get();
    bottom.scratchData.deviceAddress = alignUp(bottomScratch_.address(), device.scratchAlignment());
    const VkAccelerationStructureBuildRangeInfoKHR bottomRange{.primitiveCount = triangleCount_};
    const VkAccelerationStructureBuildRangeInfoKHR* bottomRanges = &bottomRange;

    const VkAccelerationStructureGeometryKHR instances = instanceGeometry(instance_.address());
    VkAccelerationStructureBuildGeometryInfoKHR top =
        buildInfo(VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, instances);
    top.dstAccelerationStructure = topLevel_.get();
    top.scratchData.deviceAddress = alignUp(topScratch_.address(), device.scratchAlignment());
    const VkAccelerationStructureBuildRangeInfoKHR topRange{.primitiveCount = 1};
    const VkAccelerationStructureBuildRangeInfoKHR* topRanges = &topRange;

    const auto start = std::chrono::steady_clock::now();
    device.submitAndWait([&](VkCommandBuffer commands) {
        device.cmdBuild(commands, 1, &bottom, &bottomRanges);
        // The top level reads the bottom level's address and bounds.
        memoryBarrier(commands, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                      VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR,
                      VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                      VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR);
        device.cmdBuild(commands, 1, &top, &topRanges);
    });
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// ---- RayQueryTrace -----------------------------------------------------------------------------

RayQueryTrace::RayQueryTrace(const RayQueryDevice& device, const RayQueryScene& scene, std::span<const TracedRay> rays,
                             std::span<const std::size_t> order)
    : count_(std::uint32_t(order.size())) {
    rays_ = RayQueryBuffer(device, std::max<VkDeviceSize>(32, VkDeviceSize(count_) * 2 * sizeof(glm::vec4)),
                           VK_BUFFER_USAGE_STORAGE_TEXEL_BUFFER_BIT, true);
    // R32G32B32A32_UINT storage texel buffers, which every device supports (VulkanDevice checks
    // it for vitrum's kernels), as the trace-only kernel reads its rays.
    const VkBufferViewCreateInfo viewInfo{
        .sType = VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO,
        .buffer = rays_.buffer(),
        .format = VK_FORMAT_R32G32B32A32_UINT,
        .offset = 0,
        .range = VK_WHOLE_SIZE,
    };
    VkBufferView view = VK_NULL_HANDLE;
    VK_CHECK(vkCreateBufferView(device.device(), &viewInfo, nullptr, &view));
    raysView_ = UniqueBufferView(device.device(), view);
    auto* texels = static_cast<glm::vec4*>(rays_.mapped());
    for (std::size_t k = 0; k < order.size(); ++k) {
        const TracedRay& r = rays[order[k]];
        texels[2 * k] = glm::vec4(r.origin, r.tMin);
        texels[2 * k + 1] = glm::vec4(r.direction, r.anyHit ? -r.tMax : r.tMax);
    }
    hits_ = RayQueryBuffer(device, std::max<VkDeviceSize>(sizeof(Hit), VkDeviceSize(count_) * sizeof(Hit)),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);

    const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR, 1},
                                          {VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER, 1},
                                          {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1}};
    const VkDescriptorPoolCreateInfo poolInfo{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
        .maxSets = 1,
        .poolSizeCount = std::uint32_t(std::size(sizes)),
        .pPoolSizes = sizes,
    };
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VK_CHECK(vkCreateDescriptorPool(device.device(), &poolInfo, nullptr, &pool));
    pool_ = UniqueDescriptorPool(device.device(), pool);
    const VkDescriptorSetLayout setLayout = device.setLayout();
    const VkDescriptorSetAllocateInfo allocateInfo{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
        .descriptorPool = pool,
        .descriptorSetCount = 1,
        .pSetLayouts = &setLayout,
    };
    VK_CHECK(vkAllocateDescriptorSets(device.device(), &allocateInfo, &set_));

    const VkAccelerationStructureKHR topLevel = scene.topLevel().get();
    const VkWriteDescriptorSetAccelerationStructureKHR structure{
        .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR,
        .accelerationStructureCount = 1,
        .pAccelerationStructures = &topLevel,
    };
    const VkDescriptorBufferInfo hitsInfo{.buffer = hits_.buffer(), .offset = 0, .range = VK_WHOLE_SIZE};
    const VkWriteDescriptorSet writes[] = {
        {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
         .pNext = &structure,
         .dstSet = set_,
         .dstBinding = 0,
         .descriptorCount = 1,
         .descriptorType = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR},
        {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
         .dstSet = set_,
         .dstBinding = 1,
         .descriptorCount = 1,
         .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER,
         .pTexelBufferView = &view},
        {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
         .dstSet = set_,
         .dstBinding = 2,
         .descriptorCount = 1,
         .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
         .pBufferInfo = &hitsInfo},
    };
    vkUpdateDescriptorSets(device.device(), std::uint32_t(std::size(writes)), writes, 0, nullptr);
}

double RayQueryTrace::trace(const RayQueryDevice& device) const {
    // As TraceOnlyKernel dispatches: 64 invocations a group, rows of at most 32768 groups.
    constexpr std::uint32_t kGroupSize = 64, kMaxGroupsX = 32768;
    const std::uint32_t groups = (count_ + kGroupSize - 1) / kGroupSize;
    const std::uint32_t groupsX = std::max(1u, std::min(groups, kMaxGroupsX));
    const std::uint32_t groupsY = (groups + groupsX - 1) / groupsX;
    const auto start = std::chrono::steady_clock::now();
    device.submitAndWait([&](VkCommandBuffer commands) {
        // A build of the scene's structures may have come before, in another submission: its
        // writes are made visible to the queries.
        memoryBarrier(commands, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                      VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                      VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR);
        vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, device.pipeline());
        vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, device.pipelineLayout(), 0, 1, &set_, 0,
                                nullptr);
        vkCmdPushConstants(commands, device.pipelineLayout(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof count_, &count_);
        vkCmdDispatch(commands, groupsX, groupsY, 1);
        memoryBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                      VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    });
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace vitrum::bench
