// The state of the pixel an invocation traces: its ray tree's current ray, hit and phase
// (shared/gpu_types.h's TraceState). The resumable kernel keeps it between dispatches (suspend.glsl).
#ifndef VITRUM_TRACE_STATE_GLSL
#define VITRUM_TRACE_STATE_GLSL

#include "shared/gpu_types.h"

// The whole state of this pixel.
TraceState st;

const uint kPhaseStartSample = 0u;  // make the next primary ray, or finish the pixel
const uint kPhaseTrace = 1u;        // closest-hit traversal of st.ray
const uint kPhaseNextLight = 2u;    // direct light from light st.control.z, or go on to scatter
const uint kPhaseShadow = 3u;       // any-hit traversal towards light st.control.z
const uint kPhaseScatter = 4u;      // spawn reflected / refracted rays
const uint kPhaseNextRay = 5u;      // pop a pending ray, or finish the sample
const uint kPhaseDone = 6u;

uint rayDepth(PendingRay r) { return floatBitsToUint(r.origin.w); }
uint mediaCount(PendingRay r) { return floatBitsToUint(r.direction.w); }
uint hitMaterial() { return floatBitsToUint(st.hitNormal.w); }
uint hitObject() { return floatBitsToUint(st.hitGeometricNormal.w); }
uint materialModel(GpuMaterial m) { return floatBitsToUint(m.ambient.w); }

#endif
