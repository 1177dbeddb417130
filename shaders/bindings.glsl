// The buffers of trace.comp; layouts from shared/gpu_types.h, binding numbers from
// shared/trace_bindings.h.
#ifndef VITRUM_BINDINGS_GLSL
#define VITRUM_BINDINGS_GLSL

#include "shared/gpu_types.h"

#include "shared/trace_bindings.h"

layout(set = 0, binding = kBindingParams, rgba32ui) uniform readonly uimageBuffer paramTexels;  // one RenderParams
// The parameters and the scene's geometry, materials, lights and object media are storage texel
// buffers of uvec4 texels (gpu_types.h: kTraversalNodeTexels and the others), read with imageLoad:
// on lavapipe a texel read is one load a lane, not a loop over the lanes, and imageLoad, unlike
// texelFetch, is compiled into the kernel (docs/gpu-design.md, "Data").
layout(set = 0, binding = kBindingNodes, rgba32ui) uniform readonly uimageBuffer nodeTexels;
layout(set = 0, binding = kBindingVertices, rgba32ui) uniform readonly uimageBuffer vertexTexels;
layout(set = 0, binding = kBindingShading, rgba32ui) uniform readonly uimageBuffer shadingTexels;
layout(set = 0, binding = kBindingMaterials, rgba32ui) uniform readonly uimageBuffer materialTexels;
layout(set = 0, binding = kBindingLights, rgba32ui) uniform readonly uimageBuffer lightTexels;
layout(set = 0, binding = kBindingTextures, rgba32ui) uniform readonly uimageBuffer textureTable;  // TextureInfo a texel
layout(set = 0, binding = kBindingTexels, rgba32ui) uniform readonly uimageBuffer textureTexels;  // RGB in xyz
layout(set = 0, binding = kBindingObjectMedia, rgba32ui) uniform readonly uimageBuffer objectMediumTexels;
// Texel 0: .x = the number of wavelength samples (0 where nothing disperses); texel 1 + k:
// sample k's weight (.xyz) and its 1 / lambda^2 - 1 / lambda_d^2 (.w), WavelengthSample's.
layout(set = 0, binding = kBindingWavelengths, rgba32ui) uniform readonly uimageBuffer wavelengthTexels;
// One tile's pixels, by slot; .w is the slot's status (suspend.glsl), which the resumable kernel reads.
layout(std430, set = 0, binding = kBindingPixels) buffer Pixels { vec4 pixels[]; };
layout(std430, set = 0, binding = kBindingStates) buffer States { uvec4 stateTexels[]; };  // TraceStates, see suspend.glsl
layout(std430, set = 0, binding = kBindingStats) buffer Stats { uint stats[]; };
layout(std430, set = 0, binding = kBindingPendingRays) buffer PendingRays { PendingRay pendingRays[]; };  // pending_rays.glsl's pendingRayIndex
layout(std430, set = 0, binding = kBindingTraversalStacks) buffer TraversalStacks { uint traversalStacks[]; };  // kTraversalStackSize a pixel

#include "geometry_texels.glsl"  // fetchVec4, loadTraversalNode, loadTriangle

// The render parameters, read once at the start of main(). Not a uniform buffer: lavapipe
// recompiles a kernel at every dispatch for the values of uniforms that decide branches
// (docs/gpu-design.md, "Data", binding 0).
RenderParams params;

#include "render_params.glsl"  // its lanes by name

