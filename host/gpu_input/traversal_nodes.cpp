#include "gpu_input/traversal_nodes.h"

#include <algorithm>
#include <bit>
#include <stdexcept>

namespace vitrum {
namespace {

bool isInterior(const gpu::BvhNode& node) {
    return (std::bit_cast<std::uint32_t>(node.boundsMax.w) & gpu::kInteriorNodeFlag) != 0;
}

// A child's entry: its TraversalNode index when it is interior, else its triangle range.
std::uint32_t traversalEntry(const gpu::BvhNode& node, std::uint32_t interiorIndex) {
    if (isInterior(node)) return interiorIndex;
    const std::uint32_t first = std::bit_cast<std::uint32_t>(node.boundsMin.w);
    const std::uint32_t count = std::bit_cast<std::uint32_t>(node.boundsMax.w);
    if (first > gpu::kMaxTriangles || count > gpu::kMaxLeafTriangles)
        throw std::logic_error("a BVH leaf does not fit a traversal entry");
    return gpu::kLeafEntryFlag | first << 4 | count;
}

}  // namespace

std::size_t traversalNodeCount(std::span<const gpu::BvhNode> nodes) {
    return std::size_t(std::count_if(nodes.begin(), nodes.end(), isInterior));
}

void writeTraversalNodes(std::span<const gpu::BvhNode> nodes, std::span<gpu::TraversalNode> into) {
    if (into.size() != traversalNodeCount(nodes)) throw std::logic_error("writeTraversalNodes: wrong node count");
    // Interior nodes are numbered in their depth-first order, so node 0 is the root.
    std::vector<std::uint32_t> interiorIndex(nodes.size(), 0);
    std::uint32_t interior = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i)
        if (isInterior(nodes[i])) interiorIndex[i] = interior++;
    std::size_t written = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const gpu::BvhNode& node = nodes[i];
        if (!isInterior(node)) continue;
        const std::uint32_t children[2] = {std::uint32_t(i + 1), std::bit_cast<std::uint32_t>(node.boundsMin.w)};
        const gpu::BvhNode& c0 = nodes[children[0]];
        const gpu::BvhNode& c1 = nodes[children[1]];
        const std::uint32_t axis = std::bit_cast<std::uint32_t>(node.boundsMax.w) & 3u;
        into[written++] = {
            .min0 = glm::vec4(glm::vec3(c0.boundsMin), std::bit_cast<float>(traversalEntry(c0, interiorIndex[children[0]]))),
            .max0 = glm::vec4(glm::vec3(c0.boundsMax), std::bit_cast<float>(axis)),
            .min1 = glm::vec4(glm::vec3(c1.boundsMin), std::bit_cast<float>(traversalEntry(c1, interiorIndex[children[1]]))),
            .max1 = glm::vec4(glm::vec3(c1.boundsMax), 0.0f),
        };
    }
}

std::uint32_t traversalRootEntry(std::span<const gpu::BvhNode> nodes) {
    // No triangles: the root is an empty leaf.
    return nodes.empty() ? gpu::kLeafEntryFlag : traversalEntry(nodes[0], 0);
}

TraversalNodes makeTraversalNodes(std::span<const gpu::BvhNode> nodes) {
    TraversalNodes out;
    out.nodes.resize(traversalNodeCount(nodes));
    writeTraversalNodes(nodes, out.nodes);
    out.rootEntry = traversalRootEntry(nodes);
    return out;
}

}  // namespace vitrum
