#include "gpu/touching_kernel.h"

#include "gpu/test_kernel.h"
#include "touching_test.spv.h"

namespace vitrum {

std::vector<TouchingResult> evaluateTouchingOnGpu(VulkanDevice& device, std::span<const TouchingCase> cases) {
    return runTestKernel<TouchingCase, TouchingResult>(
        device, std::span<const std::uint32_t>(touching_test_spv, std::size(touching_test_spv)),
        gpu::kTouchingTestGroupSize, cases, "touching test cases");
}

}  // namespace vitrum
