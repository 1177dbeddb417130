// The search for glass surfaces close enough to touch (analysis/glass_proximity.h): the
// separating-axis test on pairs whose distance is known by construction, its soundness on random
// pairs against sampled distances, and the search on built and project scenes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <utility>

#include "glass_scenes.h"
#include "analysis/double_box.h"
#include "analysis/glass_proximity.h"
#include "scene/scene_loader.h"

namespace vitrum {
namespace {

using Corners = glm::dvec3[3];

// Whether the test keeps a and b apart at a distance a little below and a little above `gap`,
// their true distance: it must at the first, and must not at the second.
void expectApartBelowTheGap(const Corners& a, const Corners& b, double gap) {
    EXPECT_TRUE(trianglesApart(a, b, gap * 0.99)) << "gap " << gap;
    EXPECT_FALSE(trianglesApart(a, b, gap * 1.01)) << "gap " << gap;
    EXPECT_TRUE(trianglesApart(b, a, gap * 0.99)) << "the pair the other way round";
    EXPECT_FALSE(trianglesApart(b, a, gap * 1.01)) << "the pair the other way round";
}

TEST(GlassProximity, TheSweepOverBoxesFindsEveryPairThatComparingAllPairsFinds) {
    // 600 boxes of random sizes in a 10-wide cube, some long and thin along x (so that a box's x
    // range covers many others'), some flat, two equal: the pairs within the margin are exactly
    // those that comparing every two finds, each once, the lower index first.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> position(0.0, 10.0), size(0.0, 0.6);
    std::vector<DoubleBox> boxes;
    for (int i = 0; i < 600; ++i) {
        const glm::dvec3 lo(position(rng), position(rng), position(rng));
        glm::dvec3 extent(size(rng), size(rng), size(rng));
        if (i % 50 == 0) extent.x = 8.0;
        if (i % 7 == 0) extent.z = 0.0;
        DoubleBox box;
        box.grow(lo);
        box.grow(lo + extent);
        boxes.push_back(box);
    }
    boxes.push_back(boxes[10]);
    for (const double margin : {0.0, 0.05, 0.5}) {
        std::set<std::pair<std::size_t, std::size_t>> expected, found;
        for (std::size_t i = 0; i < boxes.size(); ++i)
            for (std::size_t j = i + 1; j < boxes.size(); ++j)
                if (boxes[i].within(boxes[j], margin)) expected.insert({i, j});
        std::size_t calls = 0;
        forEachBoxPairWithin(boxes, margin, [&](std::size_t i, std::size_t j) {
            ++calls;
            EXPECT_LT(i, j);
            found.insert({i, j});
        });
        EXPECT_EQ(found, expected) << "margin " << margin;
        EXPECT_EQ(calls, expected.size()) << "margin " << margin;
        EXPECT_GT(expected.size(), 30u);  // the boxes do meet one another (measured: 40 to 61 and more)
    }
}

TEST(GlassProximity, ParallelTrianglesAreApartByTheirPlanesDistance) {
    const Corners a = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const Corners b = {{0.2, 0.2, 0.5}, {1.2, 0.2, 0.5}, {0.2, 1.2, 0.5}};
    expectApartBelowTheGap(a, b, 0.5);
}

TEST(GlassProximity, TrianglesSideBySideInOnePlaneAreApartByTheirGap) {
    // Only an axis in the common plane separates them (the normals and the edges' cross products
    // are all perpendicular to it).
    const Corners a = {{-1, 0, 0}, {0, 0, 0}, {0, 1, 0}};
    const Corners b = {{0.25, 0, 0}, {1.25, 0, 0}, {0.25, 1, 0}};
    expectApartBelowTheGap(a, b, 0.25);
}

TEST(GlassProximity, CrossedEdgesAreApartByTheirDistance) {
    // A's edge along x at z = 0 passes under B's edge along y at z = 0.3; the rest of A lies below,
    // the rest of B above. Neither normal separates them, the cross product of the two edges does.
    const Corners a = {{-1, 0, 0}, {1, 0, 0}, {0, -1, -1}};
    const Corners b = {{0, -1, 0.3}, {0, 1, 0.3}, {1, 0, 1.3}};
    expectApartBelowTheGap(a, b, 0.3);
}

TEST(GlassProximity, CornersFacingEachOtherAreApartByTheirDistance) {
    // The closest points are a corner of each: no normal or edge cross product is their direction.
    const glm::dvec3 diagonal = glm::normalize(glm::dvec3(1, 1, 1));
    const Corners a = {{0, 0, 0}, {-1, -0.2, -0.5}, {-0.3, -1, -0.4}};
    const Corners b = {diagonal * 0.2, diagonal * 0.2 + glm::dvec3(1, 0.3, 0.5), diagonal * 0.2 + glm::dvec3(0.4, 1, 0.2)};
    expectApartBelowTheGap(a, b, 0.2);
}

TEST(GlassProximity, ACornerBesideAnEdgeIsApartByItsDistanceToTheEdge) {
    // b's corner lies 0.1 off the middle of a's edge along x, in a's plane and away from a.
    const Corners a = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}};
    const Corners b = {{0, 0.1, 0}, {-0.5, 1, 0.7}, {0.5, 1, -0.7}};
    expectApartBelowTheGap(a, b, 0.1);
}

