// A compute pipeline over one descriptor set of buffers (binding i = buffers[i]), with its
// layout and descriptor set. Used for trace.comp and the GLSL unit-test kernels.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "gpu/gpu_buffer.h"
#include "gpu/vulkan_device.h"
#include "gpu/vulkan_handle.h"

namespace vitrum {

class ComputePipeline {
public:
    // `bindings[i]` is the descriptor type of binding i; `specialization` (may be null) sets the
    // kernel's specialization constants; `stageFlags` are its VkPipelineShaderStageCreateFlags.
    ComputePipeline(const VulkanDevice& device, std::span<const std::uint32_t> spirv,
                    std::span<const VkDescriptorType> bindings, const VkSpecializationInfo* specialization = nullptr,
                    VkPipelineShaderStageCreateFlags stageFlags = 0);

    // Points binding i of the descriptor set at buffers[i] (at its texel view for a uniform or
    // storage texel buffer binding).
    void bind(std::span<const GpuBuffer* const> buffers);
    // Records the dispatch and a barrier that makes its writes visible to the host.
    void record(VkCommandBuffer commands, std::uint32_t groupsX, std::uint32_t groupsY = 1) const;

private:
    VkDevice device_;
    std::vector<VkDescriptorType> bindings_;
    UniqueDescriptorSetLayout setLayout_;
    UniquePipelineLayout pipelineLayout_;
    UniquePipeline pipeline_;
    UniqueDescriptorPool pool_;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace vitrum
