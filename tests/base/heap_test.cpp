// The heap's set-up (base/heap.h): where a reserve in huge pages costs nothing, the blocks a loader
// allocates lie in it; FACET_HUGE_PAGES=0 keeps the heap as it is.
#include "base/heap.h"

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace facet {
namespace {

// The VmFlags line of /proc/self/smaps for the mapping that holds `address` (empty if none does).
std::string mappingFlags(const void* address) {
    const auto at = reinterpret_cast<std::uintptr_t>(address);
    std::ifstream smaps("/proc/self/smaps");
    std::string line;
    bool inside = false;
    while (std::getline(smaps, line)) {
        std::uintptr_t from = 0, to = 0;
        char dash = 0;
        std::istringstream range(line);
        if (range >> std::hex >> from >> dash >> to && dash == '-') {
            inside = from <= at && at < to;
        } else if (inside && line.rfind("VmFlags:", 0) == 0) {
            return line;
        }
    }
    return {};
}

// Breaks caught: the reserve not marked for huge pages (madvise dropped or given another range), or a
// reserve that the heap's blocks do not come from (a block allocated before the reserve is made).
TEST(Heap, ALoadersBuffersLieInTheHugePageReserve) {
    const HeapSetUp done = setUpHeap();
    if (!done.hugePages)
        GTEST_SKIP() << "no reserve here: an address-space limit, strict overcommit, transparent huge "
                        "pages off, or a sanitizer's allocator";
    EXPECT_GE(done.reservedBytes, kHeapReserve);
    std::vector<char> buffer(8 << 20, 1);  // a model's vertices, say
    // Its middle: the reserve starts at the first 2 MB boundary of the heap's free top, and the block may
    // start below it.
    const std::string flags = mappingFlags(buffer.data() + buffer.size() / 2);
    ASSERT_FALSE(flags.empty());
    EXPECT_NE((flags + " ").find(" hg "), std::string::npos) << flags;  // hg: MADV_HUGEPAGE
}

// Breaks caught: FACET_HUGE_PAGES=0 ignored.
TEST(Heap, HugePagesCanBeTurnedOff) {
    ::setenv("FACET_HUGE_PAGES", "0", 1);
    EXPECT_FALSE(setUpHeap().hugePages);
    ::unsetenv("FACET_HUGE_PAGES");
}

}  // namespace
}  // namespace facet
