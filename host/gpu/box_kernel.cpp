#include "gpu/box_kernel.h"

#include "box_test.spv.h"
#include "gpu/test_kernel.h"

namespace vitrum {

std::vector<BoxResult> evaluateBoxTestsOnGpu(VulkanDevice& device, std::span<const BoxCase> cases) {
    return runTestKernel<BoxCase, BoxResult>(device, std::span<const std::uint32_t>(box_test_spv, std::size(box_test_spv)),
                                             gpu::kBoxTestGroupSize, cases, "box test cases");
}

}  // namespace vitrum
