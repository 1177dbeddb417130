// Reflection, refraction and Fresnel, as the lecture derives them
// (../shared/seed/dielectrics-lecture.txt, "Dielectric Transparent Materials").
// `d` is the unit incoming direction, `n` the unit normal facing the incoming ray (d.n <= 0),
// `eta` = n1 / n2. The CPU reference has its own copy in host/cpu/optics.h; tests hold both to
// the lecture's worked example.
#ifndef VITRUM_OPTICS_GLSL
#define VITRUM_OPTICS_GLSL

#include "ieee_vector_math.glsl"
#include "shared/gpu_types.h"

// r = d - 2 (d.n) n  (lecture: law of reflection)
vec3 reflectDirection(vec3 d, vec3 n) { return d - 2.0 * ieeeDot(d, n) * n; }

// 1 - eta^2 (1 - (d.n)^2) = cos^2(theta_2); negative means total internal reflection.
float cosSquaredTransmitted(vec3 d, vec3 n, float eta) {
    float dn = ieeeDot(d, n);
    return 1.0 - eta * eta * (1.0 - dn * dn);
}

// The lecture's final formula l = eta d - (eta (d.n) + sqrt(1 - eta^2 (1 - (d.n)^2))) n.
// It never divides by sin(theta_1), so normal incidence is fine. Call only when
// cosSquaredTransmitted(...) >= 0.
vec3 refractDirection(vec3 d, vec3 n, float eta, float cos2t) {
    float dn = ieeeDot(d, n);
    return eta * d - (eta * dn + sqrt(cos2t)) * n;
}

// Exact Fresnel for unpolarised light: R = (Rs + Rp) / 2 (lecture: "Amount of Refraction and
// Reflection"). cosI = cos(theta_1) >= 0, cosT = cos(theta_2) >= 0.
float fresnelExact(float n1, float n2, float cosI, float cosT) {
    float rs = (n2 * cosT - n1 * cosI) / (n2 * cosT + n1 * cosI);
    float rp = (n2 * cosI - n1 * cosT) / (n2 * cosI + n1 * cosT);
    return 0.5 * (rs * rs + rp * rp);
}

float schlickF0(float n1, float n2) {
    float r = (n1 - n2) / (n1 + n2);
    return r * r;
}

// Schlick: R = F0 + (1 - F0)(1 - cos theta)^5 with theta = theta_i if n1 <= n2 else theta_t.
float fresnelSchlick(float n1, float n2, float cosI, float cosT) {
    float c = 1.0 - (n1 <= n2 ? cosI : cosT);
    float c2 = c * c;
    float f0 = schlickF0(n1, n2);
    return f0 + (1.0 - f0) * (c2 * c2 * c);
}

// The lecture's alternative: R = F0 + (1 - F0) 2^((-5.55473 cos - 6.98316) cos).
float fresnelSchlickExp2(float n1, float n2, float cosI, float cosT) {
    float c = n1 <= n2 ? cosI : cosT;
    float f0 = schlickF0(n1, n2);
    return f0 + (1.0 - f0) * exp2((-5.55473 * c - 6.98316) * c);
}

// R for the given model; 1 at total internal reflection (cos2t < 0), 0 at an index-matched
// interface (render model: there is no optical interface).
float fresnelReflectance(uint model, float n1, float n2, float cosI, float cos2t) {
    if (cos2t < 0.0) return 1.0;
    if (n1 == n2) return 0.0;
    float cosT = sqrt(cos2t);
    if (model == kFresnelExact) return fresnelExact(n1, n2, cosI, cosT);
    if (model == kFresnelSchlickExp2) return fresnelSchlickExp2(n1, n2, cosI, cosT);
    return fresnelSchlick(n1, n2, cosI, cosT);
}

// A thin pane's reflectance and transmittance from one face's R (render-model-decisions.md,
// "Thin-walled glass"; pbrt-v4, ThinDielectricBxDF): (2R / (1 + R), (1 - R) / (1 + R)).
vec2 thinPane(float r) { return vec2(2.0 * r / (1.0 + r), (1.0 - r) / (1.0 + r)); }

// Beer-Lambert transmittance over a segment of length t in a medium of attenuation mu.
vec3 beerLambert(vec3 mu, float t) { return exp(-mu * t); }

#endif
