// The size an image file declares, checked before anything is allocated for it: a forged or
// truncated header must not make a reader allocate gigabytes for a file of a few bytes (found by
// fuzzing, tests/fuzz/regressions/image). At most 16384 pixels on a side (the largest image
// vitrum renders), and at most 8192 pixels a byte of file beyond the first 2^20 pixels (about
// what the densest deflate stream of a 1-bit PNG holds).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "common/error.h"

namespace vitrum {

inline constexpr std::int64_t kLargestImageSide = 16384;
inline constexpr std::int64_t kDeclaredPixelsPerByte = 8192;

// Throws InputError naming the file when `what` (such as "image" or "OpenEXR data window") of
// width x height pixels breaks either limit for a file of fileBytes bytes.
inline void checkDeclaredSize(const std::filesystem::path& path, const std::string& what, std::int64_t width,
                              std::int64_t height, std::uint64_t fileBytes) {
    const std::string size = std::to_string(width) + "x" + std::to_string(height);
    if (width > kLargestImageSide || height > kLargestImageSide)
        throw inputError(path, 0, what + " too large: " + size + " pixels (at most 16384 on a side)");
    if (std::uint64_t(width) * std::uint64_t(height) >
        (std::uint64_t(1) << 20) + fileBytes * std::uint64_t(kDeclaredPixelsPerByte))
        throw inputError(path, 0,
                         "corrupt or truncated file: its header declares " + what + " of " + size +
                             " pixels, but the file has only " + std::to_string(fileBytes) + " bytes");
}

}  // namespace vitrum
