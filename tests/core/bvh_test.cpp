// BVH build and traversal against brute force over every triangle, on random soups, generated
// spheres, the course meshes and degenerate inputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "bvh/bvh_traversal.h"

namespace vitrum {
namespace {

// Positions of an OBJ file: `v` and `f` lines only ("f a b c", "f a/b/c", "f a//c"), polygons
// fanned. Enough for the tests without depending on the scene loader.
std::vector<Triangle> readObjTriangles(const std::string& path) {
    std::ifstream in(path);
    EXPECT_TRUE(in.good()) << path;
    std::vector<glm::vec3> positions;
    std::vector<Triangle> triangles;
    std::string line;
    while (std::getline(in, line)) {
        std::istringstream words(line);
        std::string tag;
        words >> tag;
        if (tag == "v") {
            glm::vec3 p;
            words >> p.x >> p.y >> p.z;
            positions.push_back(p);
        } else if (tag == "f") {
            std::vector<int> indices;
            std::string vertex;
            while (words >> vertex) indices.push_back(std::stoi(vertex.substr(0, vertex.find('/'))) - 1);
            for (std::size_t k = 2; k < indices.size(); ++k) {
                Triangle t{};
                t.position[0] = positions.at(indices[0]);
                t.position[1] = positions.at(indices[k - 1]);
                t.position[2] = positions.at(indices[k]);
                triangles.push_back(t);
            }
        }
    }
    return triangles;
}

std::vector<Triangle> randomSoup(std::size_t count, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> centre(-10.0f, 10.0f);
    std::uniform_real_distribution<float> offset(-1.0f, 1.0f);
    std::vector<Triangle> triangles(count);
    for (Triangle& t : triangles) {
        glm::vec3 c(centre(rng), centre(rng), centre(rng));
        for (auto& p : t.position) p = c + glm::vec3(offset(rng), offset(rng), offset(rng));
    }
    return triangles;
}

// UV spheres on a k x k x k grid, outward wound.
std::vector<Triangle> sphereGrid(int k, int segments) {
    std::vector<Triangle> triangles;
    const float pi = 3.14159265358979f;
    auto point = [&](glm::vec3 c, int i, int j) {
        float theta = pi * float(i) / float(segments);
        float phi = 2.0f * pi * float(j) / float(segments);
        return c + 0.8f * glm::vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    };
    for (int x = 0; x < k; ++x)
        for (int y = 0; y < k; ++y)
            for (int z = 0; z < k; ++z) {
                glm::vec3 c(2.0f * x, 2.0f * y, 2.0f * z);
                for (int i = 0; i < segments; ++i)
                    for (int j = 0; j < segments; ++j) {
                        glm::vec3 a = point(c, i, j), b = point(c, i + 1, j), cc = point(c, i + 1, j + 1),
                                  d = point(c, i, j + 1);
                        if (i != segments - 1) triangles.push_back(Triangle{{a, b, cc}, {}, {}, 0, 0});
                        if (i != 0) triangles.push_back(Triangle{{a, cc, d}, {}, {}, 0, 0});
                    }
            }
    return triangles;
}

std::uint32_t bits(float f) { return std::bit_cast<std::uint32_t>(f); }

// Every triangle in exactly one leaf, children inside parents, leaf sizes in range, depth-first
// layout consistent. Returns the depth of the deepest leaf.
void checkInvariants(const Bvh& bvh, std::size_t triangleCount) {
    ASSERT_FALSE(bvh.nodes.empty());
    ASSERT_EQ(bvh.triangleOrder.size(), triangleCount);
    std::vector<int> seen(triangleCount, 0);
    for (std::uint32_t t : bvh.triangleOrder) {
        ASSERT_LT(t, triangleCount);
        seen[t] += 1;
    }
    for (int s : seen) ASSERT_EQ(s, 1);

    std::vector<int> covered(triangleCount, 0);
    std::uint32_t leaves = 0, maxDepth = 0;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> stack{{0u, 0u}};  // node, depth
    std::size_t visited = 0;
    while (!stack.empty()) {
        auto [index, depth] = stack.back();
        stack.pop_back();
        ASSERT_LT(index, bvh.nodes.size());
        ++visited;
        maxDepth = std::max(maxDepth, depth);
        const gpu::BvhNode& node = bvh.nodes[index];
        const std::uint32_t meta = bits(node.boundsMax.w), link = bits(node.boundsMin.w);
        if (meta & gpu::kInteriorNodeFlag) {
            ASSERT_LE(meta & ~gpu::kInteriorNodeFlag, 2u);
            ASSERT_GT(link, index + 1);
            for (std::uint32_t child : {index + 1, link}) {
                ASSERT_LT(child, bvh.nodes.size());
                for (int a = 0; a < 3; ++a) {
                    EXPECT_GE(bvh.nodes[child].boundsMin[a], node.boundsMin[a]);
                    EXPECT_LE(bvh.nodes[child].boundsMax[a], node.boundsMax[a]);
                }
                stack.push_back({child, depth + 1});
            }
        } else {
            ++leaves;
            ASSERT_GE(meta, 1u);
            ASSERT_LE(meta, gpu::kMaxLeafTriangles);
            ASSERT_LE(link + meta, triangleCount);
            for (std::uint32_t i = link; i < link + meta; ++i) covered[i] += 1;
        }
    }
    EXPECT_EQ(visited, bvh.nodes.size());
    for (int c : covered) ASSERT_EQ(c, 1);
    EXPECT_EQ(leaves, bvh.stats.leafCount);
    EXPECT_EQ(maxDepth, bvh.stats.maxDepth);
    EXPECT_LT(maxDepth + 2, gpu::kTraversalStackSize);
    EXPECT_EQ(bvh.stats.nodeCount, bvh.nodes.size());
}

// Leaf triangles inside their leaf's box.
void checkLeafBoxes(const Bvh& bvh, std::span<const gpu::TriangleVertices> packed) {
    for (const gpu::BvhNode& node : bvh.nodes) {
        const std::uint32_t meta = bits(node.boundsMax.w), link = bits(node.boundsMin.w);
        if (meta & gpu::kInteriorNodeFlag) continue;
        for (std::uint32_t i = link; i < link + meta; ++i)
            for (const glm::vec4& v : {packed[i].v0, packed[i].v1, packed[i].v2})
                for (int a = 0; a < 3; ++a) {
                    EXPECT_GE(v[a], node.boundsMin[a]);
                    EXPECT_LE(v[a], node.boundsMax[a]);
                }
    }
}

template <class Real>
std::optional<TriangleHit<Real>> bruteClosest(std::span<const gpu::TriangleVertices> tris, const Ray<Real>& ray) {
    std::optional<TriangleHit<Real>> best;
    Ray<Real> probe = ray;
    for (std::uint32_t i = 0; i < tris.size(); ++i)
        if (auto hit = intersectTriangle(tris[i], probe)) {
            hit->triangle = i;
            best = hit;
            probe.tMax = hit->t;
        }
    return best;
}

// Random rays from inside and around the mesh's box, compared with brute force.
template <class Real>
void checkAgainstBruteForce(const std::vector<Triangle>& triangles, int rayCount, std::uint32_t seed) {
    const Bvh bvh = buildBvh(triangles);
    const auto packed = packTriangleVertices(bvh, triangles);
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const Triangle& t : triangles)
        for (const glm::vec3& p : t.position) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
    const glm::vec3 centre = 0.5f * (lo + hi);
    const glm::vec3 half = 0.5f * (hi - lo) + glm::vec3(1e-3f);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    int hits = 0, mismatches = 0, anyMismatches = 0;
    TraversalCounters counters;
    for (int r = 0; r < rayCount; ++r) {
        const float spread = r % 2 == 0 ? 1.0f : 3.0f;  // half inside the box, half mostly outside
        const glm::vec3 o = centre + spread * half * glm::vec3(unit(rng), unit(rng), unit(rng));
        glm::vec3 d(unit(rng), unit(rng), unit(rng));
        if (r % 3 == 2) {
            // Aimed at a random triangle's centroid, so small or far-apart geometry gets hits too.
            const Triangle& t = triangles[std::uniform_int_distribution<std::size_t>(0, triangles.size() - 1)(rng)];
            d = (t.position[0] + t.position[1] + t.position[2]) / 3.0f - o;
        }
        if (r % 7 == 0) d[r % 3] = 0.0f;  // axis-parallel components: inf in the inverse direction
        if (glm::dot(d, d) == 0.0f) d = glm::vec3(0, 0, 1);
        Ray<Real> ray{glm::vec<3, Real>(o), glm::vec<3, Real>(glm::normalize(d))};
        if (r % 5 == 0) ray.tMax = Real(glm::length(hi - lo) * 0.3f);
        const auto expected = bruteClosest(std::span<const gpu::TriangleVertices>(packed), ray);
        const auto actual = traceClosest<Real>(bvh.nodes, packed, ray, &counters);
        ASSERT_EQ(expected.has_value(), actual.has_value()) << "ray " << r;
        if (expected) {
            ++hits;
            const bool sameTriangle = expected->triangle == actual->triangle;
            const Real tolerance = Real(1e-6) * std::max(Real(1), std::abs(expected->t));
            if (!sameTriangle) ++mismatches;
            EXPECT_TRUE(sameTriangle || std::abs(expected->t - actual->t) <= tolerance)
                << "ray " << r << ": t " << expected->t << " vs " << actual->t;
            EXPECT_NEAR(double(expected->t), double(actual->t), double(tolerance));
            if (sameTriangle) {
                EXPECT_EQ(expected->u, actual->u);
                EXPECT_EQ(expected->v, actual->v);
            }
        }
        if (traceAny<Real>(bvh.nodes, packed, ray) != expected.has_value()) ++anyMismatches;
    }
    EXPECT_EQ(anyMismatches, 0);
    EXPECT_GT(hits, rayCount / 20);  // the test is not vacuous
    std::cout << "    " << triangles.size() << " triangles, " << bvh.stats.nodeCount << " nodes, "
              << bvh.stats.leafCount << " leaves, depth " << bvh.stats.maxDepth << ", SAH cost " << bvh.stats.sahCost
              << ", build "
              << bvh.stats.buildSeconds * 1e3 << " ms, " << hits << "/" << rayCount << " rays hit, "
              << double(counters.nodeVisits) / rayCount << " nodes/ray, ties on other triangles " << mismatches
              << "\n";
}

void checkMesh(const std::vector<Triangle>& triangles, int rayCount) {
    const Bvh bvh = buildBvh(triangles);
    checkInvariants(bvh, triangles.size());
    checkLeafBoxes(bvh, packTriangleVertices(bvh, triangles));
    ::testing::Test::RecordProperty("triangles", std::to_string(triangles.size()));
    ::testing::Test::RecordProperty("nodes", std::to_string(bvh.stats.nodeCount));
    ::testing::Test::RecordProperty("sah_cost", std::to_string(bvh.stats.sahCost));
    checkAgainstBruteForce<float>(triangles, rayCount, 1234);
    checkAgainstBruteForce<double>(triangles, rayCount, 5678);
}

std::string coursePath(const std::string& name) {
    return std::string(VITRUM_SHARED_DIR) + "/scenes/course/" + name + "/" + name + ".obj";
}

// The share of triangles in the leaves made so far, now and then (every 1/256 of them and at the
// end), never backwards; the tree is the one built without listening.
TEST(Bvh, BuildReportsItsProgress) {
    const std::vector<Triangle> triangles = randomSoup(20000, 7);
    std::vector<double> fractions;
    const Bvh bvh = buildBvh(triangles, [&](double f) { fractions.push_back(f); });
    EXPECT_GE(fractions.size(), 128u);
    EXPECT_LE(fractions.size(), 20000u / 8u);
    EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
    EXPECT_GT(fractions.front(), 0.0);
    EXPECT_EQ(fractions.back(), 1.0);
    const Bvh quiet = buildBvh(triangles);
    EXPECT_EQ(bvh.triangleOrder, quiet.triangleOrder);
    EXPECT_EQ(bvh.stats.sahCost, quiet.stats.sahCost);
}

// Subtrees of 65,536 triangles and more are built by other threads and joined in depth-first
// order: the nodes and the triangle order are those one thread builds, byte for byte, whatever the
// number of threads (the SAH sums, added in another order, to rounding).
TEST(Bvh, ThreadsBuildTheTreeOneThreadBuilds) {
    for (const auto& triangles : {randomSoup(400'000, 11), sphereGrid(3, 80)}) {
        const Bvh one = buildBvh(triangles, {}, 1);
        ASSERT_GT(one.triangleOrder.size(), 300'000u);
        for (unsigned threads : {2u, 3u, 8u}) {
            SCOPED_TRACE(std::to_string(threads) + " threads");
            const Bvh many = buildBvh(triangles, {}, threads);
            ASSERT_EQ(many.nodes.size(), one.nodes.size());
            EXPECT_EQ(std::memcmp(many.nodes.data(), one.nodes.data(), one.nodes.size() * sizeof(gpu::BvhNode)), 0);
            EXPECT_EQ(many.triangleOrder, one.triangleOrder);
            EXPECT_EQ(many.stats.leafCount, one.stats.leafCount);
            EXPECT_EQ(many.stats.maxDepth, one.stats.maxDepth);
            EXPECT_EQ(many.stats.maxLeafTriangles, one.stats.maxLeafTriangles);
            EXPECT_NEAR(many.stats.sahCost, one.stats.sahCost, 1e-9 * one.stats.sahCost);
        }
    }
}

TEST(Bvh, RandomSoup) { checkMesh(randomSoup(5000, 42), 4000); }

TEST(Bvh, SphereGrid) { checkMesh(sphereGrid(4, 12), 3000); }

TEST(Bvh, CourseGeosphere) { checkMesh(readObjTriangles(coursePath("geosphere")), 4000); }

TEST(Bvh, CourseCornellBox) { checkMesh(readObjTriangles(coursePath("cornell_box2")), 4000); }

TEST(Bvh, CourseGeospheres5x5) {
    const auto triangles = readObjTriangles(coursePath("geospheres_5x5"));
    ASSERT_EQ(triangles.size(), 32000u);
    checkMesh(triangles, 1000);
}

TEST(Bvh, SingleTriangle) {
    std::vector<Triangle> one{Triangle{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}, {}, 3, 7}};
    const Bvh bvh = buildBvh(one);
    checkInvariants(bvh, 1);
    ASSERT_EQ(bvh.nodes.size(), 1u);
    const auto packed = packTriangleVertices(bvh, one);
    EXPECT_EQ(bits(packed[0].v0.w), 3u);
    EXPECT_EQ(bits(packed[0].v1.w), 7u);
    EXPECT_EQ(packed[0].v2.w, 0.0f);
    Ray<float> down{{0.25f, 0.25f, 1.0f}, {0.0f, 0.0f, -1.0f}};
    auto hit = traceClosest<float>(bvh.nodes, packed, down);
    ASSERT_TRUE(hit);
    EXPECT_FLOAT_EQ(hit->t, 1.0f);
    EXPECT_FLOAT_EQ(hit->u, 0.25f);
    EXPECT_FLOAT_EQ(hit->v, 0.25f);
    Ray<float> up{{0.25f, 0.25f, -1.0f}, {0.0f, 0.0f, 1.0f}};  // back face: hit too
    EXPECT_TRUE(traceAny<float>(bvh.nodes, packed, up));
    up.tMax = 0.5f;
    EXPECT_FALSE(traceAny<float>(bvh.nodes, packed, up));
    Ray<double> miss{{2.0, 2.0, 1.0}, {0.0, 0.0, -1.0}};
    EXPECT_FALSE(traceClosest<double>(bvh.nodes, packed, miss));
}

// Cut-out triangles (TraversalInput::cutouts): a hit the cut-outs reject is no hit for any of
// the three traversals, and only marked triangles are asked about, with their barycentrics.
TEST(Bvh, ACutAwayHitIsNoHitOfAnyTraversal) {
    // Two stacked triangles, the upper (z = 0) marked, cut where u < 1/2.
    std::vector<Triangle> two{Triangle{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}, {}, 0, 0},
                              Triangle{{{0, 0, -1}, {1, 0, -1}, {0, 1, -1}}, {}, {}, 0, 1}};
    const Bvh bvh = buildBvh(two);
    auto packed = packTriangleVertices(bvh, two);
    const std::uint32_t upper = bvh.triangleOrder[0] == 0 ? 0u : 1u;
    packed[upper].v2.w = std::bit_cast<float>(gpu::kTriangleCutout | 5u);
    struct HalfCut final : Cutouts {
        mutable std::vector<std::uint32_t> asked;
        bool cutAway(std::uint32_t triangle, std::uint32_t mark, float u, float) const override {
            asked.push_back(triangle);
            EXPECT_EQ(mark, gpu::kTriangleCutout | 5u);
            return u < 0.5f;
        }
        bool cutAway(std::uint32_t triangle, std::uint32_t mark, double u, double v) const override {
            return cutAway(triangle, mark, float(u), float(v));
        }
    } cutouts;
    const TraversalInput input{bvh.nodes, packed, {}, &cutouts};
    const Ray<float> throughTheCut{{0.25f, 0.25f, 1.0f}, {0.0f, 0.0f, -1.0f}};
    const Ray<float> onTheRest{{0.75f, 0.125f, 1.0f}, {0.0f, 0.0f, -1.0f}};
    const auto passing = traceClosest<float>(input, throughTheCut);
    ASSERT_TRUE(passing);
    EXPECT_EQ(passing->triangle, 1u - upper);
    EXPECT_FLOAT_EQ(passing->t, 2.0f);
    const auto stopped = traceClosest<double>(input, Ray<double>{{0.75, 0.125, 1.0}, {0.0, 0.0, -1.0}});
    ASSERT_TRUE(stopped);
    EXPECT_EQ(stopped->triangle, upper);
    Ray<float> shadow = throughTheCut;
    shadow.tMax = 1.5f;  // reaches the upper triangle only
    EXPECT_FALSE(traceAny<float>(input, shadow));
    shadow.origin = onTheRest.origin;
    EXPECT_TRUE(traceAny<float>(input, shadow));
    std::vector<TriangleHit<float>> hits;
    traceAll<float>(input, throughTheCut, hits);
    ASSERT_EQ(hits.size(), 1u);
    EXPECT_EQ(hits[0].triangle, 1u - upper);
    for (std::uint32_t asked : cutouts.asked) EXPECT_EQ(asked, upper) << "only the marked triangle is asked";
    EXPECT_FALSE(cutouts.asked.empty());
    // Without cut-outs the marked triangle is whole.
    EXPECT_EQ(traceClosest<float>(TraversalInput{bvh.nodes, packed}, throughTheCut)->triangle, upper);
}

// A ray going on through a partly covered surface (Ray::passCoveredBelow) passes by the triangles
// marked kTriangleCovered that it hits below its window, in every traversal; beyond the window,
// and unmarked triangles anywhere, it hits as any ray does.
TEST(Bvh, ARayPassingThroughACoveredSurfacePassesCoveredTrianglesByWithinItsWindow) {
    std::vector<Triangle> two{Triangle{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}, {}, 0, 0},
                              Triangle{{{0, 0, -1}, {1, 0, -1}, {0, 1, -1}}, {}, {}, 0, 1}};
    const Bvh bvh = buildBvh(two);
    auto packed = packTriangleVertices(bvh, two);
    const std::uint32_t upper = bvh.triangleOrder[0] == 0 ? 0u : 1u;
    packed[upper].v2.w = std::bit_cast<float>(gpu::kTriangleCovered);
    const TraversalInput input{bvh.nodes, packed};
    Ray<double> down{{0.25, 0.25, 1.0}, {0.0, 0.0, -1.0}};
    down.passCoveredBelow = 1.5;  // the upper triangle is met at t = 1, the lower at 2
    const auto passing = traceClosest<double>(input, down);
    ASSERT_TRUE(passing);
    EXPECT_EQ(passing->triangle, 1u - upper);
    EXPECT_DOUBLE_EQ(passing->t, 2.0);
    std::vector<TriangleHit<double>> hits;
    traceAll<double>(input, down, hits);
    ASSERT_EQ(hits.size(), 1u);
    EXPECT_EQ(hits[0].triangle, 1u - upper);
    down.passCoveredBelow = 0.5;  // crossed before the upper triangle
    EXPECT_EQ(traceClosest<double>(input, down)->triangle, upper);
    down.passCoveredBelow = 0.0;  // every other ray
    EXPECT_EQ(traceClosest<double>(input, down)->triangle, upper);
    packed[upper].v2.w = 0.0f;  // unmarked: hit within the window too
    down.passCoveredBelow = 1.5;
    EXPECT_EQ(traceClosest<double>(TraversalInput{bvh.nodes, packed}, down)->triangle, upper);
}

TEST(Bvh, Empty) {
    const Bvh bvh = buildBvh({});
    Ray<float> ray{{0, 0, -1}, {0, 0, 1}};
    EXPECT_FALSE(traceClosest<float>(bvh.nodes, {}, ray));
    EXPECT_FALSE(traceAny<float>(bvh.nodes, {}, ray));
}

TEST(Bvh, IdenticalTriangles) {
    std::vector<Triangle> same(1000, Triangle{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {}, {}, 0, 0});
    const Bvh bvh = buildBvh(same);
    checkInvariants(bvh, same.size());
    EXPECT_LE(bvh.stats.maxDepth, 12u);
    const auto packed = packTriangleVertices(bvh, same);
    Ray<float> down{{0.2f, 0.2f, 1.0f}, {0.0f, 0.0f, -1.0f}};
    auto hit = traceClosest<float>(bvh.nodes, packed, down);
    ASSERT_TRUE(hit);
    EXPECT_FLOAT_EQ(hit->t, 1.0f);
    checkAgainstBruteForce<float>(same, 500, 9);
}

TEST(Bvh, ZeroAreaTriangles) {
    // Points and segments mixed with a few real triangles: must build and ignore the degenerate ones.
    std::vector<Triangle> tris;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int i = 0; i < 500; ++i) {
        glm::vec3 p(u(rng), u(rng), u(rng)), q(u(rng), u(rng), u(rng));
        if (i % 3 == 0) tris.push_back(Triangle{{p, p, p}, {}, {}, 0, 0});
        else if (i % 3 == 1) tris.push_back(Triangle{{p, q, 0.5f * (p + q)}, {}, {}, 0, 0});
        else tris.push_back(Triangle{{p, q, glm::vec3(u(rng), u(rng), u(rng))}, {}, {}, 0, 0});
    }
    const Bvh bvh = buildBvh(tris);
    checkInvariants(bvh, tris.size());
    checkAgainstBruteForce<float>(tris, 2000, 11);
    checkAgainstBruteForce<double>(tris, 2000, 12);
    // All at one point: every centroid equal.
    std::vector<Triangle> points(300, Triangle{{{1, 2, 3}, {1, 2, 3}, {1, 2, 3}}, {}, {}, 0, 0});
    checkInvariants(buildBvh(points), points.size());
}

