// Which pixels an invocation traces: the units of work of a dispatch over one tile, and how many
// a persistent subgroup may take.
#ifndef VITRUM_SCHEDULE_GLSL
#define VITRUM_SCHEDULE_GLSL

#include "shared/trace_statistics.h"
#include "bindings.glsl"
#include "specialization.glsl"
#include "lanes.glsl"

// The work of a dispatch comes in units: where subgroups are full, a unit is a subgroup's share
// of an 8x8 block of the tile's part inside the image; elsewhere a workgroup traces its own block
// and there is one unit, its own.
//
// lavapipe gives each thread a fixed run of consecutive workgroups (Mesa's lp_cs_tpool), so where
// subgroups are full each subgroup takes the next unit from a counter instead, and the threads
// share every part of the tile; a unit is the same pixels whichever thread takes it
// (docs/gpu-design.md, "A dispatch on lavapipe's threads").
uvec2 tileBlocks() {
    uvec2 inside = min(uvec2(tileWidth(), tileHeight()), uvec2(imageWidth(), imageHeight()) - min(uvec2(tileX(), tileY()), uvec2(imageWidth(), imageHeight())));
    return (inside + gl_WorkGroupSize.xy - 1u) / gl_WorkGroupSize.xy;
}

uint tileUnits() {
#ifndef VITRUM_NO_SUBGROUP_OPERATIONS
    if (kFullSubgroups) {
        uvec2 blocks = tileBlocks();
        return blocks.x * blocks.y * gl_NumSubgroups;
    }
#endif
    return 1u;
}

// The dispatch's next unit (the same in every lane).
uint takeUnit() {
#ifndef VITRUM_NO_SUBGROUP_OPERATIONS
    if (kFullSubgroups) {
        uint unit = 0u;
        if (firstLane()) unit = atomicAdd(stats[kWorkCursor], 1u);
        return fromFirstLane(unit);
    }
#endif
    return 0u;
}

// This invocation's pixel in `unit`, relative to the tile. A block is walked in Morton order, so
// that the 8 lanes of a lavapipe SIMD group cover 4x2 pixels rather than a row of 8: nearer rays
// visit more of the same nodes (docs/gpu-design.md, "What makes it fast on lavapipe").
uvec2 tilePixel(uint unit) {
    uvec2 block = gl_WorkGroupID.xy;
    uint i = gl_LocalInvocationIndex;
#ifndef VITRUM_NO_SUBGROUP_OPERATIONS
    if (kFullSubgroups) {
        uint blockIndex = unit / gl_NumSubgroups;
        uint blocksX = tileBlocks().x;
        block = uvec2(blockIndex % blocksX, blockIndex / blocksX);
        i = (unit % gl_NumSubgroups) * gl_SubgroupSize + gl_SubgroupInvocationID;
    }
#endif
    uvec2 inBlock = uvec2((i & 1u) | ((i >> 1u) & 2u) | ((i >> 2u) & 4u), ((i >> 1u) & 1u) | ((i >> 2u) & 2u) | ((i >> 3u) & 4u));
    return block * gl_WorkGroupSize.xy + inBlock;
}

// The persistent kernel: the first dispatch's, where subgroups are full, on a device that runs
// on the CPU (host/gpu/vulkan_renderer.cpp). Its subgroups take units until none is left or the
// driver's loop limit could not hold another unit's budget.
#ifndef VITRUM_NO_SUBGROUP_OPERATIONS
const bool kPersistent = kPersistentSubgroups && kFullSubgroups && !kResumable;
#else
const bool kPersistent = false;
#endif

// lavapipe counts a subgroup's loop iterations over all the units it traces: their steps, the few
// a unit runs beyond them, the loop over the units and the statistics' loops. A unit is counted
// for 64 beyond its steps and the limit kept 256 below lavapipe's (docs/gpu-design.md, "One loop,
// bounded, resumable", point 2).
const uint kUnitIterationsBeyondSteps = 64u;
const uint kDriverLoopIterations = 65535u - 256u;

#endif
