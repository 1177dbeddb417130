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

struct PackedScene {
    TraversalNodes bvh;
    std::vector<gpu::TriangleVertices> vertices;
    std::vector<gpu::TriangleShading> shading;
    std::vector<gpu::GpuMaterial> materials;
    std::vector<gpu::GpuLight> lights;
    std::vector<gpu::TextureInfo> textures;
    std::vector<float> texels;  // RGB, 3 floats a texel
    // The material of each object's medium (objectMediumMaterials, render_model/medium_materials.h).
    std::vector<std::uint32_t> objectMaterials;
};

PackedScene packScene(const Scene& scene, const Bvh& bvh);

}  // namespace vitrum
