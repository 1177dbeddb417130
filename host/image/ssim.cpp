#include "image/ssim.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "common/error.h"
#include "image/srgb.h"

namespace vitrum {
namespace {

constexpr int kRadius = 5;  // the 11x11 window
constexpr double kSigma = 1.5;
constexpr double kC1 = 0.01 * 0.01;
constexpr double kC2 = 0.03 * 0.03;

std::array<double, 2 * kRadius + 1> gaussianWeights() {
    std::array<double, 2 * kRadius + 1> w{};
    for (int i = -kRadius; i <= kRadius; ++i) w[i + kRadius] = std::exp(-0.5 * i * i / (kSigma * kSigma));
    return w;
}

// The window-weighted sum of `values` around every pixel, separably, with the weights cut at the
// border (blurring all ones gives the weights each pixel kept).
std::vector<double> blur(const std::vector<double>& values, int width, int height) {
    static const auto w = gaussianWeights();
    std::vector<double> rows(values.size()), out(values.size());
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double sum = 0.0;
            for (int i = std::max(-kRadius, -x); i <= std::min(kRadius, width - 1 - x); ++i)
                sum += w[i + kRadius] * values[std::size_t(y) * width + x + i];
            rows[std::size_t(y) * width + x] = sum;
        }
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double sum = 0.0;
            for (int j = std::max(-kRadius, -y); j <= std::min(kRadius, height - 1 - y); ++j)
                sum += w[j + kRadius] * rows[std::size_t(y + j) * width + x];
            out[std::size_t(y) * width + x] = sum;
        }
    return out;
}

}  // namespace

double srgbLuma(const glm::vec3& linear) {
    return 0.2126 * displayedSrgb(linear.r) + 0.7152 * displayedSrgb(linear.g) + 0.0722 * displayedSrgb(linear.b);
}

std::vector<double> ssimMap(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height) {
        throw InputError("image sizes differ: " + std::to_string(a.width) + "x" + std::to_string(a.height) + " vs " +
                         std::to_string(b.width) + "x" + std::to_string(b.height));
    }
    const int width = int(a.width), height = int(a.height);
    const std::size_t n = a.pixels.size();
    std::vector<double> x(n), y(n), xx(n), yy(n), xy(n), one(n, 1.0);
    for (std::size_t i = 0; i < n; ++i) {
        x[i] = srgbLuma(a.pixels[i]);
        y[i] = srgbLuma(b.pixels[i]);
        xx[i] = x[i] * x[i];
        yy[i] = y[i] * y[i];
        xy[i] = x[i] * y[i];
    }
    const std::vector<double> weight = blur(one, width, height);
    const std::vector<double> sx = blur(x, width, height), sy = blur(y, width, height);
    const std::vector<double> sxx = blur(xx, width, height), syy = blur(yy, width, height), sxy = blur(xy, width, height);
    std::vector<double> map(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double mx = sx[i] / weight[i], my = sy[i] / weight[i];
        const double vx = sxx[i] / weight[i] - mx * mx, vy = syy[i] / weight[i] - my * my;
        const double cxy = sxy[i] / weight[i] - mx * my;
        map[i] = (2.0 * mx * my + kC1) * (2.0 * cxy + kC2) / ((mx * mx + my * my + kC1) * (vx + vy + kC2));
    }
    return map;
}

double meanSsim(const Image& a, const Image& b) {
    const std::vector<double> map = ssimMap(a, b);
    if (map.empty()) return 1.0;
    double sum = 0.0;
    for (double v : map) sum += v;
    return sum / double(map.size());
}

}  // namespace vitrum
