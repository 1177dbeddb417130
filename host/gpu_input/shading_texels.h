// A scene's shading attributes in the GPU's layout (gpu::ShadingTexel, shaders/shared/gpu_types.h):
// a texel a triangle, then the distinct vertex normals of the triangles that are not flat, then
// the corner uvs of the textured ones. Planned first, so that the buffer's size is known before it
// is made, then written where it is to live (docs/gpu-design.md, "Shading data by index").
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "bvh/bvh.h"
#include "scene/scene.h"
#include "shared/gpu_types.h"

namespace vitrum {

struct ShadingPlan {
    std::size_t triangles = 0;
    // The distinct normals (exact bits) of the triangles that are not flat or have a texture, in
    // the order of their first use in the scene, and each corner's index among them: three a
    // triangle, by its index in the scene (empty where every triangle is flat and untextured).
    std::vector<glm::vec3> normals;
    std::vector<std::uint32_t> cornerNormals;
    // The first uv texel of each triangle, by its index in the scene, kNoCornerUvs for an
    // untextured one (empty where no material has a texture).
    std::vector<std::uint32_t> uvTexels;
    std::size_t texturedTriangles = 0;

    std::size_t texels() const { return triangles + normals.size() + gpu::kCornerUvsTexels * texturedTriangles; }
};

// A triangle is flat when its three normals have the same bits.
bool isFlat(const Triangle& t);

ShadingPlan planShading(const Scene& scene, const Bvh& bvh);

// Writes the plan's texels (plan.texels() of them) into `into`, on every core.
void writeShading(const Scene& scene, const Bvh& bvh, const ShadingPlan& plan, std::span<gpu::ShadingTexel> into);

}  // namespace vitrum
