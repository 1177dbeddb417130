// Reading textures and environment maps: texel centres at (i + 0.5) / size, bilinear or nearest,
// wrap or clamp per axis; the same steps as host/cpu/texture_sampling.h. A texel is one texel of
// the texture texel buffer (gpu_types.h's TextureInfo).
#ifndef VITRUM_TEXTURE_GLSL
#define VITRUM_TEXTURE_GLSL

#include "bindings.glsl"
#include "specialization.glsl"

#include "ieee_vector_math.glsl"

// GLSL leaves % undefined for a negative operand (C++ truncates), so a texel left of 0 is counted
// from the right end (docs/other-devices.md).
int addressTexel(int i, int size, bool wrap) {
    if (!wrap) return clamp(i, 0, size - 1);
    return i >= 0 ? i % size : (size - 1) - (-(i + 1)) % size;
}

vec3 texelAt(uvec4 info, int x, int y, bool wrapU, bool wrapV) {
    int w = int(info.y);
    int h = int(info.z);
    return fetchVec4(textureTexels, info.x, uint(addressTexel(y, h, wrapV) * w + addressTexel(x, w, wrapU))).xyz;
}

// The value of texture `index` at (u, v) in [0, 1]^2, v = 0 at the top row.
vec3 sampleTexture(uint index, vec2 uv, bool wrapU, bool wrapV) {
    uvec4 info = imageLoad(textureTable, int(index));
    if (any(isnan(uv)) || any(isinf(uv))) return vec3(0.0);
    float x = uv.x * float(info.y);
    float y = uv.y * float(info.z);
    if (textureFilter() == kFilterNearest) return texelAt(info, int(floor(x)), int(floor(y)), wrapU, wrapV);
    float xc = x - 0.5;
    float yc = y - 0.5;
    float x0 = floor(xc);
    float y0 = floor(yc);
    float fx = xc - x0;
    float fy = yc - y0;
    int ix = int(x0);
    int iy = int(y0);
    vec3 top = ieeeMix(texelAt(info, ix, iy, wrapU, wrapV), texelAt(info, ix + 1, iy, wrapU, wrapV), fx);
    vec3 bottom =
        ieeeMix(texelAt(info, ix, iy + 1, wrapU, wrapV), texelAt(info, ix + 1, iy + 1, wrapU, wrapV), fx);
    return ieeeMix(top, bottom, fy);
}

// A mesh texture (map_Kd, a cutout or coverage texture) at a surface's texture coordinates: read at
// (u, 1 - v), wrapping in both (render-model-decisions.md, "Texture coordinates"), as the CPU
// reference's sampling::sampleMeshTexture reads it.
vec3 sampleMeshTexture(uint index, vec2 uv) { return sampleTexture(index, vec2(uv.x, 1.0 - uv.y), true, true); }

#endif
