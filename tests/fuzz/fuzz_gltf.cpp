// libFuzzer entry for fuzzGltf() (tests/fuzz/fuzz_targets.h); built only with -DVITRUM_FUZZ=ON.
#include <cstddef>
#include <cstdint>

#include "fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return vitrum::fuzzGltf(data, size);
}
