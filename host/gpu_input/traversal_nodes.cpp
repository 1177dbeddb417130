#include "gpu_input/traversal_nodes.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>

namespace vitrum {
namespace {

bool isInterior(const gpu::BvhNode& node) {
    return (std::bit_cast<std::uint32_t>(node.boundsMax.w) & gpu::kInteriorNodeFlag) != 0;
}

// A child's entry: its TraversalNode index when it is interior, else its triangle range, or for a
// top-level leaf its instance (gpu_types.h, "Instances"): the world triangles' tree is entered
// at its root directly.
std::uint32_t traversalEntry(std::span<const gpu::BvhNode> nodes, std::span<const gpu::GpuInstance> instances,
                             const std::vector<std::uint32_t>& interiorIndex, std::uint32_t index) {
    const gpu::BvhNode& node = nodes[index];
    if (isInterior(node)) return interiorIndex[index];
    const std::uint32_t first = std::bit_cast<std::uint32_t>(node.boundsMin.w);
    const std::uint32_t count = std::bit_cast<std::uint32_t>(node.boundsMax.w);
    if (count == 0 && !instances.empty()) {
        if (first >= instances.size() || first >= gpu::kMaxInstances) throw std::logic_error("a BVH leaf names no instance");
        const gpu::GpuInstance& instance = instances[first];
        if (instance.info.w == gpu::kIdentityInstance) return traversalEntry(nodes, instances, interiorIndex, instance.info.x);
        return gpu::kLeafEntryFlag | (first + 1) << 4;
    }
    if (first > gpu::kMaxTriangles || count > gpu::kMaxLeafTriangles)
        throw std::logic_error("a BVH leaf does not fit a traversal entry");
    return gpu::kLeafEntryFlag | first << 4 | count;
}

// Interior nodes are numbered in their depth-first order, so node 0 is the root.
std::vector<std::uint32_t> interiorIndices(std::span<const gpu::BvhNode> nodes) {
    std::vector<std::uint32_t> interiorIndex(nodes.size(), 0);
    std::uint32_t interior = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i)
        if (isInterior(nodes[i])) interiorIndex[i] = interior++;
    return interiorIndex;
}

}  // namespace

std::size_t traversalNodeCount(std::span<const gpu::BvhNode> nodes, std::span<const gpu::GpuInstance> instances) {
    return std::size_t(std::count_if(nodes.begin(), nodes.end(), isInterior)) + gpu::kGpuInstanceNodes * instances.size();
}

void writeTraversalNodes(std::span<const gpu::BvhNode> nodes, std::span<gpu::TraversalNode> into,
                         std::span<const gpu::GpuInstance> instances) {
    if (into.size() != traversalNodeCount(nodes, instances))
        throw std::logic_error("writeTraversalNodes: wrong node count");
    const std::vector<std::uint32_t> interiorIndex = interiorIndices(nodes);
    std::size_t written = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const gpu::BvhNode& node = nodes[i];
        if (!isInterior(node)) continue;
        const std::uint32_t children[2] = {std::uint32_t(i + 1), std::bit_cast<std::uint32_t>(node.boundsMin.w)};
        const gpu::BvhNode& c0 = nodes[children[0]];
        const gpu::BvhNode& c1 = nodes[children[1]];
        const std::uint32_t axis = std::bit_cast<std::uint32_t>(node.boundsMax.w) & 3u;
        const std::uint32_t entry0 = traversalEntry(nodes, instances, interiorIndex, children[0]);
        const std::uint32_t entry1 = traversalEntry(nodes, instances, interiorIndex, children[1]);
        into[written++] = {
            .min0 = glm::vec4(glm::vec3(c0.boundsMin), std::bit_cast<float>(entry0)),
            .max0 = glm::vec4(glm::vec3(c0.boundsMax), std::bit_cast<float>(axis)),
            .min1 = glm::vec4(glm::vec3(c1.boundsMin), std::bit_cast<float>(entry1)),
            .max1 = glm::vec4(glm::vec3(c1.boundsMax), 0.0f),
        };
    }
    // The instances after the nodes, two nodes' texels each, with their mesh trees' entries.
    for (const gpu::GpuInstance& instance : instances) {
        gpu::GpuInstance placed = instance;
        placed.info.y = traversalEntry(nodes, instances, interiorIndex, instance.info.x);
        static_assert(sizeof(gpu::GpuInstance) == gpu::kGpuInstanceNodes * sizeof(gpu::TraversalNode));
        std::memcpy(&into[written], &placed, sizeof placed);
        written += gpu::kGpuInstanceNodes;
    }
}

std::uint32_t traversalRootEntry(std::span<const gpu::BvhNode> nodes, std::span<const gpu::GpuInstance> instances) {
    // No triangles: the root is an empty leaf.
    return nodes.empty() ? gpu::kLeafEntryFlag : traversalEntry(nodes, instances, interiorIndices(nodes), 0);
}

std::uint32_t firstInstanceNode(std::span<const gpu::BvhNode> nodes) {
    return std::uint32_t(std::count_if(nodes.begin(), nodes.end(), isInterior));
}

TraversalNodes makeTraversalNodes(std::span<const gpu::BvhNode> nodes, std::span<const gpu::GpuInstance> instances) {
    TraversalNodes out;
    out.nodes.resize(traversalNodeCount(nodes, instances));
    writeTraversalNodes(nodes, out.nodes, instances);
    out.rootEntry = traversalRootEntry(nodes, instances);
    out.firstInstance = firstInstanceNode(nodes);
    return out;
}

}  // namespace vitrum
