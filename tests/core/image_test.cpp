// Image files (PNG, PFM, HDR; OpenEXR in openexr_file_test.cpp), their failure modes, the image comparison and the sRGB curve.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <stb/stb_image_write.h>
#include <webp/encode.h>
#include <zlib.h>

#include "common/error.h"
#include "image/image.h"
#include "image/image_diff.h"
#include "image/png_chunks.h"
#include "image/srgb.h"

#include "../support/temporary_folder_test.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;

class ImageIoTest : public testing::TemporaryFolderTest {
protected:
    // Number of entries in the test directory (temporary files included).
    int entryCount() const {
        int n = 0;
        for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir_)) ++n;
        return n;
    }
    void writeBytes(const fs::path& path, const std::string& bytes) const {
        std::ofstream out(path, std::ios::binary);
        out.write(bytes.data(), std::streamsize(bytes.size()));
    }
};

// A gradient over the whole [0, 1] range, different in each channel, plus a few out-of-range values.
Image gradient(std::uint32_t w, std::uint32_t h) {
    Image image(w, h);
    for (std::uint32_t y = 0; y < h; ++y) {
        for (std::uint32_t x = 0; x < w; ++x) {
            const float t = float(x) / float(w - 1);
            const float s = float(y) / float(h - 1);
            image.at(x, y) = glm::vec3(t, 1.0f - t, t * s);
        }
    }
    return image;
}

std::string exceptionMessage(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "<no InputError>";
}

// WebP (webp_file.h): libwebp's own lossless encoder writes 8-bit sRGB values that read back as
// exactly their linear values, row 0 the top row, whatever the file's name; a file cut short is
// an InputError naming it.
TEST_F(ImageIoTest, LosslessWebpReadsAsItsSrgbValues) {
    const int width = 5, height = 3;
    std::vector<std::uint8_t> rgb(width * height * 3);
    for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = std::uint8_t(i * 17 % 256);
    std::uint8_t* encoded = nullptr;
    const std::size_t size = WebPEncodeLosslessRGB(rgb.data(), width, height, width * 3, &encoded);
    ASSERT_GT(size, 0u);
    const std::string bytes(reinterpret_cast<const char*>(encoded), size);
    WebPFree(encoded);
    const fs::path path = dir_ / "texture.webp", misnamed = dir_ / "texture.png", cut = dir_ / "cut.webp";
    for (const fs::path& file : {path, misnamed}) std::ofstream(file, std::ios::binary) << bytes;
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    for (const fs::path& file : {path, misnamed}) {
        const Image image = readImage(file);
        ASSERT_EQ(image.width, std::uint32_t(width));
        ASSERT_EQ(image.height, std::uint32_t(height));
        for (std::size_t i = 0; i < image.pixels.size(); ++i)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(image.pixels[i][c], srgbToLinear(float(rgb[3 * i + std::size_t(c)]) / 255.0f));
    }
    try {
        readImage(cut);
        ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("cut.webp: cannot read WebP image"), std::string::npos) << e.what();
    }
}

