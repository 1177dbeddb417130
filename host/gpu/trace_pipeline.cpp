#include "gpu/trace_pipeline.h"

#include <algorithm>

#include "trace.spv.h"
#include "trace_atomic_statistics.spv.h"

namespace vitrum {

ComputePipeline makeTracePipeline(const VulkanDevice& device, const TraceSpecialization& specialization,
                                  bool resumable, bool subgroupStatistics) {
    std::array<VkDescriptorType, kTraceBindingCount> bindings;
    bindings.fill(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    for (TraceBinding texels : {kBindingParams, kBindingNodes, kBindingVertices, kBindingShading, kBindingMaterials, kBindingLights,
                                kBindingObjectMaterials})
        bindings[texels] = VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
    const auto sceneConstants = specialization.constants();
    std::array<std::uint32_t, sceneConstants.size() + 1> constants;  // then kResumable (constant_id 11)
    std::copy(sceneConstants.begin(), sceneConstants.end(), constants.begin());
    constants.back() = resumable ? 1u : 0u;
    std::array<VkSpecializationMapEntry, constants.size()> entries;
    for (std::uint32_t id = 0; id < entries.size(); ++id)
        entries[id] = {.constantID = id, .offset = id * std::uint32_t(sizeof(std::uint32_t)), .size = sizeof(std::uint32_t)};
    const VkSpecializationInfo info{
        .mapEntryCount = std::uint32_t(entries.size()),
        .pMapEntries = entries.data(),
        .dataSize = sizeof(constants),
        .pData = constants.data(),
    };
    const auto code = subgroupStatistics
                          ? std::span<const std::uint32_t>(trace_spv, std::size(trace_spv))
                          : std::span<const std::uint32_t>(trace_atomic_statistics_spv, std::size(trace_atomic_statistics_spv));
    return ComputePipeline(device, code, bindings, &info);
}

}  // namespace vitrum
