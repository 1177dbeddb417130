// OpenEXR files (host/image/openexr_file.h) through readImage and writeImage. The files other than
// vitrum's own are written here with the OpenEXR library directly (half channels, grey, luminance
// and chroma, windows) or come from the course (test.exr, beside the same picture as test.hdr).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <Imath/ImathBox.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfRgbaFile.h>

#include "common/error.h"
#include "image/image.h"

#include "../support/temporary_folder_test.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;

using OpenExrTest = testing::TemporaryFolderTest;

std::string inputErrorOf(const fs::path& path) {
    try {
        readImage(path);
    } catch (const InputError& e) {
        return e.what();
    }
    return "<no InputError>";
}

// A file of float channels `names` over `data` (display window `display`), channel c of pixel
// (x, y) of the data window being value(x, y, c).
template <class Value>
void writeFloatChannels(const fs::path& path, const Imath::Box2i& display, const Imath::Box2i& data,
                        const std::vector<std::string>& names, Value value) {
    const int w = data.max.x - data.min.x + 1;
    const int h = data.max.y - data.min.y + 1;
    const std::size_t n = names.size();
    std::vector<float> values(std::size_t(w) * h * n);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (std::size_t c = 0; c < n; ++c) values[(std::size_t(y) * w + x) * n + c] = value(x, y, int(c));
    Imf::Header header(display, data);
    Imf::FrameBuffer frame;
    for (std::size_t c = 0; c < n; ++c) {
        header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
        frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, values.data() + c, data, n * sizeof(float),
                                                n * sizeof(float) * std::size_t(w)));
    }
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(h);
}

// The course's test.exr (float RGBA, ZIP) and test.hdr are the same picture: they agree to RGBE's
// precision, each channel within one mantissa step of the pixel's largest (at most 2/256 of it).
TEST_F(OpenExrTest, CourseExrIsTheCourseHdrsPicture) {
    const fs::path images = fs::path(VITRUM_SHARED_DIR) / "scenes/course/images";
    const Image exr = readImage(images / "test.exr");
    const Image hdr = readImage(images / "test.hdr");
    ASSERT_EQ(exr.width, 64u);
    ASSERT_EQ(exr.height, 32u);
    ASSERT_EQ(hdr.width, exr.width);
    ASSERT_EQ(hdr.height, exr.height);
    float largestOfAll = 0.0f;
    for (std::size_t i = 0; i < exr.pixels.size(); ++i) {
        const float largest = std::max({exr.pixels[i].r, exr.pixels[i].g, exr.pixels[i].b});
        largestOfAll = std::max(largestOfAll, largest);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(hdr.pixels[i][c], exr.pixels[i][c], largest / 128.0f) << i << " " << c;
    }
    EXPECT_GT(largestOfAll, 0.5f);  // not a black picture that would agree with anything
}

