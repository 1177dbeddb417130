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
// Which unit: lavapipe splits a dispatch's workgroups, in order, into one run of consecutive
// workgroups a thread (Mesa's lp_cs_tpool), so a thread whose run covers the glass works on while
// the other waits. Where subgroups are full, each subgroup instead takes the dispatch's next unit
// from a counter: the threads take turns through the tile, each near the other, and a unit is the
// same pixels whichever thread takes it (so are the images and statistics). The persistent
// kernel's subgroups go on taking units (main), so that a thread that is ahead takes more of them.
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
// that the 8 lanes of a lavapipe SIMD group cover 4x2 pixels rather than a row of 8: nearer pixels
// send nearer rays, which visit more of the same BVH nodes, and the group's loops run fewer
// iterations (docs/gpu-design.md).
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

// lavapipe counts a subgroup's loop iterations over all the units it traces: their steps, at
// most about 20 more a unit that the count misses (docs/gpu-design.md), the loop over the units
// and, once, the statistics' loops. A unit is counted for 64 beyond its steps, and the limit is
// kept 256 below lavapipe's.
const uint kUnitIterationsBeyondSteps = 64u;
const uint kDriverLoopIterations = 65535u - 256u;

#endif
