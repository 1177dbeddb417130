// Mesh textures: bilinear filtering with wrap-around addressing, sampled at (u, 1 - v) (row 0
// is the top of the image), texel centres at (i + 0.5) / size (docs/render-model.md).
#ifndef VITRUM_TEXTURE_GLSL
#define VITRUM_TEXTURE_GLSL

vec3 texelAt(uvec4 info, int x, int y) {
    int w = int(info.y);
    int h = int(info.z);
    x = ((x % w) + w) % w;
    y = ((y % h) + h) % h;
    return texels[info.x + uint(y * w + x)].xyz;
}

vec3 sampleTextureBilinear(uint index, vec2 uv) {
    uvec4 info = textures[index].offsetAndSize;
    vec2 wrapped = vec2(uv.x - floor(uv.x), (1.0 - uv.y) - floor(1.0 - uv.y));
    float x = wrapped.x * float(info.y) - 0.5;
    float y = wrapped.y * float(info.z) - 0.5;
    float x0 = floor(x);
    float y0 = floor(y);
    float fx = x - x0;
    float fy = y - y0;
    int ix = int(x0);
    int iy = int(y0);
    vec3 top = mix(texelAt(info, ix, iy), texelAt(info, ix + 1, iy), fx);
    vec3 bottom = mix(texelAt(info, ix, iy + 1), texelAt(info, ix + 1, iy + 1), fx);
    return mix(top, bottom, fy);
}

#endif
