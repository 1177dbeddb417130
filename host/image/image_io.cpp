// Reading and writing images: PNG and the other 8-bit formats through stb (sRGB), binary PNM by hand
// (sRGB, pnm_file.h), WebP through libwebp (sRGB, webp_file.h), Radiance HDR through stb (linear), PFM by hand (linear), OpenEXR through its
// library (linear, openexr_file.h). Writes go to a temporary file next to the target that is
// renamed into place, so a failed write never leaves a partial output behind.
#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/file_extension.h"
#include "common/input_file.h"
#include "image/declared_size.h"
#include "image/image.h"
#include "image/openexr_file.h"
#include "image/jpeg_segments.h"
#include "image/png_chunks.h"
#include "image/png_writer.h"
#include "image/pnm_file.h"
#include "image/radiance_extent.h"
#include "image/srgb.h"
#include "image/webp_file.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;

// A value fit for a file: non-finite becomes 0.
float finiteOrZero(float v) { return std::isfinite(v) ? v : 0.0f; }

// stb's reason for a failure, printable: it names an unknown PNG chunk by its four bytes,
// whatever they are ("\xD5\xF6;\x0B PNG chunk not known"), and those are shown escaped.
std::string stbReason() {
    const char* reason = stbi_failure_reason();
    if (!reason) return "unknown error";
    std::string shown;
    for (const char* c = reason; *c; ++c) {
        const auto byte = static_cast<unsigned char>(*c);
        if (byte >= 0x20 && byte < 0x7f) {
            shown += char(byte);
        } else {
            static constexpr char kHex[] = "0123456789ABCDEF";
            shown += {'\\', 'x', kHex[byte >> 4], kHex[byte & 15]};
        }
    }
    return shown;
}

// ---- PFM ----------------------------------------------------------------------------------------

void putFloatLittleEndian(std::vector<char>& out, float v) {
    auto bits = std::bit_cast<std::uint32_t>(v);
    for (int i = 0; i < 4; ++i) out.push_back(char((bits >> (8 * i)) & 0xffu));
}

float getFloat(const unsigned char* p, bool littleEndian) {
    std::uint32_t bits = 0;
    for (int i = 0; i < 4; ++i) {
        std::uint32_t byte = littleEndian ? p[i] : p[3 - i];
        bits |= byte << (8 * i);
    }
    return std::bit_cast<float>(bits);
}

// Writes a little-endian PFM (scale -1), rows bottom to top. Returns false with errno set on failure.
bool writePfm(const Image& image, const fs::path& file) {
    std::vector<char> data;
    std::string header = "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
    data.reserve(header.size() + image.pixels.size() * 12);
    data.insert(data.end(), header.begin(), header.end());
    for (std::uint32_t row = image.height; row-- > 0;) {
        for (std::uint32_t x = 0; x < image.width; ++x) {
            const glm::vec3& p = image.at(x, row);
            for (int c = 0; c < 3; ++c) putFloatLittleEndian(data, finiteOrZero(p[c]));
        }
    }
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    if (!out) return false;
    out.write(data.data(), std::streamsize(data.size()));
    out.close();
    return bool(out);
}

// Reads the next whitespace-separated token of a PFM header; `pos` ends on the character after it.
std::string pfmToken(const std::vector<unsigned char>& bytes, std::size_t& pos) {
    while (pos < bytes.size() && std::isspace(bytes[pos])) ++pos;
    std::string token;
    while (pos < bytes.size() && !std::isspace(bytes[pos]) && token.size() < 64) token.push_back(char(bytes[pos++]));
    return token;
}

