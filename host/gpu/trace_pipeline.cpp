#include "gpu/trace_pipeline.h"

#include <algorithm>
#include <stdexcept>

#include "trace.spv.h"
#include "trace_without_subgroups.spv.h"

namespace vitrum {

StatisticsSums statisticsSumsFor(const SubgroupSupport& device, StatisticsSums preferred) {
    if (preferred == StatisticsSums::shuffles && device.fullSubgroups && kTraceGroupSize % device.maxSize == 0)
        return StatisticsSums::shuffles;
    if (preferred != StatisticsSums::atomics && device.arithmeticAndBallot) return StatisticsSums::subgroupAdd;
    return StatisticsSums::atomics;
}

StatisticsSums statisticsSumsFor(const VulkanDevice& device, StatisticsSums preferred) {
    return statisticsSumsFor(device.subgroups(), preferred);
}

const char* statisticsSumsName(StatisticsSums sums) {
    switch (sums) {
        case StatisticsSums::atomics: return "atomics";
        case StatisticsSums::subgroupAdd: return "subgroupAdd";
        case StatisticsSums::shuffles: return "shuffles";
    }
    return "?";
}

std::span<const std::uint32_t> traceKernelCode(StatisticsSums sums) {
    return sums != StatisticsSums::atomics
               ? std::span<const std::uint32_t>(trace_spv, std::size(trace_spv))
               : std::span<const std::uint32_t>(trace_without_subgroups_spv, std::size(trace_without_subgroups_spv));
}

TraceKernelConstants traceKernelConstants(const TraceSpecialization& specialization, bool resumable, StatisticsSums sums,
                                          bool persistent) {
    const bool fullSubgroups = sums == StatisticsSums::shuffles;
    if (persistent && (resumable || !fullSubgroups))
        throw std::logic_error("only the first dispatch's kernel in full subgroups can be persistent");
    TraceKernelConstants constants = specialization.constants();
    constants[gpu::kConstantResumable] = resumable ? 1u : 0u;
    constants[gpu::kConstantFullSubgroups] = fullSubgroups ? 1u : 0u;
    constants[gpu::kConstantPersistentSubgroups] = persistent ? 1u : 0u;
    return constants;
}

ComputePipeline makeTracePipeline(const VulkanDevice& device, const TraceSpecialization& specialization,
                                  bool resumable, StatisticsSums sums, bool persistent) {
    std::array<VkDescriptorType, gpu::kTraceBindingCount> bindings;
    bindings.fill(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    for (std::uint32_t texels : {gpu::kBindingParams, gpu::kBindingNodes, gpu::kBindingVertices, gpu::kBindingShading,
                                 gpu::kBindingMaterials, gpu::kBindingLights, gpu::kBindingTextures,
                                 gpu::kBindingTexels, gpu::kBindingObjectMedia, gpu::kBindingWavelengths})
        bindings[texels] = VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER;
    const TraceKernelConstants constants = traceKernelConstants(specialization, resumable, sums, persistent);
    std::array<VkSpecializationMapEntry, constants.size()> entries;
    for (std::uint32_t id = 0; id < entries.size(); ++id)
        entries[id] = {.constantID = id, .offset = id * std::uint32_t(sizeof(std::uint32_t)), .size = sizeof(std::uint32_t)};
    const VkSpecializationInfo info{
        .mapEntryCount = std::uint32_t(entries.size()),
        .pMapEntries = entries.data(),
        .dataSize = sizeof(constants),
        .pData = constants.data(),
    };
    // Full subgroups are asked for exactly when the kernel is told it has them (kFullSubgroups).
    const bool fullSubgroups = constants[gpu::kConstantFullSubgroups] != 0u;
    return ComputePipeline(device, traceKernelCode(sums), bindings, &info,
                           fullSubgroups ? VK_PIPELINE_SHADER_STAGE_CREATE_REQUIRE_FULL_SUBGROUPS_BIT_EXT : 0);
}

}  // namespace vitrum
