// The binary BVH collapsed into 8-wide nodes, for the trace-only kernel that tests a node's eight
// children in the eight lanes of a subgroup (bench/trace_only/trace_rays_wide.comp). Each wide
// node takes the children of a binary node and, while it has fewer than eight, replaces its
// interior child of largest surface area by that child's two children (as Embree's BVH8 builder
// collapses a binary tree). Leaves keep their triangles (at most kMaxLeafTriangles = 8, one a lane).
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include <glm/glm.hpp>

#include "shared/gpu_types.h"

namespace vitrum::bench {

constexpr std::uint32_t kWideChildren = 8;
constexpr std::uint32_t kWideNodeTexels = 2 * kWideChildren;  // trace_rays_wide.comp's
constexpr std::uint32_t kNoWideEntry = 0xFFFFFFFFu;

struct WideBvh {
    std::vector<glm::vec4> texels;  // kWideNodeTexels a node: (min.xyz, entry bits), (max.xyz, 0) a child
    std::uint32_t rootEntry = gpu::kLeafEntryFlag;  // node 0, or the root leaf's entry
    std::uint32_t nodes = 0;
    double meanChildren = 0;  // children a node, over all nodes
};

namespace detail {

inline bool isInterior(const gpu::BvhNode& node) {
    return (std::bit_cast<std::uint32_t>(node.boundsMax.w) & gpu::kInteriorNodeFlag) != 0;
}

inline double area(const gpu::BvhNode& node) {
    const glm::vec3 e = glm::max(glm::vec3(node.boundsMax) - glm::vec3(node.boundsMin), glm::vec3(0.0f));
    return double(e.x) * e.y + double(e.y) * e.z + double(e.z) * e.x;
}

inline std::uint32_t leafEntry(const gpu::BvhNode& node) {
    const std::uint32_t first = std::bit_cast<std::uint32_t>(node.boundsMin.w);
    const std::uint32_t count = std::bit_cast<std::uint32_t>(node.boundsMax.w);
    if (first > gpu::kMaxTriangles || count > gpu::kMaxLeafTriangles)
        throw std::logic_error("a BVH leaf does not fit a wide-tree entry");
    return gpu::kLeafEntryFlag | first << 4 | count;
}

class WideBuilder {
public:
    explicit WideBuilder(std::span<const gpu::BvhNode> nodes) : nodes_(nodes) {}

    // Builds the wide node for binary interior node `i` and returns its index.
    std::uint32_t build(std::uint32_t i) {
        std::vector<std::uint32_t> children = {i + 1, std::bit_cast<std::uint32_t>(nodes_[i].boundsMin.w)};
        while (children.size() < kWideChildren) {
            auto widest = children.end();
            for (auto c = children.begin(); c != children.end(); ++c)
                if (isInterior(nodes_[*c]) && (widest == children.end() || area(nodes_[*c]) > area(nodes_[*widest])))
                    widest = c;
            if (widest == children.end()) break;
            const std::uint32_t opened = *widest;
            *widest = opened + 1;
            children.push_back(std::bit_cast<std::uint32_t>(nodes_[opened].boundsMin.w));
        }
        const std::uint32_t index = std::uint32_t(out_.texels.size() / kWideNodeTexels);
        out_.texels.resize(out_.texels.size() + kWideNodeTexels);
        childCount_ += children.size();
        for (std::uint32_t k = 0; k < kWideChildren; ++k) {
            glm::vec4 low(1e30f, 1e30f, 1e30f, std::bit_cast<float>(kNoWideEntry)), high(-1e30f, -1e30f, -1e30f, 0.0f);
            if (k < children.size()) {
                const gpu::BvhNode& child = nodes_[children[k]];
                const std::uint32_t entry = isInterior(child) ? build(children[k]) : leafEntry(child);
                low = glm::vec4(glm::vec3(child.boundsMin), std::bit_cast<float>(entry));
                high = glm::vec4(glm::vec3(child.boundsMax), 0.0f);
            }
            out_.texels[index * kWideNodeTexels + 2 * k] = low;
            out_.texels[index * kWideNodeTexels + 2 * k + 1] = high;
        }
        return index;
    }

    WideBvh finish() {
        out_.nodes = std::uint32_t(out_.texels.size() / kWideNodeTexels);
        out_.meanChildren = out_.nodes == 0 ? 0.0 : double(childCount_) / out_.nodes;
        return std::move(out_);
    }

private:
    std::span<const gpu::BvhNode> nodes_;
    WideBvh out_;
    std::size_t childCount_ = 0;
};

}  // namespace detail

inline WideBvh makeWideBvh(std::span<const gpu::BvhNode> nodes) {
    if (nodes.empty()) return {};
    if (!detail::isInterior(nodes[0])) {
        WideBvh leaf;
        leaf.rootEntry = detail::leafEntry(nodes[0]);
        leaf.texels.resize(kWideNodeTexels);  // a texel buffer may not be empty
        return leaf;
    }
    detail::WideBuilder builder(nodes);
    builder.build(0);
    WideBvh tree = builder.finish();
    tree.rootEntry = 0;
    return tree;
}

}  // namespace vitrum::bench
