#include "image/image_diff.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/error.h"
#include "image/srgb8_codes.h"

namespace vitrum {
namespace {

// The absolute difference of two channel values; a non-finite value on either side that is not
// matched exactly on the other counts as an infinite error, so a broken image never compares well.
double channelError(float a, float b) {
    if (std::isfinite(a) && std::isfinite(b)) return std::fabs(double(a) - double(b));
    if (a == b) return 0.0;  // the same infinity on both sides
    return std::numeric_limits<double>::infinity();
}

std::string sizeText(const Image& image) { return std::to_string(image.width) + "x" + std::to_string(image.height); }

}  // namespace

ImageDiff diffImages(const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height) {
        throw InputError("image sizes differ: " + sizeText(a) + " vs " + sizeText(b));
    }
    ImageDiff diff;
    const std::size_t pixelCount = std::size_t(a.width) * a.height;
    if (pixelCount == 0) {
        diff.psnr = std::numeric_limits<double>::infinity();
        return diff;
    }
    double sumSquared = 0.0;
    double sumAbs = 0.0;
    std::size_t over1of255 = 0;
    std::size_t over005 = 0;
    std::size_t srgb8Changed = 0;
    for (std::size_t i = 0; i < pixelCount; ++i) {
        double pixelMax = 0.0;
        bool codeChanged = false;
        for (int c = 0; c < 3; ++c) {
            const double e = channelError(a.pixels[i][c], b.pixels[i][c]);
            sumSquared += e * e;
            sumAbs += e;
            pixelMax = std::max(pixelMax, e);
            codeChanged = codeChanged || srgb8Code(a.pixels[i][c]) != srgb8Code(b.pixels[i][c]);
        }
        if (codeChanged) ++srgb8Changed;
        diff.maxAbsError = std::max(diff.maxAbsError, pixelMax);
        if (pixelMax > 1.0 / 255.0) ++over1of255;
        if (pixelMax > 0.05) ++over005;
    }
    const double samples = double(pixelCount) * 3.0;
    const double mse = sumSquared / samples;
    diff.rmse = std::sqrt(mse);
    diff.psnr = mse == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(1.0 / mse);
    diff.meanAbsError = sumAbs / samples;
    diff.shareOver1of255 = double(over1of255) / double(pixelCount);
    diff.shareOver005 = double(over005) / double(pixelCount);
    diff.shareSrgb8Changed = double(srgb8Changed) / double(pixelCount);
    return diff;
}

Image diffHeatMap(const Image& a, const Image& b, float fullScale) {
    if (a.width != b.width || a.height != b.height) {
        throw InputError("image sizes differ: " + sizeText(a) + " vs " + sizeText(b));
    }
    if (!(fullScale > 0.0f) || !std::isfinite(fullScale)) {
        throw std::invalid_argument("diffHeatMap: fullScale must be positive and finite");
    }
    Image heat(a.width, a.height);
    for (std::size_t i = 0; i < heat.pixels.size(); ++i) {
        double worst = 0.0;
        for (int c = 0; c < 3; ++c) worst = std::max(worst, channelError(a.pixels[i][c], b.pixels[i][c]));
        const float e = float(std::clamp(worst / double(fullScale), 0.0, 1.0));
        heat.pixels[i] = glm::vec3(std::clamp(3.0f * e, 0.0f, 1.0f), std::clamp(3.0f * e - 1.0f, 0.0f, 1.0f),
                                   std::clamp(3.0f * e - 2.0f, 0.0f, 1.0f));
    }
    return heat;
}

}  // namespace vitrum
