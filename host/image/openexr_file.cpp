#include "image/openexr_file.h"

#include <cmath>
#include <cstdint>
#include <exception>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Imath/ImathBox.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfRgbaFile.h>
#include <OpenEXR/openexr.h>

#include "common/error.h"
#include "image/declared_size.h"

namespace vitrum {
namespace {

namespace fs = std::filesystem;

std::int64_t width(const Imath::Box2i& box) { return std::int64_t(box.max.x) - box.min.x + 1; }
std::int64_t height(const Imath::Box2i& box) { return std::int64_t(box.max.y) - box.min.y + 1; }

// The last message of the OpenEXR core library's header parse (it prints to stderr without a handler).
thread_local std::string gCoreMessage;

void keepCoreMessage(exr_const_context_t, exr_result_t, const char* message) { gCoreMessage = message ? message : ""; }

Imath::Box2i box(const exr_attr_box2i_t& b) {
    return Imath::Box2i(Imath::V2i(b.min.x, b.min.y), Imath::V2i(b.max.x, b.max.y));
}

// Both windows, the display window (the image vitrum allocates) and the data window (what the
// reader allocates), within the limits of declared_size.h.
void checkWindowSizes(const fs::path& path, const Imath::Box2i& display, const Imath::Box2i& data) {
    if (display.isEmpty()) throw inputError(path, 0, "OpenEXR display window is empty");
    std::error_code ec;
    const std::uintmax_t bytes = fs::file_size(path, ec);
    checkDeclaredSize(path, "OpenEXR display window", width(display), height(display), ec ? 0 : bytes);
    if (!data.isEmpty()) checkDeclaredSize(path, "OpenEXR data window", width(data), height(data), ec ? 0 : bytes);
}

// The first part's windows as the core library parses its header, checked before the C++ reader
// opens the file: that reader allocates for the windows (line buffers, chunk tables) as it opens
// it. The two libraries parse a malformed header each its own way (found by fuzzing), so
// readOpenExr checks the C++ reader's windows too.
void checkHeaderWindows(const fs::path& path) {
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = keepCoreMessage;
    gCoreMessage.clear();
    exr_context_t context = nullptr;
    exr_attr_box2i_t displayBox{};
    exr_attr_box2i_t dataBox{};
    exr_result_t result = exr_start_read(&context, path.c_str(), &init);
    if (result == EXR_ERR_SUCCESS) result = exr_get_display_window(context, 0, &displayBox);
    if (result == EXR_ERR_SUCCESS) result = exr_get_data_window(context, 0, &dataBox);
    exr_finish(&context);
    if (result != EXR_ERR_SUCCESS) {
        throw inputError(path, 0,
                         "cannot read OpenEXR image: " +
                             (gCoreMessage.empty() ? std::string(exr_get_error_code_as_string(result)) : gCoreMessage));
    }
    checkWindowSizes(path, box(displayBox), box(dataBox));
}

// The bytes OpenEXR's C++ reader reads for an attribute of a type it knows whose value has a
// fixed size, whatever size the attribute declares (ImfHeader.cpp's known types).
std::optional<std::uint32_t> fixedValueBytes(const std::string& type) {
    static const std::map<std::string, std::uint32_t> kFixed{
        {"box2i", 16}, {"box2f", 16},  {"compression", 1}, {"lineOrder", 1}, {"envmap", 1}, {"deepImageState", 1},
        {"int", 4},    {"float", 4},   {"double", 8},      {"rational", 8},  {"timecode", 8}, {"keycode", 28},
        {"v2i", 8},    {"v2f", 8},     {"v2d", 16},        {"v3i", 12},      {"v3f", 12},     {"v3d", 24},
        {"m33f", 36},  {"m33d", 72},   {"m44f", 64},       {"m44d", 128},    {"tiledesc", 9}, {"chromaticities", 32},
    };
    const auto found = kFixed.find(type);
    if (found == kFixed.end()) return std::nullopt;
    return found->second;
}

// Walks every header of the file as OpenEXR's C++ reader reads it and refuses one that would make
// it allocate more than the file holds. That reader allocates a string, a vector, a preview image
// or an attribute of a type it does not know at the size the file declares before reading it
// (docs/testing.md, "What fuzzing has found"), and it reads the other types by their content, not
// their declared size (a channel list up to its empty name, a compression as one byte), so the
// walk does too, to meet the attributes it meets.
// Anything else wrong with the header is left to the readers, which say what.
void checkHeaderAllocations(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::error_code ec;
    const std::uintmax_t fileBytes = fs::file_size(path, ec);
    if (!in || ec) return;
    unsigned char start[8];
    if (!in.read(reinterpret_cast<char*>(start), 8)) return;
    const std::size_t maxName = 255;  // the reader's Name::MAX_LENGTH, long-names flag or not
    const bool multiPart = (start[5] & 0x10) != 0;
    // As the reader's Xdr::read(stream, n, name): up to n + 1 characters, or to a zero byte. Where
    // none comes it goes on with the next byte (what its name buffer then holds is not ours to know).
    const auto readName = [&](std::string& name, std::size_t most) {
        name.clear();
        for (int c; (c = in.get()) != EOF;) {
            if (c == 0) return true;
            name.push_back(char(c));
            if (name.size() > most) return true;
        }
        return false;
    };
    const auto readUint = [&](std::uint32_t& value) {
        unsigned char b[4];
        if (!in.read(reinterpret_cast<char*>(b), 4)) return false;
        value = std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 | std::uint32_t(b[3]) << 24;
        return true;
    };
    const auto left = [&] { return fileBytes - std::uintmax_t(in.tellg()); };
    // A name as the message shows it: printable ASCII, the rest as '?'.
    const auto shown = [](std::string text) {
        for (char& c : text)
            if (c < 32 || c > 126) c = '?';
        return text.size() > 40 ? text.substr(0, 40) + "..." : text;
    };
    std::string name, type;
    const auto refuse = [&](std::uintmax_t bytes) {
        throw inputError(path, 0,
                         "cannot read OpenEXR image: header attribute \"" + shown(name) + "\" (" + shown(type) + ") declares " +
                             std::to_string(bytes) + " bytes, but only " + std::to_string(left()) +
                             " are left in the file");
    };
    for (int headers = 0; headers < 1 || multiPart;) {
        if (!readName(name, maxName)) return;
        if (name.empty()) {  // a header's end; a multi-part file's headers end with one more
            ++headers;
            if (!multiPart || in.peek() == 0) return;
            continue;
        }
        std::uint32_t size = 0;
        if (!readName(type, maxName) || !readUint(size)) return;
        if (const auto fixed = fixedValueBytes(type)) {
            in.seekg(std::streamoff(*fixed), std::ios::cur);
        } else if (type == "chlist") {
            std::string channel;
            for (;;) {
                if (!readName(channel, 255)) return;
                if (channel.empty()) break;
                in.seekg(16, std::ios::cur);  // pixel type, linear, reserved, x and y sampling
            }
        } else if (type == "preview") {
            std::uint32_t width = 0, height = 0;
            if (!readUint(width) || !readUint(height)) return;
            const std::uintmax_t bytes = std::uintmax_t(width) * height * 4;
            if (bytes > left()) refuse(bytes);
            in.seekg(std::streamoff(bytes), std::ios::cur);
        } else if (type == "stringvector") {
            if (size > left()) refuse(size);
            for (std::uint32_t read = 0; read < size;) {
                std::uint32_t length = 0;
                if (!readUint(length)) return;
                if (length > left()) refuse(length);
                in.seekg(std::streamoff(length), std::ios::cur);
                read += 4 + length;
            }
        } else if (type == "idmanifest") {
            throw inputError(path, 0, "cannot read OpenEXR image: its header has an ID manifest (attribute \"" +
                                          shown(name) + "\"), which vitrum does not read");
        } else {  // string, floatvector, or a type the reader does not know: read at its declared size
            if (size > left()) refuse(size);
            in.seekg(std::streamoff(size), std::ios::cur);
        }
        if (!in) return;
    }
}

std::string channelNames(const Imf::ChannelList& channels) {
    std::string names;
    for (auto c = channels.begin(); c != channels.end(); ++c)
        names += (names.empty() ? "" : ", ") + std::string(c.name());
    return names.empty() ? "none" : names;
}

// The data window's colour, 3 floats a pixel, row by row.
std::vector<float> readDataWindow(const fs::path& path, Imf::InputFile& file) {
    const Imf::Header& header = file.header();
    const Imath::Box2i data = header.dataWindow();
    const Imf::ChannelList& channels = header.channels();
    std::vector<float> rgb(std::size_t(width(data) * height(data)) * 3, 0.0f);
    const bool hasRgb = channels.findChannel("R") || channels.findChannel("G") || channels.findChannel("B");
    const bool hasChroma = channels.findChannel("RY") || channels.findChannel("BY");
    if (!hasRgb && hasChroma) {
        // Luminance and subsampled chroma: the library's RGBA interface rebuilds RGB (in half
        // precision, which is what such a file holds).
        Imf::RgbaInputFile rgba(path.c_str());
        std::vector<Imf::Rgba> halves(std::size_t(width(data) * height(data)));
        const std::intptr_t origin = std::intptr_t(data.min.x) + std::intptr_t(data.min.y) * std::intptr_t(width(data));
        rgba.setFrameBuffer(reinterpret_cast<Imf::Rgba*>(reinterpret_cast<std::intptr_t>(halves.data()) -
                                                         origin * std::intptr_t(sizeof(Imf::Rgba))),
                            1, std::size_t(width(data)));
        rgba.readPixels(data.min.y, data.max.y);
        for (std::size_t i = 0; i < halves.size(); ++i) {
            rgb[i * 3 + 0] = float(halves[i].r);
            rgb[i * 3 + 1] = float(halves[i].g);
            rgb[i * 3 + 2] = float(halves[i].b);
        }
        return rgb;
    }
    const bool grey = !hasRgb && channels.findChannel("Y");
    if (!hasRgb && !grey)
        throw inputError(path, 0,
                         "an OpenEXR image needs R, G and B (or Y) channels; this one has " + channelNames(channels));
    Imf::FrameBuffer frame;
    const std::size_t pixelBytes = 3 * sizeof(float);
    const std::size_t rowBytes = pixelBytes * std::size_t(width(data));
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < (grey ? 1 : 3); ++c) {
        frame.insert(grey ? "Y" : names[c],
                     Imf::Slice::Make(Imf::FLOAT, rgb.data() + c, data, pixelBytes, rowBytes, 1, 1, 0.0));
    }
    file.setFrameBuffer(frame);
    file.readPixels(data.min.y, data.max.y);
    if (grey) {
        for (std::size_t i = 0; i < rgb.size(); i += 3) rgb[i + 1] = rgb[i + 2] = rgb[i];
    }
    return rgb;
}

}  // namespace

