#version 460
// Traversal alone with one ray a subgroup, for bench/whitted_bench.cpp: the subgroup's lanes
// test the children of one 8-wide node (each lane one child's box) or the triangles of one leaf
// (each lane one triangle), as a CPU tracer's SIMD lanes do for one ray (Embree's BVH8). The
// subgroup traces its lanes' rays one after another, so no lane waits on a ray that went another
// way: the lanes are busy however incoherent the rays are. Same rays, same results and same
// output as trace_rays.comp; the tree is bench/wide_bvh.h's.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_shuffle : require

#include "shared/gpu_types.h"

layout(local_size_x = 64) in;

// The wide nodes: kWideNodeTexels texels a node, two a child: (min.xyz, entry bits), (max.xyz, 0).
// An entry is a node index, or kLeafEntryFlag | first triangle << 4 | count as in TraversalNode;
// an empty child slot has an empty box and entry kNoEntry.
layout(set = 0, binding = 0, rgba32ui) uniform readonly uimageBuffer nodeTexels;
layout(set = 0, binding = 1, rgba32ui) uniform readonly uimageBuffer vertexTexels;
layout(set = 0, binding = 2, rgba32ui) uniform readonly uimageBuffer rayTexels;
layout(std430, set = 0, binding = 3) readonly buffer Control { uvec4 control; };
layout(std430, set = 0, binding = 4) writeonly buffer Hits { vec4 hits[]; };

#define fetchVec4(texels, first, k) uintBitsToFloat(imageLoad(texels, int((first) + (k))))

#include "ray_box.glsl"
#include "triangle_test.glsl"

const uint kWideChildren = 8u;
const uint kWideNodeTexels = 2u * kWideChildren;
const uint kNoEntry = 0xFFFFFFFFu;
const uint kStackSize = 64u;
// At most 8 subgroups in a workgroup of 64: the bench runs this kernel only where subgroups are
// full and at least kWideChildren lanes wide.
const uint kSubgroupsPerGroup = 8u;

// Each subgroup's stack: entries and the distances at which the ray enters their boxes.
shared uint stackEntry[kSubgroupsPerGroup * kStackSize];
shared float stackT[kSubgroupsPerGroup * kStackSize];

// The slab test of ray_box.glsl, returning the entry distance (or +inf on a miss).
float enterBox(vec3 boxMin, vec3 boxMax, BoxRay ray, float tMin, float tMax) {
    const float kFarScale = 1.00000036;
    vec3 t0 = (boxMin - ray.origin) * ray.inverseDirection;
    vec3 t1 = (boxMax - ray.origin) * ray.inverseDirection;
    vec3 tNear = mix(t0, t1, ray.negative);
    vec3 tFar = mix(t1, t0, ray.negative) * kFarScale;
    float enter = raiseTo(tNear.z, raiseTo(tNear.y, raiseTo(tNear.x, tMin)));
    float leave = lowerTo(tFar.z, lowerTo(tFar.y, lowerTo(tFar.x, tMax)));
    return enter <= leave ? enter : uintBitsToFloat(0x7F800000u);
}

