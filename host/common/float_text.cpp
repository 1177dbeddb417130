#include "common/float_text.h"

#include <charconv>
#include <algorithm>
#include <cmath>
#include <limits>

namespace vitrum {

namespace {

// Whether a decimal number that std::from_chars read in full is below 1 in magnitude, from its
// digits and exponent alone: "1e-999999999" is beyond even long double's range.
bool belowOne(std::string_view text) {
    const std::size_t e = std::min(text.find_first_of("eE"), text.size());
    long long exponent = 0;
    if (e < text.size()) {
        std::string_view digits = text.substr(e + 1);
        if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);
        if (std::from_chars(digits.data(), digits.data() + digits.size(), exponent).ec != std::errc())
            exponent = !digits.empty() && digits.front() == '-' ? std::numeric_limits<int>::min()
                                                                 : std::numeric_limits<int>::max();
    }
    // The power of ten of the first non-zero digit of the mantissa, before the exponent.
    const std::string_view mantissa = text.substr(0, e);
    const std::size_t point = std::min(mantissa.find('.'), mantissa.size());
    const std::size_t first = mantissa.find_first_of("123456789");
    if (first == std::string_view::npos) return true;  // zero
    const long long lead = first < point ? (long long)(point - first) - 1 : -(long long)(first - point);
    return lead + exponent < 0;
}

}  // namespace

FloatText readFloat(std::string_view text, float& value) {
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    value = 0.0f;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (text.empty() || ptr != end) return FloatText::NotANumber;
    if (ec == std::errc::result_out_of_range) {
        if (!belowOne(text)) return FloatText::NotFinite;
        value = text.front() == '-' ? -0.0f : 0.0f;
        return FloatText::Number;
    }
    return ec == std::errc() && std::isfinite(value) ? FloatText::Number : FloatText::NotFinite;
}

}  // namespace vitrum
