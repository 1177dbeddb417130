#version 460
// Test kernel for shaders/touching.glsl: one invocation feeds one TouchingCase's crossings to
// addTouchingCandidate, starting from the empty slots trace.comp starts every closest-hit
// traversal with, and writes selectTouching's verdict as one TouchingResult.
#extension GL_GOOGLE_include_directive : require

#include "shared/gpu_types.h"
#include "touching_test_types.h"

#include "touching.glsl"

layout(local_size_x = kTouchingTestGroupSize) in;

layout(std430, binding = 0) readonly buffer Cases { TouchingCase cases[]; };
layout(std430, binding = 1) writeonly buffer Results { TouchingResult results[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    // The last group may run past the end; both buffers hold exactly the cases.
    if (i >= uint(cases.length()) || i >= uint(results.length())) return;

    TouchingCase c = cases[i];
    uvec4 objects = uvec4(0u);
    vec4 ts = vec4(kNoCandidate);
    uint dropped = 0u;
    for (uint k = 0u; k < min(c.control.x, kTouchingTestCrossings); ++k) {
        uint tagged = k < 4u ? c.objects0[k] : c.objects1[k - 4u];
        float t = k < 4u ? c.t0[k] : c.t1[k - 4u];
        float limit = k < 4u ? c.limit0[k] : c.limit1[k - 4u];
        addTouchingCandidate(objects, ts, tagged & 0x7FFFFFFFu, (tagged & 0x80000000u) != 0u, t, limit, dropped);
    }
    float farthest = c.hit.y;
    TouchingResult r;
    r.touching = selectTouching(objects, ts, c.hit.x, c.control.y, farthest);
    r.farthest = vec4(farthest, 0.0, 0.0, 0.0);
    r.counts = uvec4(dropped, 0u, 0u, 0u);
    results[i] = r;
}
