#include "common/float_text.h"

#include <charconv>
#include <cmath>

namespace vitrum {

FloatText readFloat(std::string_view text, float& value) {
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    value = 0.0f;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (text.empty() || ptr != end) return FloatText::NotANumber;
    if (ec == std::errc::result_out_of_range) {
        long double wide = 0.0L;
        if (std::from_chars(text.data(), end, wide).ec == std::errc() && std::abs(wide) < 1.0L) {
            value = std::signbit(wide) ? -0.0f : 0.0f;
            return FloatText::Number;
        }
        return FloatText::NotFinite;
    }
    return ec == std::errc() && std::isfinite(value) ? FloatText::Number : FloatText::NotFinite;
}

}  // namespace vitrum