Image readOpenExr(const fs::path& path, const PixelLimit& limit) {
    checkHeaderAllocations(path);
    checkHeaderWindows(path);
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i display = file.header().displayWindow();
        const Imath::Box2i data = file.header().dataWindow();
        checkWindowSizes(path, display, data);
        limit.check(path, "OpenEXR display window", std::uint64_t(width(display)), std::uint64_t(height(display)));
        Image image(std::uint32_t(width(display)), std::uint32_t(height(display)));
        if (data.isEmpty()) return image;
        const std::vector<float> rgb = readDataWindow(path, file);
        bool nonFinite = false;
        // The display window's pixels that the data window covers.
        const Imath::Box2i both(Imath::V2i(std::max(display.min.x, data.min.x), std::max(display.min.y, data.min.y)),
                                Imath::V2i(std::min(display.max.x, data.max.x), std::min(display.max.y, data.max.y)));
        for (std::int64_t y = both.min.y; y <= both.max.y; ++y) {
            for (std::int64_t x = both.min.x; x <= both.max.x; ++x) {
                const float* p = rgb.data() + ((y - data.min.y) * width(data) + (x - data.min.x)) * 3;
                glm::vec3& out = image.at(std::uint32_t(x - display.min.x), std::uint32_t(y - display.min.y));
                for (int c = 0; c < 3; ++c) {
                    nonFinite = nonFinite || !std::isfinite(p[c]);
                    out[c] = std::isfinite(p[c]) ? p[c] : 0.0f;
                }
            }
        }
        if (nonFinite) warn(path.string() + ": non-finite pixel values read as 0");
        return image;
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw inputError(path, 0, std::string("cannot read OpenEXR image: ") + e.what());
    }
}

void writeOpenExr(const Image& image, const fs::path& path) {
    std::vector<float> rgb(image.pixels.size() * 3);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = std::isfinite(image.pixels[i][c]) ? image.pixels[i][c] : 0.0f;
    }
    Imf::Header header(int(image.width), int(image.height));
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer frame;
    const std::size_t pixelBytes = 3 * sizeof(float);
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
        header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
        frame.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(rgb.data() + c), pixelBytes,
                                          pixelBytes * image.width));
    }
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(frame);
    file.writePixels(int(image.height));
}

}  // namespace vitrum
