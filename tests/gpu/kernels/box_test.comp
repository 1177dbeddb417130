#version 460
// Test kernel for shaders/ray_box.glsl: one invocation runs hitsBox for one BoxCase, with the
// ray made as bvh.glsl's traverse makes it.
#extension GL_GOOGLE_include_directive : require

#include "shared/gpu_types.h"
#include "box_test_types.h"
#include "ray_box.glsl"

layout(local_size_x = kBoxTestGroupSize) in;

layout(std430, binding = 0) readonly buffer Cases { BoxCase cases[]; };
layout(std430, binding = 1) writeonly buffer Results { BoxResult results[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    // The last group may run past the end; both buffers hold exactly the cases.
    if (i >= uint(cases.length()) || i >= uint(results.length())) return;
    BoxCase c = cases[i];
    bool hit = hitsBox(c.boxMin.xyz, c.boxMax.xyz, makeBoxRay(c.origin.xyz, c.direction.xyz), c.boxMin.w, c.boxMax.w);
    results[i].hit = uvec4(hit ? 1u : 0u, 0u, 0u, 0u);
}
