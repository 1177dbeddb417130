// A pixel's pending rays: refractions that wait while their reflection is traced first
// (shading.glsl's scatter), in the pendingRays buffer.
#ifndef VITRUM_PENDING_RAYS_GLSL
#define VITRUM_PENDING_RAYS_GLSL

#include "trace_state.glsl"
#include "bindings.glsl"
#include "specialization.glsl"

// This pixel's pending rays: entries 0 .. kPendingRayCapacity - 1 of its place in pendingRays
// (pendingRayIndex), the ones waiting from gBottom up to st.pendingRays; below gBottom, those that
// other lanes took (ray_sharing.glsl).
uint gBottom = 0u;

// Where entry `entry` of this pixel's pending rays is: entry-major, so that the deeper entries,
// which few pixels reach, lie together. In the first dispatch they are the invocation's, needed
// only while it traces a unit (a pixel it gives up starts again from nothing), so the persistent
// kernel touches 8 times fewer pages; the resumable kernel keeps them by slot, across dispatches
// (docs/gpu-design.md, "Page faults").
uint gPendingPlace = 0u;
uint gPendingStride = 0u;
uint pendingRayIndex(uint entry) { return entry * gPendingStride + gPendingPlace; }

void placePendingRays(uint slot) {
    if (kResumable) {
        gPendingPlace = slot;
        gPendingStride = tileWidth() * tileHeight();
    } else {
        uint invocations = gl_WorkGroupSize.x * gl_WorkGroupSize.y;
        uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
        gPendingPlace = group * invocations + gl_LocalInvocationIndex;
        gPendingStride = gl_NumWorkGroups.x * gl_NumWorkGroups.y * invocations;
    }
}

// The pending ray read this round, at its one load site (traceUnit's loop, after shading; a lane that
// gives a ray to another reads it there too): on lavapipe every storage-buffer load site is a
// loop over the lanes each round, whether a lane loads or not.
uint gLoadIndex = 0u;
bool gLoad = false;

// A pending ray in the buffer. On lavapipe each member moved is a loop over the lanes, so with a
// medium stack of one the ray's medium travels in its weight's unused .w (a child's weight.w is
// 0, and media beyond the first are 0): three members, not four (docs/gpu-design.md, "Three
// members a pending ray with a medium stack of one). Not where some surface is partly there:
// there a ray going on through one carries its window in weight.w (shading.glsl's coverSurface).
void storePendingRay(uint index, PendingRay r) {
    if (kMediumStackDepth > 1u || kPartialCoverage) {
        pendingRays[index] = r;
        return;
    }
    pendingRays[index].origin = r.origin;
    pendingRays[index].direction = r.direction;
    pendingRays[index].weight = vec4(r.weight.xyz, uintBitsToFloat(r.media.x));
}

PendingRay readPendingRay(uint index) {
    if (kMediumStackDepth > 1u || kPartialCoverage) return pendingRays[index];
    PendingRay r;
    r.origin = pendingRays[index].origin;
    r.direction = pendingRays[index].direction;
    vec4 weight = pendingRays[index].weight;
    r.weight = vec4(weight.xyz, 0.0);
    r.media = uvec4(floatBitsToUint(weight.w), 0u, 0u, 0u);
    return r;
}

// The pending ray at `index` goes on as st.ray: read at the round's end (traceUnit).
void loadPendingRay(uint index) {
    gLoadIndex = index;
    gLoad = true;
    st.phase = kPhaseTrace;  // beginRay, once the ray is read, begins its traversal
}

// A unit's pixel starts with no pending rays and none to read.
void resetPendingRays() {
    gBottom = 0u;
    gLoadIndex = 0u;
    gLoad = false;
}

#endif
