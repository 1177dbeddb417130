#include "common/huge_pages.h"

#include <sys/mman.h>

#include <cstdint>

namespace vitrum {

void adviseHugePages(void* block, std::size_t bytes) {
    constexpr std::uintptr_t kHugePage = std::uintptr_t(2) << 20;  // x86-64's and most arm64 kernels'
    if (bytes < kHugePageBlock) return;
    const auto begin = (reinterpret_cast<std::uintptr_t>(block) + kHugePage - 1) & ~(kHugePage - 1);
    const auto end = (reinterpret_cast<std::uintptr_t>(block) + bytes) & ~(kHugePage - 1);
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

}  // namespace vitrum
