// dot, cross, length, normalize and mix written out in the operations and the order in which GLM,
// and so the CPU reference, computes them: a driver may evaluate GLSL's built-ins as it likes,
// while a single multiply or add is an IEEE operation that no kernel may fuse with another
// (host/gpu/spirv_float_semantics.h). So a ray that grazes an edge takes the same branch on both
// backends; a square root and a division may still round differently where Vulkan allows it
// (docs/gpu-design.md, "Arithmetic as the CPU does it").
#ifndef VITRUM_IEEE_VECTOR_MATH_GLSL
#define VITRUM_IEEE_VECTOR_MATH_GLSL

float ieeeDot(vec3 a, vec3 b) {
    vec3 p = a * b;
    return p.x + p.y + p.z;
}

vec3 ieeeCross(vec3 a, vec3 b) {
    return vec3(a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y);
}

float ieeeLength(vec3 v) { return sqrt(ieeeDot(v, v)); }

vec3 ieeeNormalize(vec3 v) { return v * (1.0 / sqrt(ieeeDot(v, v))); }

vec3 ieeeMix(vec3 x, vec3 y, float a) { return x * (1.0 - a) + y * a; }

#endif