// The alpha channel (glTF's alphaMode MASK reads it): an RGBA or grey-and-alpha PNG (8 or 16
// bits) and an RGBA WebP keep it, linear (a / 255, a / 65535), beside colours decoded as without
// it; an image without alpha has none. The files are written by stb_image_write and libwebp.
TEST_F(ImageIoTest, AlphaIsReadBesideTheColourWhereTheFileHasIt) {
    auto png = [&](const std::string& name, int channels, const std::vector<std::uint8_t>& values) {
        const fs::path path = dir_ / name;
        EXPECT_NE(stbi_write_png(path.string().c_str(), 2, 1, channels, values.data(), 2 * channels), 0);
        return readImage(path);
    };
    const Image rgba = png("rgba.png", 4, {10, 20, 30, 0, 200, 150, 100, 77});
    EXPECT_EQ(rgba.pixels[1],
              glm::vec3(srgbToLinear(200 / 255.0f), srgbToLinear(150 / 255.0f), srgbToLinear(100 / 255.0f)));
    EXPECT_EQ(rgba.alpha, (std::vector<float>{0.0f, 77 / 255.0f}));
    const Image greyAlpha = png("grey_alpha.png", 2, {40, 255, 90, 128});
    EXPECT_EQ(greyAlpha.pixels[0], glm::vec3(srgbToLinear(40 / 255.0f)));
    EXPECT_EQ(greyAlpha.alpha, (std::vector<float>{1.0f, 128 / 255.0f}));
    EXPECT_TRUE(png("rgb.png", 3, {1, 2, 3, 4, 5, 6}).alpha.empty());
    EXPECT_TRUE(png("grey.png", 1, {1, 2}).alpha.empty());

    // A 16-bit RGBA PNG, written here byte by byte (stb writes 8 bits): big-endian samples.
    const std::uint16_t samples[4] = {0x1234, 0xFFFF, 0x0000, 0x8000};
    std::vector<unsigned char> raw = {0};  // filter type 0, then one pixel
    for (std::uint16_t v : samples) {
        raw.push_back(std::uint8_t(v >> 8));
        raw.push_back(std::uint8_t(v & 0xFF));
    }
    std::vector<unsigned char> compressed(compressBound(uLong(raw.size())));
    uLongf compressedSize = uLongf(compressed.size());
    ASSERT_EQ(compress(compressed.data(), &compressedSize, raw.data(), uLong(raw.size())), Z_OK);
    compressed.resize(compressedSize);
    std::string file("\x89PNG\r\n\x1a\n", 8);
    auto chunk = [&](const char* type, const std::vector<unsigned char>& data) {
        auto u32 = [&](std::uint32_t v) {
            for (int s = 24; s >= 0; s -= 8) file += char((v >> s) & 0xFF);
        };
        u32(std::uint32_t(data.size()));
        std::string body(type, 4);
        body.append(data.begin(), data.end());
        file += body;
        u32(std::uint32_t(crc32(0, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size()))));
    };
    chunk("IHDR", {0, 0, 0, 1, 0, 0, 0, 1, 16, 6, 0, 0, 0});  // 1 x 1, 16 bits, RGBA
    chunk("IDAT", compressed);
    chunk("IEND", {});
    std::ofstream(dir_ / "deep.png", std::ios::binary) << file;
    const Image deep = readImage(dir_ / "deep.png");
    EXPECT_EQ(deep.pixels[0].x, srgbToLinear(0x1234 / 65535.0f));
    EXPECT_EQ(deep.alpha, std::vector<float>{0x8000 / 65535.0f});

    const std::uint8_t webpPixels[8] = {255, 0, 0, 255, 0, 0, 255, 3};
    std::uint8_t* encoded = nullptr;
    const std::size_t size = WebPEncodeLosslessRGBA(webpPixels, 2, 1, 8, &encoded);
    ASSERT_GT(size, 0u);
    std::ofstream(dir_ / "alpha.webp", std::ios::binary) << std::string(reinterpret_cast<const char*>(encoded), size);
    WebPFree(encoded);
    const Image webp = readImage(dir_ / "alpha.webp");
    EXPECT_EQ(webp.pixels[1], glm::vec3(0.0f, 0.0f, 1.0f));
    EXPECT_EQ(webp.alpha, (std::vector<float>{1.0f, 3 / 255.0f}));
}

TEST_F(ImageIoTest, PngRoundTripWithinQuantisation) {
    Image image = gradient(256, 5);
    image.at(0, 0) = glm::vec3(-0.5f, 2.0f, std::numeric_limits<float>::quiet_NaN());  // clamped, NaN -> 0
    const fs::path path = dir_ / "gradient.png";
    writeImage(image, path);
    ASSERT_TRUE(fs::exists(path));
    EXPECT_EQ(entryCount(), 1);  // no temporary left behind
    const Image read = readImage(path);
    ASSERT_EQ(read.width, image.width);
    ASSERT_EQ(read.height, image.height);
    EXPECT_EQ(read.at(0, 0), glm::vec3(0.0f, 1.0f, 0.0f));
    for (std::size_t i = 1; i < image.pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const float v = image.pixels[i][c];
            const float got = read.pixels[i][c];
            // Exactly the 8-bit code nearest to the sRGB value, decoded ...
            const float expected = srgbToLinear(std::round(linearToSrgb(v) * 255.0f) / 255.0f);
            EXPECT_NEAR(got, expected, 1e-6f) << "pixel " << i << " channel " << c;
            // ... which is within half an 8-bit step of the value in sRGB space.
            EXPECT_LE(std::fabs(linearToSrgb(got) - linearToSrgb(v)), 0.5f / 255.0f + 1e-5f);
        }
    }
}

// PFM and OpenEXR keep 32-bit floats: negative, tiny and huge (beyond half floats) values alike.
TEST_F(ImageIoTest, FloatFormatsRoundTripExactly) {
    Image image(7, 3);
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> dist(-3.0f, 1000.0f);
    for (auto& p : image.pixels) p = glm::vec3(dist(rng), dist(rng), dist(rng));
    image.at(1, 1) = glm::vec3(1e-30f, 0.0f, 65504.0f);
    image.at(2, 1) = glm::vec3(-0.0f, 1e30f, 1.0f / 3.0f);
    for (const char* name : {"exact.PFM", "exact.EXR"}) {  // the extension is case-insensitive
        const fs::path path = dir_ / name;
        writeImage(image, path);
        const Image read = readImage(path);
        ASSERT_EQ(read.width, 7u) << name;
        ASSERT_EQ(read.height, 3u) << name;
        for (std::size_t i = 0; i < image.pixels.size(); ++i) EXPECT_EQ(read.pixels[i], image.pixels[i]) << name << " " << i;
    }
}

