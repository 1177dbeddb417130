#include "common/huge_pages.h"

#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <iterator>

namespace vitrum {

void adviseHugePages(void* block, std::size_t bytes) {
    constexpr std::uintptr_t kHugePage = std::uintptr_t(2) << 20;  // x86-64's and most arm64 kernels'
    if (bytes < kHugePageBlock) return;
    const auto begin = (reinterpret_cast<std::uintptr_t>(block) + kHugePage - 1) & ~(kHugePage - 1);
    const auto end = (reinterpret_cast<std::uintptr_t>(block) + bytes) & ~(kHugePage - 1);
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

namespace {
// glibc's own initial values (mallopt(3)).
constexpr int kDefaultTrimThreshold = 128 << 10;
constexpr int kDefaultTopPad = 128 << 10;
}  // namespace

HugePageHeap::HugePageHeap() {
#ifndef VITRUM_SANITIZED_ALLOCATOR
    // Any mallopt call stops glibc from raising its mmap threshold as blocks are freed: fixed at
    // the ceiling it would rise to, the blocks of 128 KiB to 32 MiB that Mesa allocates and frees
    // again (its device memory among them) come from the heap, not from fresh mappings each time.
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, int(2 * kHugePageHeapBytes));
    mallopt(M_TOP_PAD, int(kHugePageHeapBytes));
    // The heap grows by the pad once a block does not fit its free memory: blocks of growing size,
    // all below the mmap threshold, until the break moves.
    const auto before = reinterpret_cast<std::uintptr_t>(sbrk(0));
    constexpr std::size_t kMiB[] = {1, 2, 4, 8, 16, 31};
    void* blocks[std::size(kMiB)] = {};
    std::uintptr_t from = 0;
    for (std::size_t i = 0; i < std::size(kMiB) && reinterpret_cast<std::uintptr_t>(sbrk(0)) == before; ++i) {
        blocks[i] = std::malloc(kMiB[i] << 20);
        if (blocks[i]) from = reinterpret_cast<std::uintptr_t>(blocks[i]);
    }
    const auto top = reinterpret_cast<std::uintptr_t>(sbrk(0));
    if (top > before && from > 0 && top > from) advised_ = {reinterpret_cast<void*>(from), top - from};
    adviseHugePages(advised_.begin, advised_.bytes);
    for (void* block : blocks) std::free(block);
    mallopt(M_TOP_PAD, kDefaultTopPad);
#endif
}

HugePageHeap::~HugePageHeap() {
#ifndef VITRUM_SANITIZED_ALLOCATOR
    mallopt(M_TRIM_THRESHOLD, kDefaultTrimThreshold);
    malloc_trim(0);
#endif
}

}  // namespace vitrum
