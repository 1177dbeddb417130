// The vitrum program's global operator new: C++ blocks of a big model (the OBJ's text,
// the OBJ parser's vectors, the triangles, the BVH, the analysis' edges) go to huge pages
// (common/huge_pages.h). Blocks this large are fresh mappings of their own (glibc's mmap threshold
// is at most 32 MiB), so the advice reaches no other allocation. Sanitizer builds keep theirs.
#include <cstdlib>
#include <new>

#include "common/huge_pages.h"

#ifndef VITRUM_SANITIZED_ALLOCATOR
// A replacement of the global allocation function ([new.delete.single]); libstdc++'s operator
// delete (free), and its array and nothrow forms of new, which call this one, stay as they are.
void* operator new(std::size_t size) {
    if (size == 0) size = 1;
    void* block;
    while ((block = std::malloc(size)) == nullptr) {
        const std::new_handler handler = std::get_new_handler();
        if (!handler) throw std::bad_alloc();
        handler();
    }
    vitrum::adviseHugePages(block, size);
    return block;
}
#endif
