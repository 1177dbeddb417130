// Transparent huge pages where first touches of 4 KiB pages cost most: each is a page fault, slow
// on the virtual machines the benchmarks ran on. A big model touches gigabytes (issue 52;
// docs/gpu-design.md, "A big model to the image as fast as an Embree renderer"), and every render
// touches tens of MB of fresh heap in Mesa's device and pipeline creation (docs/gpu-design.md,
// "Huge pages for the heap").
#pragma once

#include <cstddef>

// Defined where a sanitizer replaces malloc: its allocator is left as it is.
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer)
#define VITRUM_SANITIZED_ALLOCATOR 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define VITRUM_SANITIZED_ALLOCATOR 1
#endif

namespace vitrum {

// Blocks smaller than this are left alone: they hold at most one whole 2 MiB huge page.
inline constexpr std::size_t kHugePageBlock = std::size_t(4) << 20;

// Advises the kernel (madvise MADV_HUGEPAGE) to back the whole 2 MiB pages inside the block with
// huge pages. Advice only: it changes no contents, and a kernel without THP, or a block that is
// not ordinary memory, ignores it. Call it before the block is first written.
void adviseHugePages(void* block, std::size_t bytes);

// The heap's bytes that a HugePageHeap puts in huge pages: more than Mesa's pipeline creation
// takes from it.
inline constexpr std::size_t kHugePageHeapBytes = std::size_t(128) << 20;

struct AdvisedRange {
    void* begin = nullptr;
    std::size_t bytes = 0;
};

// While it lives, the heap (glibc's main arena) has kHugePageHeapBytes at its top advised for huge
// pages and kept from being given back: for work that takes and frees tens of MB of blocks, as
// Mesa's device creation, pipeline creation and device memory do, where each fresh 4 KiB page
// would be a fault. Its end gives back what is free on the heap (malloc_trim), so that the
// process's memory between windows (a big model's load and BVH) is as it was without them.
// Blocks below glibc's largest mmap threshold (32 MiB) come from the heap from the first window
// on. One window at a time, on one thread.
class HugePageHeap {
public:
    HugePageHeap();
    ~HugePageHeap();
    HugePageHeap(const HugePageHeap&) = delete;
    HugePageHeap& operator=(const HugePageHeap&) = delete;
    // The advised range ({nullptr, 0} where nothing was: a sanitizer's allocator, or a heap that
    // did not grow).
    AdvisedRange advised() const { return advised_; }

private:
    AdvisedRange advised_;
};

}  // namespace vitrum
