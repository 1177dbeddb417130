// The counters of a render, one member a statistic of shaders/shared/trace_statistics.h, summed
// in 64 bits: the GPU's dispatches add their statistics buffers, the CPU reference its threads'.
#pragma once

#include <cstdint>

#include <nlohmann/json_fwd.hpp>

#include "shared/trace_statistics.h"

namespace vitrum {

// Each statistic's index in the GPU's statistics buffer: TraceStatistic::unfinishedPixels.
namespace TraceStatistic {
#define VITRUM_STATISTIC_INDEX(index, name, combine, group, key, measured) name = index,
enum : std::uint32_t { VITRUM_TRACE_STATISTICS(VITRUM_STATISTIC_INDEX) };
#undef VITRUM_STATISTIC_INDEX
}  // namespace TraceStatistic

struct TraceCounts {
#define VITRUM_COUNT_MEMBER(index, name, combine, group, key, measured) std::uint64_t name = 0;
    VITRUM_TRACE_STATISTICS(VITRUM_COUNT_MEMBER)
#undef VITRUM_COUNT_MEMBER

    std::uint64_t totalRays() const {
        return primaryRays + shadowRays + reflectionRays + refractionRays + passThroughRays;
    }

    // Sums add, maxima take the larger.
    TraceCounts& operator+=(const TraceCounts& other);
    // Adds one dispatch's statistics buffer: gpu::kStatCount uints, by index.
    void addDispatch(const std::uint32_t* counters);
};

// Writes the counters where trace_statistics.h says (rays.KEY, limits.KEY or KEY): with
// `gpuOnlyToo` false (the CPU reference) only those both backends measure.
void addToJson(const TraceCounts& counts, bool gpuOnlyToo, nlohmann::json& json);

}  // namespace vitrum
