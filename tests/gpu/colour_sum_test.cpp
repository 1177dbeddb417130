// A pixel's colour sum in fixed point (shaders/colour_sum.glsl) on lavapipe through
// tests/gpu/kernels/colour_sum_test.comp, against the same sums worked out with 64-bit integers here: each
// term is floor(c * 2^32) of the float c clamped to [0, 4294967040], NaN and negative terms are
// 0, and a sum past 2^64 - 1 stays at 2^64 - 1; signed sums (dispersion's negative channels) are
// two's complement, a negative term's floor(|c| * 2^32) subtracted, wrapping.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "test_kernels.h"
#include "gpu_test_support.h"

namespace vitrum::testing {
namespace {

using glm::vec3;

constexpr std::uint64_t kSaturated = std::numeric_limits<std::uint64_t>::max();

std::uint64_t termOf(float c) {
    if (!(c > 0.0f)) return 0;
    return std::uint64_t(std::ldexp(std::min(double(c), 4294967040.0), 32));  // exact: 24 bits, times 2^32
}

std::uint64_t saturatingAdd(std::uint64_t a, std::uint64_t b) { return a > kSaturated - b ? kSaturated : a + b; }

struct Case {
    std::string what;
    glm::u64vec3 start;
    std::vector<vec3> terms;
    std::uint32_t flags = 0;  // kColourSumSigned, kColourSumDoubleStart
};

ColourSumCase toGpu(const Case& c) {
    ColourSumCase g{};
    for (int k = 0; k < 3; ++k) {
        g.startLow[k] = std::uint32_t(c.start[k]);
        g.startHigh[k] = std::uint32_t(c.start[k] >> 32);
    }
    g.startLow.w = std::uint32_t(c.terms.size());
    g.startHigh.w = c.flags;
    for (std::size_t t = 0; t < c.terms.size(); ++t) g.terms[t] = glm::vec4(c.terms[t], 0.0f);
    return g;
}

glm::u64vec3 expectedSum(const Case& c) {
    glm::u64vec3 sum = c.start;
    for (const vec3& term : c.terms)
        for (int k = 0; k < 3; ++k) sum[k] = saturatingAdd(sum[k], termOf(term[k]));
    return sum;
}

// A signed case's sum: unsigned 64-bit arithmetic wraps as two's complement does.
glm::u64vec3 expectedSignedSum(const Case& c) {
    glm::u64vec3 sum = c.start;
    if (c.flags & gpu::kColourSumDoubleStart) sum += sum;
    for (const vec3& term : c.terms)
        for (int k = 0; k < 3; ++k) {
            const float magnitude = std::isnan(term[k]) ? 0.0f : std::fabs(term[k]);
            if (term[k] < 0.0f) sum[k] -= termOf(magnitude);
            else sum[k] += termOf(magnitude);
        }
    return sum;
}

double signedValue(std::uint64_t sum) { return std::ldexp(double(std::int64_t(sum)), -32); }

std::vector<ColourSumResult> evaluate(const std::vector<Case>& cases) {
    std::vector<ColourSumCase> gpuCases;
    for (const Case& c : cases) gpuCases.push_back(toGpu(c));
    const std::uint32_t before = testDevice().validationMessages();
    std::vector<ColourSumResult> results = evaluateColourSumsOnGpu(testDevice(), gpuCases);
    EXPECT_EQ(testDevice().validationMessages(), before) << "Vulkan validation messages in colour_sum_test.comp";
    return results;
}

glm::u64vec3 sumOf(const ColourSumResult& r) {
    glm::u64vec3 sum;
    for (int k = 0; k < 3; ++k) sum[k] = (std::uint64_t(r.high[k]) << 32) | r.low[k];
    return sum;
}

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

TEST(GlslColourSum, AddsTermsAsSixtyFourBitFixedPoint) {
    const std::vector<Case> cases = {
        {"a carry into the high word", {0, 0, 0}, {vec3(0.75f, 0.5f, 0.99999994f), vec3(0.75f, 0.5f, 0.99999994f)}},
        {"terms of many magnitudes", {0, 0, 0}, {vec3(1e-3f, 1.0f, 3e-7f), vec3(123.456f, 7e-5f, 0.1f),
                                                vec3(0.2f, 65536.5f, 2.0f), vec3(1e-9f, 1e-8f, 1e6f)}},
        {"the same terms in the opposite order", {0, 0, 0}, {vec3(1e-9f, 1e-8f, 1e6f), vec3(0.2f, 65536.5f, 2.0f),
                                                             vec3(123.456f, 7e-5f, 0.1f), vec3(1e-3f, 1.0f, 3e-7f)}},
        {"NaN and negative terms add nothing", {5, 6, 7}, {vec3(-1.0f, kNaN, 0.5f), vec3(kNaN, -0.0f, -kInf)}},
        {"terms below 2^-32 are truncated", {0, 0, 0}, {vec3(1e-10f, 3e-10f, 2.3283064e-10f)}},
        {"an infinite or huge term is clamped", {0, 0, 0}, {vec3(kInf, 1e20f, 4294967296.0f)}},
        {"a sum past 2^64 - 1 saturates", {0, 0, kSaturated - 5}, {vec3(1e20f, 4294967040.0f, 1e-9f), vec3(1e20f, 4294967040.0f, 1e-9f)}},
        {"a saturated sum stays saturated", {kSaturated, kSaturated, kSaturated}, {vec3(0.0f), vec3(1.0f, 0.5f, 1e-9f)}},
    };
    const std::vector<ColourSumResult> results = evaluate(cases);
    ASSERT_EQ(results.size(), cases.size());
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const glm::u64vec3 expected = expectedSum(cases[i]);
        for (int k = 0; k < 3; ++k) EXPECT_EQ(sumOf(results[i])[k], expected[k]) << cases[i].what << ", channel " << k;
    }
    // The worked examples: 0.75 + 0.75 = 1.5 is high word 1, low word 2^31.
    EXPECT_EQ(results[0].high.x, 1u);
    EXPECT_EQ(results[0].low.x, 0x80000000u);
    EXPECT_EQ(sumOf(results[1]), sumOf(results[2]));  // the order does not matter
    EXPECT_EQ(sumOf(results[4]), glm::u64vec3(0, 1, 1));  // 1e-10 * 2^32 = 0.43, 3e-10 * 2^32 = 1.29, 2^-32
    EXPECT_EQ(sumOf(results[5])[0], (std::uint64_t(1) << 63 << 1) - (std::uint64_t(1) << 40));  // 2^64 - 2^40
    EXPECT_EQ(sumOf(results[6]), glm::u64vec3(kSaturated));
}

// A float of 2^-8 or more is a whole number of 2^-32, so it comes back from the sum as itself;
// a sum of many comes back to within float rounding.
TEST(GlslColourSum, GivesBackTheColourItHolds) {
    const std::vector<Case> cases = {
        {"one term", {0, 0, 0}, {vec3(0.3f, 0.75f, 1234.5f)}},
        {"four terms", {0, 0, 0}, {vec3(0.1f), vec3(0.2f), vec3(1e-5f), vec3(3.0f)}},
    };
    const std::vector<ColourSumResult> results = evaluate(cases);
    ASSERT_EQ(results.size(), cases.size());
    EXPECT_EQ(vec3(results[0].colour), vec3(0.3f, 0.75f, 1234.5f));
    const double exact = double(expectedSum(cases[1]).x) / 4294967296.0;
    EXPECT_NEAR(exact, double(0.1f) + double(0.2f) + double(1e-5f) + 3.0, 4.0 / 4294967296.0);  // < 2^-32 a term
    // Half an ulp of 3.3 (1.2e-7) and the low word's rounding to float (0.3 * 2^-24).
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(results[1].colour[k], exact, 1.2e-7 + 1.8e-8);
}

// With dispersion a round's colour may be negative in a channel (render-model-decisions.md,
// "Dispersion"): the signed sum subtracts it, comes back negative where the sum is, and keeps the
// order of terms out of the result as the unsigned one does.
TEST(GlslColourSum, SignedSumsSubtractNegativeTermsInTwosComplement) {
    const std::uint32_t s = gpu::kColourSumSigned;
    const std::uint64_t minusOneAndAHalf = ~((std::uint64_t(3) << 31)) + 1;  // -1.5 in 32.32 fixed point
    const std::vector<Case> cases = {
        {"a negative term under a positive sum", {0, 0, 0}, {vec3(0.75f, 0.5f, 2.0f), vec3(-0.25f, -1.5f, -2.0f)}, s},
        {"negative sums", {0, 0, 0}, {vec3(-3.5f, -1e-3f, -1234.5f), vec3(-0.5f, 0.0f, 0.25f)}, s},
        {"the same terms in the opposite order", {0, 0, 0}, {vec3(-0.5f, 0.0f, 0.25f), vec3(-3.5f, -1e-3f, -1234.5f)}, s},
        {"NaN adds nothing, an infinite term is clamped, -0 subtracts nothing", {5, 6, 7},
         {vec3(kNaN, -kInf, -0.0f), vec3(kInf, 0.0f, kNaN)}, s},
        {"sums of sums wrap", {minusOneAndAHalf, 1, minusOneAndAHalf}, {vec3(1.0f, -1e-9f, 3.0f)},
         s | gpu::kColourSumDoubleStart},
    };
    const std::vector<ColourSumResult> results = evaluate(cases);
    ASSERT_EQ(results.size(), cases.size());
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const glm::u64vec3 expected = expectedSignedSum(cases[i]);
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(sumOf(results[i])[k], expected[k]) << cases[i].what << ", channel " << k;
            // Back to a float: exact where the sum is, else within the float's half ulp.
            const double value = signedValue(expected[k]);
            EXPECT_NEAR(results[i].colour[k], value, std::fabs(value) * 6e-8 + 1e-9) << cases[i].what << ", channel " << k;
        }
    }
    // The worked examples: 0.75 - 0.25 = 0.5, 0.5 - 1.5 = -1, 2 - 2 = 0; -3.5 - 0.5 = -4 exactly.
    EXPECT_EQ(vec3(results[0].colour), vec3(0.5f, -1.0f, 0.0f));
    EXPECT_EQ(results[1].colour.x, -4.0f);
    EXPECT_EQ(results[1].colour.z, -1234.25f);
    EXPECT_EQ(sumOf(results[1]), sumOf(results[2]));
    // (-1.5) + (-1.5) + 1 = -2: the doubled start wrapped past zero and back.
    EXPECT_EQ(results[4].colour.x, -2.0f);
    EXPECT_EQ(results[4].colour.z, 0.0f);
}

}  // namespace
}  // namespace vitrum::testing
