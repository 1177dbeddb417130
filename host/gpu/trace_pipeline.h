// The compute pipeline of shaders/trace.comp; binding numbers as in shaders/bindings.glsl.
#pragma once

#include <array>
#include <cstdint>

#include "gpu/compute_pipeline.h"
#include "render/trace_specialization.h"

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
    kBindingPendingRays,
    kBindingTraversalStacks,
    kTraceBindingCount,
};

constexpr std::uint32_t kTraceGroupSize = 8;  // local_size_x = local_size_y in trace.comp

// The first dispatch of every tile runs the kernel built with `resumable` false; the pixels it
// gives up are restarted by the resumable one (shaders/suspend.glsl).
// `subgroupStatistics`: the build of trace.comp that sums its counters with subgroup arithmetic
// (VulkanDevice::hasSubgroupArithmeticAndBallot must be true), else the one with plain atomics.
ComputePipeline makeTracePipeline(const VulkanDevice& device, const TraceSpecialization& specialization,
                                  bool resumable, bool subgroupStatistics);

}  // namespace vitrum
