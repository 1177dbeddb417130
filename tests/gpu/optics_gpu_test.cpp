// The GLSL optics functions (shaders/optics.glsl) run on lavapipe through tests/gpu/kernels/optics_test.comp,
// held to the same numbers as the CPU versions in tests/core/reference_renderer_test.cpp: the
// lecture's worked example (../shared/seed/dielectrics-lecture.txt, "Example with real numbers"),
// hand calculations, and a property sweep of random cases against host/cpu/optics.h in float.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <vector>

#include "cpu/optics.h"
#include "test_kernels.h"
#include "gpu_test_support.h"

namespace vitrum::testing {
namespace {

using glm::vec3;

constexpr double kDegrees = 180.0 / 3.14159265358979323846;

OpticsCase makeCase(vec3 d, vec3 n, float n1, float n2, vec3 mu = vec3(0.0f), float t = 0.0f) {
    return OpticsCase{
        .direction = glm::vec4(d, 0.0f),
        .normal = glm::vec4(n, 0.0f),
        .media = glm::vec4(n1, n2, t, 0.0f),
        .attenuation = glm::vec4(mu, 0.0f),
    };
}


OpticsResult evaluateOne(const OpticsCase& c) { return evaluateOptics({c}).at(0); }

vec3 xyz(const glm::vec4& v) { return vec3(v); }

// The lecture prints d = (-0.429, -0.903, 0) rounded; it comes from theta1 = 25.391 deg, which
// the example also prints (same choice as the CPU test). Computed in double, rounded once.
vec3 lectureDirection() {
    const double theta1 = 25.391 / kDegrees;
    return vec3(float(-std::sin(theta1)), float(-std::cos(theta1)), 0.0f);
}
const vec3 kUp(0.0f, 1.0f, 0.0f);

// Lecture example: n1 = 1.5 (glass), n2 = 1 (air).
OpticsCase lectureCase() { return makeCase(lectureDirection(), kUp, 1.5f, 1.0f); }

// ---- The lecture's worked example -------------------------------------------------------------

TEST(GlslOptics, RefractionMatchesLectureExample) {
    // n1 = 1.5, n2 = 1, d = (-0.429, -0.903, 0), n = (0, 1, 0): l = (-0.643, -0.766, 0),
    // theta2 = 40.03 deg.
    const OpticsResult r = evaluateOne(lectureCase());
    ASSERT_GE(r.refracted.w, 0.0f) << "no total internal reflection at 25.4 deg";
    const vec3 l = xyz(r.refracted);
    EXPECT_NEAR(l.x, -0.643, 5e-4);
    EXPECT_NEAR(l.y, -0.766, 5e-4);
    EXPECT_NEAR(l.z, 0.0, 1e-7);
    EXPECT_NEAR(glm::length(l), 1.0, 1e-6);
    EXPECT_NEAR(std::acos(-double(l.y)) * kDegrees, 40.03, 5e-3);
    // cos2t is cos^2(theta2).
    EXPECT_NEAR(std::sqrt(r.refracted.w), 0.766, 5e-4);
    // Snell: n1 sin(theta1) = n2 sin(theta2) = 0.643.
    const vec3 d = lectureDirection();
    EXPECT_NEAR(1.5 * std::sqrt(1.0 - double(d.y) * d.y), 1.0 * std::sqrt(1.0 - double(l.y) * l.y), 1e-6);
}

TEST(GlslOptics, ReflectionMatchesLectureExample) {
    // r = d - 2 (d.n) n = (-0.429, 0.903, 0).
    const std::vector<OpticsResult> r = evaluateOptics({lectureCase(), makeCase(lectureDirection(), -kUp, 1.5f, 1.0f)});
    const vec3 reflected = xyz(r[0].reflected);
    EXPECT_NEAR(reflected.x, -0.429, 5e-4);
    EXPECT_NEAR(reflected.y, 0.903, 5e-4);
    EXPECT_NEAR(reflected.z, 0.0, 1e-7);
    EXPECT_NEAR(glm::length(reflected), 1.0, 1e-6);
    // "Note that the orientation of n is not important here."
    EXPECT_EQ(xyz(r[1].reflected), reflected);
}

TEST(GlslOptics, FresnelExactMatchesLectureExample) {
    // Rs = 0.077, Rp = 0.014, R = (Rs + Rp) / 2 = 0.046, 1 - R = 0.954. optics.glsl folds Rs and Rp
    // into R, so the GPU is checked on R; Rs and Rp themselves come from the CPU's fresnelTerms.
    const OpticsResult r = evaluateOne(lectureCase());
    const float exact = r.reflectance.y;
    EXPECT_NEAR(exact, 0.046, 5e-4);
    EXPECT_NEAR(1.0 - exact, 0.954, 5e-4);
    EXPECT_NEAR(exact, (0.077 + 0.014) / 2.0, 5e-4);
    const double cosI = -double(lectureDirection().y);
    const auto terms = optics::fresnelTerms(1.5, 1.0, cosI, *optics::cosTransmitted(1.5, 1.0, cosI));
    EXPECT_NEAR(terms.rs, 0.077, 5e-4);
    EXPECT_NEAR(terms.rp, 0.014, 5e-4);
    EXPECT_NEAR(exact, 0.5 * (terms.rs + terms.rp), 1e-6);
}

// ---- Physics ----------------------------------------------------------------------------------

TEST(GlslOptics, TotalInternalReflectionGivesFullReflectance) {
    // From glass to air beyond the critical angle (41.8 deg): sin(theta1) = 0.8. Lecture: "when TIR
    // occurs we should return 1", for every model.
    const OpticsResult r = evaluateOne(makeCase(vec3(0.8f, -0.6f, 0.0f), kUp, 1.5f, 1.0f));
    EXPECT_LT(r.refracted.w, 0.0f);
    EXPECT_EQ(r.reflectance.x, 1.0f);
    EXPECT_EQ(r.reflectance.y, 1.0f);
    EXPECT_EQ(r.reflectance.z, 1.0f);
    // Just inside and just beyond the critical angle, sin(theta1) = 1 / 1.5 -+ 1e-3.
    const float sinCritical = 1.0f / 1.5f;
    const auto at = [&](float sinTheta) {
        return makeCase(vec3(sinTheta, -std::sqrt(1.0f - sinTheta * sinTheta), 0.0f), kUp, 1.5f, 1.0f);
    };
    const std::vector<OpticsResult> near = evaluateOptics({at(sinCritical - 1e-3f), at(sinCritical + 1e-3f)});
    EXPECT_GT(near[0].refracted.w, 0.0f);
    EXPECT_LT(near[0].reflectance.y, 1.0f);
    EXPECT_NEAR(glm::length(xyz(near[0].refracted)), 1.0, 1e-5);
    EXPECT_LT(near[1].refracted.w, 0.0f);
    EXPECT_EQ(near[1].reflectance.x, 1.0f);
    EXPECT_EQ(near[1].reflectance.y, 1.0f);
    EXPECT_EQ(near[1].reflectance.z, 1.0f);
}

TEST(GlslOptics, ReversedRefractionReturnsTheIncomingDirection) {
    // Lecture: "What happens when we reverse the direction ... it doesn't matter". Refract d from
    // n1 = 1.5 into n2 = 1 to get l; then -l refracted from n2 back into n1 gives -d.
    const OpticsResult forward = evaluateOne(lectureCase());
    const vec3 l = xyz(forward.refracted);
    const OpticsResult back = evaluateOne(makeCase(-l, -kUp, 1.0f, 1.5f));
    ASSERT_GE(back.refracted.w, 0.0f);
    EXPECT_NEAR(glm::length(xyz(back.refracted) + lectureDirection()), 0.0, 1e-6);
    // The reflectance is the same both ways (Schlick takes theta_t going out and theta_i coming
    // in, which are the same angle here; the exact equations are reciprocal).
    EXPECT_NEAR(back.reflectance.x, forward.reflectance.x, 1e-6);
    EXPECT_NEAR(back.reflectance.y, forward.reflectance.y, 1e-6);
    EXPECT_NEAR(back.reflectance.z, forward.reflectance.z, 1e-6);
}

TEST(GlslOptics, RefractionAtNormalIncidenceGoesStraight) {
    // The final formula never divides by sin(theta1), which is 0 here.
    const std::vector<OpticsResult> r = evaluateOptics(
        {makeCase(vec3(0, 0, -1), vec3(0, 0, 1), 1.0f, 1.5f), makeCase(vec3(0, 0, -1), vec3(0, 0, 1), 1.5f, 1.0f)});
    for (const OpticsResult& result : r) {
        EXPECT_NEAR(glm::length(xyz(result.refracted) - vec3(0, 0, -1)), 0.0, 1e-6);
        EXPECT_EQ(result.refracted.w, 1.0f);  // cos^2(theta2) = 1 exactly: 1 - eta^2 (1 - 1)
        EXPECT_EQ(xyz(result.reflected), vec3(0, 0, 1));
    }
}

TEST(GlslOptics, SchlickMatchesExactAtNormalIncidence) {
    // F0 = ((1 - 1.5) / (1 + 1.5))^2 = 0.04, going in and coming out.
    const std::vector<OpticsResult> r = evaluateOptics(
        {makeCase(vec3(0, 0, -1), vec3(0, 0, 1), 1.0f, 1.5f), makeCase(vec3(0, 0, -1), vec3(0, 0, 1), 1.5f, 1.0f)});
    for (const OpticsResult& result : r) {
        EXPECT_NEAR(result.reflected.w, 0.04, 1e-7);    // schlickF0
        EXPECT_NEAR(result.reflectance.x, 0.04, 1e-7);  // Schlick
        EXPECT_NEAR(result.reflectance.y, 0.04, 1e-7);  // exact
        // Exp2 variant: 2^((-5.55473 - 6.98316) * 1) = 2^-12.53789 ~ 1.7e-4, so R ~ F0.
        EXPECT_NEAR(result.reflectance.z, 0.04 + 0.96 * std::exp2(-12.53789), 1e-7);
    }
    // At grazing incidence (cos(theta1) = 0) every model goes to 1.
    const OpticsResult grazing = evaluateOne(makeCase(vec3(1, 0, 0), vec3(0, 0, 1), 1.0f, 1.5f));
    EXPECT_NEAR(grazing.reflectance.x, 1.0, 1e-6);
    EXPECT_NEAR(grazing.reflectance.y, 1.0, 1e-6);
    EXPECT_NEAR(grazing.reflectance.z, 1.0, 1e-6);
}

TEST(GlslOptics, SchlickUsesTransmittedAngleWhenLeavingTheDenserMedium) {
    // Lecture: theta = theta_i if n1 <= n2, else theta_t. In the worked example (1.5 -> 1),
    // cos(theta_t) = 0.765707 and cos(theta_i) = 0.903403, by hand:
    //   Schlick with theta_t: 0.04 + 0.96 (1 - 0.765707)^5 = 0.0406778,
    //   Schlick with theta_i: 0.04 + 0.96 (1 - 0.903403)^5 = 0.0400081 (the wrong choice),
    //   exp2 with theta_t:    0.04 + 0.96 2^((-5.55473 * 0.765707 - 6.98316) * 0.765707) = 0.0424675.
    const OpticsResult r = evaluateOne(lectureCase());
    EXPECT_NEAR(r.reflectance.x, 0.0406778, 1e-6);
    EXPECT_GT(std::abs(r.reflectance.x - 0.0400081), 5e-4);
    EXPECT_NEAR(r.reflectance.z, 0.0424675, 1e-6);
}

TEST(GlslOptics, SchlickExp2MatchesHandCalculation) {
    // Air into glass at theta1 = 60 deg, cos = 0.5:
    //   2^((-5.55473 * 0.5 - 6.98316) * 0.5) = 2^-4.8802625 = 0.0339543,
    //   R = 0.04 + 0.96 * 0.0339543 = 0.0725961; plain Schlick: 0.04 + 0.96 * 0.5^5 = 0.07.
    const float s = std::sqrt(3.0f) / 2.0f;
    const OpticsResult r = evaluateOne(makeCase(vec3(-s, -0.5f, 0.0f), kUp, 1.0f, 1.5f));
    EXPECT_NEAR(r.reflectance.z, 0.0725961, 1e-6);
    EXPECT_NEAR(r.reflectance.x, 0.07, 1e-6);
}

TEST(GlslOptics, IndexMatchedInterfaceReflectsNothing) {
    // n1 == n2 is no optical interface (render model, "The ray tree"): R = 0 for every model, and
    // the ray goes straight on.
    const vec3 d(-std::sqrt(1.0f - 0.09f), -0.3f, 0.0f);
    const OpticsResult r = evaluateOne(makeCase(d, kUp, 1.5f, 1.5f));
    EXPECT_EQ(r.reflectance.x, 0.0f);
    EXPECT_EQ(r.reflectance.y, 0.0f);
    EXPECT_EQ(r.reflectance.z, 0.0f);
    EXPECT_EQ(r.reflected.w, 0.0f);  // F0
    EXPECT_NEAR(glm::length(xyz(r.refracted) - d), 0.0, 1e-6);
}

TEST(GlslOptics, BeerLambertIsExponential) {
    // Lecture, "Attenuation of Refracted Ray": exp(-mu t) per channel; mu = 0 (air) or t = 0 gives 1.
    const std::vector<OpticsResult> r = evaluateOptics({makeCase(lectureDirection(), kUp, 1.5f, 1.0f, vec3(0, 1, 0.5f), 2),
                                                  makeCase(lectureDirection(), kUp, 1.5f, 1.0f, vec3(3, 1, 7), 0)});
    EXPECT_EQ(r[0].beer.x, 1.0f);
    EXPECT_NEAR(r[0].beer.y, std::exp(-2.0), 1e-7);
    EXPECT_NEAR(r[0].beer.z, std::exp(-1.0), 1e-7);
    EXPECT_EQ(xyz(r[1].beer), vec3(1.0f));
}

// ---- Property sweep against the CPU reference ---------------------------------------------------

// Deterministic on every platform: the shared PCG hash, not a <random> distribution.
float uniform(std::uint32_t caseIndex, std::uint32_t k) {
    return gpu::hashToUnit(gpu::pcgHash(0x5EEDu ^ gpu::pcgHash(caseIndex * 16u + k)));
}

vec3 randomUnit(std::uint32_t caseIndex, std::uint32_t k) {
    const float z = 2.0f * uniform(caseIndex, k) - 1.0f;
    const float phi = 6.28318530718f * uniform(caseIndex, k + 1);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return glm::normalize(vec3(r * std::cos(phi), r * std::sin(phi), z));
}

OpticsCase randomCase(std::uint32_t i) {
    const vec3 n = randomUnit(i, 0);
    vec3 d = randomUnit(i, 2);
    if (glm::dot(d, n) > 0.0f) d = -d;  // our convention: n faces the incoming ray
    // A quarter of the cases draw both IORs from common media (so some are index-matched), a
    // quarter are index-matched on purpose, the rest are anything in [1, 2.5].
    static constexpr float kMedia[] = {1.0f, 1.33f, 1.5f, 2.42f};
    float n1 = 1.0f + 1.5f * uniform(i, 4), n2 = 1.0f + 1.5f * uniform(i, 5);
    switch (gpu::pcgHash(i ^ 0xA5A5u) % 4u) {
        case 0:
            n1 = kMedia[gpu::pcgHash(i * 2u) % 4u];
            n2 = kMedia[gpu::pcgHash(i * 2u + 1u) % 4u];
            break;
        case 1: n2 = n1; break;
        default: break;
    }
    const vec3 mu = 4.0f * vec3(uniform(i, 6), uniform(i, 7), uniform(i, 8));
    return makeCase(d, n, n1, n2, mu, 3.0f * uniform(i, 9));
}

bool finite(const glm::vec4& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

double maxAbs(vec3 a, vec3 b) {
    const vec3 e = glm::abs(a - b);
    return std::max({double(e.x), double(e.y), double(e.z)});
}

TEST(GlslOptics, RandomCasesMatchCpuReferenceAndPhysics) {
    // 4,099 cases: not a multiple of the group size, so the kernel's index guard is exercised.
    constexpr std::uint32_t kCases = 64u * 64u + 3u;
    std::vector<OpticsCase> cases;
    for (std::uint32_t i = 0; i < kCases; ++i) cases.push_back(randomCase(i));
    const std::vector<OpticsResult> results = evaluateOptics(cases);
    ASSERT_EQ(results.size(), cases.size());

    constexpr double kTolerance = 1e-5;
    double maxReflected = 0, maxDirection = 0, maxCos2t = 0, maxReflectance = 0, maxBeer = 0, maxSnell = 0, maxUnit = 0;
    std::uint32_t refracted = 0, totalInternal = 0, matched = 0, tirDisagreements = 0;
    for (std::uint32_t i = 0; i < kCases; ++i) {
        SCOPED_TRACE("case " + std::to_string(i));
        const OpticsCase& c = cases[i];
        const OpticsResult& g = results[i];
        const vec3 d = xyz(c.direction), n = xyz(c.normal), mu = xyz(c.attenuation);
        const float n1 = c.media.x, n2 = c.media.y, t = c.media.z, eta = n1 / n2;
        const float cosI = -glm::dot(d, n);
        matched += n1 == n2;
        ASSERT_TRUE(finite(g.reflected) && finite(g.refracted) && finite(g.reflectance) && finite(g.beer));

        // The CPU reference in float: the same operations in the same order.
        const vec3 reflected = optics::reflect(d, n);
        const float cos2t = optics::cosSquaredTransmitted(d, n, eta);
        const auto l = optics::refract(d, n, eta);
        const float reflectance[3] = {optics::fresnel(FresnelModel::Schlick, n1, n2, cosI),
                                      optics::fresnel(FresnelModel::Exact, n1, n2, cosI),
                                      optics::fresnel(FresnelModel::SchlickExp2, n1, n2, cosI)};
        const vec3 beer = optics::beerLambert(mu, t);

        maxReflected = std::max(maxReflected, maxAbs(xyz(g.reflected), reflected));
        EXPECT_NEAR(g.reflected.w, optics::schlickF0(n1, n2), kTolerance);
        maxCos2t = std::max(maxCos2t, std::abs(double(g.refracted.w) - cos2t));
        // Vulkan lets a device round a division to 2.5 ulp (lavapipe and the CPU round it exactly).
        // Near the critical angle R has an unbounded slope, so the one division into eta moves R by
        // far more than its ulps: what it moved by on this device is allowed on top.
        const float gpuEta = g.reflectance.w;
        EXPECT_LE(std::abs(double(gpuEta) - double(n1) / n2), 2.5 * std::ldexp(1.0, std::ilogb(eta) - 23)) << "n1 / n2";
        // (In double, with n2 = n1 / eta for either eta: every step but that division exact.)
        const FresnelModel models[3] = {FresnelModel::Schlick, FresnelModel::Exact, FresnelModel::SchlickExp2};
        for (int m = 0; m < 3; ++m) {
            const double byDivision = std::abs(optics::fresnel<double>(models[m], n1, double(n1) / gpuEta, cosI) -
                                               optics::fresnel<double>(models[m], n1, double(n1) / eta, cosI));
            maxReflectance = std::max(maxReflectance, std::abs(double(g.reflectance[m]) - reflectance[m]) - byDivision);
        }
        maxBeer = std::max(maxBeer, maxAbs(xyz(g.beer), beer));

        // Law of reflection: unit length, same angle to n on the other side.
        maxUnit = std::max(maxUnit, std::abs(glm::length(glm::dvec3(xyz(g.reflected))) - 1.0));
        EXPECT_NEAR(glm::dot(xyz(g.reflected), n), cosI, kTolerance);

        for (int m = 0; m < 3; ++m) {
            EXPECT_GE(g.reflectance[m], 0.0f) << "model " << m;
            EXPECT_LE(g.reflectance[m], 1.0f) << "model " << m;
        }
        for (int k = 0; k < 3; ++k) {
            EXPECT_GT(g.beer[k], 0.0f);
            EXPECT_LE(g.beer[k], 1.0f);
        }

        if ((g.refracted.w < 0.0f) != !l.has_value()) {
            // Only a rounding difference right at the critical angle may split the two.
            ++tirDisagreements;
            EXPECT_LT(std::abs(g.refracted.w), 1e-6);
            continue;
        }
        const glm::dvec3 dd(d), nd(n);
        const double sin1 = glm::length(glm::cross(dd, nd));
        if (!l) {
            ++totalInternal;
            EXPECT_EQ(g.reflectance.x, 1.0f);
            EXPECT_EQ(g.reflectance.y, 1.0f);
            EXPECT_EQ(g.reflectance.z, 1.0f);
            EXPECT_GT(n1 * sin1, n2 - kTolerance) << "TIR below the critical angle";
            continue;
        }
        ++refracted;
        maxDirection = std::max(maxDirection, maxAbs(xyz(g.refracted), *l));
        const glm::dvec3 ld(xyz(g.refracted));
        maxUnit = std::max(maxUnit, std::abs(glm::length(ld) - 1.0));
        // Snell: n1 sin(theta1) = n2 sin(theta2); l stays in the plane of d and n, on the far side.
        const double sin2 = glm::length(glm::cross(ld, nd));
        maxSnell = std::max(maxSnell, std::abs(n1 * sin1 - n2 * sin2));
        EXPECT_NEAR(glm::dot(ld, glm::cross(dd, nd)), 0.0, kTolerance);
        EXPECT_LE(glm::dot(ld, nd), kTolerance);
        // cos2t is cos^2(theta2) of the direction returned.
        EXPECT_NEAR(g.refracted.w, glm::dot(ld, nd) * glm::dot(ld, nd), kTolerance);
        if (n1 == n2) {
            // Straight on. Near grazing, float cancellation in 1 - (1 - (d.n)^2) costs up to an ulp
            // of 1 (2^-23), which sqrt turns into 2^-23 / (2 cos(theta1)) in l (the CPU loses the same).
            EXPECT_NEAR(glm::length(ld - dd), 0.0, kTolerance + 0x1p-23 / (2.0 * cosI)) << "cos(theta1) " << cosI;
        }
    }
    std::cout << "GlslOptics sweep: " << kCases << " cases, " << refracted << " refracted, " << totalInternal
              << " TIR, " << matched << " index-matched, " << tirDisagreements << " TIR disagreements\n"
              << "  max |GPU - CPU|: reflected " << maxReflected << ", refracted " << maxDirection << ", cos2t "
              << maxCos2t << ", reflectance " << maxReflectance << " (beyond what the division into eta moved)"
              << ", Beer-Lambert " << maxBeer << "\n"
              << "  max Snell residual " << maxSnell << ", max | |v| - 1 | " << maxUnit << "\n";
    // d - 2 (d.n) n is multiplies and adds only, which every device rounds as IEEE says: the CPU's
    // result to the bit unless the driver fused some into FMAs (gpu/spirv_float_semantics.h forbids
    // it). Refraction takes a square root and the Fresnel terms divide, which Vulkan lets a device
    // round less exactly (2.5 ulp for a division).
    EXPECT_EQ(maxReflected, 0.0) << "the device contracts multiplies and adds that the CPU rounds apart";
    EXPECT_LE(maxDirection, kTolerance);
    EXPECT_LE(maxCos2t, kTolerance);
    EXPECT_LE(maxReflectance, kTolerance);
    EXPECT_LE(maxBeer, kTolerance);
    EXPECT_LE(maxSnell, kTolerance * 2.5);  // residual scales with the IORs (up to 2.5)
    EXPECT_LE(maxUnit, kTolerance);
    // The sweep must really cover every branch.
    EXPECT_GT(refracted, kCases / 2);
    EXPECT_GT(totalInternal, 100u);
    EXPECT_GT(matched, 500u);
}

}  // namespace
}  // namespace vitrum::testing
