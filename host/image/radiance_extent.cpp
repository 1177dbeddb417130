#include "image/radiance_extent.h"

#include <string_view>

namespace vitrum {

RadianceExtent radianceExtent(std::span<const unsigned char> bytes, std::uint32_t width, std::uint32_t height) {
    const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    // The header ends with an empty line; the next line is the resolution ("-Y h +X w").
    const std::size_t headerEnd = text.find("\n\n");
    if (headerEnd == std::string_view::npos) return RadianceExtent::Unknown;
    const std::size_t resolutionEnd = text.find('\n', headerEnd + 2);
    if (resolutionEnd == std::string_view::npos) return RadianceExtent::Unknown;
    std::size_t pos = resolutionEnd + 1;
    const std::size_t size = bytes.size();
    auto flatRest = [&](std::uint64_t pixels) {
        return pos + pixels * 4 > size ? RadianceExtent::EndsEarly : RadianceExtent::Complete;
    };
    // stb reads flat pixels for widths it cannot run-length decode, and from the first scanline
    // that does not start with the encoding's marker on.
    if (width < 8 || width >= 32768) return flatRest(std::uint64_t(width) * height);
    for (std::uint32_t y = 0; y < height; ++y) {
        if (pos + 4 > size) return RadianceExtent::EndsEarly;
        if (bytes[pos] != 2 || bytes[pos + 1] != 2 || (bytes[pos + 2] & 0x80))
            return flatRest(std::uint64_t(width) * (height - y));
        pos += 4;
        for (int channel = 0; channel < 4; ++channel) {
            for (std::uint32_t x = 0; x < width;) {
                if (pos >= size) return RadianceExtent::EndsEarly;
                std::uint32_t count = bytes[pos++];
                std::size_t data = count;
                if (count > 128) {
                    count -= 128;
                    data = 1;
                }
                // A zero or overlong run is stb's to report (as bad RLE data); nothing follows it.
                if (count == 0 || count > width - x) return RadianceExtent::Complete;
                if (pos + data > size) return RadianceExtent::EndsEarly;
                pos += data;
                x += count;
            }
        }
    }
    return RadianceExtent::Complete;
}

}  // namespace vitrum
