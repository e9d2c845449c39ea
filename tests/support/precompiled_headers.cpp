// Nothing of its own: the target compiling this file makes the precompiled header the test programs
// share (tests/CMakeLists.txt, facet_test_headers_*).