// Half channels are read exactly; a file with only Y is grey; one with luminance and chroma is
// converted to RGB by the library; alpha changes nothing.
TEST_F(OpenExrTest, HalfGreyAndLuminanceChromaFiles) {
    const int w = 8;
    const int h = 4;
    // Values exact in half: k / 64, and up to 16384 in blue.
    auto exactInHalf = [](int x, int y, int c) {
        return c == 2 ? float(x + 1) * std::ldexp(1.0f, y + 8) : float(x + 8 * y + c) / 64.0f;
    };
    std::vector<Imf::Rgba> pixels(w * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            pixels[y * w + x] = Imf::Rgba(exactInHalf(x, y, 0), exactInHalf(x, y, 1), exactInHalf(x, y, 2), 0.25f);
    {
        Imf::RgbaOutputFile file((dir_ / "half.exr").c_str(), w, h, Imf::WRITE_RGBA);
        file.setFrameBuffer(pixels.data(), 1, w);
        file.writePixels(h);
    }
    const Image half = readImage(dir_ / "half.exr");
    ASSERT_EQ(half.width, unsigned(w));
    ASSERT_EQ(half.height, unsigned(h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            EXPECT_EQ(half.at(x, y), glm::vec3(exactInHalf(x, y, 0), exactInHalf(x, y, 1), exactInHalf(x, y, 2)));

    const Imath::Box2i window(Imath::V2i(0, 0), Imath::V2i(w - 1, h - 1));
    writeFloatChannels(dir_ / "grey.exr", window, window, {"Y"}, [](int x, int y, int) { return 0.1f * float(x - y); });
    const Image grey = readImage(dir_ / "grey.exr");
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) EXPECT_EQ(grey.at(x, y), glm::vec3(0.1f * float(x - y)));

    // Luminance and chroma (chroma on every second pixel each way) of one colour: the same colour
    // back, to half precision and the conversion's rounding.
    const glm::vec3 colour(0.8f, 0.35f, 0.1f);
    std::fill(pixels.begin(), pixels.end(), Imf::Rgba(colour.r, colour.g, colour.b, 1.0f));
    {
        Imf::RgbaOutputFile file((dir_ / "yc.exr").c_str(), w, h, Imf::WRITE_YC);
        file.setFrameBuffer(pixels.data(), 1, w);
        file.writePixels(h);
    }
    const Image yc = readImage(dir_ / "yc.exr");
    for (const glm::vec3& p : yc.pixels)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(p[c], colour[c], 0.01f * colour[c]) << c;
}

// The display window is the image: pixels it has and the data window lacks are 0, data outside
// it is left out.
TEST_F(OpenExrTest, DisplayWindowIsTheImage) {
    const Imath::Box2i display(Imath::V2i(10, 20), Imath::V2i(13, 22));  // 4x3
    const Imath::Box2i data(Imath::V2i(12, 19), Imath::V2i(15, 20));     // 4x2, overlapping 2x1
    writeFloatChannels(dir_ / "window.exr", display, data, {"B", "G", "R"},
                       [](int x, int y, int c) { return float(100 * c + 10 * y + x + 1); });
    const Image image = readImage(dir_ / "window.exr");
    ASSERT_EQ(image.width, 4u);
    ASSERT_EQ(image.height, 3u);
    for (std::uint32_t y = 0; y < 3; ++y) {
        for (std::uint32_t x = 0; x < 4; ++x) {
            // Display pixel (x, y) is data pixel (x - 2, y + 1) of the data window where both exist.
            const bool inData = x >= 2 && y == 0;
            const int dx = int(x) - 2;
            const int dy = int(y) + 1;
            // Channels were given in the order B, G, R.
            const glm::vec3 expected = inData ? glm::vec3(float(200 + 10 * dy + dx + 1), float(100 + 10 * dy + dx + 1),
                                                          float(10 * dy + dx + 1))
                                              : glm::vec3(0.0f);
            EXPECT_EQ(image.at(x, y), expected) << x << ", " << y;
        }
    }
}

TEST_F(OpenExrTest, NonFiniteValuesReadAsZeroNegativesKept) {
    const Imath::Box2i window(Imath::V2i(0, 0), Imath::V2i(1, 0));
    const float inf = std::numeric_limits<float>::infinity();
    writeFloatChannels(dir_ / "nan.exr", window, window, {"R", "G", "B"}, [&](int x, int, int c) {
        const float values[2][3] = {{inf, std::numeric_limits<float>::quiet_NaN(), -2.0f}, {-inf, 0.5f, 3.0f}};
        return values[x][c];
    });
    const Image image = readImage(dir_ / "nan.exr");
    EXPECT_EQ(image.at(0, 0), glm::vec3(0.0f, 0.0f, -2.0f));
    EXPECT_EQ(image.at(1, 0), glm::vec3(0.0f, 0.5f, 3.0f));
}

TEST_F(OpenExrTest, FilesWithoutColourOrDataAreInputErrors) {
    const Imath::Box2i window(Imath::V2i(0, 0), Imath::V2i(3, 3));
    writeFloatChannels(dir_ / "depth.exr", window, window, {"Z", "A"}, [](int, int, int) { return 1.0f; });
    const std::string noColour = inputErrorOf(dir_ / "depth.exr");
    EXPECT_NE(noColour.find("depth.exr"), std::string::npos) << noColour;
    EXPECT_NE(noColour.find("R, G and B"), std::string::npos) << noColour;
    EXPECT_NE(noColour.find("A, Z"), std::string::npos) << noColour;

    // Noise behind the magic number, and a good file cut short.
    std::mt19937 rng(7);
    std::string noise("\x76\x2f\x31\x01\x02\x00\x00\x00", 8);
    for (int i = 0; i < 600; ++i) noise.push_back(char(rng() & 0xff));
    std::ofstream((dir_ / "noise.exr"), std::ios::binary) << noise;
    const std::string corrupt = inputErrorOf(dir_ / "noise.exr");
    EXPECT_NE(corrupt.find("noise.exr"), std::string::npos) << corrupt;

    Image image(64, 64);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        image.pixels[i] = glm::vec3(float(i % 97), float(i % 89), 0.5f);
    writeImage(image, dir_ / "whole.exr");
    std::ifstream in(dir_ / "whole.exr", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(dir_ / "cut.exr", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    const std::string cut = inputErrorOf(dir_ / "cut.exr");
    EXPECT_NE(cut.find("cut.exr"), std::string::npos) << cut;
}

// A header may declare any size: one larger than vitrum reads, or one that the file's bytes
// cannot hold, is refused before the reader allocates for it.
TEST_F(OpenExrTest, OversizedWindowsAreRefusedBeforeReading) {
    const Imath::Box2i pixel(Imath::V2i(0, 0), Imath::V2i(0, 0));
    writeFloatChannels(dir_ / "wide.exr", Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(99999, 0)), pixel, {"R", "G", "B"},
                       [](int, int, int) { return 1.0f; });
    const std::string wide = inputErrorOf(dir_ / "wide.exr");
    EXPECT_NE(wide.find("100000x1"), std::string::npos) << wide;
    EXPECT_NE(wide.find("at most 16384"), std::string::npos) << wide;

    // The display window is the image vitrum allocates: 4096 x 4096 pixels (16.8 M) over one pixel
    // of data in a file of a few hundred bytes (which the limit puts at about 1 M + 8192 a byte).
    writeFloatChannels(dir_ / "vast.exr", Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(4095, 4095)), pixel,
                       {"R", "G", "B"}, [](int, int, int) { return 1.0f; });
    const std::string vast = inputErrorOf(dir_ / "vast.exr");
    EXPECT_NE(vast.find("display window of 4096x4096"), std::string::npos) << vast;
    EXPECT_NE(vast.find("bytes"), std::string::npos) << vast;

    // 16384 x 16384 pixels of one constant value compress to a few hundred kilobytes at most, far
    // less than 2^28 pixels need by the limit of 8192 pixels a byte; a header that declares them
    // over a file of a few hundred bytes is refused. It is written by hand: only the data window
    // of a one-pixel file is changed.
    writeFloatChannels(dir_ / "one.exr", pixel, pixel, {"R", "G", "B"}, [](int, int, int) { return 1.0f; });
    std::ifstream in(dir_ / "one.exr", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string attribute = std::string("dataWindow") + '\0' + "box2i" + '\0';
    const std::size_t at = bytes.find(attribute);
    ASSERT_NE(at, std::string::npos);
    const std::size_t box = at + attribute.size() + 4;  // after the attribute's size
    const std::int32_t forged[4] = {0, 0, 16383, 16383};
    bytes.replace(box, sizeof forged, reinterpret_cast<const char*>(forged), sizeof forged);
    std::ofstream(dir_ / "forged.exr", std::ios::binary) << bytes;
    const std::string forgedMessage = inputErrorOf(dir_ / "forged.exr");
    EXPECT_NE(forgedMessage.find("16384x16384"), std::string::npos) << forgedMessage;
    EXPECT_NE(forgedMessage.find("bytes"), std::string::npos) << forgedMessage;
}

// An attribute whose declared size is more than the file holds is refused before either reader
// opens the file: OpenEXR's C++ reader allocates an attribute of a type it does not know at its
// declared size first (an 853-byte file made it allocate 1.1 GB; tests/fuzz/regressions/image).
TEST_F(OpenExrTest, AnAttributeLargerThanTheFileIsRefusedBeforeAnyAllocation) {
    const Imath::Box2i pixel(Imath::V2i(0, 0), Imath::V2i(0, 0));
    writeFloatChannels(dir_ / "one.exr", pixel, pixel, {"R", "G", "B"}, [](int, int, int) { return 1.0f; });
    std::ifstream in(dir_ / "one.exr", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // A first attribute of a type no reader knows, declaring 1 GiB, and nothing of it in the file.
    const std::string opaque = std::string("mystery") + '\0' + "blob" + '\0' + std::string("\x00\x00\x00\x40", 4);
    bytes.insert(8, opaque);
    std::ofstream(dir_ / "opaque.exr", std::ios::binary) << bytes;
    const std::string message = inputErrorOf(dir_ / "opaque.exr");
    EXPECT_NE(message.find("\"mystery\" (blob) declares 1073741824 bytes"), std::string::npos) << message;
    EXPECT_NE(message.find("opaque.exr"), std::string::npos) << message;

    // The reader reads a compression as its one byte, whatever size the attribute declares: an
    // attribute right after it is one it meets, though a declared size of 513 would skip it.
    std::string skipped((std::istreambuf_iterator<char>(std::ifstream(dir_ / "one.exr", std::ios::binary).rdbuf())),
                        std::istreambuf_iterator<char>());
    const std::string compression = std::string("compression") + '\0' + "compression" + '\0';
    const std::size_t at = skipped.find(compression);
    ASSERT_NE(at, std::string::npos);
    const std::size_t size = at + compression.size();
    skipped.replace(size, 4, std::string("\x01\x02\x00\x00", 4));  // 513
    skipped.insert(size + 5, std::string("x") + '\0' + "mystery" + '\0' + std::string("\x00\x00\x00\x40", 4));
    std::ofstream(dir_ / "skipped.exr", std::ios::binary) << skipped;
    const std::string skippedMessage = inputErrorOf(dir_ / "skipped.exr");
    EXPECT_NE(skippedMessage.find("\"x\" (mystery) declares 1073741824 bytes"), std::string::npos) << skippedMessage;
}

}  // namespace
}  // namespace vitrum
