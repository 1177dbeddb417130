// A PNG file's chunks, walked before stb_image decodes it, to take out what stb would read with
// undefined behaviour.
#pragma once

#include <cstddef>
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

}  // namespace vitrum