Image readPfm(const fs::path& path, const PixelLimit& limit) {
    const std::vector<unsigned char> bytes = readInputFile(path, "the image", kMaxImageFileBytes);

    auto corrupt = [&](const std::string& what) { return inputError(path, 0, "corrupt PFM file: " + what); };
    if (bytes.size() < 2 || bytes[0] != 'P' || (bytes[1] != 'F' && bytes[1] != 'f')) {
        throw corrupt("expected the magic 'PF' or 'Pf'");
    }
    const int channels = bytes[1] == 'F' ? 3 : 1;
    std::size_t pos = 2;
    std::string widthText = pfmToken(bytes, pos);
    std::string heightText = pfmToken(bytes, pos);
    std::string scaleText = pfmToken(bytes, pos);
    long long width = 0;
    long long height = 0;
    double scale = 0.0;
    try {
        std::size_t used = 0;
        width = std::stoll(widthText, &used);
        if (used != widthText.size()) throw std::invalid_argument("width");
        height = std::stoll(heightText, &used);
        if (used != heightText.size()) throw std::invalid_argument("height");
        scale = std::stod(scaleText, &used);
        if (used != scaleText.size()) throw std::invalid_argument("scale");
    } catch (const std::exception&) {
        throw corrupt("expected 'width height scale' in the header, got '" + widthText + " " + heightText + " " +
                      scaleText + "'");
    }
    if (width <= 0 || height <= 0 || width > (1 << 16) || height > (1 << 16)) {
        throw corrupt("bad size " + widthText + "x" + heightText);
    }
    if (scale == 0.0 || !std::isfinite(scale)) throw corrupt("bad scale " + scaleText);
    limit.check(path, "image", std::uint64_t(width), std::uint64_t(height));
    // Exactly one whitespace character separates the header from the raster.
    if (pos >= bytes.size() || !std::isspace(bytes[pos])) throw corrupt("truncated header");
    ++pos;
    const bool littleEndian = scale < 0.0;
    const std::size_t needed = std::size_t(width) * std::size_t(height) * std::size_t(channels) * 4;
    if (bytes.size() - pos < needed) {
        throw corrupt("expected " + std::to_string(needed) + " bytes of pixel data, got " +
                      std::to_string(bytes.size() - pos));
    }

    Image image(static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height));
    bool nonFinite = false;
    const unsigned char* p = bytes.data() + pos;
    for (std::uint32_t row = image.height; row-- > 0;) {
        for (std::uint32_t x = 0; x < image.width; ++x) {
            glm::vec3 v;
            for (int c = 0; c < channels; ++c, p += 4) v[c] = getFloat(p, littleEndian);
            if (channels == 1) v = glm::vec3(v[0]);
            for (int c = 0; c < 3; ++c) {
                if (!std::isfinite(v[c])) {
                    nonFinite = true;
                    v[c] = 0.0f;
                }
            }
            image.at(x, row) = v;
        }
    }
    if (nonFinite) warn(path.string() + ": non-finite pixel values read as 0");
    return image;
}

// ---- stb ----------------------------------------------------------------------------------------

// The whole file, for stb to decode from memory: stb 2.27 rewinds a FILE only within its first
// 128-byte buffer, so a format test that reads further left the next test looking at the middle
// of the file (its PNM reader, with its 16-bit bugs, found "P5" at byte 128; found by fuzzing).
struct FileBytes {
    std::vector<unsigned char> bytes;
    int size() const { return int(bytes.size()); }
    const unsigned char* data() const { return bytes.data(); }
};

FileBytes readFileBytes(const fs::path& path) {
    static_assert(kMaxImageFileBytes <= std::uint64_t(std::numeric_limits<int>::max()), "stb takes an int size");
    return FileBytes{readInputFile(path, "the image", kMaxImageFileBytes)};
}

// stb decodes whatever size a header declares, reading zeros past the end of a truncated file:
// 137 bytes of TGA can ask for 256 x 65535 pixels (found by fuzzing). So the declared size is
// checked first (declared_size.h).
void checkStbDeclaredSize(const fs::path& path, const FileBytes& file, const PixelLimit& limit) {
    int w = 0;
    int h = 0;
    int n = 0;
    if (!stbi_info_from_memory(file.data(), file.size(), &w, &h, &n)) return;  // stbi_load reports why
    checkDeclaredSize(path, "image", std::max(w, 0), std::max(h, 0), std::uint64_t(file.size()));
    limit.check(path, "image", std::uint64_t(std::max(w, 0)), std::uint64_t(std::max(h, 0)));
}

// The size stb decoded must be the one its header parser declared, which the limits were checked
// against (checkStbDeclaredSize): two parsers of one header must not disagree unseen.
void requireDeclaredSize(const fs::path& path, const FileBytes& file, int width, int height) {
    int w = 0;
    int h = 0;
    int n = 0;
    if (!stbi_info_from_memory(file.data(), file.size(), &w, &h, &n) || w != width || h != height)
        throw inputError(path, 0, "cannot read image: decoded as " + std::to_string(width) + "x" +
                                      std::to_string(height) + " pixels, but its header declares " + std::to_string(w) +
                                      "x" + std::to_string(h));
}

