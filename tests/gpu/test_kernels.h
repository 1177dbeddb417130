// Runs GLSL functions of the ray tracer on the device through test kernels (shaders/*_test.comp),
// one case per invocation, so that tests can check what trace.comp computes directly rather than
// only through rendered images:
//   optics_test.comp    shaders/optics.glsl (reflection, refraction, Fresnel, Beer-Lambert)
//   touching_test.comp  shaders/touching.glsl (touching glass surfaces during a traversal)
//   box_test.comp       shaders/ray_box.glsl (the traversal's ray/box test)
//   colour_sum_test.comp shaders/colour_sum.glsl (a pixel's colour sum in fixed point)
// and probes what a driver does beyond the spec:
//   loop_limit_probe.comp  whether it ends a shader's loops early
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "gpu/vulkan_device.h"
#include "kernels/box_test_types.h"
#include "kernels/colour_sum_test_types.h"
#include "kernels/optics_test_types.h"
#include "kernels/touching_test_types.h"

namespace vitrum {

using OpticsCase = gpu::OpticsCase;
using OpticsResult = gpu::OpticsResult;
using TouchingCase = gpu::TouchingCase;
using TouchingResult = gpu::TouchingResult;
using BoxCase = gpu::BoxCase;
using BoxResult = gpu::BoxResult;
using ColourSumCase = gpu::ColourSumCase;
using ColourSumResult = gpu::ColourSumResult;

// std430 sizes, as the kernels see them.
static_assert(sizeof(OpticsCase) == 64 && sizeof(OpticsResult) == 64);
static_assert(sizeof(TouchingCase) == 128 && sizeof(TouchingResult) == 48);
static_assert(sizeof(BoxCase) == 64 && sizeof(BoxResult) == 16);
static_assert(sizeof(ColourSumCase) == 96 && sizeof(ColourSumResult) == 48);

// Each evaluates every case on `device` in one dispatch and returns the results in the same order.
std::vector<OpticsResult> evaluateOpticsOnGpu(VulkanDevice& device, std::span<const OpticsCase> cases);
std::vector<TouchingResult> evaluateTouchingOnGpu(VulkanDevice& device, std::span<const TouchingCase> cases);
std::vector<BoxResult> evaluateBoxTestsOnGpu(VulkanDevice& device, std::span<const BoxCase> cases);
std::vector<ColourSumResult> evaluateColourSumsOnGpu(VulkanDevice& device, std::span<const ColourSumCase> cases);

// Runs a loop of `iterations` on `device`: how many of them ran, where the driver ended it early
// (Mesa 22.3's lavapipe: 65,535), or nothing where it ran them all.
std::optional<std::uint32_t> probeLoopLimit(VulkanDevice& device, std::uint32_t iterations);

}  // namespace vitrum
