// The scene in the GPU's layout (shaders/shared/gpu_types.h): what the Vulkan backend uploads.
// Triangles are in BVH order.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "bvh/bvh.h"
#include "gpu_input/shading_texels.h"
#include "gpu_input/traversal_nodes.h"
#include "render_model/dispersion.h"
#include "scene/scene.h"
#include "shared/gpu_types.h"

namespace vitrum {

// Everything but the arrays a triangle: materials, lights, textures, and each object's medium.
struct PackedTables {
    std::vector<gpu::GpuMaterial> materials;
    std::vector<gpu::GpuLight> lights;
    std::vector<gpu::TextureInfo> textures;
    std::vector<glm::vec4> texels;  // RGB in xyz, a texel each (gpu_types.h, TextureInfo)
    // The material of each object's medium (objectMediumMaterials, render_model/medium_materials.h).
    std::vector<std::uint32_t> objectMaterials;
    std::vector<std::int32_t> objectPriorities;  // the priority of each object's medium
    std::vector<float> objectDispersions;        // the Cauchy B of each object's medium (0: none)
    std::vector<glm::vec3> objectTints;          // the tint of each object's surface (Material::tint)
    // The scene's wavelength samples where some medium disperses, else none.
    std::vector<WavelengthSample> wavelengths;
};

PackedTables packTables(const Scene& scene);

// The triangles' vertices in BVH order (bvh.triangleOrder.size() of them), written where they are
// to live, on every core: the renderer writes them into the device's buffer where the host can map
// it, so that a big model's host memory holds no second copy (as the shading texels,
// gpu_input/shading_texels.h, and the BVH nodes, gpu_input/traversal_nodes.h).
void packVertices(const Scene& scene, const Bvh& bvh, std::span<gpu::TriangleVertices> into);  // with their marks

// All of it at once (tests, benchmarks).
struct PackedScene {
    TraversalNodes bvh;
    std::vector<gpu::TriangleVertices> vertices;
    std::vector<gpu::ShadingTexel> shading;
    PackedTables tables;
};

PackedScene packScene(const Scene& scene, const Bvh& bvh);

}  // namespace vitrum
