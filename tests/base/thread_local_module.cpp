// A module with thread-local storage, loaded by sanitizer_exit_test.cpp: its block of a thread's storage
// is allocated by the dynamic linker at the first use in that thread.
thread_local int uses = 0;

extern "C" int* facet_test_thread_local() {
    ++uses;
    return &uses;
}
