// Adds invocations' counters to stats[] (indices of shared/trace_statistics.h): `sums` holds the
// counters 0 .. kStatFirstMax - 1 in index order (sumsOf), `maxima` the ones from kStatFirstMax on.
//
// On lavapipe every atomic and every subgroupAdd is a loop over the lanes, so the counters are
// summed over the subgroup, by a butterfly of shuffles where subgroups are full (kFullSubgroups),
// and each lane then adds a different one (docs/gpu-design.md, "Data", binding 11). A shuffle
// reads another lane: there every lane must call this, those without a pixel with zeros (main).
#ifndef VITRUM_STATISTICS_GLSL
#define VITRUM_STATISTICS_GLSL

#ifndef VITRUM_NO_SUBGROUP_OPERATIONS
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_shuffle : require
#endif

#include "counters.glsl"
#include "bindings.glsl"
#include "specialization.glsl"

void addSums(inout StatisticSums total, StatisticSums sums) {
    total.v0 += sums.v0;
    total.v1 += sums.v1;
    total.v2 += sums.v2;
    total.v3 += sums.v3;
    total.v4 += sums.v4;
    total.v5 += sums.v5;
}

uint statisticAt(StatisticSums s, uint index) {
    if (index >= 20u) return s.v5[index - 20u];
    uvec4 v = index < 4u ? s.v0 : (index < 8u ? s.v1 : (index < 12u ? s.v2 : (index < 16u ? s.v3 : s.v4)));
    return v[index & 3u];
}

void addStatistics(StatisticSums sums, uvec3 maxima) {
#ifdef VITRUM_NO_SUBGROUP_OPERATIONS
    // No subgroup arithmetic on this device: one atomic a lane and counter.
    for (uint index = 0u; index < kStatFirstMax; ++index) {
        uint value = statisticAt(sums, index);
        if (value != 0u) atomicAdd(stats[index], value);
    }
    for (uint i = 0u; i < kStatCount - kStatFirstMax; ++i)
        if (maxima[i] != 0u) atomicMax(stats[kStatFirstMax + i], maxima[i]);
#else
    // Every lane ends up with the subgroup's sums; `lanes` of them, ranked 0 .. lanes - 1, then
    // add one counter each.
    uint lanes, rank;
    if (kFullSubgroups) {
        for (uint distance = 1u; distance < gl_SubgroupSize; distance <<= 1u) {
            sums.v0 += subgroupShuffleXor(sums.v0, distance);
            sums.v1 += subgroupShuffleXor(sums.v1, distance);
            sums.v2 += subgroupShuffleXor(sums.v2, distance);
            sums.v3 += subgroupShuffleXor(sums.v3, distance);
            sums.v4 += subgroupShuffleXor(sums.v4, distance);
            sums.v5 += subgroupShuffleXor(sums.v5, distance);
            maxima = max(maxima, subgroupShuffleXor(maxima, distance));
        }
        lanes = gl_SubgroupSize;
        rank = gl_SubgroupInvocationID;
    } else {
        sums.v0 = subgroupAdd(sums.v0);
        sums.v1 = subgroupAdd(sums.v1);
        sums.v2 = subgroupAdd(sums.v2);
        sums.v3 = subgroupAdd(sums.v3);
        sums.v4 = subgroupAdd(sums.v4);
        sums.v5 = subgroupAdd(sums.v5);
        maxima = subgroupMax(maxima);
        uvec4 activeLanes = subgroupBallot(true);
        lanes = subgroupBallotBitCount(activeLanes);
        rank = subgroupBallotExclusiveBitCount(activeLanes);
    }
    for (uint first = 0u; first < kStatFirstMax; first += lanes) {
        uint index = first + rank;
        uint value = statisticAt(sums, index);
        if (index < kStatFirstMax && value != 0u) atomicAdd(stats[index], value);
    }
    for (uint first = 0u; first < kStatCount - kStatFirstMax; first += lanes) {
        uint i = first + rank;
        uint value = i == 0u ? maxima.x : (i == 1u ? maxima.y : maxima.z);
        if (i < kStatCount - kStatFirstMax && value != 0u) atomicMax(stats[kStatFirstMax + i], value);
    }
#endif
}

#endif
