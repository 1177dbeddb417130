// SSIM against the paper's closed forms and against a direct, non-separable computation of its
// definition (Wang et al. 2004, equations 13-15 with the Gaussian window of section III-C).
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "common/error.h"
#include "image/image.h"
#include "image/ssim.h"

namespace vitrum {
namespace {

Image uniform(std::uint32_t w, std::uint32_t h, float linear) {
    Image image(w, h);
    for (auto& p : image.pixels) p = glm::vec3(linear);
    return image;
}

Image noise(std::uint32_t w, std::uint32_t h, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Image image(w, h);
    for (auto& p : image.pixels) p = glm::vec3(u(rng), u(rng), u(rng));
    return image;
}

TEST(Ssim, IdenticalImagesScoreOne) {
    const Image a = noise(23, 17, 1);
    EXPECT_NEAR(meanSsim(a, a), 1.0, 1e-12);
}

// Flat images have no variance, so only the luminance term is left:
// SSIM = (2 mu_x mu_y + C1) / (mu_x^2 + mu_y^2 + C1), here with luma 0.5 and 0.25 exactly
// (sRGB codes 0.5 and 0.25 on every channel).
TEST(Ssim, FlatImagesKeepOnlyTheLuminanceTerm) {
    const float half = 0.21404114f;      // linear value whose sRGB encoding is 0.5
    const float quarter = 0.05087609f;   // ... 0.25
    const double x = srgbLuma(glm::vec3(half)), y = srgbLuma(glm::vec3(quarter));
    ASSERT_NEAR(x, 0.5, 1e-6);
    ASSERT_NEAR(y, 0.25, 1e-6);
    const double c1 = 1e-4;
    EXPECT_NEAR(meanSsim(uniform(16, 12, half), uniform(16, 12, quarter)), (2 * x * y + c1) / (x * x + y * y + c1), 1e-9);
}

// The definition computed directly: at every pixel the Gaussian-weighted means, variances and
// covariance over the window cut to the image.
TEST(Ssim, MatchesADirectComputationOfTheDefinition) {
    const Image a = noise(19, 14, 2);
    Image b = a;
    std::mt19937 rng(3);
    std::normal_distribution<float> n(0.0f, 0.05f);
    for (auto& p : b.pixels) p = glm::clamp(p + glm::vec3(n(rng), n(rng), n(rng)), 0.0f, 1.0f);
    const std::vector<double> map = ssimMap(a, b);
    ASSERT_EQ(map.size(), a.pixels.size());
    for (int py = 0; py < 14; ++py)
        for (int px = 0; px < 19; ++px) {
            double w = 0, mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
            for (int y = std::max(0, py - 5); y <= std::min(13, py + 5); ++y)
                for (int x = std::max(0, px - 5); x <= std::min(18, px + 5); ++x) {
                    const double g = std::exp(-((x - px) * (x - px) + (y - py) * (y - py)) / (2 * 1.5 * 1.5));
                    const double u = srgbLuma(a.at(x, y)), v = srgbLuma(b.at(x, y));
                    w += g, mx += g * u, my += g * v, xx += g * u * u, yy += g * v * v, xy += g * u * v;
                }
            mx /= w, my /= w;
            const double vx = xx / w - mx * mx, vy = yy / w - my * my, cxy = xy / w - mx * my;
            const double expected = (2 * mx * my + 1e-4) * (2 * cxy + 9e-4) / ((mx * mx + my * my + 1e-4) * (vx + vy + 9e-4));
            EXPECT_NEAR(map[std::size_t(py) * 19 + px], expected, 1e-9) << px << "," << py;
        }
}

// Structure matters: noise against its negative (anticorrelated) scores below zero, while the
// same noise slightly brighter stays close to one.
TEST(Ssim, NegativeStructureScoresBelowZero) {
    const Image a = noise(32, 32, 4);
    Image negative = a, brighter = a;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        negative.pixels[i] = glm::vec3(1.0f) - a.pixels[i];
        brighter.pixels[i] = a.pixels[i] * 1.02f;
    }
    EXPECT_LT(meanSsim(a, negative), 0.0);
    EXPECT_GT(meanSsim(a, brighter), 0.99);
    EXPECT_LT(meanSsim(a, brighter), 1.0);
}

TEST(Ssim, SizeMismatchIsAnInputError) {
    EXPECT_THROW(meanSsim(Image(3, 2), Image(2, 3)), InputError);
}

}  // namespace
}  // namespace vitrum
