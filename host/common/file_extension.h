// A file's extension as the loaders and writers choose a format by it: ".PNG" and ".png" alike.
#pragma once

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace vitrum {

// The extension of `path` with its dot, in lower case ("" where it has none).
inline std::string lowerCaseExtension(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

}  // namespace vitrum