TEST(GlassProximity, IntersectingOrSharedTrianglesAreNeverApart) {
    const Corners a = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    const Corners piercing = {{0, 0, -1}, {0, 0.2, 1}, {0.1, -0.3, 1}};
    const Corners shared = {{-1, -1, 0}, {1, -1, 0}, {0, -3, 0}};  // one edge in common
    EXPECT_FALSE(trianglesApart(a, piercing, 0.0));
    EXPECT_FALSE(trianglesApart(a, shared, 0.0));
    EXPECT_FALSE(trianglesApart(a, a, 0.0));
}

TEST(GlassProximity, DegenerateTrianglesAreStillSeparatedByTheOthersPlane) {
    const Corners point = {{0.2, 0.2, 0.4}, {0.2, 0.2, 0.4}, {0.2, 0.2, 0.4}};
    const Corners segment = {{0.1, 0.1, 0.4}, {0.5, 0.2, 0.4}, {0.3, 0.15, 0.4}};  // collinear
    const Corners a = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    expectApartBelowTheGap(a, point, 0.4);
    expectApartBelowTheGap(a, segment, 0.4);
}

// Sound: a pair the test keeps apart at distance d is farther apart than d. Points sampled on
// both triangles give an upper bound on their distance, so a sampled pair of points within d
// of each other would prove the test wrong. And exact: a pair it does not keep apart is within
// d, so the sampled distance is within d plus the sampling's step.
TEST(GlassProximity, ApartIsNeverSaidOfTrianglesWithinTheDistance) {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
    auto triangle = [&](Corners& t, const glm::dvec3& offset) {
        for (glm::dvec3& p : t) p = offset + glm::dvec3(coordinate(random), coordinate(random), coordinate(random));
    };
    auto sampledDistance = [](const Corners& a, const Corners& b) {
        constexpr int kSteps = 24;
        constexpr double kStep = 1.0 / kSteps;
        double best = std::numeric_limits<double>::max();
        std::vector<glm::dvec3> pointsOfB;
        for (int i = 0; i <= kSteps; ++i)
            for (int j = 0; i + j <= kSteps; ++j)
                pointsOfB.push_back(b[0] + (b[1] - b[0]) * (i * kStep) + (b[2] - b[0]) * (j * kStep));
        for (int i = 0; i <= kSteps; ++i)
            for (int j = 0; i + j <= kSteps; ++j) {
                const glm::dvec3 p = a[0] + (a[1] - a[0]) * (i * kStep) + (a[2] - a[0]) * (j * kStep);
                for (const glm::dvec3& q : pointsOfB) best = std::min(best, glm::length(p - q));
            }
        return best;
    };
    // How far a point of either triangle can be from the nearest sampled one.
    auto step = [](const Corners& a, const Corners& b) {
        double longest = 0.0;
        for (const Corners* t : {&a, &b})
            for (int i = 0; i < 3; ++i) longest = std::max(longest, glm::length((*t)[(i + 1) % 3] - (*t)[i]));
        return longest / 24.0;
    };
    int apart = 0, close = 0;
    for (int n = 0; n < 400; ++n) {
        Corners a, b;
        triangle(a, glm::dvec3(0.0));
        triangle(b, glm::dvec3(coordinate(random), coordinate(random), coordinate(random)));
        const double sampled = sampledDistance(a, b);
        for (double d : {0.05, 0.2, 0.5}) {
            if (trianglesApart(a, b, d)) {
                ++apart;
                EXPECT_GT(sampled, d) << "pair " << n << " is said apart at " << d;
            } else {
                ++close;
                EXPECT_LE(sampled, d + 2.0 * step(a, b)) << "pair " << n << " is not said apart at " << d;
            }
        }
    }
    // Both answers were given often enough for the check to mean something.
    EXPECT_GT(apart, 100);
    EXPECT_GT(close, 100);
}

