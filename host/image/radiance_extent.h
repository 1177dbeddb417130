// Whether a Radiance HDR file holds all the pixel data its header declares. stb_image reads zeros
// past the end of the data and returns the image without an error, so a file cut short loaded as
// a map whose lower part was black (issue 48). This walks the scanlines as stb decodes them (new
// run-length encoding, else flat RGBE pixels), without decoding them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace vitrum {

enum class RadianceExtent {
    Complete,   // every scanline's data is there
    EndsEarly,  // the file ends before the last scanline's data
    Unknown,    // no header or resolution line found: stb reports it
};

// `bytes`: the whole file; `width` x `height`: the size stb read from its header.
RadianceExtent radianceExtent(std::span<const unsigned char> bytes, std::uint32_t width, std::uint32_t height);

}  // namespace vitrum
