// dot, cross, length, normalize and mix written out in the operations and the order in which GLM,
// and so the CPU reference, computes them. A driver may evaluate GLSL's built-ins as it likes
// (NVIDIA's dot rounds as if fused), while a single multiply or add is an IEEE operation that no
// kernel may fuse with another (host/gpu/spirv_float_semantics.h): written out, they round as the
// CPU's do, and a ray that grazes an edge takes the same branch on both backends. A square root
// and a division may still round differently where a device is allowed to (Vulkan: 2.5 ulp for a
// division).
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
