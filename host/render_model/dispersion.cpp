#include "render_model/dispersion.h"

#include <cmath>

namespace vitrum {

namespace {

// A piecewise Gaussian: width `below` left of the mean, `above` right of it (Wyman et al. 2013).
double lobe(double x, double mean, double below, double above) {
    const double t = (x - mean) / (x < mean ? below : above);
    return std::exp(-0.5 * t * t);
}

// CIE 1931 2-degree colour-matching functions, the multi-lobe fit of Wyman et al. 2013, eq. 2.
glm::dvec3 colourMatching(double nm) {
    return {1.056 * lobe(nm, 599.8, 37.9, 31.0) + 0.362 * lobe(nm, 442.0, 16.0, 26.7) - 0.065 * lobe(nm, 501.1, 20.4, 26.2),
            0.821 * lobe(nm, 568.8, 46.9, 40.5) + 0.286 * lobe(nm, 530.9, 16.3, 31.1),
            1.217 * lobe(nm, 437.0, 11.8, 36.0) + 0.681 * lobe(nm, 459.0, 26.0, 13.8)};
}

// CIE XYZ to linear sRGB (D65), IEC 61966-2-1.
glm::dvec3 linearSrgb(const glm::dvec3& xyz) {
    return {3.2404542 * xyz.x - 1.5371385 * xyz.y - 0.4985314 * xyz.z,
            -0.9692660 * xyz.x + 1.8760108 * xyz.y + 0.0415560 * xyz.z,
            0.0556434 * xyz.x - 0.2040259 * xyz.y + 1.0572252 * xyz.z};
}

}  // namespace

double cauchyB(double nd, double abbe) {
    if (!(abbe > 0.0)) return 0.0;
    return (nd - 1.0) / (abbe * (1.0 / (kLambdaF * kLambdaF) - 1.0 / (kLambdaC * kLambdaC)));
}

std::vector<WavelengthSample> wavelengthSamples(std::uint32_t count) {
    // The visible range on a 0.1 nm grid: each step's share of x + y + z (where the eye sees
    // energy) and its colour in linear sRGB.
    constexpr double kFirst = 380.0, kLast = 780.0, kStep = 0.1;
    const int steps = int(std::lround((kLast - kFirst) / kStep));
    std::vector<double> mass(static_cast<std::size_t>(steps));
    std::vector<glm::dvec3> rgb(static_cast<std::size_t>(steps));
    double totalMass = 0.0;
    glm::dvec3 white(0.0);
    for (int i = 0; i < steps; ++i) {
        const glm::dvec3 xyz = colourMatching(kFirst + (i + 0.5) * kStep);
        mass[std::size_t(i)] = xyz.x + xyz.y + xyz.z;
        rgb[std::size_t(i)] = linearSrgb(xyz);
        totalMass += mass[std::size_t(i)];
        white += rgb[std::size_t(i)];
    }
    // Strata of equal mass; a sample at its stratum's middle in mass, weighing the stratum's
    // colour: the weights sum to the white of an equal-energy spectrum, which is (1, 1, 1).
    std::vector<WavelengthSample> samples(count);
    double cumulative = 0.0;
    int i = 0;
    for (std::uint32_t k = 0; k < count; ++k) {
        const double end = totalMass * double(k + 1) / double(count), middle = totalMass * (double(k) + 0.5) / double(count);
        glm::dvec3 band(0.0);
        double nm = kLast;
        bool placed = false;
        for (; i < steps && (cumulative + mass[std::size_t(i)] <= end || k + 1 == count); ++i) {
            if (!placed && cumulative + mass[std::size_t(i)] >= middle) {
                nm = kFirst + (i + 0.5) * kStep;
                placed = true;
            }
            cumulative += mass[std::size_t(i)];
            band += rgb[std::size_t(i)];
        }
        const double micrometres = nm * 1e-3;
        samples[k].nanometres = float(nm);
        samples[k].offset = float(1.0 / (micrometres * micrometres) - 1.0 / (kLambdaD * kLambdaD));
        samples[k].weight = glm::vec3(band / white);
    }
    return samples;
}

}  // namespace vitrum
