// Runs a test kernel (shaders/*_test.comp) that reads one Case and writes one Result per
// invocation from two storage buffers (bindings 0 and 1), so tests can check GLSL functions on the
// device directly rather than only through rendered images.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "gpu/compute_pipeline.h"
#include "gpu/gpu_buffer.h"
#include "gpu/vulkan_device.h"

namespace vitrum {

// One dispatch of `spirv` (local size `groupSize` in x) over `cases`; the results in the same
// order. Both buffers hold exactly the cases (at least 16 bytes each): the kernel's guard reads
// the case count from their lengths.
template <typename Case, typename Result>
std::vector<Result> runTestKernel(VulkanDevice& device, std::span<const std::uint32_t> spirv, std::uint32_t groupSize,
                                  std::span<const Case> cases, const char* name) {
    static_assert(sizeof(Case) % 16 == 0 && sizeof(Result) % 16 == 0);
    if (cases.empty()) return {};  // Vulkan has no empty buffers and no empty dispatches to make.
    const std::array<VkDescriptorType, 2> bindings = {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                                      VK_DESCRIPTOR_TYPE_STORAGE_BUFFER};
    ComputePipeline pipeline(device, spirv, bindings);
    GpuBuffer input = makeStorageBuffer(device, cases, name);
    GpuBuffer output(device, cases.size() * sizeof(Result), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, name);
    const std::array<const GpuBuffer*, 2> bound = {&input, &output};
    pipeline.bind(bound);
    const auto groups = std::uint32_t((cases.size() + groupSize - 1) / groupSize);
    device.submitAndWait([&](VkCommandBuffer commands) { pipeline.record(commands, groups); });
    const Result* results = output.as<Result>();
    return std::vector<Result>(results, results + cases.size());
}

}  // namespace vitrum
