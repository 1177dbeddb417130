#version 460
// Traversal alone, for bench/whitted_bench.cpp: each invocation traces one ray of a list with
// vitrum's own traversal (shaders/bvh.glsl, as trace.comp runs it: closest hit, or any hit for a
// shadow ray) and writes what it found. No shading, no pixel state, no pending rays: what the
// trace pass of a wavefront renderer, one kernel a kind of work, would cost for the same rays.
#extension GL_GOOGLE_include_directive : require

#include "shared/gpu_types.h"

layout(local_size_x = 64) in;

// The scene as trace.comp reads it (shaders/bindings.glsl), and the rays: two texels a ray,
// (origin, tMin) and (direction, tMax), tMax negative for a shadow ray (any hit in (tMin, -tMax)),
// tMin negative for no ray (an idle lane).
layout(set = 0, binding = 0, rgba32ui) uniform readonly uimageBuffer nodeTexels;
layout(set = 0, binding = 1, rgba32ui) uniform readonly uimageBuffer vertexTexels;
layout(set = 0, binding = 2, rgba32ui) uniform readonly uimageBuffer rayTexels;
// .x = the root entry, .y = the rays.
layout(std430, set = 0, binding = 3) readonly buffer Control { uvec4 control; };
// A ray's result: .x = the hit's t, -1 for none; .y = the triangle (bits); .z = 1 when the
// traversal is over; .w = the group's steps.
layout(std430, set = 0, binding = 4) writeonly buffer Hits { vec4 hits[]; };

#include "geometry_texels.glsl"  // fetchVec4, loadTraversalNode, loadTriangle, as trace.comp reads them

// What bvh.glsl reads of trace.comp: the features (a shadow ray ends at its first hit; no
// touching probe, no glass on opaque surfaces and no coincident opaque ones; full subgroups,
// which the bench asks for when it creates the pipeline; a traversal that is never resumed), the
// parameters. The traversal's state and counters are bvh.glsl's own (trace_state.glsl, counters.glsl).
const bool kShadowRays = true;
const bool kTouchingProbe = false;
const bool kOpaqueContact = false;
const bool kCoincidentOpaque = false;
const bool kInstancing = false;
const bool kResumable = false;
const bool kFullSubgroups = true;
// The benchmark's scenes have no cut-out or partly covered surfaces (shaders/cutout.glsl,
// shading.glsl's coverSurface).
const bool kCutouts = false;
const bool kPartialCoverage = false;
bool cutAway(uint triangle, uint mark, vec2 barycentrics) { return false; }
RenderParams params;
#include "render_params.glsl"

#include "bvh.glsl"

void main() {
    uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    uint ray = i < control.y ? i : 0u;
    params.bvh = uvec4(control.x, 0u, 0u, 0u);
    params.surfaceChecks = uvec4(0u);
    params.thresholds = vec4(0.0);
    vec4 origin = fetchVec4(rayTexels, 2u * ray, 0u);
    vec4 direction = fetchVec4(rayTexels, 2u * ray, 1u);
    bool tracing = i < control.y && origin.w >= 0.0;
    bool anyHit = direction.w < 0.0;
    beginTraversal(origin.xyz, direction.xyz, origin.w, abs(direction.w));
    // Every lane of the subgroup calls traverse (its group maxima read every lane); lavapipe's
    // limit of 65,535 iterations a SIMD group is far above one ray's steps, and the host checks
    // that every traversal is over.
    uint steps = 0u;
    bool over = traverse(anyHit ? kTraverseAny : kTraverseClosest, tracing, steps, 60000u);
    if (i >= control.y) return;
    if (!tracing) {
        hits[i] = vec4(-1.0, 0.0, 1.0, float(steps));
        return;
    }
    bool found = st.traversal.closest != kNoTriangle;
    hits[i] = vec4(found ? st.traversal.tMax : -1.0, uintBitsToFloat(st.traversal.closest), over ? 1.0 : 0.0, float(steps));
}
