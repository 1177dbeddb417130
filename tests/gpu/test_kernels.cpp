#include "test_kernels.h"

#include <array>
#include <cstdint>

#include "box_test.spv.h"
#include "colour_sum_test.spv.h"
#include "loop_limit_probe.spv.h"
#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"
#include "optics_test.spv.h"
#include "touching_test.spv.h"

namespace vitrum {
namespace {

// One dispatch of a test kernel that reads one Case and writes one Result per invocation from
// storage buffers 0 and 1 (local size `groupSize` in x). Both buffers hold exactly the cases (at
// least 16 bytes each): the kernel's guard reads the case count from their lengths.
template <typename Case, typename Result>
std::vector<Result> runTestKernel(VulkanDevice& device, std::span<const std::uint32_t> spirv, std::uint32_t groupSize,
                                  std::span<const Case> cases, const char* name) {
    static_assert(sizeof(Case) % 16 == 0 && sizeof(Result) % 16 == 0);
    if (cases.empty()) return {};  // Vulkan has no empty buffers and no empty dispatches to make.
    const std::array<VkDescriptorType, 2> bindings = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                                      VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
    ComputePipeline pipeline(device, spirv, bindings);
    GpuBuffer input = makeStorageBuffer(device, cases, name);
    GpuBuffer output(device, cases.size() * sizeof(Result), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, name, MemoryUse::Readback);
    const std::array<const GpuBuffer*, 2> bound = {&input, &output};
    pipeline.bind(bound);
    const auto groups = std::uint32_t((cases.size() + groupSize - 1) / groupSize);
    device.submitAndWait([&](VkCommandBuffer commands) { pipeline.record(commands, groups); });
    const Result* results = output.as<Result>();
    return std::vector<Result>(results, results + cases.size());
}

template <std::size_t N>
std::span<const std::uint32_t> code(const std::uint32_t (&spirv)[N]) {
    return std::span<const std::uint32_t>(spirv, N);
}

}  // namespace

std::vector<OpticsResult> evaluateOpticsOnGpu(VulkanDevice& device, std::span<const OpticsCase> cases) {
    return runTestKernel<OpticsCase, OpticsResult>(device, code(optics_test_spv), gpu::kOpticsTestGroupSize, cases,
                                                   "optics test cases");
}

std::vector<TouchingResult> evaluateTouchingOnGpu(VulkanDevice& device, std::span<const TouchingCase> cases) {
    return runTestKernel<TouchingCase, TouchingResult>(device, code(touching_test_spv), gpu::kTouchingTestGroupSize,
                                                       cases, "touching test cases");
}

std::vector<BoxResult> evaluateBoxTestsOnGpu(VulkanDevice& device, std::span<const BoxCase> cases) {
    return runTestKernel<BoxCase, BoxResult>(device, code(box_test_spv), gpu::kBoxTestGroupSize, cases,
                                             "box test cases");
}

std::vector<ColourSumResult> evaluateColourSumsOnGpu(VulkanDevice& device, std::span<const ColourSumCase> cases) {
    return runTestKernel<ColourSumCase, ColourSumResult>(device, code(colour_sum_test_spv), gpu::kColourSumTestGroupSize,
                                                         cases, "colour sum test cases");
}

std::optional<std::uint32_t> probeLoopLimit(VulkanDevice& device, std::uint32_t iterations) {
    const std::array<VkDescriptorType, 1> bindings = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
    ComputePipeline pipeline(device, code(loop_limit_probe_spv), bindings);
    GpuBuffer probe(device, 4 * sizeof(std::uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "loop limit probe");
    std::uint32_t* values = probe.as<std::uint32_t>();
    values[0] = iterations;
    values[1] = 0;
    const std::array<const GpuBuffer*, 1> bound = {&probe};
    pipeline.bind(bound);
    device.submitAndWait([&](VkCommandBuffer commands) { pipeline.record(commands, 1); });
    if (values[1] >= iterations) return std::nullopt;
    return values[1];
}

}  // namespace vitrum