TEST_F(ImageIoTest, PfmWrittenLittleEndianBottomUp) {
    Image image(1, 2);
    image.at(0, 0) = glm::vec3(1.0f, 2.0f, 3.0f);  // top row
    image.at(0, 1) = glm::vec3(4.0f, 5.0f, 6.0f);  // bottom row: first in the file
    const fs::path path = dir_ / "layout.pfm";
    writeImage(image, path);
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string header = "PF\n1 2\n-1.0\n";
    ASSERT_EQ(bytes.size(), header.size() + 24);
    EXPECT_EQ(bytes.substr(0, header.size()), header);
    float first = 0.0f;
    std::memcpy(&first, bytes.data() + header.size(), 4);  // the test machine is little endian
    EXPECT_EQ(first, 4.0f);
}

TEST_F(ImageIoTest, PfmReadsBigEndianAndGrey) {
    // 2x1 big-endian greyscale: values 0.5 and 2.0.
    std::string bytes = "Pf\n2 1\n1.0\n";
    const unsigned char data[] = {0x3f, 0x00, 0x00, 0x00, 0x40, 0x00, 0x00, 0x00};
    bytes.append(reinterpret_cast<const char*>(data), sizeof(data));
    const fs::path path = dir_ / "grey.pfm";
    writeBytes(path, bytes);
    const Image read = readImage(path);
    ASSERT_EQ(read.width, 2u);
    ASSERT_EQ(read.height, 1u);
    EXPECT_EQ(read.at(0, 0), glm::vec3(0.5f));
    EXPECT_EQ(read.at(1, 0), glm::vec3(2.0f));
}

TEST_F(ImageIoTest, PfmTruncatedIsInputError) {
    const fs::path path = dir_ / "short.pfm";
    writeBytes(path, "PF\n4 4\n-1.0\nabc");
    const std::string message = exceptionMessage([&] { readImage(path); });
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find("PFM"), std::string::npos) << message;
}

// stb_image reads zeros past the end of a Radiance file's data and returns the image: one cut
// short loaded with a black lower part (issue 48). Every cut of a run-length encoded file (64
// wide) and of a flat one (4 wide) is refused now, and the whole files still load.
TEST_F(ImageIoTest, RadianceHdrCutShortIsRefusedWherever) {
    for (const std::uint32_t width : {64u, 4u}) {
        const fs::path whole = dir_ / ("whole" + std::to_string(width) + ".hdr");
        writeImage(gradient(width, 32), whole);
        const Image read = readImage(whole);
        ASSERT_EQ(read.width, width);
        std::ifstream in(whole, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const std::size_t dataStart = bytes.find('\n', bytes.find("\n\n") + 2) + 1;
        int cuts = 0;
        for (std::size_t end = dataStart; end < bytes.size(); end += 7, ++cuts) {
            const fs::path cut = dir_ / "cut.hdr";
            writeBytes(cut, bytes.substr(0, end));
            const std::string message = exceptionMessage([&] { readImage(cut); });
            EXPECT_NE(message.find("truncated Radiance HDR file"), std::string::npos)
                << "width " << width << ", cut at " << end << " of " << bytes.size() << ": " << message;
        }
        EXPECT_GT(cuts, 20);
    }
}

// stb_image also decodes BMP, TGA, GIF, PSD and PIC, and reads zeros past the end of a truncated
// one without an error: vitrum reads PNG and JPEG (docs/scene-format.md) and refuses the rest.
TEST_F(ImageIoTest, ImageFormatsBeyondTheDocumentedOnesAreRefused) {
    std::string bmp = "BM";
    bmp.resize(54 + 4 * 4 * 3, '\0');
    const std::uint32_t header[] = {std::uint32_t(bmp.size()), 0, 54, 40, 4, 4};
    std::memcpy(bmp.data() + 2, header, sizeof(header));
    bmp[26] = 1;   // planes
    bmp[28] = 24;  // bits a pixel
    const fs::path path = dir_ / "map.bmp";
    writeBytes(path, bmp);
    const std::string message = exceptionMessage([&] { readImage(path); });
    EXPECT_NE(message.find("map.bmp: cannot read image: not PNG, JPEG, WebP, Radiance HDR, PFM, binary PNM or OpenEXR"),
              std::string::npos)
        << message;
}

TEST_F(ImageIoTest, HdrRoundTripWithinRgbePrecision) {
    Image image(16, 4);
    for (std::uint32_t y = 0; y < 4; ++y) {
        for (std::uint32_t x = 0; x < 16; ++x) {
            image.at(x, y) = glm::vec3(0.01f + float(x) * 0.7f, float(y) * 3.1f + 0.002f, 0.5f + float(x * y));
        }
    }
    const fs::path path = dir_ / "round.hdr";
    writeImage(image, path);
    const Image read = readImage(path);
    ASSERT_EQ(read.width, image.width);
    ASSERT_EQ(read.height, image.height);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        const glm::vec3& v = image.pixels[i];
        const float largest = std::max({v.r, v.g, v.b});
        for (int c = 0; c < 3; ++c) {
            // RGBE shares one exponent: each channel is exact to one mantissa step of the largest,
            // which is at most 2 / 256 of it (the mantissa of the largest lies in [128, 256)).
            EXPECT_NEAR(read.pixels[i][c], v[c], largest / 128.0f) << "pixel " << i << " channel " << c;
        }
        EXPECT_NEAR(std::max({read.pixels[i].r, read.pixels[i].g, read.pixels[i].b}), largest, largest / 128.0f);
    }
}

