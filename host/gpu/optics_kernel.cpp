#include "gpu/optics_kernel.h"

#include <array>
#include <cstdint>

#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"
#include "optics_test.spv.h"

namespace vitrum {

std::vector<OpticsResult> evaluateOpticsOnGpu(VulkanDevice& device, std::span<const OpticsCase> cases) {
    if (cases.empty()) return {};  // Vulkan has no empty buffers and no empty dispatches to make.
    const std::array<VkDescriptorType, 2> bindings = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                                      VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
    ComputePipeline pipeline(device, std::span<const std::uint32_t>(optics_test_spv, std::size(optics_test_spv)),
                             bindings);
    // Both buffers hold exactly the cases (64 bytes each, so never under the 16-byte minimum): the
    // kernel's guard reads the count from their length.
    GpuBuffer input = makeStorageBuffer(device, cases, "optics test cases");
    GpuBuffer output(device, cases.size_bytes(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "optics test results");
    const std::array<const GpuBuffer*, 2> bound = {&input, &output};
    pipeline.bind(bound);
    const auto groups = std::uint32_t((cases.size() + gpu::kOpticsTestGroupSize - 1) / gpu::kOpticsTestGroupSize);
    device.submitAndWait([&](VkCommandBuffer commands) { pipeline.record(commands, groups); });
    const OpticsResult* results = output.as<OpticsResult>();
    return std::vector<OpticsResult>(results, results + cases.size());
}

}  // namespace vitrum
