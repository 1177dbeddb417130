#include "gpu/optics_kernel.h"

#include "gpu/test_kernel.h"
#include "optics_test.spv.h"

namespace vitrum {

std::vector<OpticsResult> evaluateOpticsOnGpu(VulkanDevice& device, std::span<const OpticsCase> cases) {
    return runTestKernel<OpticsCase, OpticsResult>(
        device, std::span<const std::uint32_t>(optics_test_spv, std::size(optics_test_spv)), gpu::kOpticsTestGroupSize,
        cases, "optics test cases");
}

}  // namespace vitrum