// PNM (host/image/pnm_file.h): a sample is v / maxval, sRGB-decoded; 16-bit samples are
// big-endian words; grey goes to all three channels, colour keeps its own.
TEST_F(ImageIoTest, PnmSamplesAreScaledByMaxvalAndBigEndian) {
    const unsigned char grey[] = {0x00, 0x00, 0x80, 0x00, 0xff, 0xff};
    writeBytes(dir_ / "grey16.pgm", "P5\n3 1\n65535\n" + std::string(reinterpret_cast<const char*>(grey), sizeof grey));
    const Image g = readImage(dir_ / "grey16.pgm");
    ASSERT_EQ(g.width, 3u);
    ASSERT_EQ(g.height, 1u);
    EXPECT_EQ(g.at(0, 0), glm::vec3(0.0f));
    EXPECT_EQ(g.at(1, 0), glm::vec3(srgbToLinear(32768.0f / 65535.0f)));
    EXPECT_EQ(g.at(2, 0), glm::vec3(1.0f));

    const unsigned char rgb[] = {0x03, 0xe8, 0x00, 0x00, 0x01, 0xf4, 0x00, 0x00, 0x00, 0x01, 0x03, 0xe8};
    writeBytes(dir_ / "rgb16.ppm", "P6\n2 1\n1000\n" + std::string(reinterpret_cast<const char*>(rgb), sizeof rgb));
    const Image c = readImage(dir_ / "rgb16.ppm");
    ASSERT_EQ(c.width, 2u);
    EXPECT_EQ(c.at(0, 0), glm::vec3(1.0f, 0.0f, srgbToLinear(500.0f / 1000.0f)));
    EXPECT_EQ(c.at(1, 0), glm::vec3(0.0f, srgbToLinear(1.0f / 1000.0f), 1.0f));

    // 8 bits with maxval 15, a comment in the header and bytes after the raster.
    const unsigned char eight[] = {15, 5, 0, 3, 15, 10, 0xAA};
    writeBytes(dir_ / "eight.ppm",
               "P6 # made by hand\n2 1 15\n" + std::string(reinterpret_cast<const char*>(eight), sizeof eight));
    const Image e = readImage(dir_ / "eight.ppm");
    EXPECT_EQ(e.at(0, 0), glm::vec3(1.0f, srgbToLinear(5.0f / 15.0f), 0.0f));
    EXPECT_EQ(e.at(1, 0), glm::vec3(srgbToLinear(3.0f / 15.0f), 1.0f, srgbToLinear(10.0f / 15.0f)));
}

TEST_F(ImageIoTest, CorruptPnmIsInputErrorNamingWhatIsWrong) {
    const std::pair<const char*, const char*> cases[] = {
        {"P6\n2 2\n255\nabc", "expected 12 bytes of pixel data, got 3"},
        {"P5\n2 2\n65535\n\x01\x02\x03\x04", "expected 8 bytes"},
        {"P6 99999999999 1 255\n", "width is too large"},
        {"P5\n20000 1\n255\n", "bad size 20000x1"},
        {"P5\n1 1\n70000\n\x01\x02", "maxval 70000"},
        {"P5\n1 1\n0\n\x01", "maxval 0"},
        {"P6\n1\n", "expected the height"},
    };
    for (const auto& [bytes, expected] : cases) {
        const fs::path path = dir_ / "bad.ppm";
        writeBytes(path, bytes);
        const std::string message = exceptionMessage([&] { readImage(path); });
        EXPECT_NE(message.find(path.string()), std::string::npos) << message;
        EXPECT_NE(message.find(expected), std::string::npos) << bytes << ": " << message;
    }
}

