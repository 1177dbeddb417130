#include "image/png_chunks.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cctype>
#include <cstring>
#include <string>

namespace vitrum {
namespace {

constexpr std::array<unsigned char, 8> kSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

// A chunk: 4-byte big-endian data length, 4-byte type, the data, a 4-byte CRC.
constexpr std::size_t kChunkOverhead = 12;

std::uint32_t bigEndian32(const unsigned char* p) {
    return std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 | std::uint32_t(p[3]);
}

}  // namespace

bool isPng(const std::vector<unsigned char>& bytes) {
    return bytes.size() >= kSignature.size() && std::equal(kSignature.begin(), kSignature.end(), bytes.begin());
}

std::size_t removeEmptyImageDataChunks(std::vector<unsigned char>& png) {
    if (!isPng(png)) return 0;
    std::size_t removed = 0;
    std::size_t at = kSignature.size();
    while (png.size() - at >= kChunkOverhead) {
        const std::uint64_t length = bigEndian32(&png[at]);
        if (length > png.size() - at - kChunkOverhead) break;  // runs past the end: stb reports it
        const unsigned char* type = &png[at + 4];
        if (std::memcmp(type, "IEND", 4) == 0) break;
        if (length == 0 && std::memcmp(type, "IDAT", 4) == 0) {
            png.erase(png.begin() + std::ptrdiff_t(at), png.begin() + std::ptrdiff_t(at + kChunkOverhead));
            ++removed;
            continue;
        }
        at += kChunkOverhead + std::size_t(length);
    }
    return removed;
}

std::optional<std::string> pngChunkPastTheEnd(const std::vector<unsigned char>& png) {
    if (!isPng(png)) return std::nullopt;
    for (std::size_t at = kSignature.size(); png.size() - at >= kChunkOverhead;) {
        const std::uint64_t length = bigEndian32(&png[at]);
        const std::string type(reinterpret_cast<const char*>(&png[at + 4]), 4);
        if (length > png.size() - at - kChunkOverhead) {
            std::string name;
            for (char c : type) name += std::isalpha(static_cast<unsigned char>(c)) ? c : '?';
            return name + " chunk of " + std::to_string(length) + " bytes at byte " + std::to_string(at) + ", where " +
                   std::to_string(png.size() - at - kChunkOverhead) + " are left";
        }
        if (type == "IEND") break;
        at += kChunkOverhead + std::size_t(length);
    }
    return std::nullopt;
}

}  // namespace vitrum
