#version 460
// The driver's traversal, for bench/ray_query_bench.cpp: each invocation traces one ray of a list
// with a ray query (GL_EXT_ray_query, VK_KHR_ray_query) against the driver's own acceleration
// structure, and writes what it found: the counterpart of bench/trace_only/trace_rays.comp, which
// traces the same list with vitrum's traversal.
#extension GL_EXT_ray_query : require

layout(local_size_x = 64) in;

// The scene: one top-level structure, one identity instance of the triangles.
layout(set = 0, binding = 0) uniform accelerationStructureEXT scene;
// Two texels a ray, read as trace_rays.comp reads them (a storage texel buffer, which lavapipe
// reads with one gather: docs/gpu-design.md): (origin, tMin) and (direction, tMax), tMax negative
// for a shadow ray (any hit in (tMin, -tMax)).
layout(set = 0, binding = 1, rgba32ui) uniform readonly uimageBuffer rays;
// A ray's result: the committed hit's t, -1 for none, and its primitive (the triangle's index in
// the order the structure was built from; for a shadow ray, whichever hit ended its traversal).
struct Hit {
    float t;
    uint primitive;
};
layout(std430, set = 0, binding = 2) writeonly buffer Hits { Hit hits[]; };
layout(push_constant) uniform Control { uint rayCount; } control;

void main() {
    uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    if (i >= control.rayCount) return;
    vec4 origin = uintBitsToFloat(imageLoad(rays, int(2u * i)));
    vec4 direction = uintBitsToFloat(imageLoad(rays, int(2u * i + 1u)));
    bool anyHit = direction.w < 0.0;
    // Every triangle is opaque, so the query never stops at a candidate for the shader to confirm:
    // the loop runs once. A shadow ray only needs to know whether something blocks it.
    uint flags = gl_RayFlagsOpaqueEXT | (anyHit ? gl_RayFlagsTerminateOnFirstHitEXT : 0u);
    rayQueryEXT query;
    rayQueryInitializeEXT(query, scene, flags, 0xFFu, origin.xyz, origin.w, direction.xyz, abs(direction.w));
    while (rayQueryProceedEXT(query)) {
    }
    if (rayQueryGetIntersectionTypeEXT(query, true) == gl_RayQueryCommittedIntersectionTriangleEXT)
        hits[i] = Hit(rayQueryGetIntersectionTEXT(query, true), uint(rayQueryGetIntersectionPrimitiveIndexEXT(query, true)));
    else
        hits[i] = Hit(-1.0, 0u);
}
