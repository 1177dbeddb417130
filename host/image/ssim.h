// SSIM, the structural similarity index of Wang, Bovik, Sheikh and Simoncelli (IEEE TIP 13(4),
// 2004): a perceptual comparison of two images that weighs local changes of mean, contrast and
// structure. Computed the paper's way on one channel, the luma of the sRGB-encoded image (what a
// viewer sees), with an 11x11 Gaussian window of sigma 1.5 and K1 = 0.01, K2 = 0.03 for a
// dynamic range of 1. Near the border the window is cut to the image and renormalized, so every
// pixel has a value and images smaller than the window work.
#pragma once

#include <vector>

#include "image/image.h"

namespace vitrum {

// Per pixel, row-major; 1 where the images agree, down to -1. Throws InputError when the sizes differ.
std::vector<double> ssimMap(const Image& a, const Image& b);

// The mean of ssimMap: 1 for identical images. Throws InputError when the sizes differ.
double meanSsim(const Image& a, const Image& b);

// The luma SSIM compares: Rec. 709 weights on the sRGB-encoded channels, each clamped to [0, 1].
double srgbLuma(const glm::vec3& linear);

}  // namespace vitrum
