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

ComputePipeline makeTracePipeline(const VulkanDevice& device, const TraceSpecialization& specialization);

}  // namespace vitrum
