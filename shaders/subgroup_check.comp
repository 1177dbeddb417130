#version 460
// The device self-check of the fast kernel's subgroup machinery (host/gpu/subgroup_self_check.h):
// trace.comp's full-subgroup path in miniature, checked on the host. Subgroups of one workgroup
// take units from a counter (an elected lane's atomic, broadcast) until none is left, as the
// persistent kernel does; in each unit the lanes loop together, each for a trip count of its own,
// until the last is done, every round reading one another by shuffles (a butterfly for the
// group's largest value, and a value from a lane picked by the group, as ray sharing does), and
// sum their counts by a butterfly as the statistics do. Every lane writes what it saw.
//
// With kSubgroupBarrier each round also has a subgroup barrier: the minimal kernel of the Mesa 25
// lavapipe defect in docs/gpu-design.md ("Two drivers"); trace.comp has no barrier.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_shuffle : require

#include "shared/subgroup_check_types.h"

layout(local_size_x = 8, local_size_y = 8) in;  // trace.comp's workgroup

// The pipeline requires full subgroups, as the fast kernel's does: lanes.glsl's functions are
// then trace.comp's own (butterflies of shuffles, the elected lane's value broadcast).
const bool kFullSubgroups = true;
#include "lanes.glsl"

layout(constant_id = 0) const bool kSubgroupBarrier = false;

layout(std430, set = 0, binding = 0) buffer Control { SubgroupCheckControl control; };
layout(std430, set = 0, binding = 1) buffer Results { SubgroupCheckResult results[]; };

// The butterfly sum of statistics.glsl's addStatistics.
uint groupSum(uint value) {
    for (uint distance = 1u; distance < gl_SubgroupSize; distance <<= 1u)
        value += subgroupShuffleXor(value, distance);
    return value;
}

void main() {
    for (;;) {
        uint unit = 0u;
        if (firstLane()) unit = atomicAdd(control.cursor, 1u);
        unit = fromFirstLane(unit);
        if (unit >= control.units) break;
        uint lane = gl_SubgroupInvocationID;
        uint trips = subgroupCheckTrips(unit, lane);
        // The injected fault (tests only): one lane of unit 0 leaves its loop at once, as a lane
        // a driver lost would.
        bool lost = control.fault != 0u && unit == 0u && lane == 1u;
        uint mine = 0u;
        uint rounds = 0u;
        uint received = 0u;
        bool busy = trips > 0u && !lost;
        if (groupAny(busy)) do {
            rounds += 1u;
            if (busy) mine += 1u;
            // The lane with the most trips left (the lowest among equals) gives this round's value.
            uint left = trips - mine;
            uint key = groupMax(busy ? (left << 8u) | (255u - lane) : 0u);
            uint giver = key == 0u ? 0u : 255u - (key & 0xFFu);
            uint given = subgroupShuffle(subgroupCheckValue(unit, lane, rounds), giver);
            if (kSubgroupBarrier) subgroupBarrier();
            received += given;
            busy = busy && mine < trips;
        } while (groupAny(busy));
        uint sum = groupSum(mine);
        const uint counts = (rounds << 24u) | (mine << 16u) | (sum + 1u);
        if (!lost) results[unit * gl_SubgroupSize + lane] = SubgroupCheckResult(counts, received);
    }
}
