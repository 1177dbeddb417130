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

// 1-based line of a byte offset (as in nlohmann's parse_error::byte).
int lineOfOffset(std::string_view text, std::size_t offset);

}  // namespace vitrum
