// Offsetting a new ray's origin off the surface it starts on: Waechter and Binder, "A Fast and
// Robust Method for Avoiding Self-Intersection", Ray Tracing Gems, ch. 6. `n` is the geometric
// normal on the side the new ray leaves towards.
#ifndef VITRUM_RAY_OFFSET_GLSL
#define VITRUM_RAY_OFFSET_GLSL

float offsetComponent(float p, float n) {
    const float kOrigin = 1.0 / 32.0;
    const float kFloatScale = 1.0 / 65536.0;
    const float kIntScale = 256.0;
    int offsetInt = int(kIntScale * n);
    float pInt = intBitsToFloat(floatBitsToInt(p) + (p < 0.0 ? -offsetInt : offsetInt));
    return abs(p) < kOrigin ? p + kFloatScale * n : pInt;
}

vec3 offsetRayOrigin(vec3 p, vec3 n) {
    return vec3(offsetComponent(p.x, n.x), offsetComponent(p.y, n.y), offsetComponent(p.z, n.z));
}

#endif
