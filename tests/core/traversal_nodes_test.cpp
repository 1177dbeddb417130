// The GPU's node layout (gpu_input/traversal_nodes.h) against the BVH it is made from: walked from
// its root entry, it must reach every triangle once, in leaf order, inside the boxes above it.
#include <gtest/gtest.h>

#include <bit>
#include <random>

#include "bvh/bvh.h"
#include "gpu_input/traversal_nodes.h"

namespace vitrum {
namespace {

std::uint32_t bits(float f) { return std::bit_cast<std::uint32_t>(f); }

std::vector<Triangle> randomSoup(std::size_t count, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> centre(-10.0f, 10.0f), offset(-1.0f, 1.0f);
    std::vector<Triangle> triangles(count);
    for (Triangle& t : triangles) {
        const glm::vec3 c(centre(rng), centre(rng), centre(rng));
        for (auto& p : t.position) p = c + glm::vec3(offset(rng), offset(rng), offset(rng));
    }
    return triangles;
}

bool contains(glm::vec3 lo, glm::vec3 hi, glm::vec3 p) {
    return glm::all(glm::lessThanEqual(lo, p)) && glm::all(glm::lessThanEqual(p, hi));
}

struct Box {
    glm::vec3 lo, hi;
};

// Depth first, child 0 before child 1, as the GPU visits a ray with a positive direction on
// every axis: the leaves come in the order of bvh.nodes, so their triangles are 0, 1, 2, ...
void walk(const TraversalNodes& tree, const std::vector<gpu::TriangleVertices>& vertices, std::uint32_t entry,
          std::vector<Box>& boxes, std::uint32_t& nextTriangle, std::size_t& interiorVisits) {
    if (entry & gpu::kLeafEntryFlag) {
        const std::uint32_t first = (entry & ~gpu::kLeafEntryFlag) >> 4, count = entry & 15u;
        ASSERT_GE(count, 1u);
        ASSERT_LE(count, gpu::kMaxLeafTriangles);
        EXPECT_EQ(first, nextTriangle);
        for (std::uint32_t t = first; t < first + count; ++t)
            for (const Box& box : boxes)
                for (const glm::vec4& v : {vertices[t].v0, vertices[t].v1, vertices[t].v2})
                    EXPECT_TRUE(contains(box.lo, box.hi, glm::vec3(v))) << "triangle " << t;
        nextTriangle = first + count;
        return;
    }
    ASSERT_LT(entry, tree.nodes.size());
    ++interiorVisits;
    const gpu::TraversalNode& node = tree.nodes[entry];
    EXPECT_LE(bits(node.max0.w), 2u);  // the split axis
    boxes.push_back({glm::vec3(node.min0), glm::vec3(node.max0)});
    walk(tree, vertices, bits(node.min0.w), boxes, nextTriangle, interiorVisits);
    boxes.back() = {glm::vec3(node.min1), glm::vec3(node.max1)};
    walk(tree, vertices, bits(node.min1.w), boxes, nextTriangle, interiorVisits);
    boxes.pop_back();
}

TEST(TraversalNodes, HoldEveryTriangleOnceInsideItsBoxes) {
    for (std::size_t count : {9u, 100u, 5000u}) {
        const std::vector<Triangle> triangles = randomSoup(count, std::uint32_t(count));
        const Bvh bvh = buildBvh(triangles);
        const std::vector<gpu::TriangleVertices> vertices = packTriangleVertices(bvh, triangles);
        const TraversalNodes tree = makeTraversalNodes(bvh.nodes);
        // Only the interior nodes: a binary tree of L leaves has L - 1 of them.
        EXPECT_EQ(tree.nodes.size(), bvh.stats.leafCount - 1);
        EXPECT_EQ(tree.rootEntry, 0u);
        std::vector<Box> boxes;
        std::uint32_t nextTriangle = 0;
        std::size_t interiorVisits = 0;
        walk(tree, vertices, tree.rootEntry, boxes, nextTriangle, interiorVisits);
        EXPECT_EQ(nextTriangle, count);
        EXPECT_EQ(interiorVisits, tree.nodes.size());
    }
}

TEST(TraversalNodes, OneLeafTreeIsItsRootEntry) {
    const std::vector<Triangle> triangles = randomSoup(1, 7);
    const TraversalNodes tree = makeTraversalNodes(buildBvh(triangles).nodes);
    EXPECT_TRUE(tree.nodes.empty());
    EXPECT_EQ(tree.rootEntry, gpu::kLeafEntryFlag | 1u);  // triangle 0 alone
}

TEST(TraversalNodes, EmptySceneIsAnEmptyLeaf) {
    const TraversalNodes tree = makeTraversalNodes({});
    EXPECT_TRUE(tree.nodes.empty());
    EXPECT_EQ(tree.rootEntry, gpu::kLeafEntryFlag);
}

}  // namespace
}  // namespace vitrum
