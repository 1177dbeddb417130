#include "image/jpeg_segments.h"

#include <algorithm>
#include <cstddef>

namespace vitrum {
namespace {

constexpr unsigned char kDht = 0xC4;  // define Huffman tables
constexpr unsigned char kSos = 0xDA;  // start of scan: entropy-coded data follows
constexpr unsigned char kEoi = 0xD9;

// Markers without a length: TEM and the restart markers RST0-7 (and SOI, EOI).
bool standsAlone(unsigned char marker) { return marker == 0x01 || (marker >= 0xD0 && marker <= 0xD9); }

}  // namespace

std::optional<std::string> jpegHuffmanTableProblem(const std::vector<unsigned char>& jpeg) {
    const std::size_t n = jpeg.size();
    std::size_t pos = 2;  // after SOI
    while (pos + 1 < n) {
        if (jpeg[pos] != 0xFF) {  // entropy-coded data: up to the next marker that is not a stuffed byte or RSTn
            ++pos;
            continue;
        }
        const unsigned char marker = jpeg[pos + 1];
        if (marker == 0xFF || marker == 0x00) {  // fill byte, or a stuffed 0xFF inside a scan
            pos += marker == 0xFF ? 1 : 2;
            continue;
        }
        if (marker == kEoi) return std::nullopt;
        if (standsAlone(marker)) {
            pos += 2;
            continue;
        }
        if (pos + 4 > n) return std::nullopt;
        const std::size_t length = std::size_t(jpeg[pos + 2]) << 8 | jpeg[pos + 3];
        if (length < 2) return std::nullopt;
        if (marker == kDht) {
            // Tables of: class and destination (1 byte), the codes of each length 1-16, their symbols.
            // A segment that runs past the end of the file is checked too, as far as the file goes:
            // stb builds its tables from what is there (and zeros beyond; found by fuzzing).
            std::size_t table = pos + 4;
            const std::size_t end = std::min(pos + 2 + length, n);
            while (table + 1 < end) {
                std::size_t codes = 0;
                for (std::size_t i = table + 1; i <= table + 16 && i < n; ++i) codes += jpeg[i];
                if (codes > 256)
                    return "a Huffman table (DHT segment at byte " + std::to_string(pos) + ") declares " +
                           std::to_string(codes) + " codes, more than a JPEG table holds (256)";
                table += 17 + codes;
            }
        }
        if (pos + 2 + length > n) return std::nullopt;
        pos += 2 + length;
    }
    return std::nullopt;
}

}  // namespace vitrum
