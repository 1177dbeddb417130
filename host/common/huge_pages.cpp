#include "common/huge_pages.h"

#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>

namespace vitrum {

void adviseHugePages(void* block, std::size_t bytes) {
    constexpr std::uintptr_t kHugePage = std::uintptr_t(2) << 20;  // x86-64's and most arm64 kernels'
    if (bytes < kHugePageBlock) return;
    const auto begin = (reinterpret_cast<std::uintptr_t>(block) + kHugePage - 1) & ~(kHugePage - 1);
    const auto end = (reinterpret_cast<std::uintptr_t>(block) + bytes) & ~(kHugePage - 1);
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

AdvisedRange useHugePagesForTheHeap() {
#ifdef VITRUM_SANITIZED_ALLOCATOR
    return {};
#else
    // Any mallopt call stops glibc from raising its mmap threshold as blocks are freed: fixed at
    // the ceiling it would rise to, the blocks of 128 KiB to 32 MiB that a render allocates and
    // frees again (Mesa's device memory among them) come from the advised heap, not from fresh
    // mappings each time.
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TOP_PAD, int(kHugePageHeapBytes));
    void* grow = std::malloc(std::size_t(1) << 20);  // below the threshold: the heap grows by the pad
    if (!grow) return {};
    const auto from = reinterpret_cast<std::uintptr_t>(grow);
    const auto top = reinterpret_cast<std::uintptr_t>(sbrk(0));
    const AdvisedRange range = top > from ? AdvisedRange{grow, top - from} : AdvisedRange{};
    adviseHugePages(range.begin, range.bytes);
    std::free(grow);
    return range;
#endif
}

}  // namespace vitrum