Image readLinearHdr(const fs::path& path, const FileBytes& file) {
    int w = 0;
    int h = 0;
    int n = 0;
    if (stbi_info_from_memory(file.data(), file.size(), &w, &h, &n) &&
        radianceExtent(file.bytes, std::uint32_t(w), std::uint32_t(h)) == RadianceExtent::EndsEarly)
        throw inputError(path, 0, "truncated Radiance HDR file: its " + std::to_string(w) + "x" + std::to_string(h) +
                                      " pixels need more data than the file holds");
    float* data = stbi_loadf_from_memory(file.data(), file.size(), &w, &h, &n, 3);
    if (!data) throw inputError(path, 0, "cannot read image: " + stbReason());
    std::unique_ptr<float, void (*)(void*)> owned(data, stbi_image_free);
    requireDeclaredSize(path, file, w, h);
    Image image(static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h));
    bool nonFinite = false;
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            float v = data[i * 3 + c];
            if (!std::isfinite(v)) {
                nonFinite = true;
                v = 0.0f;
            }
            image.pixels[i][c] = v;
        }
    }
    if (nonFinite) warn(path.string() + ": non-finite pixel values read as 0");
    return image;
}

// PNG and JPEG, the 8- and 16-bit images vitrum reads (docs/scene-format.md). stb_image decodes
// more (BMP, TGA, GIF, PSD, PIC) but reads zeros past the end of a truncated one and returns it
// without an error (a BMP cut in half loaded as a half-black map, issue 48): those are refused.
bool isPngOrJpeg(const FileBytes& file) {
    const std::vector<unsigned char>& b = file.bytes;
    static constexpr unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (b.size() >= 8 && std::equal(kPng, kPng + 8, b.begin())) return true;
    return b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF;
}

Image readSrgb(const fs::path& path, const FileBytes& file) {
    if (!isPngOrJpeg(file))
        throw inputError(path, 0, "cannot read image: not PNG, JPEG, WebP, Radiance HDR, PFM, binary PNM or OpenEXR");
    int w = 0;
    int h = 0;
    int n = 0;
    // Grey or colour with alpha (stb's 2 and 4 channels): alpha is kept beside the colour.
    const bool withAlpha = stbi_info_from_memory(file.data(), file.size(), &w, &h, &n) && (n == 2 || n == 4);
    const int channels = withAlpha ? 4 : 3;
    if (stbi_is_16_bit_from_memory(file.data(), file.size())) {
        stbi_us* data = stbi_load_16_from_memory(file.data(), file.size(), &w, &h, &n, channels);
        if (!data) throw inputError(path, 0, "cannot read image: " + stbReason());
        std::unique_ptr<stbi_us, void (*)(void*)> owned(data, stbi_image_free);
        requireDeclaredSize(path, file, w, h);
        Image image(static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h));
        for (std::size_t i = 0; i < image.pixels.size(); ++i) {
            for (int c = 0; c < 3; ++c) image.pixels[i][c] = srgbToLinear(float(data[i * channels + c]) / 65535.0f);
        }
        if (channels == 4) {
            image.alpha.resize(image.pixels.size());
            for (std::size_t i = 0; i < image.alpha.size(); ++i) image.alpha[i] = float(data[i * 4 + 3]) / 65535.0f;
        }
        return image;
    }
    stbi_uc* data = stbi_load_from_memory(file.data(), file.size(), &w, &h, &n, channels);
    if (!data) throw inputError(path, 0, "cannot read image: " + stbReason());
    std::unique_ptr<stbi_uc, void (*)(void*)> owned(data, stbi_image_free);
    requireDeclaredSize(path, file, w, h);
    float table[256];
    for (int i = 0; i < 256; ++i) table[i] = srgbToLinear(float(i) / 255.0f);
    Image image(static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h));
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) image.pixels[i][c] = table[data[i * channels + c]];
    }
    if (channels == 4) {
        image.alpha.resize(image.pixels.size());
        for (std::size_t i = 0; i < image.alpha.size(); ++i) image.alpha[i] = float(data[i * 4 + 3]) / 255.0f;
    }
    return image;
}

bool writePng(const Image& image, const fs::path& file) {
    const std::vector<unsigned char> png = encodePng(image);
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
    out.close();
    return bool(out);
}