TEST(GlassProximity, BoxesAreCloseExactlyWhenTheirGapIsWithinTheDistance) {
    for (const auto& [gap, close] : {std::pair{1e-3f, true}, std::pair{3e-3f, false}}) {
        Scene scene = glassScene();
        addGlassBox(scene, {0, 0, 0}, {2, 2, 2});
        addGlassBox(scene, {2 + gap, 0.5f, 0.5f}, {4, 1.5f, 1.5f});
        const CloseTriangles found = findCloseGlassTriangles(scene, 2e-3);
        EXPECT_EQ(found.found, close) << "gap " << gap;
        EXPECT_FALSE(found.gaveUp);
    }
}

TEST(GlassProximity, NestedBoxesApartAreNotClose) {
    // A box inside another, 0.1 from each face: nested, never touching.
    Scene scene = glassScene();
    addGlassBox(scene, {0, 0, 0}, {1, 1, 1});
    addGlassBox(scene, {0.1f, 0.1f, 0.1f}, {0.9f, 0.9f, 0.9f});
    EXPECT_FALSE(findCloseGlassTriangles(scene, 0.05).found);
    EXPECT_TRUE(findCloseGlassTriangles(scene, 0.15).found);
}

// Triangles shrunk to one point each (a fuzzed OBJ of "v 0 1 0" only): at distance 0 two of them
// at the same place lie within it, and elsewhere they do not. The search's grid has no extent to
// divide then: cells of size 0 made 0 / 0, a NaN turned into a cell index, which is undefined
// behaviour that the release build happens to survive with the same answer, so it is this test
// and the fuzz regression obj_mtl/glass_triangles_all_one_point under `make sanitize` (with
// float-cast-overflow) that fail without the fix.
TEST(GlassProximity, TrianglesThatArePointsAreCloseOnlyWhereTheyCoincide) {
    for (const auto& [second, close] : {std::pair{glm::vec3(0, 1, 0), true}, std::pair{glm::vec3(0, 2, 0), false}}) {
        Scene scene = glassScene();
        for (const glm::vec3& point : {glm::vec3(0, 1, 0), second}) {
            Triangle t;
            t.position[0] = t.position[1] = t.position[2] = point;
            t.object = std::uint32_t(scene.objectNames.size());
            scene.objectNames.push_back("point");
            scene.triangles.push_back(t);
        }
        const CloseTriangles found = findCloseGlassTriangles(scene, 0.0);
        EXPECT_EQ(found.found, close) << "second point at " << second.y;
        EXPECT_EQ(found.examinedPairs, close ? 1u : 0u);
    }
}

TEST(GlassProximity, ALargeFaceOverAFineSheetIsPairedWithEveryTriangle) {
    // The large quad covers far more grid cells than the sheet's small triangles: it is paired
    // with all of them rather than put in each cell.
    for (const auto& [height, close] : {std::pair{0.004f, true}, std::pair{0.02f, false}}) {
        Scene scene = glassScene();
        addGlassSheet(scene, 40, 1.0f, 0.0f);
        addGlassSheet(scene, 1, 1.0f, height);
        EXPECT_EQ(findCloseGlassTriangles(scene, 0.01).found, close) << "height " << height;
    }
}

TEST(GlassProximity, GivesUpAsCloseBeyondItsBoundOnPairs) {
    // Two parallel sheets 0.03 apart, both turned 45 degrees about y: their triangles' boxes
    // overlap, so many pairs are looked at, and none is within 0.02.
    Scene scene = glassScene();
    addGlassSheet(scene, 20, 1.0f, 0.0f);
    addGlassSheet(scene, 20, 1.0f, 0.03f);
    const float c = std::sqrt(0.5f);
    for (Triangle& t : scene.triangles)
        for (glm::vec3& p : t.position) p = glm::vec3(c * p.x + c * p.z, p.y, -c * p.x + c * p.z);
    const CloseTriangles full = findCloseGlassTriangles(scene, 0.02);
    EXPECT_FALSE(full.found);
    EXPECT_GT(full.examinedPairs, 100u);
    EXPECT_TRUE(findCloseGlassTriangles(scene, 0.04).found);
    const CloseTriangles bounded = findCloseGlassTriangles(scene, 0.02, 100);
    EXPECT_TRUE(bounded.found);
    EXPECT_TRUE(bounded.gaveUp);
}

TEST(GlassProximity, ProjectScenes) {
    auto close = [](const std::string& file) {
        const Scene scene = loadScene(std::string(VITRUM_SOURCE_DIR) + "/scenes/" + file);
        return findCloseGlassTriangles(scene, 1e-3).found;
    };
    EXPECT_TRUE(close("touching_cubes.json"));  // two cubes sharing a face
    EXPECT_TRUE(close("water_glass.json"));     // water filling a glass
    EXPECT_FALSE(close("bubble.json"));         // a bubble well inside a block
    EXPECT_FALSE(close("demo.json"));
}

}  // namespace
}  // namespace vitrum
