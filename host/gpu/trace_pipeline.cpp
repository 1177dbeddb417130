#include "gpu/trace_pipeline.h"

#include "trace.spv.h"

namespace vitrum {

ComputePipeline makeTracePipeline(const VulkanDevice& device) {
    std::array<VkDescriptorType, kTraceBindingCount> bindings;
    bindings.fill(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    bindings[kBindingParams] = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    return ComputePipeline(device, std::span<const std::uint32_t>(trace_spv, std::size(trace_spv)), bindings);
}

}  // namespace vitrum
