// The compute pipeline of shaders/trace.comp; its bindings and specialization constants are
// shaders/shared/trace_bindings.h and trace_constants.h.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "gpu/compute_pipeline.h"
#include "gpu_input/trace_specialization.h"
#include "shared/trace_bindings.h"
#include "shared/trace_constants.h"

namespace vitrum {

constexpr std::uint32_t kTraceGroupSize = 8;  // local_size_x = local_size_y in trace.comp

// How trace.comp adds up its counters (shaders/statistics.glsl). All three give the same numbers;
// each needs more of the device than the one before it, and costs less.
enum class StatisticsSums {
    atomics,      // one atomic a counter and invocation (trace_without_subgroups: no subgroup operations)
    subgroupAdd,  // summed over each subgroup (subgroup arithmetic and ballots), then each lane adds another counter
    shuffles,     // the same, summed by a butterfly of shuffles, in full subgroups (SubgroupSupport::fullSubgroups)
};

// `preferred` where `device` can run it, else the nearest way before it that it can.
StatisticsSums statisticsSumsFor(const SubgroupSupport& device, StatisticsSums preferred);
StatisticsSums statisticsSumsFor(const VulkanDevice& device, StatisticsSums preferred);

// "atomics", "subgroupAdd", "shuffles".
const char* statisticsSumsName(StatisticsSums sums);

// The SPIR-V of the trace.comp build that sums its statistics so (one with subgroup operations,
// one without).
std::span<const std::uint32_t> traceKernelCode(StatisticsSums sums);

// The specialization constants of one trace kernel, by id (shaders/shared/trace_constants.h): the
// scene's (TraceSpecialization::constants) and the kernel's role and device. Together with the
// code (traceKernelCode(sums)) they name the kernel.
TraceKernelConstants traceKernelConstants(const TraceSpecialization& specialization, bool resumable, StatisticsSums sums,
                                          bool persistent);

// The first dispatch of every tile runs the kernel built with `resumable` false; the pixels it
// gives up are restarted by the resumable one (shaders/suspend.glsl). `sums` must be one that
// statisticsSumsFor allows. With `persistent` (the first dispatch's kernel in full subgroups
// only), its subgroups take units of work until none is left (trace.comp's main), so the host
// dispatches fewer workgroups than units.
ComputePipeline makeTracePipeline(const VulkanDevice& device, const TraceSpecialization& specialization,
                                  bool resumable, StatisticsSums sums, bool persistent = false);

}  // namespace vitrum
