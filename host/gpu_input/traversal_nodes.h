// The BVH in the layout the GPU traverses (gpu::TraversalNode, shaders/shared/gpu_types.h): the
// interior nodes only, each with both children's boxes, in the depth-first order of bvh.nodes.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "shared/gpu_types.h"

namespace vitrum {

struct TraversalNodes {
    std::vector<gpu::TraversalNode> nodes;  // empty when the whole tree is one leaf
    std::uint32_t rootEntry = gpu::kLeafEntryFlag;  // node 0, or the root leaf's entry
    std::uint32_t firstInstance = 0;  // the node of the first instance (gpu_types.h, "Instances")
};

// `instances`: Bvh::instances, written after the interior nodes (two nodes' room each).
TraversalNodes makeTraversalNodes(std::span<const gpu::BvhNode> nodes, std::span<const gpu::GpuInstance> instances = {});

// The same in parts, for writing in place (a big model's nodes straight into the GPU's buffer):
// the number of traversal nodes, the nodes into `into` (that many), the root's entry and the node
// of the first instance.
std::size_t traversalNodeCount(std::span<const gpu::BvhNode> nodes, std::span<const gpu::GpuInstance> instances = {});
void writeTraversalNodes(std::span<const gpu::BvhNode> nodes, std::span<gpu::TraversalNode> into,
                         std::span<const gpu::GpuInstance> instances = {});
std::uint32_t traversalRootEntry(std::span<const gpu::BvhNode> nodes, std::span<const gpu::GpuInstance> instances = {});
std::uint32_t firstInstanceNode(std::span<const gpu::BvhNode> nodes);

}  // namespace vitrum
