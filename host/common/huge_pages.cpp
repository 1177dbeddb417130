#include "common/huge_pages.h"

#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <vector>

namespace vitrum {

void adviseHugePages(void* block, std::size_t bytes) {
    constexpr std::uintptr_t kHugePage = std::uintptr_t(2) << 20;  // x86-64's and most arm64 kernels'
    if (bytes < kHugePageBlock) return;
    const auto begin = (reinterpret_cast<std::uintptr_t>(block) + kHugePage - 1) & ~(kHugePage - 1);
    const auto end = (reinterpret_cast<std::uintptr_t>(block) + bytes) & ~(kHugePage - 1);
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

#ifndef VITRUM_SANITIZED_ALLOCATOR
namespace {
// glibc's own initial values (mallopt(3)).
constexpr int kDefaultTrimThreshold = 128 << 10;
constexpr int kDefaultTopPad = 128 << 10;
}  // namespace
#endif

HugePageHeap::HugePageHeap() {
#ifndef VITRUM_SANITIZED_ALLOCATOR
    // Any mallopt call stops glibc from raising its mmap threshold as blocks are freed: fixed at
    // the ceiling it would rise to, the blocks of 128 KiB to 32 MiB that Mesa allocates and frees
    // again (its device memory among them) come from the heap, not from fresh mappings each time.
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, int(2 * kHugePageHeapBytes));
    mallopt(M_TOP_PAD, int(kHugePageHeapBytes));
    // The heap grows by the pad once a block does not fit its free memory: blocks of growing size,
    // all below the mmap threshold, until the break moves. A heap with much free memory (work
    // before the window freed it) takes more of them, up to kMaxProbeBytes; taking a free block
    // writes only its header.
    constexpr std::size_t kMaxProbeBytes = std::size_t(4) << 30;
    std::vector<void*> blocks;
    blocks.reserve(kMaxProbeBytes / (std::size_t(31) << 20) + 6);  // no growth of its own while probing
    const auto before = reinterpret_cast<std::uintptr_t>(sbrk(0));
    std::size_t taken = 0;
    std::uintptr_t from = 0;
    for (std::size_t mib = 1; reinterpret_cast<std::uintptr_t>(sbrk(0)) == before && taken < kMaxProbeBytes;
         mib = std::min<std::size_t>(2 * mib, 31)) {
        void* block = std::malloc(mib << 20);
        if (!block) break;
        blocks.push_back(block);
        taken += mib << 20;
        from = reinterpret_cast<std::uintptr_t>(block);
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
