// The ray/box test of trace.comp's traversal (bvh.glsl), on its own so that box_test.comp can run
// it on single cases.
#ifndef VITRUM_RAY_BOX_GLSL
#define VITRUM_RAY_BOX_GLSL

// The larger and the smaller of two numbers that are never NaN, as selects: GLSL's max and min
// come with NaN fix-ups on lavapipe: 7-9% of a render's time (docs/gpu-design.md).
float larger(float a, float b) { return a > b ? a : b; }
float smaller(float a, float b) { return a < b ? a : b; }

// Slab test against (tMin, tMax) (Kay and Kajiya), as host/bvh/bvh_traversal.cpp does it: an axis
// whose slab distance is NaN (0 * inf: the ray runs in the plane of a face) does not constrain
// the segment, and the exit distance is widened by 1 + 2 gamma(3) so that rounding never culls a
// triangle lying on a face of the box (pbrt-v4, "Robust Ray-Bounds Intersections").
bool hitsBox(vec3 boxMin, vec3 boxMax, vec3 origin, vec3 inverseDirection, float tMin, float tMax) {
    const float kFarScale = 1.00000036;
    vec3 t0 = (boxMin - origin) * inverseDirection;
    vec3 t1 = (boxMax - origin) * inverseDirection;
    bvec3 valid = bvec3(vec3(equal(t0, t0)) * vec3(equal(t1, t1)));
    bvec3 t0Nearer = lessThan(t0, t1);  // a NaN axis is replaced below, whichever it picks
    vec3 tNear = mix(vec3(-3.0e38), mix(t1, t0, t0Nearer), valid);
    vec3 tFar = mix(vec3(3.0e38), mix(t0, t1, t0Nearer) * kFarScale, valid);
    float enter = larger(larger(tNear.x, tNear.y), larger(tNear.z, tMin));
    float leave = smaller(smaller(tFar.x, tFar.y), smaller(tFar.z, tMax));
    return enter <= leave;
}

#endif
