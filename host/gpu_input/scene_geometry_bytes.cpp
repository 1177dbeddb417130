#include "gpu_input/scene_geometry_bytes.h"

#include "gpu_input/traversal_nodes.h"
#include "shared/gpu_types.h"

namespace vitrum {

SceneGeometryBytes sceneGeometryAtLeast(std::size_t triangles) {
    // A binary tree of L leaves has L - 1 interior nodes, the traversal nodes.
    const std::uint64_t leaves = (triangles + gpu::kMaxLeafTriangles - 1) / gpu::kMaxLeafTriangles;
    return {(leaves > 0 ? leaves - 1 : 0) * sizeof(gpu::TraversalNode), triangles * sizeof(gpu::TriangleVertices),
            triangles * sizeof(gpu::ShadingTexel)};
}

SceneGeometryBytes sceneGeometry(const Bvh& bvh, const ShadingPlan& shading) {
    return {traversalNodeCount(bvh.nodes, bvh.instances) * sizeof(gpu::TraversalNode),
            bvh.triangleOrder.size() * sizeof(gpu::TriangleVertices), shading.texels() * sizeof(gpu::ShadingTexel)};
}

}  // namespace vitrum
