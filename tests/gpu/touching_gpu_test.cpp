// The touching-surface functions of shaders/touching.glsl, run on lavapipe through
// tests/gpu/kernels/touching_test.comp. They collect, during the closest-hit traversal, what the CPU
// reference finds with a second traversal (findTouchingCrossings in host/cpu/reference_renderer.cpp):
// for every other object than the hit's, its nearest glass crossing within the touching distance
// of the hit, nearest first, ties by object index (docs/render-model-decisions.md, "Touching
// objects"). The expectations below come from that rule, computed here over the whole sequence
// at once; the kernel sees the crossings one at a time, in traversal order, under a shrinking limit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "test_kernels.h"
#include "gpu_test_support.h"

namespace vitrum::testing {
namespace {

constexpr std::uint32_t kEntering = 0x80000000u;
constexpr float kTolerance = 1e-3f;  // the touching distance e of these cases

struct Crossing {
    std::uint32_t object;
    bool entering;
    float t;
};

// A closest-hit traversal meeting `crossings` in this order (all glass): each is handed over
// while it lies below the nearest hit so far plus e, as bvh.glsl does; the hit is the nearest
// (the first of equals).
TouchingCase traversalCase(const std::vector<Crossing>& crossings) {
    TouchingCase c{};
    float nearest = 3.0e38f;
    std::uint32_t hitObject = 0;
    std::uint32_t handed = 0;
    for (const Crossing& x : crossings) {
        const float limit = nearest + kTolerance;
        if (x.t >= limit) continue;  // the traversal never hands it over
        glm::uvec4& objects = handed < 4 ? c.objects0 : c.objects1;
        glm::vec4& ts = handed < 4 ? c.t0 : c.t1;
        glm::vec4& limits = handed < 4 ? c.limit0 : c.limit1;
        objects[handed % 4] = x.object | (x.entering ? kEntering : 0u);
        ts[handed % 4] = x.t;
        limits[handed % 4] = limit;
        handed += 1;
        if (x.t < nearest) {
            nearest = x.t;
            hitObject = x.object;
        }
    }
    c.control = glm::uvec4(handed, hitObject, 0, 0);
    c.hit = glm::vec4(nearest + kTolerance, nearest, 0.0f, 0.0f);
    return c;
}

struct Expected {
    std::vector<std::uint32_t> touching;  // object | entering << 31, nearest first
    float farthest;
};

// The rule, from the whole sequence: per other object its nearest crossing below t + e (the
// first of equals), sorted by (t, object), at most 3.
Expected expectedTouching(const std::vector<Crossing>& crossings) {
    float nearest = 3.0e38f;
    std::uint32_t hitObject = 0;
    for (const Crossing& x : crossings)
        if (x.t < nearest) {
            nearest = x.t;
            hitObject = x.object;
        }
    std::vector<Crossing> others;
    for (const Crossing& x : crossings) {
        if (x.object == hitObject || x.t >= nearest + kTolerance) continue;
        auto known = std::find_if(others.begin(), others.end(), [&](const Crossing& o) { return o.object == x.object; });
        if (known == others.end()) others.push_back(x);
        else if (x.t < known->t) *known = x;
    }
    std::sort(others.begin(), others.end(),
              [](const Crossing& a, const Crossing& b) { return a.t < b.t || (a.t == b.t && a.object < b.object); });
    if (others.size() > 3) others.resize(3);
    Expected e{{}, nearest};
    for (const Crossing& o : others) {
        e.touching.push_back(o.object | (o.entering ? kEntering : 0u));
        e.farthest = std::max(e.farthest, o.t);
    }
    return e;
}

std::vector<TouchingResult> evaluate(const std::vector<TouchingCase>& cases) {
    const std::uint32_t before = testDevice().validationMessages();
    std::vector<TouchingResult> results = evaluateTouchingOnGpu(testDevice(), cases);
    EXPECT_EQ(testDevice().validationMessages(), before) << "Vulkan validation messages in touching_test.comp";
    EXPECT_EQ(results.size(), cases.size());
    return results;
}

TouchingResult evaluateOne(const std::vector<Crossing>& crossings) {
    return evaluate({traversalCase(crossings)}).at(0);
}

std::vector<std::uint32_t> touchingOf(const TouchingResult& r) {
    std::vector<std::uint32_t> objects;
    for (std::uint32_t i = 0; i < std::min(r.touching.w, 3u); ++i) objects.push_back(r.touching[i]);
    return objects;
}

TEST(GlslTouching, AnotherObjectJustBeyondTheHitTouchesIt) {
    // Leaving cube 1 at t = 2 and entering cube 2 at 2 + e/2: one interface (lecture, P2).
    const TouchingResult r = evaluateOne({{1, false, 2.0f}, {2, true, 2.0f + 0.5f * kTolerance}});
    EXPECT_EQ(touchingOf(r), std::vector<std::uint32_t>({2u | kEntering}));
    EXPECT_EQ(r.farthest.x, 2.0f + 0.5f * kTolerance);
    EXPECT_EQ(r.counts.x, 0u);
}

TEST(GlslTouching, SurfacesBeyondTheToleranceOrOfTheHitObjectDoNotTouch) {
    // Object 2 beyond t + e; the hit's own object at an edge (two triangles, the same t).
    const TouchingResult r = evaluateOne({{1, true, 2.0f}, {1, true, 2.0f}, {2, true, 2.0f + 2.0f * kTolerance}});
    EXPECT_EQ(r.touching.w, 0u);
    EXPECT_EQ(r.farthest.x, 2.0f);
}

TEST(GlslTouching, AnObjectKeepsItsNearestCrossing) {
    // Object 2 is met leaving, then nearer entering: the nearer crossing decides.
    const TouchingResult r =
        evaluateOne({{1, true, 2.0f}, {2, false, 2.0f + 0.8f * kTolerance}, {2, true, 2.0f + 0.2f * kTolerance}});
    EXPECT_EQ(touchingOf(r), std::vector<std::uint32_t>({2u | kEntering}));
    EXPECT_EQ(r.farthest.x, 2.0f + 0.2f * kTolerance);
}

TEST(GlslTouching, CandidatesBeyondANearerHitFoundLaterAreDropped) {
    // Objects 2 and 3 lie within e of the first hit (object 1 at t = 5) but not of the nearer
    // one found after them (object 4 at t = 4): neither touches. Their slots are free again for
    // objects 5, 6 and 7, so nothing overflows.
    const TouchingResult r = evaluateOne({{1, true, 5.0f},
                                          {2, true, 5.0f + 0.5f * kTolerance},
                                          {3, true, 5.0f + 0.6f * kTolerance},
                                          {4, true, 4.0f},
                                          {5, true, 4.0f + 0.3f * kTolerance},
                                          {6, false, 4.0f + 0.1f * kTolerance},
                                          {7, true, 4.0f + 0.2f * kTolerance}});
    EXPECT_EQ(touchingOf(r), std::vector<std::uint32_t>({6u, 7u | kEntering, 5u | kEntering}));
    EXPECT_EQ(r.farthest.x, 4.0f + 0.3f * kTolerance);
    EXPECT_EQ(r.counts.x, 0u);
}

TEST(GlslTouching, EqualDistancesAreOrderedByObject) {
    const float t = 3.0f + 0.5f * kTolerance;
    const TouchingResult r = evaluateOne({{9, true, 3.0f}, {7, true, t}, {2, false, t}, {4, true, t}});
    EXPECT_EQ(touchingOf(r), std::vector<std::uint32_t>({2u, 4u | kEntering, 7u | kEntering}));
}

TEST(GlslTouching, AFourthTouchingObjectIsCountedAndTheNearestThreeKept) {
    // Objects 2..5 all within e of the hit of object 1: four slots hold the hit's and three
    // others; the farthest of the five is dropped and counted as a medium-stack overflow.
    const TouchingResult r = evaluateOne({{1, true, 1.0f},
                                          {2, true, 1.0f + 0.4f * kTolerance},
                                          {3, true, 1.0f + 0.9f * kTolerance},
                                          {4, true, 1.0f + 0.6f * kTolerance},
                                          {5, true, 1.0f + 0.1f * kTolerance}});
    EXPECT_EQ(touchingOf(r), std::vector<std::uint32_t>({5u | kEntering, 2u | kEntering, 4u | kEntering}));
    EXPECT_EQ(r.counts.x, 1u);
}

TEST(GlslTouching, RandomTraversalsMatchTheRule) {
    // Up to 8 crossings of up to 4 objects within 3e of one another, in random order: the
    // kernel, seeing them one at a time under the shrinking limit, keeps what the rule gives.
    std::mt19937 random(20261201u);
    std::uniform_int_distribution<int> count(1, 8), object(1, 4), side(0, 1);
    std::uniform_real_distribution<float> offset(0.0f, 3.0f * kTolerance);
    std::vector<std::vector<Crossing>> sequences;
    std::vector<TouchingCase> cases;
    for (int i = 0; i < 2000; ++i) {
        std::vector<Crossing> crossings;
        for (int k = count(random); k > 0; --k)
            crossings.push_back({std::uint32_t(object(random)), side(random) == 1, 10.0f + offset(random)});
        sequences.push_back(crossings);
        cases.push_back(traversalCase(crossings));
    }
    const std::vector<TouchingResult> results = evaluate(cases);
    std::size_t withTouching = 0;
    for (std::size_t i = 0; i < results.size(); ++i) {
        const Expected e = expectedTouching(sequences[i]);
        ASSERT_EQ(touchingOf(results[i]), e.touching) << "sequence " << i;
        ASSERT_EQ(results[i].farthest.x, e.farthest) << "sequence " << i;
        ASSERT_EQ(results[i].counts.x, 0u) << "sequence " << i;  // four objects fit the slots
        if (!e.touching.empty()) withTouching += 1;
    }
    EXPECT_GT(withTouching, results.size() / 2);  // the sweep exercises the touching cases
}

}  // namespace
}  // namespace vitrum::testing
