// Quoting a piece of an input file in an error message: the input may be binary garbage, so
// control and non-ASCII bytes are escaped and long text is cut.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace vitrum {

inline std::string quoteInput(std::string_view text, std::size_t maxLength = 60) {
    std::string result = "\"";
    for (std::size_t i = 0; i < text.size() && i < maxLength; ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c >= 0x20 && c < 0x7f) {
            result += char(c);
        } else {
            char escaped[8];
            std::snprintf(escaped, sizeof escaped, "\\x%02x", c);
            result += escaped;
        }
    }
    return result + (text.size() > maxLength ? "...\"" : "\"");
}

}  // namespace vitrum
