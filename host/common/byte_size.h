// A number of bytes as messages write it.
#pragma once

#include <cstdint>
#include <string>

namespace vitrum {

// "N bytes" below 1 MiB, else "N MiB" (rounded up).
inline std::string describeBytes(std::uint64_t bytes) {
    if (bytes < (std::uint64_t(1) << 20)) return std::to_string(bytes) + " bytes";
    return std::to_string((bytes + (std::uint64_t(1) << 20) - 1) >> 20) + " MiB";
}

}  // namespace vitrum
