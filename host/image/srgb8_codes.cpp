#include "image/srgb8_codes.h"

#include <array>
#include <bit>
#include <cmath>

#include "image/srgb.h"

namespace vitrum {
namespace {

// Bins of [0, 1] of this width hold at most one code's beginning: codes begin at least
// 1 / (255 * 12.92) = 3.04e-4 apart (the curve is steepest at 0, where it is 12.92 c).
constexpr int kBins = 4096;

struct CodeTable {
    // firstValue[k]: the smallest float in [0, 1] that linearToSrgb8 makes code k (k >= 1);
    // firstValue[256] is past every value, so that code 255 never goes up.
    std::array<float, 257> firstValue{};
    // binCode[i]: the code of i / kBins, the code of every value of bin i or one less than it.
    std::array<std::uint8_t, kBins + 1> binCode{};

    CodeTable() {
        // linearToSrgb8 does not decrease on [0, 1], and there non-negative floats are ordered as
        // their bits: so the smallest float of a code is found by bisection over the bits.
        constexpr std::uint32_t kOneBits = 0x3F800000u;
        for (int k = 1; k <= 255; ++k) {
            std::uint32_t below = 0, atOrAbove = kOneBits;  // codes: < k at `below`, >= k at `atOrAbove`
            while (atOrAbove - below > 1) {
                const std::uint32_t middle = below + (atOrAbove - below) / 2;
                (linearToSrgb8(std::bit_cast<float>(middle)) >= k ? atOrAbove : below) = middle;
            }
            firstValue[std::size_t(k)] = std::bit_cast<float>(atOrAbove);
        }
        firstValue[256] = INFINITY;
        for (int i = 0; i <= kBins; ++i) binCode[std::size_t(i)] = linearToSrgb8(float(i) / float(kBins));
    }
};

const CodeTable& codeTable() {
    static const CodeTable table;
    return table;
}

}  // namespace

std::uint8_t srgb8Code(float linear) {
    const CodeTable& table = codeTable();
    // As displayedSrgb: clamped to [0, 1], a non-finite value as 0 (NaN fails every comparison).
    // Comparisons rather than std::isfinite, fmin and fmax, which g++ calls out of line here.
    const float c = linear > 0.0f ? (linear <= 1.0f ? linear : (linear < INFINITY ? 1.0f : 0.0f)) : 0.0f;
    const std::uint8_t code = table.binCode[std::size_t(c * float(kBins))];
    return std::uint8_t(code + (c >= table.firstValue[std::size_t(code) + 1] ? 1 : 0));
}

}  // namespace vitrum
