// Runs the touching-surface functions (shaders/touching.glsl) on the device through the test
// kernel shaders/touching_test.comp, one sequence of crossings per invocation.
#pragma once

#include <span>
#include <vector>

#include "gpu/vulkan_device.h"
#include "shared/touching_test_types.h"

namespace vitrum {

using TouchingCase = gpu::TouchingCase;
using TouchingResult = gpu::TouchingResult;

// std430 sizes, as touching_test.comp sees them.
static_assert(sizeof(TouchingCase) == 128);
static_assert(sizeof(TouchingResult) == 48);

std::vector<TouchingResult> evaluateTouchingOnGpu(VulkanDevice& device, std::span<const TouchingCase> cases);

}  // namespace vitrum