RenderParams loadRenderParams() {
    RenderParams p;
    p.cameraFrom = fetchVec4(paramTexels, 0u, 0u);
    p.cameraX = fetchVec4(paramTexels, 0u, 1u);
    p.cameraY = fetchVec4(paramTexels, 0u, 2u);
    p.cameraZ = fetchVec4(paramTexels, 0u, 3u);
    p.background = fetchVec4(paramTexels, 0u, 4u);
    p.image = imageLoad(paramTexels, 5);
    p.tile = imageLoad(paramTexels, 6);
    p.limits = imageLoad(paramTexels, 7);
    p.counts = imageLoad(paramTexels, 8);
    p.models = imageLoad(paramTexels, 9);
    p.surfaceChecks = imageLoad(paramTexels, 10);
    p.thresholds = fetchVec4(paramTexels, 0u, 11u);
    p.bvh = imageLoad(paramTexels, 12);
    p.cameraMedia = imageLoad(paramTexels, 13);
    p.cameraSurface = fetchVec4(paramTexels, 0u, 14u);
    p.cameraMediaBehind = imageLoad(paramTexels, 15);
    return p;
}

// A triangle's vertex normals (gpu_types.h's ShadingTexel): its own texel's, where it is flat.
mat3 loadVertexNormals(uint i) {
    uvec4 texel = imageLoad(shadingTexels, int(i));
    if (texel.w == kFlatTriangle) {
        vec3 n = uintBitsToFloat(texel.xyz);
        return mat3(n, n, n);
    }
    return mat3(fetchVec4(shadingTexels, texel.x, 0u).xyz, fetchVec4(shadingTexels, texel.y, 0u).xyz,
                fetchVec4(shadingTexels, texel.z, 0u).xyz);
}

// A triangle's texture coordinates at barycentrics (u, v) of its corners v1 and v2, interpolated
// as the hit point is (the CPU reference's uvAt); zero where its material has no texture or
// cut-outs, which then read none.
vec2 interpolatedUv(uint i, vec2 barycentrics) {
    uint first = imageLoad(shadingTexels, int(i)).w;
    bool stored = first != kFlatTriangle && first != kNoCornerUvs;
    vec4 uv0uv1 = stored ? fetchVec4(shadingTexels, first, 0u) : vec4(0.0);
    vec4 third = stored ? fetchVec4(shadingTexels, first, 1u) : vec4(0.0);
    float w0 = 1.0 - barycentrics.x - barycentrics.y;
    return w0 * uv0uv1.xy + barycentrics.x * uv0uv1.zw + barycentrics.y * third.xy;
}

GpuMaterial loadMaterial(uint i) {
    uint first = kGpuMaterialTexels * i;
    return GpuMaterial(fetchVec4(materialTexels, first, 0u), fetchVec4(materialTexels, first, 1u),
                       fetchVec4(materialTexels, first, 2u), fetchVec4(materialTexels, first, 3u),
                       fetchVec4(materialTexels, first, 4u));
}

GpuLight loadLight(uint i) {
    uint first = kGpuLightTexels * i;
    return GpuLight(fetchVec4(lightTexels, first, 0u), fetchVec4(lightTexels, first, 1u));
}

// The medium closed object `object` encloses: its material's Beer-Lambert attenuation (.xyz) and
// index of refraction (.w), GpuMaterial's `attenuation`. Its own texels, so that a medium's IOR is
// one read in a shading round, not the object's material and then the material's texel.
vec4 objectMedium(uint object) { return fetchVec4(objectMediumTexels, kObjectMediumTexels * object, 0u); }

// The priority of that medium (MTL `priority`): where media overlap, the highest is the medium.
int objectPriority(uint object) { return int(imageLoad(objectMediumTexels, int(kObjectMediumTexels * object + 1u)).x); }

// The Cauchy B of that medium (render_model/dispersion.h), 0 where it does not disperse.
float objectDispersion(uint object) {
    return uintBitsToFloat(imageLoad(objectMediumTexels, int(kObjectMediumTexels * object + 1u)).y);
}

// The colour light crossing the object's surface takes on (Material::tint), white for none.
vec3 objectTint(uint object) { return fetchVec4(objectMediumTexels, kObjectMediumTexels * object, 2u).xyz; }

uint wavelengthCount() { return imageLoad(wavelengthTexels, 0).x; }
vec4 wavelengthSample(uint k) { return fetchVec4(wavelengthTexels, 1u, k); }

#endif
