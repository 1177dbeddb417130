// Pixels that need more than one dispatch. The first dispatch runs the kernel built without
// kResumable (a resumable state stays live, lane-masked, through the whole loop) and gives up a
// pixel not done within the budget (kSlotRestart); the resumable kernel starts those afresh, and
// suspends and resumes them: their TraceState in stateTexels[], the used part of their traversal
// stack in traversalStacks[] (docs/gpu-design.md, "One loop, bounded, resumable", point 3).
//
// On lavapipe every storage-buffer access is a loop over the lanes, even when no lane is active:
// each copy is one loop, through a private array, whose trip count is zero unless a lane copies.
#ifndef VITRUM_SUSPEND_GLSL
#define VITRUM_SUSPEND_GLSL

#include "bindings.glsl"
#include "specialization.glsl"
#include "trace_state.glsl"
#include "cutout.glsl"  // cutAway, which bvh.glsl calls
#include "bvh.glsl"
#include "ray_tree.glsl"  // startPixel

uvec4 gStateTexels[kTraceStateTexels];

// A slot's status is its pixel's alpha (pixels[slot].w), written with the pixel by every dispatch
// that traces it: so the first dispatch touches no page of the state buffer, each first touch of
// a page being a page fault (docs/gpu-design.md, "Page faults").
const float kSlotRestart = 0.0;    // given up by the first dispatch: start it again
const float kSlotDone = 1.0;       // finished, its colour in .xyz: later dispatches skip it
const float kSlotSuspended = 2.0;  // suspended by the resumable kernel: its state in stateTexels

// The texels of a suspended state. Texels 10-15 hold what a closest-hit traversal collects while
// the pixel traces (kPhaseTrace), else the hit and what shading carries: the one is never needed
// while the other is (bvh.glsl's beginClosestTraversal starts the first, finishTrace the second).
void packState() {
    gStateTexels[0] = floatBitsToUint(st.ray.origin);
    gStateTexels[1] = floatBitsToUint(st.ray.direction);
    gStateTexels[2] = floatBitsToUint(st.ray.weight);
    gStateTexels[3] = st.ray.media;
    gStateTexels[4] = floatBitsToUint(vec4(st.traversal.origin, st.traversal.tMin));
    gStateTexels[5] = floatBitsToUint(vec4(st.traversal.direction, st.traversal.tMax));
    gStateTexels[6] = uvec4(st.traversal.leafCursor, st.traversal.leafEnd, st.traversal.closest, st.traversal.stackTop);
    gStateTexels[7] = uvec4(floatBitsToUint(st.traversal.barycentrics), st.samplesDone, st.steps);
    gStateTexels[8] = uvec4(st.colour.low, st.phase);
    gStateTexels[9] = uvec4(st.colour.high, st.pendingRays);
    bool tracing = st.phase == kPhaseTrace;
    Candidates c = st.candidates;
    gStateTexels[10] = tracing ? c.touchingObjects : floatBitsToUint(vec4(st.hit.position, st.hit.t));
    gStateTexels[11] = tracing ? floatBitsToUint(c.touchingT)
                               : uvec4(floatBitsToUint(st.hit.shadingNormal), st.hit.material);
    gStateTexels[12] = tracing ? floatBitsToUint(c.contact)
                               : uvec4(floatBitsToUint(st.hit.geometricNormal), st.hit.object);
    gStateTexels[13] = tracing ? floatBitsToUint(c.leaving) : st.touching;
    // With instances (kInstancing): the instance the traversal is in, and while tracing those of
    // the nearest hit and the two candidates (bvh.glsl).
    uvec3 instances = kInstancing ? uvec3(st.traversal.closestInstance, c.contactInstance, c.leavingInstance) : uvec3(0u);
    uint inInstance = kInstancing ? st.traversal.instance : 0u;
    gStateTexels[14] = tracing ? uvec4(c.closestIsGlass ? 1u : 0u, instances)
                               : floatBitsToUint(vec4(st.farthestTouching, st.shadowLight));
    gStateTexels[15] = tracing ? uvec4(0u, 0u, 0u, inInstance) : uvec4(floatBitsToUint(st.hit.uv), st.light, inInstance);
}

