#include "base/heap.h"

#include <malloc.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

namespace facet {

namespace {

constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;

std::string firstLineOf(const char* path) {
    std::ifstream file(path);
    std::string line;
    std::getline(file, line);
    return line;
}

// Whether reserving address space is free here: no address-space limit to spend it against, no strict
// overcommit to charge it as memory, and transparent huge pages not turned off.
bool reserveCostsNothing() {
    rlimit limit{};
    if (::getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur != RLIM_INFINITY) return false;
    if (firstLineOf("/proc/sys/vm/overcommit_memory") == "2") return false;
    const std::string thp = firstLineOf("/sys/kernel/mm/transparent_hugepage/enabled");
    return !thp.empty() && thp.find("[never]") == std::string::npos;
}

}  // namespace

HeapSetUp setUpHeap() {
    mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest threshold
    mallopt(M_TOP_PAD, 64 << 20);
    HeapSetUp done;
    const char* wanted = std::getenv("FACET_HUGE_PAGES");
    if ((wanted && std::strcmp(wanted, "0") == 0) || !reserveCostsNothing()) {
        mallopt(M_TRIM_THRESHOLD, 512 << 20);
        return done;
    }
    // Never trimmed, so the reserve stays marked; extended by one block larger than the heap's free top
    // (a small one may fit in what the start-up left), padded by the reserve.
    mallopt(M_TRIM_THRESHOLD, static_cast<int>(2 * kHeapReserve - 1));
    // One arena: the blocks of every thread (the OBJ reader's runs, a batch's lanes) come from the
    // reserve, not from arenas of their own in 4 KB pages. The hot path allocates nothing, so the threads
    // hardly meet at the allocator's lock.
    mallopt(M_ARENA_MAX, 1);
    mallopt(M_TOP_PAD, static_cast<int>(kHeapReserve));
    void* block = std::malloc(16 << 20);
    mallopt(M_TOP_PAD, 64 << 20);
    const auto start = reinterpret_cast<std::uintptr_t>(block);
    const auto end = reinterpret_cast<std::uintptr_t>(::sbrk(0));
    // Only a block of glibc's heap, right below the break (a sanitizer's allocator hands out its own).
    const std::uintptr_t from = (start + kHugePage - 1) & ~(kHugePage - 1);
    if (block && end > from && end - start <= 2 * kHeapReserve &&
        ::madvise(reinterpret_cast<void*>(from), end - from, MADV_HUGEPAGE) == 0) {
        done.hugePages = true;
        done.reservedBytes = end - from;
    }
    std::free(block);
    return done;
}

}  // namespace facet
