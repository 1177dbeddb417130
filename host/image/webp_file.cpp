#include "image/webp_file.h"

#include <memory>

#include <webp/decode.h>

#include "common/error.h"
#include "image/declared_size.h"
#include "image/srgb.h"

namespace vitrum {

bool isWebp(const std::vector<unsigned char>& bytes) {
    return bytes.size() >= 12 && std::equal(bytes.begin(), bytes.begin() + 4, "RIFF") &&
           std::equal(bytes.begin() + 8, bytes.begin() + 12, "WEBP");
}

Image readWebp(const std::filesystem::path& path, const std::vector<unsigned char>& bytes, const PixelLimit& limit) {
    WebPBitstreamFeatures features;
    if (WebPGetFeatures(bytes.data(), bytes.size(), &features) != VP8_STATUS_OK)
        throw inputError(path, 0, "cannot read WebP image: corrupt or truncated header");
    if (features.has_animation) throw inputError(path, 0, "cannot read WebP image: it is an animation");
    checkDeclaredSize(path, "image", features.width, features.height, bytes.size());
    limit.check(path, "image", std::uint64_t(features.width), std::uint64_t(features.height));
    int width = 0, height = 0;
    const int channels = features.has_alpha ? 4 : 3;
    const std::unique_ptr<std::uint8_t, void (*)(void*)> rgb(
        features.has_alpha ? WebPDecodeRGBA(bytes.data(), bytes.size(), &width, &height)
                           : WebPDecodeRGB(bytes.data(), bytes.size(), &width, &height),
        WebPFree);
    if (!rgb) throw inputError(path, 0, "cannot read WebP image: corrupt or truncated data");
    if (width != features.width || height != features.height)
        throw inputError(path, 0,
                         "cannot read WebP image: decoded as " + std::to_string(width) + "x" + std::to_string(height) +
                             " pixels, but its header declares " + std::to_string(features.width) + "x" +
                             std::to_string(features.height));
    float table[256];
    for (int i = 0; i < 256; ++i) table[i] = srgbToLinear(float(i) / 255.0f);
    Image image(static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height));
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) image.pixels[i][c] = table[rgb.get()[std::size_t(channels) * i + std::size_t(c)]];
    if (channels == 4) {
        image.alpha.resize(image.pixels.size());
        for (std::size_t i = 0; i < image.alpha.size(); ++i) image.alpha[i] = float(rgb.get()[4 * i + 3]) / 255.0f;
    }
    return image;
}

}  // namespace vitrum
