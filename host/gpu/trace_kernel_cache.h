// Trace pipelines kept across the renders of one process. Creating one costs lavapipe about
// 0.1 s (its passes over the kernel's NIR, then loading LLVM's code at the first dispatch), more
// than a small render takes; a process that renders many times (the benchmarks, the accuracy
// study) hands one cache to every renderVulkan call (VulkanRenderOptions::kernels), and each
// kernel is then created and compiled once. The cache must not outlive the device it was first
// used with, and is for one device only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <list>

#include "gpu/compute_pipeline.h"
#include "gpu/trace_pipeline.h"
#include "gpu/vulkan_device.h"
#include "gpu_input/trace_specialization.h"

namespace vitrum {

class TraceKernelCache {
public:
    // A render takes two kernels at most (the first dispatch's and the resumable one), so the
    // cache holds at least two: the one a render took first is never evicted by its second.
    explicit TraceKernelCache(std::size_t capacity = 4);

    struct Kernel {
        ComputePipeline& pipeline;
        bool& compiled;  // dispatched before: lavapipe has compiled its code (the renderer sets it)
    };

    // The kernel makeTracePipeline would make for these arguments: the cached one, or a new one
    // that replaces the one used least recently when the cache is full. The reference stays
    // valid until the cache holds `capacity` kernels taken after it.
    Kernel get(const VulkanDevice& device, const TraceSpecialization& specialization, bool resumable,
               StatisticsSums sums, bool persistent = false);

    std::size_t created() const { return created_; }  // pipelines created so far
    std::size_t size() const { return entries_.size(); }

private:
    struct Entry {
        TraceKernelConstants constants;
        StatisticsSums sums;  // which code (traceKernelCode)
        ComputePipeline pipeline;
        bool compiled = false;
    };

    std::size_t capacity_;
    VkDevice device_ = VK_NULL_HANDLE;
    std::list<Entry> entries_;  // most recently used first
    std::size_t created_ = 0;
};

}  // namespace vitrum
