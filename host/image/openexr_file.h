// OpenEXR files, linear like PFM and Radiance HDR, through Debian's OpenEXR library.
//
// Reading: the display window is the image (pixels it has and the data window lacks are 0, data
// outside it is cropped). Colour comes from the R, G and B channels (one that is missing is 0) in
// whatever type the file stores them, read as 32-bit floats; else from the luminance and chroma
// channels (Y, RY, BY), converted by the library; else from Y alone, as grey. Alpha is ignored:
// OpenEXR's colour is premultiplied, so R, G and B are the image over black. Non-finite values
// become 0 with a warning, negative ones are kept, as PFM's are.
//
// Writing: R, G and B as 32-bit floats (exact), ZIP-compressed scan lines; non-finite values
// become 0.
#pragma once

#include <filesystem>

#include "image/image.h"

namespace vitrum {

// Throws InputError naming the file for a missing, corrupt, oversized or colourless file, and
// ImageTooLarge for a display window beyond `limit`, before the pixels are read.
Image readOpenExr(const std::filesystem::path& path, const PixelLimit& limit = {});

// Throws std::exception (the library's) when the file cannot be written.
void writeOpenExr(const Image& image, const std::filesystem::path& path);

}  // namespace vitrum
