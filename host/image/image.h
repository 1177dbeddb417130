// An image in linear RGB float, row 0 at the top, and its files: PNG (sRGB, 8 bit), PFM, Radiance
// HDR and OpenEXR (linear) by extension. Writing is all-or-nothing: a temporary file renamed into
// place, so a failure never leaves a half-written output.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

#include "image/pixel_limit.h"

namespace vitrum {

struct Image {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<glm::vec3> pixels;  // width * height, row-major, top row first
    // The alpha channel (linear, 0 to 1) of a file that has one (PNG, WebP), as `pixels`; empty
    // for an opaque image. Only textures read it (glTF's alphaMode MASK and BLEND, MTL's map_d);
    // writing ignores it.
    std::vector<float> alpha;

    Image() = default;
    Image(std::uint32_t w, std::uint32_t h) : width(w), height(h), pixels(std::size_t(w) * h, glm::vec3(0.0f)) {}
    glm::vec3& at(std::uint32_t x, std::uint32_t y) { return pixels[std::size_t(y) * width + x]; }
    const glm::vec3& at(std::uint32_t x, std::uint32_t y) const { return pixels[std::size_t(y) * width + x]; }
};

// Throws InputError for an unknown extension or a file that cannot be written.
void writeImage(const Image& image, const std::filesystem::path& path);

// PNG/JPEG/BMP/TGA are decoded from sRGB to linear; .hdr, .pfm and .exr are linear already.
// Throws InputError naming the file for a missing, corrupt or unsupported file, and ImageTooLarge,
// before decoding, for one whose header declares more pixels than `limit`.
Image readImage(const std::filesystem::path& path, const PixelLimit& limit = {});

// The same for an image file's bytes held in memory (a glTF's embedded PNG or JPEG): `name` is
// what messages call it. PFM and OpenEXR are read from files only.
Image decodeImage(const std::filesystem::path& name, std::vector<unsigned char> bytes, const PixelLimit& limit = {});

}  // namespace vitrum
