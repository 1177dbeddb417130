// Building the BVH: binned SAH over triangle centroids (Wald, "On fast Construction of SAH-based
// Bounding Volume Hierarchies", 2007), large subtrees on other cores, flattened depth-first into
// gpu::BvhNode (pbrt-v4's LinearBVHNode layout; see shaders/shared/gpu_types.h).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "scene/scene.h"
#include "shared/gpu_types.h"

namespace vitrum {

struct BvhStats {
    std::uint32_t nodeCount = 0;
    std::uint32_t leafCount = 0;
    std::uint32_t maxDepth = 0;
    std::uint32_t maxLeafTriangles = 0;
    double sahCost = 0.0;  // expected cost with C_node = 1, C_tri = 1, relative to the root's area
    double buildSeconds = 0.0;
};

struct Bvh {
    std::vector<gpu::BvhNode> nodes;
    // Leaf ranges index triangles in BVH order; triangleOrder[i] is the scene triangle at BVH
    // position i.
    std::vector<std::uint32_t> triangleOrder;
    // A scene with instances (gpu_types.h, "Instances"): nodes begin with the top-level tree,
    // whose leaves (count 0) are these: the scene's instances in order, then the world triangles'
    // tree as an identity instance (where the scene has world triangles). Empty otherwise.
    std::vector<gpu::GpuInstance> instances;
    BvhStats stats;
};

// `progress`, when given, hears the share of the triangles placed in leaves so far, now and then.
// `threads` build it (0: one a core); the tree is the same however many.
Bvh buildBvh(std::span<const Triangle> triangles, const std::function<void(double)>& progress = {},
             unsigned threads = 0);

// The scene's: buildBvh of its triangles without instances, else the two levels (a tree of each
// mesh's triangles, each position in triangleOrder within its mesh's range of Scene::triangles).
Bvh buildSceneBvh(const Scene& scene, const std::function<void(double)>& progress = {}, unsigned threads = 0);

}  // namespace vitrum

namespace vitrum {

// Triangle positions in BVH order, as the GPU and the CPU traversal read them (material index in
// v0.w, object index in v1.w, both as uint bits).
std::vector<gpu::TriangleVertices> packTriangleVertices(const Bvh& bvh, std::span<const Triangle> triangles);
// The same into `into`: the triangles at BVH positions first, first + 1, ... (into.size() of them).
void packTriangleVertices(const Bvh& bvh, std::span<const Triangle> triangles, std::span<gpu::TriangleVertices> into,
                          std::size_t first = 0);

// The mark a triangle of material `m` carries in its vertices' v2.w, which both traversals read
// (gpu_types.h, "Triangles"): glass, cut-out parts and their texture, partial coverage.
inline std::uint32_t traversalMark(const Material& m) {
    if (m.model == MaterialModel::Glass) return gpu::kTriangleGlass;
    return (hasCutouts(m) ? gpu::kTriangleCutout | std::uint32_t(m.cutout) : 0u) |
           (hasPartialCoverage(m) ? gpu::kTriangleCovered : 0u);
}

}  // namespace vitrum
