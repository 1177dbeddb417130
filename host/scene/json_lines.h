// Where each value of a JSON text sits, for error messages: nlohmann::json keeps no positions,
// so the text (already accepted by nlohmann) is skimmed once more. Keys are JSON-pointer-like
// paths: "" for the root, "/camera/fov_y", "/objects/0/obj"; a member maps to the line of its key.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <unordered_map>

namespace vitrum {

std::unordered_map<std::string, int> jsonValueLines(std::string_view text);

// The offset of the first '[' or '{' (outside strings) that opens a value nested deeper than
// `maxDepth` levels, or text.size() where none is. Checked before parsing: a scene nested 60,000
// levels deep overflowed the stack in nlohmann's dump, and the lines' paths grew with the
// square of the depth (issue 48).
std::size_t offsetBeyondNesting(std::string_view text, int maxDepth);

// 1-based line of a byte offset (as in nlohmann's parse_error::byte).
int lineOfOffset(std::string_view text, std::size_t offset);

}  // namespace vitrum
