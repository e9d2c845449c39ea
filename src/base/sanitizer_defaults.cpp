// For sanitizer and fuzzing builds only (CMakeLists.txt links this into every target then): the
// libraries' own leaks, which LeakSanitizer would report at exit. Mesa and LLVM keep process-lifetime
// allocations (the library is loaded once and never closed), and OpenImageIO 2.4's PNG reader loses a
// copy of its error message when libpng's error handler jumps out of a read (a truncated texture).
// OpenCV (facet trade's SSIM) keeps per-thread storage for the process's lifetime.
// They are not leaks of ours; any other leak still fails the run.
extern "C" const char* __lsan_default_suppressions() {
    return "leak:libOSMesa\nleak:libLLVM\nleak:libgallium\nleak:swrast_dri\nleak:ImageInput::geterror\nleak:libopencv_\n";
}

// ...without a report of the suppressions used at exit: the command-line tests read standard error.
extern "C" const char* __lsan_default_options() {
    return "print_suppressions=0";
}
