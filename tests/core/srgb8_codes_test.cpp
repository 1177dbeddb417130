// The table-driven 8-bit sRGB codes (host/image/srgb8_codes.h) against the sRGB curve's own
// codes (srgb.h: linearToSrgb8), where the codes change and across [0, 1].
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include <gtest/gtest.h>

#include "image/srgb.h"
#include "image/srgb8_codes.h"

namespace vitrum {
namespace {

// The linear value where code k begins, from the inverse curve in double precision: sRGB value
// (k - 0.5) / 255, halfway between codes k - 1 and k (IEC 61966-2-1).
double codeBeginning(int k) {
    const double s = (k - 0.5) / 255.0;
    return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
}

TEST(Srgb8Codes, SameAsTheCurveAroundEveryCodesBeginning) {
    // A float rounding of the curve moves where a code begins by a few ulps; 8192 on either side
    // also holds any table whose bins were too coarse to see a code begin.
    constexpr std::int64_t kUlps = 8192;
    for (int k = 1; k <= 255; ++k) {
        const std::int64_t centre = std::bit_cast<std::uint32_t>(float(codeBeginning(k)));
        int mismatches = 0;
        for (std::int64_t bits = centre - kUlps; bits <= centre + kUlps; ++bits) {
            const float v = std::bit_cast<float>(std::uint32_t(bits));
            if (srgb8Code(v) != linearToSrgb8(v) && ++mismatches <= 3)
                ADD_FAILURE() << "code " << k << ": linear " << v << " gives " << int(srgb8Code(v)) << ", the curve "
                              << int(linearToSrgb8(v));
        }
        EXPECT_EQ(mismatches, 0) << "around the beginning of code " << k;
        // The curve itself: code k - 1 just below, k just above.
        EXPECT_EQ(srgb8Code(std::bit_cast<float>(std::uint32_t(centre - kUlps))), k - 1);
        EXPECT_EQ(srgb8Code(std::bit_cast<float>(std::uint32_t(centre + kUlps))), k);
    }
}

TEST(Srgb8Codes, SameAsTheCurveAcrossZeroToOne) {
    // Every 997th float from 0 to 1 (1.07 million), denormals included.
    constexpr std::uint32_t kOneBits = 0x3F800000u;
    int mismatches = 0;
    for (std::uint32_t bits = 0; bits <= kOneBits; bits += 997) {
        const float v = std::bit_cast<float>(bits);
        if (srgb8Code(v) != linearToSrgb8(v)) ++mismatches;
    }
    EXPECT_EQ(mismatches, 0);
}

TEST(Srgb8Codes, ValuesOutsideZeroToOneAsDisplayed) {
    // Clamped to [0, 1]; NaN and the infinities are shown as 0 (displayedSrgb).
    constexpr float kInf = std::numeric_limits<float>::infinity();
    EXPECT_EQ(srgb8Code(0.0f), 0);
    EXPECT_EQ(srgb8Code(-0.0f), 0);
    EXPECT_EQ(srgb8Code(-1.0f), 0);
    EXPECT_EQ(srgb8Code(std::numeric_limits<float>::denorm_min()), 0);
    EXPECT_EQ(srgb8Code(1.0f), 255);
    EXPECT_EQ(srgb8Code(std::nextafter(1.0f, 0.0f)), 255);
    EXPECT_EQ(srgb8Code(1.5f), 255);
    EXPECT_EQ(srgb8Code(std::numeric_limits<float>::max()), 255);
    EXPECT_EQ(srgb8Code(kInf), 0);
    EXPECT_EQ(srgb8Code(-kInf), 0);
    EXPECT_EQ(srgb8Code(std::numeric_limits<float>::quiet_NaN()), 0);
    // Linear 0.5 is sRGB 0.7354, 187.52 of 255.
    EXPECT_EQ(srgb8Code(0.5f), 188);
}

}  // namespace
}  // namespace vitrum
