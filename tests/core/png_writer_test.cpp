// The PNG encoder (host/image/png_writer.h), decoded by stb_image and walked chunk by chunk.
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include "image/png_writer.h"
#include "image/srgb.h"

namespace vitrum {
namespace {

std::uint32_t bigEndian(const std::vector<unsigned char>& bytes, std::size_t at) {
    return std::uint32_t(bytes[at]) << 24 | std::uint32_t(bytes[at + 1]) << 16 | std::uint32_t(bytes[at + 2]) << 8 |
           bytes[at + 3];
}

// CRC-32 as the PNG spec's annex D writes it, bit by bit: independent of the encoder's zlib.
std::uint32_t crc32Bitwise(const unsigned char* data, std::size_t size) {
    std::uint32_t crc = 0xFFFFFFFFu;
    for (std::size_t i = 0; i < size; ++i) {
        crc ^= data[i];
        for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return crc ^ 0xFFFFFFFFu;
}

struct Chunk {
    std::string type;
    std::size_t dataAt;
    std::uint32_t size;
};

// The file's chunks, each CRC checked.
std::vector<Chunk> chunksOf(const std::vector<unsigned char>& png) {
    std::vector<Chunk> chunks;
    std::size_t at = 8;
    while (at + 12 <= png.size()) {
        const std::uint32_t size = bigEndian(png, at);
        Chunk chunk{std::string(png.begin() + std::ptrdiff_t(at + 4), png.begin() + std::ptrdiff_t(at + 8)), at + 8,
                    size};
        EXPECT_LE(at + 12 + size, png.size()) << chunk.type << " runs past the file's end";
        if (at + 12 + size > png.size()) break;
        EXPECT_EQ(bigEndian(png, at + 8 + size), crc32Bitwise(&png[at + 4], size + 4)) << "CRC of " << chunk.type;
        chunks.push_back(chunk);
        at += 12 + size;
    }
    EXPECT_EQ(at, png.size()) << "bytes after the last whole chunk";
    return chunks;
}

TEST(PngWriter, DecodesToTheSrgbCodesOfEveryPixel) {
    // An odd size, values across [0, 1] and beyond it, and non-finite ones (shown as 0).
    Image image(37, 23);
    std::mt19937 random(5);
    std::uniform_real_distribution<float> value(-0.2f, 1.3f);
    for (auto& p : image.pixels) p = glm::vec3(value(random), value(random), value(random));
    image.at(3, 4) = glm::vec3(std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(), 0.5f);
    const std::vector<unsigned char> png = encodePng(image);

    int width = 0, height = 0, channels = 0;
    stbi_uc* decoded = stbi_load_from_memory(png.data(), int(png.size()), &width, &height, &channels, 0);
    ASSERT_NE(decoded, nullptr) << stbi_failure_reason();
    EXPECT_EQ(width, 37);
    EXPECT_EQ(height, 23);
    EXPECT_EQ(channels, 3);
    int wrong = 0;
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) wrong += decoded[i * 3 + c] != linearToSrgb8(image.pixels[i][c]);
    stbi_image_free(decoded);
    EXPECT_EQ(wrong, 0);
}

TEST(PngWriter, ChunksAreAWellFormedSrgbRgbImage) {
    Image image(300, 2);
    for (std::uint32_t x = 0; x < 300; ++x) image.at(x, 1) = glm::vec3(float(x) / 300.0f);
    const std::vector<unsigned char> png = encodePng(image);
    const std::vector<unsigned char> signature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    ASSERT_GE(png.size(), 8u);
    EXPECT_EQ(std::vector<unsigned char>(png.begin(), png.begin() + 8), signature);
    const std::vector<Chunk> chunks = chunksOf(png);
    ASSERT_EQ(chunks.size(), 4u);
    EXPECT_EQ(chunks[0].type, "IHDR");
    ASSERT_EQ(chunks[0].size, 13u);
    EXPECT_EQ(bigEndian(png, chunks[0].dataAt), 300u);
    EXPECT_EQ(bigEndian(png, chunks[0].dataAt + 4), 2u);
    // 8 bits a channel, colour type 2 (RGB), deflate, adaptive filters, no interlace.
    EXPECT_EQ(std::vector<unsigned char>(png.begin() + std::ptrdiff_t(chunks[0].dataAt + 8),
                                         png.begin() + std::ptrdiff_t(chunks[0].dataAt + 13)),
              (std::vector<unsigned char>{8, 2, 0, 0, 0}));
    EXPECT_EQ(chunks[1].type, "sRGB");
    ASSERT_EQ(chunks[1].size, 1u);
    EXPECT_EQ(png[chunks[1].dataAt], 0);  // perceptual intent
    EXPECT_EQ(chunks[2].type, "IDAT");
    EXPECT_EQ(chunks[3].type, "IEND");
    EXPECT_EQ(chunks[3].size, 0u);
}

TEST(PngWriter, AFlatImageIsCompressed) {
    // 512x512 of one colour: 786,944 bytes of rows, all but the first pixel of each row 0 after
    // the Sub filter: deflated, a few KiB (1,826 bytes when written); stored, it would not shrink.
    Image image(512, 512);
    for (auto& p : image.pixels) p = glm::vec3(0.25f, 0.5f, 0.75f);
    const std::vector<unsigned char> png = encodePng(image);
    EXPECT_LT(png.size(), 8000u);
    int width = 0, height = 0, channels = 0;
    stbi_uc* decoded = stbi_load_from_memory(png.data(), int(png.size()), &width, &height, &channels, 3);
    ASSERT_NE(decoded, nullptr);
    EXPECT_EQ(decoded[512 * 511 * 3 + 511 * 3 + 2], linearToSrgb8(0.75f));
    stbi_image_free(decoded);
}

}  // namespace
}  // namespace vitrum