TEST_F(ImageIoTest, CourseImagesLoad) {
    const fs::path images = fs::path(VITRUM_SHARED_DIR) / "scenes/course/images";
    const Image png = readImage(images / "test.png");
    EXPECT_EQ(png.width, 64u);
    EXPECT_EQ(png.height, 32u);
    for (const auto& p : png.pixels) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_GE(p[c], 0.0f);
            EXPECT_LE(p[c], 1.0f);
        }
    }
    const Image hdr = readImage(images / "test.hdr");
    EXPECT_GT(hdr.width, 0u);
    EXPECT_GT(hdr.height, 0u);
    EXPECT_LE(hdr.width, 8192u);
    EXPECT_LE(hdr.height, 8192u);
    float largest = 0.0f;
    for (const auto& p : hdr.pixels) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_TRUE(std::isfinite(p[c]));
            EXPECT_GE(p[c], 0.0f);
            largest = std::max(largest, p[c]);
        }
    }
    EXPECT_GT(largest, 0.0f);
}

TEST_F(ImageIoTest, CorruptFileIsInputError) {
    std::mt19937 rng(7);
    std::string bytes;
    for (int i = 0; i < 1000; ++i) bytes.push_back(char(rng() & 0xff));
    const fs::path path = dir_ / "noise.png";
    writeBytes(path, bytes);
    const std::string message = exceptionMessage([&] { readImage(path); });
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;

    // A PNG signature followed by garbage, and an .hdr that is no Radiance file.
    writeBytes(path, std::string("\x89PNG\r\n\x1a\n", 8) + bytes);
    EXPECT_THROW(readImage(path), InputError);
    const fs::path hdr = dir_ / "noise.hdr";
    writeBytes(hdr, bytes);
    EXPECT_THROW(readImage(hdr), InputError);
    const fs::path empty = dir_ / "empty.png";
    writeBytes(empty, "");
    EXPECT_THROW(readImage(empty), InputError);
}

// stb 2.27 rewinds a file only within its first 128 bytes: reading from a FILE, a format test
// that read further left the next one at byte 128, where these bytes hold a PNM header (found by
// fuzzing). Decoded from memory they are no image at all.
TEST_F(ImageIoTest, AHeaderPastTheFirst128BytesIsNoImage) {
    const fs::path path = dir_ / "late_header.png";
    writeBytes(path, std::string(128, '\xff') + "P6\n2 1\n255\n" + std::string(6, '\x80'));
    const std::string message = exceptionMessage([&] { readImage(path); });
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find("cannot read image"), std::string::npos) << message;
}

// A PNG chunk of `type` with `data`; the CRC is left 0 (stb does not check it).
std::string pngChunk(const std::string& type, const std::string& data = "") {
    const auto length = std::uint32_t(data.size());
    std::string chunk{char(length >> 24), char(length >> 16), char(length >> 8), char(length)};
    return chunk + type + data + std::string(4, '\0');
}

// Where the first IDAT chunk starts in a PNG, its length field included.
std::size_t firstImageData(const std::string& png) {
    const std::size_t type = png.find("IDAT");
    return type == std::string::npos ? type : type - 4;
}

