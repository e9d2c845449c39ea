// Sanitized builds only (tests/CMakeLists.txt): a program that loads a module with thread-local storage
// exits without LeakSanitizer's own failure. GCC 12's runtime misreads a module's block of thread-local
// storage that starts 16 bytes past a page (src/base/sanitizer_defaults.cpp says how); the test puts the
// block there, and the failure, if any, comes when this test's process exits, after the test passed.
#include <dlfcn.h>

#include <cstdint>
#include <cstdlib>

#include <gtest/gtest.h>

namespace facet {
namespace {

// Catches: intercept_tls_get_addr=0 dropped from __lsan_default_options (sanitizer_defaults.cpp): the
// process then dies at exit with "Tracer caught signal 11" instead of exiting 0.
TEST(SanitizerExit, AModulesThreadLocalStorageAtAPagesStartDoesNotCrashTheLeakCheck) {
    void* module = ::dlopen(FACET_THREAD_LOCAL_MODULE, RTLD_NOW | RTLD_LOCAL);
    ASSERT_NE(module, nullptr) << ::dlerror();
    const auto entry = reinterpret_cast<int* (*)()>(::dlsym(module, "facet_test_thread_local"));
    ASSERT_NE(entry, nullptr);
    // The block (4 bytes) comes from the allocator's 32-byte chunks, whose memory starts 16 bytes after
    // the chunk's header: small allocations, kept until the exit's leak check (a static array, which no
    // destructor empties before it), until the next chunk is a page's first.
    static void* kept[1 << 16];
    bool placed = false;
    for (void*& p : kept) {
        p = std::malloc(4);
        if ((reinterpret_cast<std::uintptr_t>(p) + 32) % 4096 == 16) {
            placed = true;
            break;
        }
    }
    ASSERT_TRUE(placed);
    const int* uses = entry();
    EXPECT_EQ(*uses, 1);
    // The case the runtime misreads was set up: otherwise this test would pass without checking it.
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(uses) % 4096, 16u)
        << "the module's thread-local block did not land 16 bytes past a page (the allocator changed?)";
}

}  // namespace
}  // namespace facet
