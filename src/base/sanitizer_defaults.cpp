// For sanitizer and fuzzing builds only (CMakeLists.txt links this into every target then): the
// libraries' own leaks, which LeakSanitizer would report at exit. Mesa and LLVM keep process-lifetime
// allocations (the library is loaded once and never closed), and OpenImageIO 2.4's PNG reader loses a
// copy of its error message when libpng's error handler jumps out of a read (a truncated texture).
// OpenCV (facet trade's SSIM) keeps per-thread storage for the process's lifetime.
// They are not leaks of ours; any other leak still fails the run.
extern "C" const char* __lsan_default_suppressions() {
    return "leak:libOSMesa\nleak:libLLVM\nleak:libgallium\nleak:swrast_dri\nleak:ImageInput::geterror\nleak:"
           "libopencv_\n";
}

// ...without a report of the suppressions used at exit: the command-line tests read standard error.
//
// intercept_tls_get_addr=0: the thread-local storage of a library loaded with dlopen (the OpenImageIO
// module's libraries, OSMesa's, a shader module with a thread_local) is a block the dynamic linker
// allocates with malloc. The runtime of GCC 12 (and LLVM up to 16) takes such a block that starts 16
// bytes past a page for one with a glibc 2.19 header, and reads the two words before it as the block's
// address and size; under AddressSanitizer every chunk that starts a page has its memory 16 bytes past
// it (the chunk's header), so now and then, as the allocations fall, LeakSanitizer scans a range such as
// 0x13-0x400001115 at exit and its thread scan dies ("Tracer caught signal 11") after every test has
// passed. Without the interception those blocks are still scanned: LeakSanitizer counts whatever the
// dynamic linker allocated as reachable, so memory held only by a thread_local is no false leak.
extern "C" const char* __lsan_default_options() {
    return "print_suppressions=0:intercept_tls_get_addr=0";
}
