// The buffers of trace.comp; layouts from shared/gpu_types.h. Binding numbers match
// host/gpu/trace_pipeline.cpp (kBinding*).
#ifndef VITRUM_BINDINGS_GLSL
#define VITRUM_BINDINGS_GLSL

layout(std140, set = 0, binding = 0) uniform Params { RenderParams params; };
// The scene's geometry, materials, lights and object media are uniform texel buffers of uvec4 texels, read with
// texelFetch: on lavapipe a fetch is a vector gather, while every storage-buffer access is a loop
// over the 8 lanes (it made the plain baseline kernel 2x faster, docs/performance.md).
layout(set = 0, binding = 1) uniform usamplerBuffer nodeTexels;      // BvhNode: 2 texels
layout(set = 0, binding = 2) uniform usamplerBuffer vertexTexels;    // TriangleVertices: 3 texels
layout(set = 0, binding = 3) uniform usamplerBuffer shadingTexels;   // TriangleShading: 5 texels
layout(set = 0, binding = 4) uniform usamplerBuffer materialTexels;  // GpuMaterial: 4 texels
layout(set = 0, binding = 5) uniform usamplerBuffer lightTexels;     // GpuLight: 2 texels
layout(std430, set = 0, binding = 6) readonly buffer Textures { TextureInfo textures[]; };
layout(std430, set = 0, binding = 7) readonly buffer Texels { float texels[]; };  // RGB, packed
layout(set = 0, binding = 8) uniform usamplerBuffer objectMaterialTexels;  // 4 objects a texel
layout(std430, set = 0, binding = 9) writeonly buffer Pixels { vec4 pixels[]; };
layout(std430, set = 0, binding = 10) buffer States { TraceState states[]; };
layout(std430, set = 0, binding = 11) buffer Stats { uint stats[]; };
layout(std430, set = 0, binding = 12) buffer PendingRays { PendingRay pendingRays[]; };  // kPendingRayCapacity a pixel
layout(std430, set = 0, binding = 13) buffer TraversalStacks { uint traversalStacks[]; };  // kTraversalStackSize a pixel

vec4 fetchVec4(usamplerBuffer texels, uint index) { return uintBitsToFloat(texelFetch(texels, int(index))); }

BvhNode loadNode(uint i) { return BvhNode(fetchVec4(nodeTexels, 2u * i), fetchVec4(nodeTexels, 2u * i + 1u)); }

// A node's (boundsMin.w, boundsMax.w) as uints: its links, without its box.
uvec2 loadNodeLinks(uint i) {
    return uvec2(texelFetch(nodeTexels, int(2u * i)).w, texelFetch(nodeTexels, int(2u * i + 1u)).w);
}

TriangleVertices loadTriangle(uint i) {
    return TriangleVertices(fetchVec4(vertexTexels, 3u * i), fetchVec4(vertexTexels, 3u * i + 1u),
                            fetchVec4(vertexTexels, 3u * i + 2u));
}

TriangleShading loadShading(uint i) {
    return TriangleShading(fetchVec4(shadingTexels, 5u * i), fetchVec4(shadingTexels, 5u * i + 1u),
                           fetchVec4(shadingTexels, 5u * i + 2u), fetchVec4(shadingTexels, 5u * i + 3u),
                           fetchVec4(shadingTexels, 5u * i + 4u));
}

GpuLight loadLight(uint i) { return GpuLight(fetchVec4(lightTexels, 2u * i), fetchVec4(lightTexels, 2u * i + 1u)); }

// The material whose medium closed object `object` encloses.
uint objectMaterial(uint object) { return texelFetch(objectMaterialTexels, int(object >> 2))[object & 3u]; }

GpuMaterial loadMaterial(uint i) {
    return GpuMaterial(fetchVec4(materialTexels, 4u * i), fetchVec4(materialTexels, 4u * i + 1u),
                       fetchVec4(materialTexels, 4u * i + 2u), fetchVec4(materialTexels, 4u * i + 3u));
}

#endif
