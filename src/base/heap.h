// How the process's heap is set up, once, at the start of main: large blocks kept after they are freed,
// and the heap backed by huge pages where that costs nothing, so that loading a model does not fault its
// buffers in 4 KB at a time.
#pragma once

#include <cstddef>

namespace facet {

// What setUpHeap did.
struct HeapSetUp {
    bool hugePages = false;         // a reserve of the heap was marked for transparent huge pages
    std::size_t reservedBytes = 0;  // the size of that reserve (address space; memory only as touched)
};

// glibc's malloc: blocks up to 32 MB from the heap, not from a mapping of their own, and freed memory kept
// (a vector grown by reallocation reuses the pages of the one before instead of faulting in new ones;
// a batch reuses them from one model to the next). Then, unless FACET_HUGE_PAGES=0: the heap is extended
// by kHeapReserve of address space at once and the extension marked for transparent huge pages (madvise
// MADV_HUGEPAGE), so that what the heap hands out is faulted in 2 MB at a time, and every thread
// allocates from it (one arena). That is done only where it costs nothing: no address-space limit
// (ulimit -v), no strict overcommit (vm.overcommit_memory 2, where the reserve would be charged as
// memory), transparent huge pages not turned off, and a heap that is glibc's own (a sanitizer's
// allocator has its own).
HeapSetUp setUpHeap();

inline constexpr std::size_t kHeapReserve = std::size_t{1} << 30;

}  // namespace facet