std::string readBytesOf(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Empty IDAT chunks hold no image data, but stb 2.27 copies the zero bytes of a first one into a
// buffer it has not allocated (memcpy(NULL, ..., 0): undefined behaviour, which clang's UBSan in
// the fuzz build reports and gcc's does not; found by fuzzing, the input kept in
// tests/fuzz/regressions/image/): they are taken out before stb decodes the file, and only they.
TEST_F(ImageIoTest, EmptyPngImageDataChunksAreTakenOutBeforeDecoding) {
    const fs::path original = dir_ / "gradient.png";
    writeImage(gradient(64, 8), original);
    const std::string bytes = readBytesOf(original);
    const std::size_t idat = firstImageData(bytes);
    ASSERT_NE(idat, std::string::npos);
    const std::uint32_t idatLength = std::uint32_t(std::uint8_t(bytes[idat])) << 24 |
                                     std::uint32_t(std::uint8_t(bytes[idat + 1])) << 16 |
                                     std::uint32_t(std::uint8_t(bytes[idat + 2])) << 8 | std::uint8_t(bytes[idat + 3]);
    const std::size_t afterIdat = idat + 12 + idatLength;
    // An empty IDAT before the first one and one after it.
    const std::string withEmpty = bytes.substr(0, idat) + pngChunk("IDAT") + bytes.substr(idat, afterIdat - idat) +
                                  pngChunk("IDAT") + bytes.substr(afterIdat);

    std::vector<unsigned char> png(withEmpty.begin(), withEmpty.end());
    EXPECT_EQ(removeEmptyImageDataChunks(png), 2u);
    EXPECT_EQ(std::string(png.begin(), png.end()), bytes);

    const fs::path mended = dir_ / "empty_idat.png";
    writeBytes(mended, withEmpty);
    EXPECT_EQ(readImage(mended).pixels, readImage(original).pixels);

    // After a chunk that runs past the end of the file nothing is taken out; nor from a non-PNG.
    const std::string cut = bytes.substr(0, idat) + bytes.substr(idat, 20) + pngChunk("IDAT");
    png.assign(cut.begin(), cut.end());
    EXPECT_EQ(removeEmptyImageDataChunks(png), 0u);
    EXPECT_EQ(std::string(png.begin(), png.end()), cut);
    std::vector<unsigned char> notPng(withEmpty.begin() + 1, withEmpty.end());
    EXPECT_EQ(removeEmptyImageDataChunks(notPng), 0u);
}

// A chunk that claims more bytes than the file has left is refused before stb decodes the file:
// stb_image 2.27 makes room for the claimed length first (1.4 GB for a mutated PNG in a glTF, found
// by fuzzing, tests/fuzz/regressions/gltf/). Bytes after IEND are no chunk of the image.
TEST_F(ImageIoTest, APngChunkRunningPastTheEndIsRefusedBeforeDecoding) {
    const fs::path original = dir_ / "gradient.png";
    writeImage(gradient(16, 4), original);
    const std::string bytes = readBytesOf(original);
    const std::size_t idat = firstImageData(bytes);
    ASSERT_NE(idat, std::string::npos);
    std::string claims = bytes;
    const std::uint32_t huge = 1407057920u;
    for (int i = 0; i < 4; ++i) claims[idat + std::size_t(i)] = char(huge >> (24 - 8 * i));
    const fs::path path = dir_ / "claims.png";
    writeBytes(path, claims);
    const std::string message = exceptionMessage([&] { readImage(path); });
    EXPECT_NE(message.find("cannot read PNG image: cut short: IDAT chunk of 1407057920 bytes at byte " +
                           std::to_string(idat) + ", where " + std::to_string(bytes.size() - idat - 12) + " are left"),
              std::string::npos)
        << message;
    EXPECT_EQ(pngChunkPastTheEnd(std::vector<unsigned char>(bytes.begin(), bytes.end())), std::nullopt);
    const fs::path trailing = dir_ / "trailing.png";
    writeBytes(trailing, bytes + std::string("\0\0\0\x7Fjunk", 8));
    EXPECT_EQ(readImage(trailing).pixels, readImage(original).pixels);
}

// stb names an unknown critical chunk by its four bytes, whatever they are: the message shows
// them escaped, never raw bytes on the user's terminal.
TEST_F(ImageIoTest, AnUnknownPngChunkIsNamedInPrintableCharacters) {
    const fs::path original = dir_ / "gradient.png";
    writeImage(gradient(8, 8), original);
    const std::string bytes = readBytesOf(original);
    const std::size_t idat = firstImageData(bytes);
    ASSERT_NE(idat, std::string::npos);
    const fs::path path = dir_ / "unknown_chunk.png";
    writeBytes(path, bytes.substr(0, idat) + pngChunk("\xD5\xF6;\x0B") + bytes.substr(idat));
    const std::string message = exceptionMessage([&] { readImage(path); });
    EXPECT_NE(message.find(R"(\xD5\xF6;\x0B PNG chunk not known)"), std::string::npos) << message;
    EXPECT_TRUE(std::all_of(message.begin(), message.end(), [](char c) { return c >= 0x20 && c < 0x7f; })) << message;
}

// A JPEG Huffman table of more than 256 codes (ITU T.81 allows no more) is refused before stb
// decodes it: stb_image 2.27 builds it past the end of its arrays (found by fuzzing,
// tests/fuzz/regressions/image/jpeg_huffman_table_of_1031_codes). The course's JPEGs still read.
TEST_F(ImageIoTest, AJpegHuffmanTableOfMoreThan256CodesIsRefused) {
    const fs::path course = fs::path(VITRUM_SHARED_DIR) / "scenes/course/allied_avenger_6887/3069bp13.jpg";
    const Image original = readImage(course);
    EXPECT_GT(original.width, 0u);
    std::string bytes = readBytesOf(course);
    const std::size_t dht = bytes.find("\xFF\xC4");
    ASSERT_NE(dht, std::string::npos);
    for (std::size_t i = 0; i < 16; ++i) bytes[dht + 5 + i] = char(20);  // 16 x 20 = 320 codes
    const fs::path path = dir_ / "huffman.jpg";
    writeBytes(path, bytes);
    const std::string message = exceptionMessage([&] { readImage(path); });
    EXPECT_NE(message.find("declares 320 codes"), std::string::npos) << message;
    EXPECT_NE(message.find("huffman.jpg"), std::string::npos) << message;
    // The same in a DHT segment whose length runs past the end of the file: stb reads the tables
    // that are there (and, before the walk checked such a segment, built this one of 700 codes
    // while reading the header for the image's size; found by fuzzing).
    const fs::path pastTheEnd =
        fs::path(VITRUM_SOURCE_DIR) / "tests/fuzz/regressions/image/jpeg_huffman_table_in_a_segment_past_the_end";
    const std::string cut = exceptionMessage([&] { readImage(pastTheEnd); });
    EXPECT_NE(cut.find("declares 700 codes"), std::string::npos) << cut;
}

TEST_F(ImageIoTest, MissingFileNamesThePath) {
    const fs::path path = dir_ / "does_not_exist.png";
    const std::string message = exceptionMessage([&] { readImage(path); });
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
}

TEST_F(ImageIoTest, UnknownExtensionWritesNothing) {
    const Image image = gradient(4, 4);
    for (const char* name : {"out.xyz", "out.jpg", "no_extension"}) {
        const fs::path path = dir_ / name;
        const std::string message = exceptionMessage([&] { writeImage(image, path); });
        EXPECT_NE(message.find(path.string()), std::string::npos) << message;
        EXPECT_FALSE(fs::exists(path));
    }
    EXPECT_EQ(entryCount(), 0);
}

TEST_F(ImageIoTest, FailedWriteLeavesNoFile) {
    const Image image = gradient(4, 4);
    for (const char* name : {"missing_dir/out.png", "missing_dir/out.pfm", "missing_dir/out.hdr", "missing_dir/out.exr"}) {
        const fs::path path = dir_ / name;
        const std::string message = exceptionMessage([&] { writeImage(image, path); });
        EXPECT_NE(message.find(path.string()), std::string::npos) << message;
        EXPECT_FALSE(fs::exists(path));
    }
    EXPECT_EQ(entryCount(), 0);
}

TEST_F(ImageIoTest, OverwriteReplacesTheFile) {
    const fs::path path = dir_ / "twice.pfm";
    Image first(2, 2);
    first.pixels.assign(4, glm::vec3(1.0f));
    writeImage(first, path);
    Image second(3, 1);
    second.pixels.assign(3, glm::vec3(0.25f));
    writeImage(second, path);
    const Image read = readImage(path);
    EXPECT_EQ(read.width, 3u);
    EXPECT_EQ(read.at(2, 0), glm::vec3(0.25f));
    EXPECT_EQ(entryCount(), 1);
}

TEST_F(ImageIoTest, NonFiniteWrittenAsZero) {
    Image image(2, 1);
    image.at(0, 0) = glm::vec3(std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN(), 1.0f);
    image.at(1, 0) = glm::vec3(-std::numeric_limits<float>::infinity(), 2.0f, 3.0f);
    for (const char* name : {"nan.pfm", "nan.hdr", "nan.exr"}) {
        const fs::path path = dir_ / name;
        writeImage(image, path);
        const Image read = readImage(path);
        EXPECT_EQ(read.at(0, 0).r, 0.0f) << name;
        EXPECT_EQ(read.at(0, 0).g, 0.0f) << name;
        EXPECT_NEAR(read.at(0, 0).b, 1.0f, 1.0f / 128.0f) << name;
        EXPECT_EQ(read.at(1, 0).r, 0.0f) << name;
    }
}

TEST(ImageDiffTest, IdenticalImages) {
    const Image a = gradient(10, 10);
    const ImageDiff d = diffImages(a, a);
    EXPECT_EQ(d.rmse, 0.0);
    EXPECT_TRUE(std::isinf(d.psnr));
    EXPECT_GT(d.psnr, 0.0);
    EXPECT_EQ(d.maxAbsError, 0.0);
    EXPECT_EQ(d.meanAbsError, 0.0);
    EXPECT_EQ(d.shareOver1of255, 0.0);
    EXPECT_EQ(d.shareOver005, 0.0);
    EXPECT_EQ(d.shareSrgb8Changed, 0.0);
}

TEST(ImageDiffTest, HandComputed2x1) {
    Image a(2, 1);
    Image b(2, 1);
    a.at(0, 0) = glm::vec3(0.0f, 0.0f, 0.0f);
    b.at(0, 0) = glm::vec3(0.01f, 0.0f, 0.0f);  // over 1/255, under 0.05
    a.at(1, 0) = glm::vec3(1.0f, 1.0f, 1.0f);
    b.at(1, 0) = glm::vec3(1.0f, 1.0f, 0.5f);  // over both
    const ImageDiff d = diffImages(a, b);
    // Channel errors 0.01, 0, 0, 0, 0, 0.5: mse = 0.2501 / 6.
    EXPECT_NEAR(d.rmse, 0.20416496597931127, 1e-7);
    EXPECT_NEAR(d.psnr, 13.80037558653141, 1e-5);
    EXPECT_NEAR(d.maxAbsError, 0.5, 1e-7);
    EXPECT_NEAR(d.meanAbsError, 0.085, 1e-7);
    EXPECT_DOUBLE_EQ(d.shareOver1of255, 1.0);
    EXPECT_DOUBLE_EQ(d.shareOver005, 0.5);
    // Symmetric.
    const ImageDiff e = diffImages(b, a);
    EXPECT_DOUBLE_EQ(e.rmse, d.rmse);
}

// The share of pixels whose PNG changes: linear 0.5 is sRGB 0.7354, code 187.52 -> 188; a
// change of 1e-4 keeps code 188, while 0.51 (sRGB 0.7416, code 189) does not.
TEST(ImageDiffTest, ShareOfChangedSrgb8Pixels) {
    Image a(4, 1);
    for (auto& p : a.pixels) p = glm::vec3(0.5f);
    Image b = a;
    ASSERT_EQ(linearToSrgb8(0.5f), 188);
    b.at(0, 0).g = 0.5001f;
    EXPECT_EQ(diffImages(a, b).shareSrgb8Changed, 0.0);
    b.at(1, 0).b = 0.51f;
    ASSERT_EQ(linearToSrgb8(0.51f), 189);
    b.at(2, 0).r = 2.0f;  // clamps to code 255
    EXPECT_DOUBLE_EQ(diffImages(a, b).shareSrgb8Changed, 0.5);
    EXPECT_DOUBLE_EQ(diffImages(b, a).shareSrgb8Changed, 0.5);
}

TEST(ImageDiffTest, NonFiniteNeverComparesWell) {
    Image a(1, 1);
    Image b(1, 1);
    b.at(0, 0) = glm::vec3(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f);
    const ImageDiff d = diffImages(a, b);
    EXPECT_TRUE(std::isinf(d.rmse));
    EXPECT_FALSE(d.psnr > 0.0);
    EXPECT_EQ(d.shareOver005, 1.0);
}

TEST(ImageDiffTest, SizeMismatch) {
    const std::string message = exceptionMessage([] { diffImages(Image(3, 2), Image(2, 3)); });
    EXPECT_EQ(message, "image sizes differ: 3x2 vs 2x3");
    EXPECT_THROW(diffHeatMap(Image(3, 2), Image(3, 3)), InputError);
}

TEST(ImageDiffTest, HeatMapRamp) {
    Image a(5, 1);
    Image b(5, 1);
    const float errors[] = {0.0f, 0.1f / 6.0f, 0.05f, 0.25f / 3.0f, 0.5f};
    for (std::uint32_t x = 0; x < 5; ++x) b.at(x, 0) = glm::vec3(0.0f, errors[x], 0.0f);
    const Image heat = diffHeatMap(a, b, 0.1f);
    ASSERT_EQ(heat.width, 5u);
    const float tol = 1e-5f;
    EXPECT_EQ(heat.at(0, 0), glm::vec3(0.0f));  // black
    EXPECT_NEAR(heat.at(1, 0).r, 0.5f, tol);  // dark red
    EXPECT_EQ(heat.at(1, 0).g, 0.0f);
    EXPECT_NEAR(heat.at(2, 0).r, 1.0f, tol);  // red to yellow
    EXPECT_NEAR(heat.at(2, 0).g, 0.5f, tol);
    EXPECT_EQ(heat.at(2, 0).b, 0.0f);
    EXPECT_NEAR(heat.at(3, 0).b, 0.5f, tol);  // yellow to white
    EXPECT_EQ(heat.at(4, 0), glm::vec3(1.0f));  // saturated white
}

TEST(SrgbTest, KnownValues) {
    EXPECT_NEAR(srgbToLinear(0.5f), 0.21404114f, 1e-6f);
    EXPECT_NEAR(linearToSrgb(0.0031308f), 0.04045f, 1e-5f);
    EXPECT_NEAR(linearToSrgb(0.5f), 0.7353570f, 1e-6f);
    EXPECT_EQ(srgbToLinear(0.0f), 0.0f);
    EXPECT_NEAR(srgbToLinear(1.0f), 1.0f, 1e-6f);
    EXPECT_NEAR(linearToSrgb(1.0f), 1.0f, 1e-6f);
    EXPECT_NEAR(srgbToLinear(0.04045f), 0.04045f / 12.92f, 1e-7f);
}

TEST(SrgbTest, RoundTrip) {
    for (int i = 0; i <= 1000; ++i) {
        const float v = float(i) / 1000.0f;
        EXPECT_NEAR(linearToSrgb(srgbToLinear(v)), v, 2e-6f) << v;
        EXPECT_NEAR(srgbToLinear(linearToSrgb(v)), v, 2e-6f) << v;
    }
    // Monotonic through the threshold between the linear and power segments.
    float previous = -1.0f;
    for (int i = 0; i <= 200; ++i) {
        const float v = 0.03f + float(i) * 0.0001f;
        const float l = srgbToLinear(v);
        EXPECT_GT(l, previous);
        previous = l;
    }
}

}  // namespace
}  // namespace vitrum
