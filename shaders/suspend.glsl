// Pixels that need more than one dispatch (trace.comp's main).
//
// The first dispatch of a tile runs the kernel built without kResumable: a pixel that is not done
// within the step budget is given up, and its slot says so (kSlotRestart). Keeping a resumable
// state costs every pixel, also those that never suspend: on lavapipe the saved state is live,
// lane-masked, through the whole loop (measured: the first dispatch runs 5-15% faster
// without it). The host then dispatches the resumable kernel until the tile is done: it starts
// the given-up pixels afresh, and suspends and resumes them, their TraceState as
// kTraceStateTexels uvec4s in stateTexels[] and the used part of their BVH traversal stack in
// traversalStacks[].
//
// On lavapipe every storage-buffer access is a loop over the 8 lanes of a SIMD group that runs
// whether or not a lane is active, and code under a false condition runs too (masked). So each
// copy goes through a private array and one loop whose trip count is zero unless a lane of the
// group copies, not 16 accesses a texel apart.
#ifndef VITRUM_SUSPEND_GLSL
#define VITRUM_SUSPEND_GLSL

#include "trace_state.glsl"
#include "bvh.glsl"
#include "bindings.glsl"
#include "specialization.glsl"

uvec4 gStateTexels[kTraceStateTexels];

// A slot's status is its pixel's alpha (pixels[slot].w), written with the pixel by every
// dispatch that traces it: so the first dispatch writes nothing else of a slot, and touches no
// page of the state buffer. A fresh buffer's every first touch of a page is a page fault, about
// 10 us on the machines of docs/performance.md. The mark was once one word of the slot's 256
// bytes of state: a fault every 16 pixels, 13% of bubble's render at 640x480 (docs/gpu-design.md).
const float kSlotRestart = 0.0;    // given up by the first dispatch: start it again
const float kSlotDone = 1.0;       // finished, its colour in .xyz: later dispatches skip it
const float kSlotSuspended = 2.0;  // suspended by the resumable kernel: its state in stateTexels

void packState() {
    gStateTexels[0] = floatBitsToUint(st.ray.origin);
    gStateTexels[1] = floatBitsToUint(st.ray.direction);
    gStateTexels[2] = floatBitsToUint(st.ray.weight);
    gStateTexels[3] = st.ray.media;
    gStateTexels[4] = floatBitsToUint(st.traceOrigin);
    gStateTexels[5] = floatBitsToUint(st.traceDirection);
    gStateTexels[6] = floatBitsToUint(st.hitPosition);
    gStateTexels[7] = floatBitsToUint(st.hitNormal);
    gStateTexels[8] = floatBitsToUint(st.hitGeometricNormal);
    gStateTexels[9] = floatBitsToUint(st.hitUv);
    gStateTexels[10] = st.colourLow;
    gStateTexels[11] = st.colourHigh;
    gStateTexels[12] = st.control;
    gStateTexels[13] = st.traversal;
    gStateTexels[14] = st.touching;
    gStateTexels[15] = floatBitsToUint(st.probe);
}

void unpackState() {
    st.ray.origin = uintBitsToFloat(gStateTexels[0]);
    st.ray.direction = uintBitsToFloat(gStateTexels[1]);
    st.ray.weight = uintBitsToFloat(gStateTexels[2]);
    st.ray.media = gStateTexels[3];
    st.traceOrigin = uintBitsToFloat(gStateTexels[4]);
    st.traceDirection = uintBitsToFloat(gStateTexels[5]);
    st.hitPosition = uintBitsToFloat(gStateTexels[6]);
    st.hitNormal = uintBitsToFloat(gStateTexels[7]);
    st.hitGeometricNormal = uintBitsToFloat(gStateTexels[8]);
    st.hitUv = uintBitsToFloat(gStateTexels[9]);
    st.colourLow = gStateTexels[10];
    st.colourHigh = gStateTexels[11];
    st.control = gStateTexels[12];
    st.traversal = gStateTexels[13];
    st.touching = gStateTexels[14];
    st.probe = uintBitsToFloat(gStateTexels[15]);
}

// Whether the pixel is inside a BVH traversal that has a stack (begun and not fresh).
bool inTraversal() {
    uint phase = st.control.x;
    return (phase == kPhaseTrace || phase == kPhaseShadow) && st.control.w != kFreshTraversal;
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
    uint entries = suspended && inTraversal() ? st.control.w : 0u;
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
    uint entries = suspended && inTraversal() ? st.control.w : 0u;
    for (uint i = 0u; i < entries; ++i) traversalStacks[slot * kTraversalStackSize + i] = gStack[i];
}

// What a dispatch writes to the pixel of its slot: the colour of a finished pixel, or the status
// of one that is not.
vec4 slotPixel(bool done, vec3 colour) {
    if (done) return vec4(colour, kSlotDone);
    return vec4(0.0, 0.0, 0.0, kResumable ? kSlotSuspended : kSlotRestart);
}

#endif
