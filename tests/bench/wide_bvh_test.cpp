// The 8-wide collapse of the BVH that the one-ray-a-subgroup benchmark kernel traverses
// (bench/wide_bvh.h): it must hold every triangle exactly once, boxes that hold what lies under
// them, and nodes opened as far as the collapse says (a node with fewer than 8 children has
// only leaves among them).
#include <gtest/gtest.h>

#include <bit>
#include <vector>

#include "../support/scenes_in_code.h"
#include "../support/test_meshes.h"
#include "bvh/bvh.h"
#include "wide_bvh.h"

namespace vitrum::testing {
namespace {

struct Walk {
    const bench::WideBvh& tree;
    const std::vector<Triangle>& triangles;  // in BVH order
    std::vector<int> seen;
    std::size_t nodes = 0;

    // Checks the subtree of `entry` against the box it was reached through.
    void visit(std::uint32_t entry, glm::vec3 low, glm::vec3 high) {
        if (entry & gpu::kLeafEntryFlag) {
            const std::uint32_t count = entry & 15u, first = (entry & ~gpu::kLeafEntryFlag) >> 4;
            ASSERT_GE(count, 1u);
            for (std::uint32_t t = first; t < first + count; ++t) {
                ASSERT_LT(t, seen.size());
                seen[t] += 1;
                for (const glm::vec3& p : triangles[t].position) {
                    EXPECT_TRUE(glm::all(glm::greaterThanEqual(p, low)) && glm::all(glm::lessThanEqual(p, high)))
                        << "triangle " << t << " outside its leaf's box";
                }
            }
            return;
        }
        ASSERT_LT(entry, tree.nodes);
        nodes += 1;
        std::uint32_t children = 0, interior = 0;
        for (std::uint32_t c = 0; c < bench::kWideChildren; ++c) {
            const glm::vec4 childLow = tree.texels[entry * bench::kWideNodeTexels + 2 * c];
            const glm::vec4 childHigh = tree.texels[entry * bench::kWideNodeTexels + 2 * c + 1];
            const std::uint32_t child = std::bit_cast<std::uint32_t>(childLow.w);
            if (child == bench::kNoWideEntry) continue;
            EXPECT_EQ(children, c) << "an empty slot before a child";
            children += 1;
            interior += (child & gpu::kLeafEntryFlag) == 0;
            EXPECT_TRUE(glm::all(glm::greaterThanEqual(glm::vec3(childLow), low)) &&
                        glm::all(glm::lessThanEqual(glm::vec3(childHigh), high)))
                << "a child's box outside its parent's";
            visit(child, glm::vec3(childLow), glm::vec3(childHigh));
        }
        EXPECT_GE(children, 2u);
        if (children < bench::kWideChildren) {
            EXPECT_EQ(interior, 0u) << "a node left with room and an unopened child";
        }
    }
};

TEST(WideBvh, HoldsEveryTriangleOnceInBoxesThatContainIt) {
    Scene scene;
    for (int i = 0; i < 5; ++i) {
        const IndexedMesh mesh = icosphere(3, 0.4f + 0.1f * float(i), glm::vec3(float(i), 0.5f * float(i % 2), 0.0f));
        for (const glm::uvec3& f : mesh.faces)
            scene.triangles.push_back(makeTriangle(mesh.vertices[f.x], mesh.vertices[f.y], mesh.vertices[f.z], 0, i));
    }
    const Bvh bvh = buildSceneBvh(scene);
    std::vector<Triangle> ordered;
    for (std::uint32_t i : bvh.triangleOrder) ordered.push_back(scene.triangles[i]);
    const bench::WideBvh tree = bench::makeWideBvh(bvh.nodes);
    ASSERT_EQ(tree.rootEntry, 0u);
    Walk walk{tree, ordered, std::vector<int>(ordered.size(), 0)};
    walk.visit(tree.rootEntry, glm::vec3(-1e30f), glm::vec3(1e30f));
    EXPECT_EQ(walk.nodes, tree.nodes) << "nodes that no path reaches";
    for (std::size_t t = 0; t < walk.seen.size(); ++t) EXPECT_EQ(walk.seen[t], 1) << "triangle " << t;
    // Fewer nodes than the binary tree's interior nodes (n - 1 for n leaves): each wide node
    // takes the place of several.
    EXPECT_LT(tree.nodes * 2, bvh.stats.nodeCount / 2);
}

TEST(WideBvh, ATreeThatIsOneLeafIsItsRootEntry) {
    Scene scene;
    scene.triangles.push_back(makeTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0, 0));
    const Bvh bvh = buildSceneBvh(scene);
    const bench::WideBvh tree = bench::makeWideBvh(bvh.nodes);
    EXPECT_EQ(tree.rootEntry, gpu::kLeafEntryFlag | 0u << 4 | 1u);
    EXPECT_EQ(tree.nodes, 0u);
}

}  // namespace
}  // namespace vitrum::testing
