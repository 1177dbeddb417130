// Dispersion (docs/render-model-decisions.md, "Dispersion"): a glass's index of refraction as a
// function of the wavelength, and the wavelength samples a ray tree splits into, with the weights
// that turn each sample's radiance into linear sRGB. One definition for both backends: the CPU
// reference calls these, the GPU reads their numbers from the wavelength table
// (gpu_input/packed_scene.h) and adds them as dispersedIor does, in float.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace vitrum {

// The Fraunhofer lines of the Abbe number V_d = (n_d - 1) / (n_F - n_C), in micrometres.
constexpr double kLambdaD = 0.5875618, kLambdaF = 0.4861327, kLambdaC = 0.6562725;

// The wavelength samples a render may ask for (render setting `wavelengths`).
constexpr std::uint32_t kMinWavelengths = 1, kMaxWavelengths = 64;

// Cauchy's n(lambda) = A + B / lambda^2 fitted to n_d and V_d (KHR_materials_dispersion's model):
// B = (n_d - 1) / (V_d (1 / lambda_F^2 - 1 / lambda_C^2)), in square micrometres. 0 without
// dispersion (V_d <= 0).
double cauchyB(double nd, double abbe);

// The index at a wavelength sample: n_d + B * (1 / lambda^2 - 1 / lambda_d^2), the sample's
// second factor precomputed (WavelengthSample::offset). A medium without dispersion (B = 0)
// keeps n_d exactly.
inline float dispersedIor(float nd, float b, float offset) { return nd + b * offset; }

struct WavelengthSample {
    float nanometres = 0.0f;
    float offset = 0.0f;       // 1 / lambda^2 - 1 / lambda_d^2, lambda in micrometres
    glm::vec3 weight{0.0f};    // linear sRGB: a ray's weight splits into these
};

// `count` samples of [380, 780] nm: the range cut into strata of equal x + y + z under the CIE
// 1931 colour-matching functions (Wyman, Sloan and Shirley, "Simple Analytic Approximations to
// the CIE XYZ Color Matching Functions", JCGT 2013), a sample at the middle of each (in that
// measure), weighing its stratum's colour in linear sRGB (IEC 61966-2-1's matrix) over the colour
// of the whole range: the weights sum to 1 in each channel, so a spectrum of equal energy (what a
// white ray carries) is white. Single channels may be negative (outside sRGB's gamut).
std::vector<WavelengthSample> wavelengthSamples(std::uint32_t count);

}  // namespace vitrum
