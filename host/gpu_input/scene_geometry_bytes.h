// The device bytes of a scene's three buffers a triangle (BVH nodes, triangle vertices, shading
// texels): the least before the BVH is built, exactly after (gpu/scene_fit.h checks them against
// the device; `vitrum info` and the benchmarks report them).
#pragma once

#include <cstddef>
#include <cstdint>

#include "bvh/bvh.h"
#include "gpu_input/shading_texels.h"

namespace vitrum {

struct SceneGeometryBytes {
    std::uint64_t nodes = 0, vertices = 0, shading = 0;

    std::uint64_t total() const { return nodes + vertices + shading; }
};

// The least any BVH and shading layout of `triangles` triangles take (leaves of
// gpu::kMaxLeafTriangles, every triangle flat): a scene refused on it cannot fit.
SceneGeometryBytes sceneGeometryAtLeast(std::size_t triangles);
// What this BVH and shading plan take.
SceneGeometryBytes sceneGeometry(const Bvh& bvh, const ShadingPlan& shading);

}  // namespace vitrum
