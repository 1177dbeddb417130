// The parameters a dispatch of trace.comp reads (shaders/shared/render_params.h): the scene's
// camera and settings with what its analysis found. The tile is set per dispatch (setTile).
#pragma once

#include <cstdint>

#include "analysis/scene_features.h"
#include "scene/scene.h"
#include "shared/render_params.h"

namespace vitrum {

// `rootEntry` and `firstInstanceNode` are the BVH's (TraversalNodes); `iterationBudget` the loop
// steps a SIMD group may run in a dispatch (VulkanRenderOptions).
gpu::RenderParams makeRenderParams(const Scene& scene, const SceneFeatures& features, std::uint32_t rootEntry,
                                   std::uint32_t iterationBudget, std::uint32_t firstInstanceNode = 0);

}  // namespace vitrum
