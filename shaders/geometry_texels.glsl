// Reading the scene's geometry from its storage texel buffers: a BVH node as the traversal visits
// it and a triangle's vertices. The includer declares `nodeTexels` and `vertexTexels` (trace.comp
// through bindings.glsl; bench/trace_only/trace_rays.comp at bindings of its own).
#ifndef VITRUM_GEOMETRY_TEXELS_GLSL
#define VITRUM_GEOMETRY_TEXELS_GLSL

// Texel k of the struct at `first` (a macro: GLSL functions cannot take the images' format).
#define fetchVec4(texels, first, k) uintBitsToFloat(imageLoad(texels, int((first) + (k))))

TraversalNode loadTraversalNode(uint i) {
    uint first = kTraversalNodeTexels * i;
    return TraversalNode(fetchVec4(nodeTexels, first, 0u), fetchVec4(nodeTexels, first, 1u),
                         fetchVec4(nodeTexels, first, 2u), fetchVec4(nodeTexels, first, 3u));
}

TriangleVertices loadTriangle(uint i) {
    uint first = kTriangleVerticesTexels * i;
    return TriangleVertices(fetchVec4(vertexTexels, first, 0u), fetchVec4(vertexTexels, first, 1u),
                            fetchVec4(vertexTexels, first, 2u));
}

// The instance at traversal node `node` (gpu_types.h, "Instances": two nodes' texels).
GpuInstance loadInstance(uint node) {
    uint first = kTraversalNodeTexels * node;
    return GpuInstance(fetchVec4(nodeTexels, first, 0u), fetchVec4(nodeTexels, first, 1u), fetchVec4(nodeTexels, first, 2u),
                       fetchVec4(nodeTexels, first, 3u), fetchVec4(nodeTexels, first, 4u), fetchVec4(nodeTexels, first, 5u),
                       imageLoad(nodeTexels, int(first + 6u)), uvec4(0u));
}

#endif
