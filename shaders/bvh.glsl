// Ray/triangle and ray/box tests and a resumable, one-node-per-step BVH traversal over the
// flattened nodes of shared/gpu_types.h. The traversal's state lives in the global `st` (see
// trace.comp) so that a dispatch can stop after any step and the next one resume it.
#ifndef VITRUM_BVH_GLSL
#define VITRUM_BVH_GLSL

const uint kNoTriangle = 0xFFFFFFFFu;

// Woop, Benthin and Wald, "Watertight Ray/Triangle Intersection" (JCGT 2013), without back-face
// culling; the same arithmetic in the same order as host/bvh/bvh_traversal.cpp, which says why it
// is watertight. Returns (t, u, v), u and v the barycentrics of v1 and v2, with t = -1 on a miss;
// both sides of the triangle are hit.
vec3 intersectTriangle(TriangleVertices tri, vec3 origin, vec3 direction) {
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
    float sx = d[kx] * sz;
    float sy = d[ky] * sz;
    vec3 a = tri.v0.xyz - origin;
    vec3 b = tri.v1.xyz - origin;
    vec3 c = tri.v2.xyz - origin;
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

// Slab test against (0, tMax) (Kay and Kajiya), as host/bvh/bvh_traversal.cpp does it: an axis
// whose slab distance is NaN (0 * inf: the ray runs in the plane of a face) does not constrain
// the segment, and the exit distance is widened by 1 + 2 gamma(3) so that rounding never culls a
// triangle lying on a face of the box (pbrt-v4, "Robust Ray-Bounds Intersections").
bool hitsBox(vec3 boxMin, vec3 boxMax, vec3 origin, vec3 inverseDirection, float tMax) {
    const float kFarScale = 1.00000036;
    vec3 t0 = (boxMin - origin) * inverseDirection;
    vec3 t1 = (boxMax - origin) * inverseDirection;
    bvec3 valid = bvec3(vec3(equal(t0, t0)) * vec3(equal(t1, t1)));
    vec3 tNear = mix(vec3(-3.0e38), min(t0, t1), valid);
    vec3 tFar = mix(vec3(3.0e38), max(t0, t1) * kFarScale, valid);
    float enter = max(max(tNear.x, tNear.y), max(tNear.z, 0.0));
    float leave = min(min(tFar.x, tFar.y), min(tFar.z, tMax));
    return enter <= leave;
}

const uint kTraverseClosest = 0u;  // the closest hit
const uint kTraverseAny = 1u;      // any hit (shadow rays)
const uint kTraverseTouching = 2u; // every glass surface of another object (see onTouchingHit)

// Starts a traversal of the ray origin + t direction, tMin < t < tMax.
void beginTraversal(vec3 origin, vec3 direction, float tMin, float tMax) {
    st.traceOrigin = vec4(origin, tMin);
    st.traceDirection = vec4(direction, tMax);
    st.stack[0] = 0u;
    st.control.w = 1u;
    st.traversal.xyz = uvec3(0u, 0u, kNoTriangle);
}

// One step of the traversal: one triangle test or one node visit. Returns true when it is over:
// the closest hit (or, for kTraverseAny, some hit) is in st.traversal.z, its t in
// st.traceDirection.w and its barycentrics in st.hitUv.zw. kTraverseTouching keeps tMax and hands
// every hit to onTouchingHit instead.
bool traversalStep(uint mode) {
    vec3 origin = st.traceOrigin.xyz;
    vec3 direction = st.traceDirection.xyz;
    if (st.traversal.x < st.traversal.y) {
        uint triangle = st.traversal.x;
        st.traversal.x += 1u;
        TriangleVertices tri = vertices[triangle];
        vec3 hit = intersectTriangle(tri, origin, direction);
        if (hit.x > st.traceOrigin.w && hit.x < st.traceDirection.w) {
            if (kTouchingProbe && mode == kTraverseTouching) {
                onTouchingHit(tri, hit.x);
                return false;
            }
            st.traceDirection.w = hit.x;
            st.traversal.z = triangle;
            st.hitUv.zw = hit.yz;
            if (kShadowRays && mode == kTraverseAny) return true;
        }
        return false;
    }
    if (st.control.w == 0u) return true;
    st.control.w -= 1u;
    uint nodeIndex = st.stack[st.control.w];
    BvhNode node = nodes[nodeIndex];
    gNodeVisits += 1u;
    if (!hitsBox(node.boundsMin.xyz, node.boundsMax.xyz, origin, 1.0 / direction, st.traceDirection.w)) return false;
    uint meta = floatBitsToUint(node.boundsMax.w);
    uint link = floatBitsToUint(node.boundsMin.w);
    if ((meta & kInteriorNodeFlag) == 0u) {
        st.traversal.x = link;
        st.traversal.y = link + meta;
        return false;
    }
    if (st.control.w + 2u > kTraversalStackSize) {
        gTraversalOverflows += 1u;
        return false;
    }
    // Visit the child on the ray's near side of the split first: push it last.
    bool negative = direction[meta & 3u] < 0.0;
    st.stack[st.control.w] = negative ? nodeIndex + 1u : link;
    st.stack[st.control.w + 1u] = negative ? link : nodeIndex + 1u;
    st.control.w += 2u;
    return false;
}

#endif
