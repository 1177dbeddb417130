// The compute pipeline of shaders/trace.comp: its descriptor set layout (bindings as in
// shaders/bindings.glsl), the pipeline itself and one descriptor set.
#pragma once

#include <array>
#include <cstdint>

#include "gpu/gpu_buffer.h"
#include "gpu/vulkan_device.h"
#include "gpu/vulkan_handle.h"

namespace vitrum {

enum TraceBinding : std::uint32_t {
    kBindingParams = 0,
    kBindingNodes,
    kBindingVertices,
    kBindingShading,
    kBindingMaterials,
    kBindingLights,
    kBindingTextures,
    kBindingTexels,
    kBindingObjectMaterials,
    kBindingPixels,
    kBindingStates,
    kBindingStats,
    kTraceBindingCount,
};

class TracePipeline {
public:
    explicit TracePipeline(const VulkanDevice& device);

    // Points the descriptor set at the buffers, indexed by TraceBinding.
    void bind(const std::array<const GpuBuffer*, kTraceBindingCount>& buffers);
    void record(VkCommandBuffer commands, std::uint32_t groupsX, std::uint32_t groupsY) const;

    static constexpr std::uint32_t kGroupSize = 8;  // local_size_x = local_size_y in trace.comp

private:
    VkDevice device_;
    UniqueDescriptorSetLayout setLayout_;
    UniquePipelineLayout pipelineLayout_;
    UniquePipeline pipeline_;
    UniqueDescriptorPool pool_;
    VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace vitrum