// Both readings of texels 10-15 are unpacked: the one not in use is never read.
void unpackState() {
    st.ray.origin = uintBitsToFloat(gStateTexels[0]);
    st.ray.direction = uintBitsToFloat(gStateTexels[1]);
    st.ray.weight = uintBitsToFloat(gStateTexels[2]);
    st.ray.media = gStateTexels[3];
    vec4 origin = uintBitsToFloat(gStateTexels[4]);
    vec4 direction = uintBitsToFloat(gStateTexels[5]);
    st.traversal.origin = origin.xyz;
    st.traversal.tMin = origin.w;
    st.traversal.direction = direction.xyz;
    st.traversal.tMax = direction.w;
    st.traversal.leafCursor = gStateTexels[6].x;
    st.traversal.leafEnd = gStateTexels[6].y;
    st.traversal.closest = gStateTexels[6].z;
    st.traversal.stackTop = gStateTexels[6].w;
    st.traversal.barycentrics = uintBitsToFloat(gStateTexels[7].xy);
    st.samplesDone = gStateTexels[7].z;
    st.steps = gStateTexels[7].w;
    st.colour = ColourSum(gStateTexels[8].xyz, gStateTexels[9].xyz);
    st.phase = gStateTexels[8].w;
    st.pendingRays = gStateTexels[9].w;
    st.candidates.touchingObjects = gStateTexels[10];
    st.candidates.touchingT = uintBitsToFloat(gStateTexels[11]);
    st.candidates.contact = uintBitsToFloat(gStateTexels[12]);
    st.candidates.leaving = uintBitsToFloat(gStateTexels[13]);
    st.candidates.closestIsGlass = gStateTexels[14].x != 0u;
    st.traversal.closestInstance = gStateTexels[14].y;
    st.candidates.contactInstance = gStateTexels[14].z;
    st.candidates.leavingInstance = gStateTexels[14].w;
    st.traversal.instance = gStateTexels[15].w;
    vec4 position = uintBitsToFloat(gStateTexels[10]);
    st.hit.position = position.xyz;
    st.hit.t = position.w;
    st.hit.shadingNormal = uintBitsToFloat(gStateTexels[11].xyz);
    st.hit.material = gStateTexels[11].w;
    st.hit.geometricNormal = uintBitsToFloat(gStateTexels[12].xyz);
    st.hit.object = gStateTexels[12].w;
    st.touching = gStateTexels[13];
    vec4 carried = uintBitsToFloat(gStateTexels[14]);
    st.farthestTouching = carried.x;
    st.shadowLight = carried.yzw;
    st.hit.uv = uintBitsToFloat(gStateTexels[15].xy);
    st.light = gStateTexels[15].z;
}

// Whether the pixel is inside a BVH traversal that has a stack (begun and not fresh).
bool inTraversal() {
    return (st.phase == kPhaseTrace || st.phase == kPhaseShadow) && st.traversal.stackTop != kFreshTraversal;
}

// The resumable kernel: the pixel of `slot` started afresh or as the last dispatch suspended it;
// false when it is done.
bool resumeState(uint slot) {
    uint first = slot * kTraceStateTexels;
    float status = pixels[slot].w;
    if (status == kSlotDone) return false;
    bool suspended = status == kSlotSuspended;
    uint texels = suspended ? kTraceStateTexels : 0u;
    for (uint i = 0u; i < texels; ++i) gStateTexels[i] = stateTexels[first + i];
    if (suspended) unpackState();
    else startPixel();
    uint entries = suspended && inTraversal() ? st.traversal.stackTop : 0u;
    for (uint i = 0u; i < entries; ++i) gStack[i] = traversalStacks[slot * kTraversalStackSize + i];
    return true;
}

// The resumable kernel: keeps the state of an unfinished pixel in `slot` for the next dispatch
// (its pixel says it is suspended, slotPixel below).
void suspendState(uint slot, bool suspended) {
    uint first = slot * kTraceStateTexels;
    packState();
    uint texels = suspended ? kTraceStateTexels : 0u;
    for (uint i = 0u; i < texels; ++i) stateTexels[first + i] = gStateTexels[i];
    uint entries = suspended && inTraversal() ? st.traversal.stackTop : 0u;
    for (uint i = 0u; i < entries; ++i) traversalStacks[slot * kTraversalStackSize + i] = gStack[i];
}

// What a dispatch writes to the pixel of its slot: the colour of a finished pixel, or the status
// of one that is not.
vec4 slotPixel(bool done, vec3 colour) {
    if (done) return vec4(colour, kSlotDone);
    return vec4(0.0, 0.0, 0.0, kResumable ? kSlotSuspended : kSlotRestart);
}

#endif
