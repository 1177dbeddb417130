#version 460
// Test kernel for shaders/optics.glsl: one invocation evaluates every optics function for one
// OpticsCase (shared/optics_test_types.h) and writes one OpticsResult. No loops (lavapipe cuts
// loops silently), no logic beyond what the ray tracer itself does around these calls, so the
// tests see exactly what trace.comp gets.
#extension GL_GOOGLE_include_directive : require

#include "shared/gpu_types.h"
#include "optics_test_types.h"
#include "optics.glsl"

layout(local_size_x = kOpticsTestGroupSize) in;

layout(std430, binding = 0) readonly buffer Cases { OpticsCase cases[]; };
layout(std430, binding = 1) writeonly buffer Results { OpticsResult results[]; };

void main() {
    uint i = gl_GlobalInvocationID.x;
    // The last group may run past the end; both buffers hold exactly the cases.
    if (i >= uint(cases.length()) || i >= uint(results.length())) return;

    OpticsCase c = cases[i];
    vec3 d = c.direction.xyz;
    vec3 n = c.normal.xyz;
    float n1 = c.media.x;
    float n2 = c.media.y;
    float eta = n1 / n2;
    float cosI = -ieeeDot(d, n);

    OpticsResult r;
    r.reflected = vec4(reflectDirection(d, n), schlickF0(n1, n2));
    float cos2t = cosSquaredTransmitted(d, n, eta);
    // refractDirection is only defined without total internal reflection (optics.glsl).
    vec3 l = vec3(0.0);
    if (cos2t >= 0.0) l = refractDirection(d, n, eta, cos2t);
    r.refracted = vec4(l, cos2t);
    r.reflectance = vec4(fresnelReflectance(kFresnelSchlick, n1, n2, cosI, cos2t),
                         fresnelReflectance(kFresnelExact, n1, n2, cosI, cos2t),
                         fresnelReflectance(kFresnelSchlickExp2, n1, n2, cosI, cos2t), eta);
    r.beer = vec4(beerLambert(c.attenuation.xyz, c.media.z), 0.0);
    results[i] = r;
}
