#include "image/pnm_file.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <string>
#include <vector>

#include "common/error.h"
#include "image/declared_size.h"
#include "image/srgb.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;

// The next header number: whitespace and '#' comments (to the end of the line) before it, then
// 1 to 9 digits. `pos` ends on the character after it.
long headerNumber(const std::vector<unsigned char>& bytes, std::size_t& pos, const char* what, const fs::path& path) {
    while (pos < bytes.size() && (std::isspace(bytes[pos]) || bytes[pos] == '#')) {
        if (bytes[pos] == '#') {
            while (pos < bytes.size() && bytes[pos] != '\n' && bytes[pos] != '\r') ++pos;
        } else {
            ++pos;
        }
    }
    long value = 0;
    int digits = 0;
    while (pos < bytes.size() && std::isdigit(bytes[pos])) {
        if (++digits > 9) throw inputError(path, 0, std::string("corrupt PNM file: the ") + what + " is too large");
        value = value * 10 + (bytes[pos++] - '0');
    }
    if (digits == 0)
        throw inputError(path, 0, std::string("corrupt PNM file: expected the ") + what + " in the header");
    return value;
}

}  // namespace

bool isBinaryPnm(const std::vector<unsigned char>& bytes) {
    return bytes.size() >= 2 && bytes[0] == 'P' && (bytes[1] == '5' || bytes[1] == '6');
}

Image readPnm(const fs::path& path, const std::vector<unsigned char>& bytes, const PixelLimit& limit) {
    if (!isBinaryPnm(bytes)) throw inputError(path, 0, "corrupt PNM file: expected the magic 'P5' or 'P6'");
    const std::size_t channels = bytes[1] == '5' ? 1 : 3;
    std::size_t pos = 2;
    const long width = headerNumber(bytes, pos, "width", path);
    const long height = headerNumber(bytes, pos, "height", path);
    const long maxval = headerNumber(bytes, pos, "maxval", path);
    if (width < 1 || height < 1 || width > kLargestImageSide || height > kLargestImageSide)
        throw inputError(path, 0,
                         "corrupt PNM file: bad size " + std::to_string(width) + "x" + std::to_string(height) +
                             " (at most 16384 pixels on a side)");
    if (maxval < 1 || maxval > 65535)
        throw inputError(path, 0, "corrupt PNM file: maxval " + std::to_string(maxval) + " (1 to 65535)");
    limit.check(path, "image", std::uint64_t(width), std::uint64_t(height));
    // Exactly one whitespace character separates the header from the raster.
    if (pos >= bytes.size() || !std::isspace(bytes[pos]))
        throw inputError(path, 0, "corrupt PNM file: truncated header");
    ++pos;
    const std::size_t sampleBytes = maxval > 255 ? 2 : 1;
    const std::size_t needed = std::size_t(width) * std::size_t(height) * channels * sampleBytes;
    if (bytes.size() - pos < needed) {
        throw inputError(path, 0,
                         "corrupt PNM file: expected " + std::to_string(needed) + " bytes of pixel data, got " +
                             std::to_string(bytes.size() - pos));
    }

    std::vector<float> linear(std::size_t(maxval) + 1);
    for (std::size_t v = 0; v < linear.size(); ++v) linear[v] = srgbToLinear(float(v) / float(maxval));
    Image image(static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height));
    const unsigned char* p = bytes.data() + pos;
    for (glm::vec3& pixel : image.pixels) {
        for (std::size_t c = 0; c < channels; ++c, p += sampleBytes) {
            const unsigned sample = sampleBytes == 2 ? (unsigned(p[0]) << 8) | p[1] : p[0];  // big-endian
            // A sample above maxval is out of the format; it is read as maxval.
            pixel[int(c)] = linear[std::min<std::size_t>(sample, std::size_t(maxval))];
        }
        if (channels == 1) pixel = glm::vec3(pixel.r);
    }
    return image;
}

}  // namespace vitrum
