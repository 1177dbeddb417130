#include "gpu/compute_pipeline.h"

#include <stdexcept>
#include <vector>

#include "gpu/spirv_float_semantics.h"
#include "gpu/vulkan_error.h"

namespace vitrum {

ComputePipeline::ComputePipeline(const VulkanDevice& device, std::span<const std::uint32_t> spirv,
                                 std::span<const VkDescriptorType> bindingTypes,
                                 const VkSpecializationInfo* specialization, VkPipelineShaderStageCreateFlags stageFlags)
    : device_(device.device()), bindings_(bindingTypes.begin(), bindingTypes.end()) {
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    for (std::uint32_t b = 0; b < bindings_.size(); ++b)
        bindings.push_back({
            .binding = b,
            .descriptorType = bindings_[b],
            .descriptorCount = 1,
            .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT,
        });
    VkDescriptorSetLayoutCreateInfo setInfo{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .bindingCount = std::uint32_t(bindings.size()),
        .pBindings = bindings.data(),
    };
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VK_CHECK(vkCreateDescriptorSetLayout(device_, &setInfo, nullptr, &setLayout));
    setLayout_ = UniqueDescriptorSetLayout(device_, setLayout);

    VkPipelineLayoutCreateInfo layoutInfo{
        .sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
        .setLayoutCount = 1,
        .pSetLayouts = &setLayout,
    };
    VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
    VK_CHECK(vkCreatePipelineLayout(device_, &layoutInfo, nullptr, &pipelineLayout));
    pipelineLayout_ = UniquePipelineLayout(device_, pipelineLayout);

    // Every kernel computes as the CPU reference does, so far as the device allows.
    const std::vector<std::uint32_t> code = withCpuFloatSemantics(spirv, {.preserveInfNan = device.preservesInfNan()});
    VkShaderModuleCreateInfo moduleInfo{
        .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
        .codeSize = code.size() * sizeof(std::uint32_t),
        .pCode = code.data(),
    };
    VkShaderModule module = VK_NULL_HANDLE;
    VK_CHECK(vkCreateShaderModule(device_, &moduleInfo, nullptr, &module));
    UniqueShaderModule shaderModule(device_, module);

    VkComputePipelineCreateInfo pipelineInfo{
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage =
            {
                .sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                .flags = stageFlags,
                .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                .module = module,
                .pName = "main",
                .pSpecializationInfo = specialization,
            },
        .layout = pipelineLayout,
    };
    VkPipeline pipeline = VK_NULL_HANDLE;
    VK_CHECK(vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &pipeline));
    pipeline_ = UniquePipeline(device_, pipeline);

    std::vector<VkDescriptorPoolSize> sizes;
    for (VkDescriptorType type : bindings_) sizes.push_back({type, 1});
    VkDescriptorPoolCreateInfo poolInfo{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
        .maxSets = 1,
        .poolSizeCount = std::uint32_t(sizes.size()),
        .pPoolSizes = sizes.data(),
    };
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VK_CHECK(vkCreateDescriptorPool(device_, &poolInfo, nullptr, &pool));
    pool_ = UniqueDescriptorPool(device_, pool);
    VkDescriptorSetAllocateInfo allocateInfo{
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
        .descriptorPool = pool,
        .descriptorSetCount = 1,
        .pSetLayouts = &setLayout,
    };
    VK_CHECK(vkAllocateDescriptorSets(device_, &allocateInfo, &set_));
}

void ComputePipeline::bind(std::span<const GpuBuffer* const> buffers) {
    if (buffers.size() != bindings_.size()) throw std::logic_error("ComputePipeline::bind: wrong number of buffers");
    std::vector<VkDescriptorBufferInfo> infos(buffers.size());
    std::vector<VkWriteDescriptorSet> writes(buffers.size());
    std::vector<VkBufferView> views(buffers.size());
    for (std::uint32_t b = 0; b < buffers.size(); ++b) {
        infos[b] = {.buffer = buffers[b]->buffer(), .offset = 0, .range = VK_WHOLE_SIZE};
        writes[b] = {
            .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
            .dstSet = set_,
            .dstBinding = b,
            .descriptorCount = 1,
            .descriptorType = bindings_[b],
        };
        if (bindings_[b] == VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER ||
            bindings_[b] == VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER) {
            if (buffers[b]->texelView() == VK_NULL_HANDLE)
                throw std::logic_error("ComputePipeline::bind: binding " + std::to_string(b) + " needs a texel buffer");
            writes[b].pTexelBufferView = &views[b];
            views[b] = buffers[b]->texelView();
        } else {
            writes[b].pBufferInfo = &infos[b];
        }
    }
    vkUpdateDescriptorSets(device_, std::uint32_t(writes.size()), writes.data(), 0, nullptr);
}

void ComputePipeline::record(VkCommandBuffer commands, std::uint32_t groupsX, std::uint32_t groupsY) const {
    vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_.get());
    vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineLayout_.get(), 0, 1, &set_, 0, nullptr);
    vkCmdDispatch(commands, groupsX, groupsY, 1);
    // Make the kernel's writes (pixels, states, statistics) visible to the host's reads.
    VkMemoryBarrier barrier{
        .sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
        .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
        .dstAccessMask = VK_ACCESS_HOST_READ_BIT,
    };
    vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                         nullptr, 0, nullptr);
}

}  // namespace vitrum
