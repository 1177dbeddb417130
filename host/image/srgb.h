// The standard sRGB transfer curve (IEC 61966-2-1): exponent 2.4, thresholds 0.04045 / 0.0031308.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace vitrum {

inline float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

inline float linearToSrgb(float c) {
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

// The sRGB value a linear one is shown as: clamped to [0, 1] first, a non-finite value as 0.
inline float displayedSrgb(float c) { return linearToSrgb(std::isfinite(c) ? std::clamp(c, 0.0f, 1.0f) : 0.0f); }

// The 8-bit sRGB code a linear value is written as in a PNG: displayedSrgb rounded to nearest.
// The definition; srgb8Code (srgb8_codes.h) gives the same codes without a pow.
inline std::uint8_t linearToSrgb8(float c) { return std::uint8_t(std::lround(displayedSrgb(c) * 255.0f)); }

}  // namespace vitrum
