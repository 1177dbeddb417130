// Transparent huge pages for the big blocks of a big model (issue 52): with 4 KiB pages, each
// first touch of a page is a page fault, and a big model touches gigabytes (measured in
// docs/gpu-design.md, "A big model to the image as fast as an Embree renderer").
#pragma once

#include <cstddef>

namespace vitrum {

// Blocks smaller than this are left alone: they hold at most one whole 2 MiB huge page.
inline constexpr std::size_t kHugePageBlock = std::size_t(4) << 20;

// Advises the kernel (madvise MADV_HUGEPAGE) to back the whole 2 MiB pages inside the block with
// huge pages. Advice only: it changes no contents, and a kernel without THP, or a block that is
// not ordinary memory, ignores it. Call it before the block is first written.
void adviseHugePages(void* block, std::size_t bytes);

}  // namespace vitrum
