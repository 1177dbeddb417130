// Runs the traversal's ray/box test (shaders/ray_box.glsl) on the device through the test kernel
// shaders/box_test.comp, one case per invocation.
#pragma once

#include <span>
#include <vector>

#include "gpu/vulkan_device.h"
#include "shared/box_test_types.h"

namespace vitrum {

using BoxCase = gpu::BoxCase;
using BoxResult = gpu::BoxResult;

static_assert(sizeof(BoxCase) == 64);
static_assert(sizeof(BoxResult) == 16);

std::vector<BoxResult> evaluateBoxTestsOnGpu(VulkanDevice& device, std::span<const BoxCase> cases);

}  // namespace vitrum
