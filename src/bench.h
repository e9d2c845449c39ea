// `facet bench`: times whole frames of a model and prints medians (never a pass/fail test).
#pragma once

#include <filesystem>
#include <iosfwd>

namespace facet {

struct BenchOptions {
    std::filesystem::path model;  // OBJ or scene file
    int width = 1920;
    int height = 1080;
    int frames = 30;  // timed frames, after one untimed warm-up frame
    int threads = 0;  // 0: one per hardware thread
};

// Renders options.frames frames on options.threads threads and prints a report to `out`:
// the median, minimum and maximum milliseconds per frame, the triangle and fragment counts, and the
// cost of clearing the framebuffer alone (the floor under any frame). Throws InputError on bad input.
void runBench(const BenchOptions& options, std::ostream& out);

}  // namespace facet
