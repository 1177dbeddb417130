// The scene in the GPU's layout (shaders/shared/gpu_types.h): what the Vulkan backend uploads.
// Triangles are in BVH order.
#pragma once

#include <cstdint>
#include <vector>

#include "bvh/bvh.h"
#include "gpu_input/traversal_nodes.h"
#include "scene/scene.h"
#include "shared/gpu_types.h"

namespace vitrum {

// Everything but the arrays a triangle: materials, lights, textures, and each object's medium.
struct PackedTables {
    std::vector<gpu::GpuMaterial> materials;
    std::vector<gpu::GpuLight> lights;
    std::vector<gpu::TextureInfo> textures;
    std::vector<float> texels;  // RGB, 3 floats a texel
    // The material of each object's medium (objectMediumMaterials, render_model/medium_materials.h).
    std::vector<std::uint32_t> objectMaterials;
};

PackedTables packTables(const Scene& scene);

// The arrays a triangle, in BVH order, each made on its own: the renderer uploads one and drops it
// before it makes the next, so that a big model's host memory holds one of them at a time beside
// the device's copies (together 192 bytes a triangle).
std::vector<gpu::TriangleVertices> packVertices(const Scene& scene, const Bvh& bvh);  // with the glass flag
std::vector<gpu::TriangleShading> packShading(const Scene& scene, const Bvh& bvh);

// All of it at once (tests, benchmarks).
struct PackedScene {
    TraversalNodes bvh;
    std::vector<gpu::TriangleVertices> vertices;
    std::vector<gpu::TriangleShading> shading;
    PackedTables tables;
};

PackedScene packScene(const Scene& scene, const Bvh& bvh);

}  // namespace vitrum
