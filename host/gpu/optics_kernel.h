// Runs the GLSL optics functions (shaders/optics.glsl) on the device through the test kernel
// shaders/optics_test.comp, one case per invocation, so tests can check the GPU's optics directly
// rather than only through rendered images.
#pragma once

#include <span>
#include <vector>

#include "gpu/vulkan_device.h"
#include "shared/optics_test_types.h"

namespace vitrum {

using OpticsCase = gpu::OpticsCase;
using OpticsResult = gpu::OpticsResult;

// std430 sizes, as optics_test.comp sees them.
static_assert(sizeof(OpticsCase) == 64);
static_assert(sizeof(OpticsResult) == 64);

// Evaluates every case on `device` (one dispatch) and returns the results in the same order.
std::vector<OpticsResult> evaluateOpticsOnGpu(VulkanDevice& device, std::span<const OpticsCase> cases);

}  // namespace vitrum
