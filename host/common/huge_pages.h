// Transparent huge pages where first touches of 4 KiB pages cost most: each is a page fault (about
// 12 us on the machines of docs/performance.md). A big model touches gigabytes (issue 52;
// docs/gpu-design.md, "A big model to the image as fast as an Embree renderer"), and every render
// touches tens of MB of fresh heap, most of it in Mesa's pipeline creation ("Huge pages for the
// heap").
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

// The heap's bytes that useHugePagesForTheHeap puts in huge pages: more than a render of a small
// scene takes from it.
inline constexpr std::size_t kHugePageHeapBytes = std::size_t(128) << 20;

// Grows the heap (glibc's main arena) by kHugePageHeapBytes at once and advises huge pages for that
// part, and keeps blocks below glibc's largest mmap threshold (32 MiB) on the heap. Call it first
// thing in a program. Address space only: a huge page is resident once touched; the heap's later
// growth stays in 4 KiB pages. Returns the advised range's start and length ({nullptr, 0} where
// nothing was advised: a sanitizer's allocator, or a heap that did not grow).
struct AdvisedRange {
    void* begin = nullptr;
    std::size_t bytes = 0;
};
AdvisedRange useHugePagesForTheHeap();

}  // namespace vitrum
