// The ray/triangle test of both GPU kernels: trace.comp (through bvh.glsl) and the plain baseline
// of bench/baseline, so that the benchmark compares traversals, not triangle tests. Needs
// TriangleVertices from shared/gpu_types.h.
#ifndef VITRUM_TRIANGLE_TEST_GLSL
#define VITRUM_TRIANGLE_TEST_GLSL

#include "ieee_vector_math.glsl"
#include "shared/gpu_types.h"

// Woop, Benthin and Wald, "Watertight Ray/Triangle Intersection" (JCGT 2013), without back-face
// culling; the same arithmetic in the same order as host/bvh/bvh_traversal.cpp, which says why it
// is watertight. What depends on the ray alone is worked out once a ray, as the paper does
// (makeTriangleRay): the same values as working it out for every triangle.
struct TriangleRay {
    vec3 origin;
    ivec3 axes;   // kx, ky, kz: kz the axis where |d| is largest, kx and ky following it
    vec3 shear;   // sx = d[kx] / d[kz], sy = d[ky] / d[kz], sz = 1 / d[kz]
};

TriangleRay makeTriangleRay(vec3 origin, vec3 direction) {
    vec3 d = direction;
    int kz = 0;
    if (abs(d.y) > abs(d[kz])) kz = 1;
    if (abs(d.z) > abs(d[kz])) kz = 2;
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
    if (d[kz] < 0.0) {
        int swapped = kx;
        kx = ky;
        ky = swapped;
    }
    float sz = 1.0 / d[kz];
    return TriangleRay(origin, ivec3(kx, ky, kz), vec3(d[kx] * sz, d[ky] * sz, sz));
}

// The triangle's normal as its corners wind (not unit length): a ray along d meets the triangle
// from the front where dot(d, n) < 0. The CPU reference's windingNormal has the same operations.
vec3 windingNormal(TriangleVertices tri) { return ieeeCross(tri.v1.xyz - tri.v0.xyz, tri.v2.xyz - tri.v0.xyz); }

// Returns (t, u, v), u and v the barycentrics of v1 and v2, with t = -1 on a miss; both sides of
// the triangle are hit.
vec3 intersectTriangle(TriangleVertices tri, TriangleRay ray) {
    int kx = ray.axes.x, ky = ray.axes.y, kz = ray.axes.z;
    float sx = ray.shear.x, sy = ray.shear.y, sz = ray.shear.z;
    vec3 a = tri.v0.xyz - ray.origin;
    vec3 b = tri.v1.xyz - ray.origin;
    vec3 c = tri.v2.xyz - ray.origin;
    float ax = a[kx] - sx * a[kz];
    float ay = a[ky] - sy * a[kz];
    float bx = b[kx] - sx * b[kz];
    float by = b[ky] - sy * b[kz];
    float cx = c[kx] - sx * c[kz];
    float cy = c[ky] - sy * c[kz];
    float u0 = cx * by - cy * bx;
    float u1 = ax * cy - ay * cx;
    float u2 = bx * ay - by * ax;
    if ((u0 < 0.0 || u1 < 0.0 || u2 < 0.0) && (u0 > 0.0 || u1 > 0.0 || u2 > 0.0)) return vec3(-1.0);
    float det = u0 + u1 + u2;
    if (det == 0.0) return vec3(-1.0);
    float scaledT = u0 * (sz * a[kz]) + u1 * (sz * b[kz]) + u2 * (sz * c[kz]);
    float invDet = 1.0 / det;
    return vec3(scaledT * invDet, u1 * invDet, u2 * invDet);
}

#endif
