// The 8-bit sRGB codes of linear values, as PNGs are written, without a pow a value: the same
// codes as linearToSrgb8 (srgb.h), found from the linear values where each code begins.
#pragma once

#include <cstdint>

namespace vitrum {

// linearToSrgb8(linear), the same for every float (NaN and infinities included).
std::uint8_t srgb8Code(float linear);

}  // namespace vitrum
