// Comparing two images of the same size, channel by channel on their linear values.
#pragma once

#include "image/image.h"

namespace vitrum {

struct ImageDiff {
    double rmse = 0.0;
    double psnr = 0.0;             // dB with peak 1; +inf for identical images
    double maxAbsError = 0.0;
    double meanAbsError = 0.0;
    double shareOver1of255 = 0.0;  // share of pixels whose largest channel error exceeds 1/255
    double shareOver005 = 0.0;     // ... exceeds 0.05
    double shareSrgb8Changed = 0.0;  // share of pixels whose 8-bit sRGB PNG value differs in a channel
};

// Throws InputError when the sizes differ.
ImageDiff diffImages(const Image& a, const Image& b);

// A heat map of the largest channel error per pixel: black (0) through red and yellow to white
// (>= `fullScale`).
Image diffHeatMap(const Image& a, const Image& b, float fullScale = 0.1f);

}  // namespace vitrum
