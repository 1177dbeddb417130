#include "gpu/trace_pipeline.h"

#include "trace.spv.h"

namespace vitrum {

ComputePipeline makeTracePipeline(const VulkanDevice& device, const TraceSpecialization& specialization) {
    std::array<VkDescriptorType, kTraceBindingCount> bindings;
    bindings.fill(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    for (TraceBinding texels : {kBindingParams, kBindingNodes, kBindingVertices, kBindingShading, kBindingMaterials, kBindingLights,
                                kBindingObjectMaterials})
        bindings[texels] = VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
    const auto constants = specialization.constants();
    std::array<VkSpecializationMapEntry, constants.size()> entries;
    for (std::uint32_t id = 0; id < entries.size(); ++id)
        entries[id] = {.constantID = id, .offset = id * std::uint32_t(sizeof(std::uint32_t)), .size = sizeof(std::uint32_t)};
    const VkSpecializationInfo info{
        .mapEntryCount = std::uint32_t(entries.size()),
        .pMapEntries = entries.data(),
        .dataSize = sizeof(constants),
        .pData = constants.data(),
    };
    return ComputePipeline(device, std::span<const std::uint32_t>(trace_spv, std::size(trace_spv)), bindings, &info);
}

}  // namespace vitrum
