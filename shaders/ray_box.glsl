// The ray/box test of trace.comp's traversal (bvh.glsl), on its own so that box_test.comp can run
// it on single cases.
#ifndef VITRUM_RAY_BOX_GLSL
#define VITRUM_RAY_BOX_GLSL

// What the box test needs of a ray, worked out once a traversal.
struct BoxRay {
    vec3 origin;
    vec3 inverseDirection;  // 1 / direction: +-inf where a component is +-0
    bvec3 negative;         // inverseDirection < 0: a slab's far plane is its lower one
};

BoxRay makeBoxRay(vec3 origin, vec3 direction) {
    vec3 inverseDirection = 1.0 / direction;
    return BoxRay(origin, inverseDirection, lessThan(inverseDirection, vec3(0.0)));
}

// max(distance, bound) and min(distance, bound) for a bound that is never NaN, as selects: a NaN
// distance fails the comparison and gives the bound. GLSL's max and min come with NaN fix-ups on
// lavapipe (docs/gpu-design.md, "What makes it fast on lavapipe").
float raiseTo(float distance, float bound) { return distance > bound ? distance : bound; }
float lowerTo(float distance, float bound) { return distance < bound ? distance : bound; }

// Slab test against (tMin, tMax) (Kay and Kajiya), with the result of host/bvh/bvh_traversal.cpp's test:
// an axis whose slab distance is NaN (0 * inf: the ray runs in the plane of a face) does not
// constrain the segment, and the exit distance is widened by 1 + 2 gamma(3) so that rounding never
// culls a triangle lying on a face of the box (pbrt-v4, "Robust Ray-Bounds Intersections").
// A slab's near plane follows from the direction's sign alone; an infinite inverse direction gives
// a NaN distance only on a plane through the origin, which drops out of the bound it is folded into.
bool hitsBox(vec3 boxMin, vec3 boxMax, BoxRay ray, float tMin, float tMax) {
    const float kFarScale = 1.00000036;
    vec3 t0 = (boxMin - ray.origin) * ray.inverseDirection;
    vec3 t1 = (boxMax - ray.origin) * ray.inverseDirection;
    vec3 tNear = mix(t0, t1, ray.negative);
    vec3 tFar = mix(t1, t0, ray.negative) * kFarScale;
    float enter = raiseTo(tNear.z, raiseTo(tNear.y, raiseTo(tNear.x, tMin)));
    float leave = lowerTo(tFar.z, lowerTo(tFar.y, lowerTo(tFar.x, tMax)));
    return enter <= leave;
}

#endif
