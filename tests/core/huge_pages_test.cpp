// The heap in huge pages while a HugePageHeap lives (common/huge_pages.h): the advice reaches the
// kernel's map of the process, the blocks Mesa allocates and frees stay on that heap, and what is
// free is given back when the window ends.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "common/huge_pages.h"

namespace vitrum {
namespace {

struct Mapping {
    std::uintptr_t begin = 0, end = 0;
    std::string name;
    bool hugePages = false;  // VmFlags "hg": advised MADV_HUGEPAGE
    std::size_t residentBytes = 0;  // Rss
};

// The process's mappings from /proc/self/smaps (proc(5)).
std::vector<Mapping> mappings() {
    std::vector<Mapping> all;
    std::ifstream smaps("/proc/self/smaps");
    for (std::string line; std::getline(smaps, line);) {
        std::istringstream fields(line);
        std::string first;
        fields >> first;
        if (first == "VmFlags:") {
            for (std::string flag; fields >> flag;)
                if (flag == "hg") all.back().hugePages = true;
        } else if (first == "Rss:") {
            fields >> all.back().residentBytes;
            all.back().residentBytes <<= 10;  // given in kB
        } else if (const auto dash = first.find('-'); dash != std::string::npos && first.back() != ':') {
            Mapping m;
            m.begin = std::stoull(first.substr(0, dash), nullptr, 16);
            m.end = std::stoull(first.substr(dash + 1), nullptr, 16);
            std::string permissions, offset, device, inode;
            fields >> permissions >> offset >> device >> inode >> m.name;
            all.push_back(m);
        }
    }
    return all;
}

// The bytes of the heap resident now.
std::size_t residentHeapBytes() {
    std::size_t bytes = 0;
    for (const Mapping& m : mappings())
        if (m.name == "[heap]") bytes += m.residentBytes;
    return bytes;
}

TEST(HugePages, AWindowGrowsTheHeapInHugePagesKeepsMesasBlocksAndGivesThemBack) {
    if (!std::filesystem::exists("/sys/kernel/mm/transparent_hugepage/enabled"))
        GTEST_SKIP() << "this kernel has no transparent huge pages";
    std::optional<HugePageHeap> window(std::in_place);
    const AdvisedRange range = window->advised();
#ifdef VITRUM_SANITIZED_ALLOCATOR
    EXPECT_EQ(range.bytes, 0u) << "a sanitizer's allocator is left alone";
    return;
#endif
    ASSERT_GE(range.bytes, kHugePageHeapBytes);
    // Every whole 2 MiB page of the range is in a mapping advised for huge pages.
    const std::uintptr_t huge = std::uintptr_t(2) << 20;
    const auto begin = (reinterpret_cast<std::uintptr_t>(range.begin) + huge - 1) & ~(huge - 1);
    const auto end = (reinterpret_cast<std::uintptr_t>(range.begin) + range.bytes) & ~(huge - 1);
    std::uintptr_t advised = 0;
    std::uintptr_t heapBegin = 0, heapEnd = 0;
    for (const Mapping& m : mappings()) {
        if (m.hugePages && m.end > begin && m.begin < end) advised += std::min(m.end, end) - std::max(m.begin, begin);
        if (m.name == "[heap]") heapBegin = std::min(heapBegin ? heapBegin : m.begin, m.begin), heapEnd = std::max(heapEnd, m.end);
    }
    EXPECT_EQ(advised, end - begin);
    // A block of 8 MiB, as Mesa allocates a tile's buffers, comes from the heap, not from a mapping
    // of its own (which glibc makes above its mmap threshold, at first 128 KiB).
    void* block = std::malloc(std::size_t(8) << 20);
    ASSERT_NE(block, nullptr);
    const auto at = reinterpret_cast<std::uintptr_t>(block);
    EXPECT_TRUE(at >= heapBegin && at < heapEnd) << "the block is not on the heap";
    // Written and freed, the block stays resident while the window lives, and is given back when
    // it ends (written through a volatile pointer: a write just before free is otherwise none).
    auto* bytes = static_cast<volatile unsigned char*>(block);
    for (std::size_t i = 0; i < (std::size_t(8) << 20); i += 4096) bytes[i] = 1;
    std::free(block);
    const std::size_t during = residentHeapBytes();
    window.reset();
    EXPECT_GE(during, residentHeapBytes() + (std::size_t(6) << 20));
}

// Work before a window can leave a hole of free memory in the heap, larger than the window's
// first blocks (1 to 31 MiB): the window takes blocks until the heap grows all the same, so that
// its range lies at the top, fresh.
TEST(HugePages, AWindowAfterWorkThatLeftTheHeapHalfFreeStillAdvisesItsRange) {
    if (!std::filesystem::exists("/sys/kernel/mm/transparent_hugepage/enabled"))
        GTEST_SKIP() << "this kernel has no transparent huge pages";
    { const HugePageHeap first; }  // since a window, blocks below 32 MiB come from the heap
    std::vector<void*> work;
    for (int i = 0; i < 24; ++i) work.push_back(std::malloc(std::size_t(8) << 20));  // 192 MiB
    void* pin = std::malloc(64);  // above them: freed, they are a hole, not the heap's top
    for (void* block : work) std::free(block);
    const HugePageHeap window;
    const AdvisedRange range = window.advised();
    std::free(pin);
#ifdef VITRUM_SANITIZED_ALLOCATOR
    EXPECT_EQ(range.bytes, 0u) << "a sanitizer's allocator is left alone";
    return;
#endif
    EXPECT_GE(range.bytes, kHugePageHeapBytes);
}

}  // namespace
}  // namespace vitrum