TEST(Bvh, DepthStaysBounded) {
    // Clusters at geometrically shrinking positions (16^-k along each axis in turn) make every
    // binned split peel off one cluster: SAH alone would build a list-like tree deeper than the
    // traversal stack. The builder must switch to median splits in time.
    std::vector<Triangle> tris;
    for (int k = 0; k < 36; ++k)
        for (int axis = 0; axis < 3; ++axis)
            for (int j = 0; j < 3; ++j) {
                glm::vec3 c(0.0f);
                c[axis] = std::ldexp(1.0f, -4 * k) * (1.0f + 0.01f * float(j));
                const float s = std::ldexp(1.0f, -4 * k - 8);
                tris.push_back(Triangle{{c, c + glm::vec3(s, 0, 0), c + glm::vec3(0, s, s)}, {}, {}, 0, 0});
            }
    const Bvh bvh = buildBvh(tris);
    checkInvariants(bvh, tris.size());
    EXPECT_GT(bvh.stats.maxDepth, 30u);  // the case is as deep as intended
    std::cout << "    " << tris.size() << " triangles, depth " << bvh.stats.maxDepth << "\n";
    // Rays at each triangle from a distance of its own scale (random rays from far away would
    // only test Moller-Trumbore's rounding on triangles 2^-140 wide). Deep leaves hold the tiny
    // triangles, so the deepest paths are walked.
    const auto packed = packTriangleVertices(bvh, tris);
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    for (std::uint32_t i = 0; i < packed.size(); ++i) {
        const glm::vec3 a(packed[i].v0), b(packed[i].v1), c(packed[i].v2);
        const glm::vec3 target = (a + b + c) / 3.0f;
        const float size = glm::length(b - a);
        if (size < 1e-15f) continue;  // det ~ size^2 would underflow float: no hit even by brute force
        const glm::vec3 o = target + 4.0f * size * glm::vec3(unit(rng), unit(rng), unit(rng) + 2.0f);
        Ray<float> ray{o, glm::normalize(target - o)};
        const auto expected = bruteClosest(std::span<const gpu::TriangleVertices>(packed), ray);
        const auto actual = traceClosest<float>(bvh.nodes, packed, ray);
        ASSERT_TRUE(expected && actual) << "triangle " << i;
        EXPECT_EQ(expected->t, actual->t) << "triangle " << i;
        EXPECT_TRUE(traceAny<float>(bvh.nodes, packed, ray));
    }
}

// Build time is a benchmark's business (machines are noisy), not a test's: this only checks that a
// 1M-triangle build stays shallow enough for the fixed traversal stack, and reports the time.
TEST(Bvh, MillionTriangleBuildFitsTheTraversalStack) {
    const auto triangles = randomSoup(1'000'000, 7);
    const Bvh bvh = buildBvh(triangles);
    std::cout << "    1M triangles: build " << bvh.stats.buildSeconds << " s, " << bvh.stats.nodeCount
              << " nodes, depth " << bvh.stats.maxDepth << ", SAH cost " << bvh.stats.sahCost << "\n";
    RecordProperty("build_seconds_1m", std::to_string(bvh.stats.buildSeconds));
    EXPECT_EQ(bvh.triangleOrder.size(), triangles.size());
    EXPECT_LT(bvh.stats.maxDepth + 2, gpu::kTraversalStackSize);
}

}  // namespace
}  // namespace vitrum
