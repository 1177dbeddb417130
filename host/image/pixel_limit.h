// The most pixels a caller can hold of an image, checked against the size its header declares
// before it is decoded: a render's device keeps every texture and environment map as linear RGB
// float in one texel buffer, so an image too large for it is refused by its header, not after
// gigabytes were decoded for nothing (docs/scene-format.md, "Size limits").
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>

#include "common/byte_size.h"
#include "common/error.h"

namespace vitrum {

// Unlike an image that cannot be read, which only warns where it is a texture, an image too large
// for the device ends the load.
class ImageTooLarge : public InputError {
public:
    using InputError::InputError;
};

struct PixelLimit {
    std::uint64_t pixels = std::numeric_limits<std::uint64_t>::max();
    std::string reason;  // why no more: "llvmpipe allows 2048 MiB per texel buffer (...) for all textures"

    // Throws ImageTooLarge naming the file when `what` of width x height pixels exceeds the limit.
    void check(const std::filesystem::path& path, const std::string& what, std::uint64_t width,
               std::uint64_t height) const {
        if (width * height <= pixels) return;
        throw ImageTooLarge(inputError(path, 0,
                                       what + " of " + std::to_string(width) + "x" + std::to_string(height) +
                                           " pixels does not fit the device: it needs " +
                                           describeBytes(width * height * kBytesPerPixel) +
                                           " as linear RGB float texels of 16 bytes, but " + reason)
                                .what());
    }

    // A pixel on the device: its RGB floats and a fourth, one texel of a texel buffer
    // (shaders/shared/gpu_types.h, TextureInfo).
    static constexpr std::uint64_t kBytesPerPixel = 4 * sizeof(float);
};

}  // namespace vitrum