bool writeHdr(const Image& image, const fs::path& file) {
    // RGBE cannot hold negative values: they become 0 like non-finite ones.
    std::vector<float> data(image.pixels.size() * 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) data[i * 3 + c] = std::max(finiteOrZero(image.pixels[i][c]), 0.0f);
    }
    return stbi_write_hdr(file.string().c_str(), int(image.width), int(image.height), 3, data.data()) != 0;
}

// The OpenEXR library reports a failure by an exception, which writeImage turns into its message.
bool writeExr(const Image& image, const fs::path& file) {
    writeOpenExr(image, file);
    return true;
}

}  // namespace

void writeImage(const Image& image, const fs::path& path) {
    const std::string ext = lowerCaseExtension(path);
    bool (*writer)(const Image&, const fs::path&) = nullptr;
    if (ext == ".png") {
        writer = writePng;
    } else if (ext == ".pfm") {
        writer = writePfm;
    } else if (ext == ".hdr") {
        writer = writeHdr;
    } else if (ext == ".exr") {
        writer = writeExr;
    } else {
        throw inputError(path, 0, "unknown image format '" + ext + "' (use .png, .pfm, .hdr or .exr)");
    }
    if (image.width == 0 || image.height == 0 || image.pixels.size() != std::size_t(image.width) * image.height) {
        throw inputError(path, 0, "cannot write an empty or malformed image (" + std::to_string(image.width) + "x" +
                                      std::to_string(image.height) + ")");
    }
    if (image.width > (1u << 16) || image.height > (1u << 16)) {
        throw inputError(path, 0, "image too large to write");
    }
    const fs::path parent = path.parent_path();
    std::error_code ec;
    if (!parent.empty() && !fs::is_directory(parent, ec)) {
        throw inputError(path, 0, "cannot write image: directory " + parent.string() + " does not exist");
    }

    const fs::path temporary = temporaryFor(path);
    errno = 0;
    std::string reason;
    try {
        if (!writer(image, temporary)) reason = errno ? std::strerror(errno) : "write failed";
    } catch (const std::exception& e) {
        reason = e.what();
    }
    if (!reason.empty()) {
        fs::remove(temporary, ec);
        throw inputError(path, 0, "cannot write image: " + reason);
    }
    fs::rename(temporary, path, ec);
    if (ec) {
        std::error_code ignored;
        fs::remove(temporary, ignored);
        throw inputError(path, 0, "cannot write image: " + ec.message());
    }
}

Image readImage(const fs::path& path, const PixelLimit& limit) {
    requireRegularFile(path, "the image");  // the OpenEXR library opens it itself
    const std::string ext = lowerCaseExtension(path);
    if (ext == ".pfm") return readPfm(path, limit);
    if (ext == ".exr") return readOpenExr(path, limit);
    FileBytes file = readFileBytes(path);
    if (ext == ".hdr" && !stbi_is_hdr_from_memory(file.data(), file.size()))
        throw inputError(path, 0, "cannot read image: not a Radiance HDR file");
    return decodeImage(path, std::move(file.bytes), limit);
}

// Decides by content between linear Radiance HDR and sRGB 8/16-bit images, so a misnamed .hdr is
// never gamma-converted by stb.
Image decodeImage(const fs::path& name, std::vector<unsigned char> bytes, const PixelLimit& limit) {
    if (bytes.size() > kMaxImageFileBytes) throw inputError(name, 0, "the image is too large");
    FileBytes file{std::move(bytes)};
    removeEmptyImageDataChunks(file.bytes);
    if (const auto problem = pngChunkPastTheEnd(file.bytes))
        throw inputError(name, 0, "cannot read PNG image: cut short: " + *problem);
    if (isBinaryPnm(file.bytes)) return readPnm(name, file.bytes, limit);
    if (isWebp(file.bytes)) return readWebp(name, file.bytes, limit);
    // Before stb reads any header: stb_image_info builds a JPEG's Huffman tables too.
    if (const auto problem = jpegHuffmanTableProblem(file.bytes); problem && !isPng(file.bytes))
        throw inputError(name, 0, "cannot read JPEG image: " + *problem);
    checkStbDeclaredSize(name, file, limit);
    if (stbi_is_hdr_from_memory(file.data(), file.size())) return readLinearHdr(name, file);
    return readSrgb(name, file);
}

}  // namespace vitrum
