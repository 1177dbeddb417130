// The standard sRGB transfer curve (IEC 61966-2-1): exponent 2.4, thresholds 0.04045 / 0.0031308.
#pragma once

#include <cmath>

namespace vitrum {

inline float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

inline float linearToSrgb(float c) {
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

}  // namespace vitrum
