// The baseline of docs/performance.md: primary rays traced the textbook GPU way. One ray per
// invocation, a binary BVH in the layout of Aila and Laine ("Understanding the Efficiency of Ray
// Traversal on GPUs", HPG 2009: each node holds both children's boxes, so a visit tests two boxes
// and pushes the far child), a per-invocation stack, and the watertight ray/triangle test vitrum
// itself uses. It writes the hit distance and triangle: no shading, no secondary rays.
//
// PLAIN_TEXEL_BUFFERS: the same kernel reading nodes and triangles through uniform texel buffers
// (usamplerBuffer) instead of storage buffers.

#include "../../shaders/shared/gpu_types.h"     // TriangleVertices
#include "../../shaders/triangle_test.glsl"     // the watertight test vitrum uses

layout(local_size_x = 8, local_size_y = 8) in;

// Node: the boxes of children 0 and 1 and their links. A link >= 0 is an inner node's index; a
// leaf is ~firstTriangle with its triangle count in counts.
struct PlainNode {
    vec4 lo0;      // xyz: child 0 box min
    vec4 hi0;      // xyz: child 0 box max
    vec4 lo1;
    vec4 hi1;
    ivec4 links;   // x: child 0, y: child 1, z: child 0 count, w: child 1 count (leaves)
};
struct Camera {
    vec4 origin;      // xyz; w: image width (float)
    vec4 lowerLeft;   // xyz: direction to the top-left pixel's corner; w: image height
    vec4 right;       // xyz: one pixel to the right
    vec4 down;        // xyz: one pixel down
    ivec4 rootLeaf;   // x: 1 when the whole tree is one leaf, y: its triangle count
};

#ifdef PLAIN_TEXEL_BUFFERS
layout(binding = 0) uniform usamplerBuffer nodeTexels;      // 5 texels a PlainNode
layout(binding = 1) uniform usamplerBuffer triangleTexels;  // 3 texels a TriangleVertices
PlainNode loadNode(int i) {
    PlainNode n;
    n.lo0 = uintBitsToFloat(texelFetch(nodeTexels, 5 * i));
    n.hi0 = uintBitsToFloat(texelFetch(nodeTexels, 5 * i + 1));
    n.lo1 = uintBitsToFloat(texelFetch(nodeTexels, 5 * i + 2));
    n.hi1 = uintBitsToFloat(texelFetch(nodeTexels, 5 * i + 3));
    n.links = ivec4(texelFetch(nodeTexels, 5 * i + 4));
    return n;
}
TriangleVertices loadTriangle(int i) {
    TriangleVertices t;
    t.v0 = uintBitsToFloat(texelFetch(triangleTexels, 3 * i));
    t.v1 = uintBitsToFloat(texelFetch(triangleTexels, 3 * i + 1));
    t.v2 = uintBitsToFloat(texelFetch(triangleTexels, 3 * i + 2));
    return t;
}
#else
layout(std430, binding = 0) readonly buffer Nodes { PlainNode nodes[]; };
layout(std430, binding = 1) readonly buffer Triangles { TriangleVertices triangles[]; };
PlainNode loadNode(int i) { return nodes[i]; }
TriangleVertices loadTriangle(int i) { return triangles[i]; }
#endif
layout(std430, binding = 2) readonly buffer Cameras { Camera camera; };
layout(std430, binding = 3) writeonly buffer Hits { vec2 hits[]; };  // x: t (-1 on a miss), y: triangle bits

// Entry distance of the ray into the box, or 1e30 when it misses it before tMax.
float boxEntry(vec3 lo, vec3 hi, vec3 originTimesInverse, vec3 inverse, float tMax) {
    vec3 t0 = lo * inverse - originTimesInverse;
    vec3 t1 = hi * inverse - originTimesInverse;
    vec3 near = min(t0, t1), far = max(t0, t1);
    float enter = max(max(near.x, near.y), max(near.z, 0.0));
    float leave = min(min(far.x, far.y), min(far.z, tMax));
    return enter <= leave ? enter : 1e30;
}

void main() {
    uvec2 pixel = gl_GlobalInvocationID.xy;
    uint width = uint(camera.origin.w), height = uint(camera.lowerLeft.w);
    if (pixel.x >= width || pixel.y >= height) return;
    vec3 origin = camera.origin.xyz;
    vec3 direction = normalize(camera.lowerLeft.xyz + (float(pixel.x) + 0.5) * camera.right.xyz +
                               (float(pixel.y) + 0.5) * camera.down.xyz);
    vec3 inverse = 1.0 / direction;
    vec3 originTimesInverse = origin * inverse;
    TriangleRay triangleRay = makeTriangleRay(origin, direction);  // the paper's per-ray setup
    float tHit = 3.0e38;
    int hitTriangle = -1;

    int stack[64];
    int top = 0;
    int leafFirst = 0, leafCount = 0;
    int node = 0;
    if (camera.rootLeaf.x != 0) {
        leafCount = camera.rootLeaf.y;
        node = -1;
    }
    while (node >= 0 || leafCount > 0) {
        // Inner nodes: test both children, go to the nearer, push the farther.
        while (node >= 0) {
            PlainNode n = loadNode(node);
            float e0 = boxEntry(n.lo0.xyz, n.hi0.xyz, originTimesInverse, inverse, tHit);
            float e1 = boxEntry(n.lo1.xyz, n.hi1.xyz, originTimesInverse, inverse, tHit);
            bool hit0 = e0 < 1e30, hit1 = e1 < 1e30;
            int next = -1, far = -1, nextCount = 0, farCount = 0;
            if (hit0 && hit1) {
                bool swap = e1 < e0;
                next = swap ? n.links.y : n.links.x;
                nextCount = swap ? n.links.w : n.links.z;
                far = swap ? n.links.x : n.links.y;
                farCount = swap ? n.links.z : n.links.w;
                stack[top++] = far;
                stack[top++] = farCount;
            } else if (hit0 || hit1) {
                next = hit0 ? n.links.x : n.links.y;
                nextCount = hit0 ? n.links.z : n.links.w;
            } else {
                if (top == 0) {
                    node = -1;
                    break;
                }
                nextCount = stack[--top];
                next = stack[--top];
            }
            if (next < 0) {  // a leaf: test its triangles, then go on from the stack
                leafFirst = ~next;
                leafCount = nextCount;
                node = -1;
            } else {
                node = next;
            }
        }
        for (int i = 0; i < leafCount; ++i) {
            vec3 h = intersectTriangle(loadTriangle(leafFirst + i), triangleRay);
            if (h.x > 0.0 && h.x < tHit) {
                tHit = h.x;
                hitTriangle = leafFirst + i;
            }
        }
        leafCount = 0;
        // Next from the stack: an inner node or another leaf.
        while (top > 0 && node < 0 && leafCount == 0) {
            int count = stack[--top];
            int link = stack[--top];
            if (link >= 0) node = link;
            else {
                leafFirst = ~link;
                leafCount = count;
            }
        }
    }
    hits[pixel.y * width + pixel.x] = vec2(hitTriangle < 0 ? -1.0 : tHit, intBitsToFloat(hitTriangle));
}
