// PNG encoding of an image as vitrum writes it: 8-bit sRGB, compressed with zlib.
#pragma once

#include <vector>

#include "image/image.h"

namespace vitrum {

// The PNG file of `image` (at least 1x1): 8-bit RGB, each channel the sRGB code of its linear
// value (srgb8Code), an sRGB chunk saying so, every row with the Sub filter, the rows deflated by
// zlib (at level 3: fast, and smaller than stb_image_write's PNGs).
std::vector<unsigned char> encodePng(const Image& image);

}  // namespace vitrum
