// What a ray that leaves the scene sees: a constant colour, a spherical (equirectangular) map or
// a cube map, with the conventions of ../shared/docs/render-model.md ("Background"); the same steps as
// host/cpu/texture_sampling.h.
#ifndef VITRUM_BACKGROUND_GLSL
#define VITRUM_BACKGROUND_GLSL

#include "bindings.glsl"
#include "specialization.glsl"
#include "texture.glsl"

const float kPi = 3.14159265358979;

// theta = acos(z), phi = atan2(y, x) + pi, u = 1 - phi / (2 pi), v = theta / pi.
vec2 sphericalUv(vec3 d) {
    float theta = acos(clamp(d.z, -1.0, 1.0));
    float phi = atan(d.y, d.x) + kPi;
    return vec2(1.0 - phi / (2.0 * kPi), theta / kPi);
}

// The face of the largest absolute component (ties: x, then y, then z) in .x (0..5 for +x, -x,
// +y, -y, +z, -z) and its (u, v) in .yz.
vec3 cubeUv(vec3 d) {
    vec3 a = abs(d);
    float face;
    float m;
    float au;
    float av;
    if (a.x >= a.y && a.x >= a.z) {
        m = a.x;
        face = d.x > 0.0 ? 0.0 : 1.0;
        au = d.x > 0.0 ? -d.y : d.y;
        av = -d.z;
    } else if (a.y >= a.z) {
        m = a.y;
        face = d.y > 0.0 ? 2.0 : 3.0;
        au = d.y > 0.0 ? d.x : -d.x;
        av = -d.z;
    } else {
        m = a.z;
        face = d.z > 0.0 ? 4.0 : 5.0;
        au = d.x;
        av = d.z > 0.0 ? d.y : -d.y;
    }
    return vec3(face, (au / m + 1.0) / 2.0, (av / m + 1.0) / 2.0);
}

vec3 backgroundRadiance(vec3 d) {
    uint kind = backgroundKind();
    if (kind == kBackgroundSpherical) return sampleTexture(backgroundTexture(), sphericalUv(d), true, false);
    if (kind == kBackgroundCube) {
        vec3 c = cubeUv(d);
        return sampleTexture(backgroundTexture() + uint(c.x), c.yz, false, false);
    }
    return backgroundColour();
}

#endif
