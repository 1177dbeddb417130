// The counters of one invocation (shared/trace_statistics.h) and their packing for the sums of
// statistics.glsl.
#ifndef VITRUM_COUNTERS_GLSL
#define VITRUM_COUNTERS_GLSL

#include "shared/trace_statistics.h"

// The counters of one invocation, one field a statistic of shared/trace_statistics.h.
#define VITRUM_COUNTER_FIELD(index, name, combine, group, key, measured) uint name;
struct TraceCounters {
    VITRUM_TRACE_STATISTICS(VITRUM_COUNTER_FIELD)
};
#undef VITRUM_COUNTER_FIELD

// This invocation's counters: what the unit it traces has counted so far (trace.comp's traceUnit).
TraceCounters counters;

TraceCounters noCounters() {
    TraceCounters c;
#define VITRUM_COUNTER_ZERO(index, name, combine, group, key, measured) c.name = 0u;
    VITRUM_TRACE_STATISTICS(VITRUM_COUNTER_ZERO)
#undef VITRUM_COUNTER_ZERO
    return c;
}

// The sums, kStatFirstMax of them, four a vector, and the maxima: so that summing over a
// subgroup takes a few vector operations, not one a counter.
struct StatisticSums {
    uvec4 v0, v1, v2, v3, v4;
    uvec3 v5;
};

const StatisticSums kNoStatistics = StatisticSums(uvec4(0u), uvec4(0u), uvec4(0u), uvec4(0u), uvec4(0u), uvec3(0u));

// The packing below is written for 23 sums and 3 maxima: a list of another length stops the build.
const uint kStatisticsPacked[kStatFirstMax == 23u && kStatCount == 26u ? 1 : -1] = uint[](0u);

StatisticSums sumsOf(TraceCounters c) {
    uint v[kStatCount];
#define VITRUM_COUNTER_VALUE(index, name, combine, group, key, measured) v[index] = c.name;
    VITRUM_TRACE_STATISTICS(VITRUM_COUNTER_VALUE)
    return StatisticSums(uvec4(v[0], v[1], v[2], v[3]), uvec4(v[4], v[5], v[6], v[7]), uvec4(v[8], v[9], v[10], v[11]),
                         uvec4(v[12], v[13], v[14], v[15]), uvec4(v[16], v[17], v[18], v[19]), uvec3(v[20], v[21], v[22]));
}

uvec3 maximaOf(TraceCounters c) {
    uint v[kStatCount];
    VITRUM_TRACE_STATISTICS(VITRUM_COUNTER_VALUE)
#undef VITRUM_COUNTER_VALUE
    return uvec3(v[23], v[24], v[25]);
}

#endif
