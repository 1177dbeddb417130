// Binary Netpbm images: P5 (grey) and P6 (RGB), 8 or 16 bits a sample, read by hand.
//
// stb_image 2.27 (Debian 12) reads 16-bit samples in the machine's byte order instead of the
// format's big-endian one, converts 16-bit grey to RGB as if it were 8-bit (into a buffer half
// the size: a heap overflow, found by fuzzing), ignores maxval and reads a truncated raster
// without a word. Here a sample is v / maxval, sRGB-decoded like every 8-bit image; grey goes to
// all three channels; a header number has at most 9 digits, a side at most 16384 pixels; a
// raster shorter than the header says is an error, bytes after it are ignored.
#pragma once

#include <filesystem>
#include <vector>

#include "image/image.h"

namespace vitrum {

// Whether the file's bytes start with "P5" or "P6".
bool isBinaryPnm(const std::vector<unsigned char>& bytes);

// The image in the bytes of the file at `path`. Throws InputError naming the file for a corrupt
// or truncated file, and ImageTooLarge for one beyond `limit`.
Image readPnm(const std::filesystem::path& path, const std::vector<unsigned char>& bytes, const PixelLimit& limit = {});

}  // namespace vitrum
