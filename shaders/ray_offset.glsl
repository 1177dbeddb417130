// Offsetting a new ray's origin off the surface it starts on: Waechter and Binder, "A Fast and
// Robust Method for Avoiding Self-Intersection", Ray Tracing Gems, ch. 6. `n` is the geometric
// normal on the side the new ray leaves towards. The chapter's absolute constants (origin region
// 1/32, offset 1/65536 there) are scaled to the scene by the host (host/render_model/ray_offset.h,
// rayOffsetScale, says why): offsetRegion and offsetDistance of shared/render_params.h.
#ifndef VITRUM_RAY_OFFSET_GLSL
#define VITRUM_RAY_OFFSET_GLSL

#include "bindings.glsl"

float offsetComponent(float p, float n) {
    float originRegion = offsetRegion();
    float absoluteOffset = offsetDistance();
    const float kIntScale = 32.0;
    int offsetInt = int(kIntScale * n);
    float pInt = intBitsToFloat(floatBitsToInt(p) + (p < 0.0 ? -offsetInt : offsetInt));
    return abs(p) < originRegion ? p + absoluteOffset * n : pInt;
}

vec3 offsetRayOrigin(vec3 p, vec3 n) {
    return vec3(offsetComponent(p.x, n.x), offsetComponent(p.y, n.y), offsetComponent(p.z, n.z));
}

#endif