void main() {
    const float kInfinity = uintBitsToFloat(0x7F800000u);
    uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    uint lane = gl_SubgroupInvocationID;
    uint base = gl_SubgroupID * kStackSize;
    uint ray = i < control.y ? i : 0u;
    vec4 myOrigin = fetchVec4(rayTexels, 2u * ray, 0u);
    vec4 myDirection = fetchVec4(rayTexels, 2u * ray, 1u);
    bool myTracing = i < control.y && myOrigin.w >= 0.0;
    float myT = -1.0;
    uint myTriangle = 0u;
    uint steps = 0u;
    bool overflowed = false;  // a stack overflow drops children: the host then refuses the results
    uvec4 tracing = subgroupBallot(myTracing);
    // The lanes' rays one after another: every value below is the same in all lanes but the
    // child or triangle each lane tests.
    for (uint r = 0u; r < gl_SubgroupSize; ++r) {
        if (!subgroupBallotBitExtract(tracing, r)) continue;
        vec4 o = subgroupShuffle(myOrigin, r);
        vec4 d = subgroupShuffle(myDirection, r);
        bool anyHit = d.w < 0.0;
        float tMin = o.w;
        float tMax = abs(d.w);
        BoxRay boxRay = makeBoxRay(o.xyz, d.xyz);
        TriangleRay triangleRay = makeTriangleRay(o.xyz, d.xyz);
        uint closest = kNoEntry;
        uint current = control.x;
        uint top = 0u;
        bool over = false;
        do {
            steps += 1u;
            if ((current & kLeafEntryFlag) == 0u) {
                // An interior node: lane c tests child c's box (lanes past the 8th none).
                uint first = kWideNodeTexels * current + 2u * min(lane, kWideChildren - 1u);
                vec4 low = fetchVec4(nodeTexels, first, 0u);
                vec4 high = fetchVec4(nodeTexels, first, 1u);
                uint entry = floatBitsToUint(low.w);
                float enter = lane < kWideChildren && entry != kNoEntry ? enterBox(low.xyz, high.xyz, boxRay, tMin, tMax) : kInfinity;
                bool hit = enter < kInfinity;
                uvec4 hits = subgroupBallot(hit);
                if (subgroupBallotBitCount(hits) != 0u) {
                    // The nearest child next; the others on the stack in lane order, each with the
                    // distance at which the ray enters it, so that a pop skips what begins beyond
                    // the closest hit (docs/gpu-design.md, "One ray a subgroup").
                    float nearest = subgroupMin(enter);
                    uint nearLane = subgroupBallotFindLSB(subgroupBallot(hit && enter == nearest));
                    bool push = hit && lane != nearLane;
                    uint slot = top + subgroupBallotExclusiveBitCount(subgroupBallot(push));
                    uint pushed = subgroupBallotBitCount(subgroupBallot(push));
                    if (push && slot < kStackSize) {
                        stackEntry[base + slot] = entry;
                        stackT[base + slot] = enter;
                    }
                    subgroupMemoryBarrierShared();
                    overflowed = overflowed || top + pushed > kStackSize;
                    top = min(top + pushed, kStackSize);
                    current = subgroupShuffle(entry, nearLane);
                    continue;
                }
            } else {
                // A leaf: lane k tests its k-th triangle.
                uint count = current & 15u;
                uint firstTriangle = (current & ~kLeafEntryFlag) >> 4u;
                float t = kInfinity;
                if (lane < count) {
                    uint v = kTriangleVerticesTexels * (firstTriangle + lane);
                    TriangleVertices tri = TriangleVertices(fetchVec4(vertexTexels, v, 0u),
                                                            fetchVec4(vertexTexels, v, 1u),
                                                            fetchVec4(vertexTexels, v, 2u));
                    vec3 h = intersectTriangle(tri, triangleRay);
                    if (h.x > tMin && h.x < tMax) t = h.x;
                }
                float best = subgroupMin(t);
                if (best < kInfinity) {
                    tMax = best;
                    closest = firstTriangle + subgroupBallotFindLSB(subgroupBallot(t == best));
                    if (anyHit) break;
                }
            }
            // The next entry off the stack whose box the ray enters before the closest hit.
            current = kNoEntry;
            while (top > 0u) {
                top -= 1u;
                if (stackT[base + top] < tMax) {
                    current = stackEntry[base + top];
                    break;
                }
            }
            over = current == kNoEntry;
        } while (!over);
        if (lane == r) {
            myT = closest != kNoEntry ? tMax : -1.0;
            myTriangle = closest;
        }
    }
    if (i >= control.y) return;
    hits[i] = vec4(myT, uintBitsToFloat(myTriangle), overflowed ? 0.0 : 1.0, float(steps));
}
