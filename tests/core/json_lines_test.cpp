// How deep a JSON text nests (scene/json_lines.h), checked before it is parsed.
#include "scene/json_lines.h"

#include <string>

#include <gtest/gtest.h>

namespace vitrum {
namespace {

TEST(JsonNesting, TheFirstBracketBeyondTheLimitIsFound) {
    EXPECT_EQ(offsetBeyondNesting(R"({"a": [1, {"b": [2]}]})", 4), std::string(R"({"a": [1, {"b": [2]}]})").size());
    EXPECT_EQ(offsetBeyondNesting(R"({"a": [1, {"b": [2]}]})", 3), std::size_t(16));
    EXPECT_EQ(offsetBeyondNesting("[][][][]", 1), std::size_t(8));  // depth goes back down
    EXPECT_EQ(offsetBeyondNesting(std::string(100000, '[') + std::string(100000, ']'), 64), std::size_t(64));
}

TEST(JsonNesting, BracketsInsideStringsDoNotCount) {
    const std::string quoted = R"({"key [[[[": "{{{{ \" [[[[ \\"})";
    EXPECT_EQ(offsetBeyondNesting(quoted, 1), quoted.size());
    // After an escaped backslash the quote closes the string, and the bracket after it counts.
    EXPECT_EQ(offsetBeyondNesting(R"(["\\", [[]]])", 2), std::size_t(8));
}

}  // namespace
}  // namespace vitrum
