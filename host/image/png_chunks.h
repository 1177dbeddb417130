// A PNG file's chunks, walked before stb_image decodes it, to take out what stb would read with
// undefined behaviour.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace vitrum {

// True when `bytes` begin with the 8-byte PNG signature.
bool isPng(const std::vector<unsigned char>& bytes);

// Removes the PNG's empty IDAT chunks and returns how many there were. They hold no image data
// (the image is the concatenation of the IDAT chunks' data), but stb_image 2.27 copies the zero
// bytes of a first one into a buffer it has not allocated yet, memcpy(NULL, ..., 0): undefined
// behaviour, found by fuzzing. The walk stops at IEND or at the first chunk that runs past the
// end of the file, whose bytes it leaves as they are for stb to report.
std::size_t removeEmptyImageDataChunks(std::vector<unsigned char>& png);

// The first chunk before IEND whose data would run past the end of the file, described ("IDAT
// chunk of 1407057920 bytes at byte 33, where 120 are left"), or nothing. stb_image 2.27 makes
// room for such a chunk's claimed length before it finds the bytes missing (a 1.4 GB allocation
// for a mutated 300-byte file, found by fuzzing): such a file is refused before it decodes.
std::optional<std::string> pngChunkPastTheEnd(const std::vector<unsigned char>& png);

}  // namespace vitrum
