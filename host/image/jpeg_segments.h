// A JPEG file's segments, walked before stb_image decodes it, to refuse what stb would read out of
// bounds.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace vitrum {

// What is wrong with the JPEG's Huffman tables (DHT segments, between scans too), or nothing. A
// table holds at most 256 codes (ITU T.81, B.2.4.2); stb_image 2.27 builds one of more past the
// end of its arrays (docs/testing.md, "What fuzzing has found"). The walk stops at EOI or at the
// first segment that runs past the end of the file, which it leaves for stb to report (a DHT
// segment's tables checked first, as far as the file goes).
std::optional<std::string> jpegHuffmanTableProblem(const std::vector<unsigned char>& jpeg);

}  // namespace vitrum
