// `facet bench --batch LIST`: a list of inputs rendered two ways, in turns: one `facet render --list`
// process on N threads, and N one-thread processes side by side, each rendering its share (--shard I/N).
// It reports each way's inputs per second and their ratio, and whether both wrote the same images.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>

namespace facet {

struct BatchBenchOptions {
    std::filesystem::path list;  // a list file as facet render --list reads it (not "-": read every round)
    int threads = 0;             // N; 0: one per hardware thread
    int rounds = 3;              // of each way, alternating
    std::optional<int> width, height;  // passed to facet render when given
};

// Runs the rounds with this program (/proc/self/exe) as the child processes, images written to a
// temporary folder removed at the end, and prints per way the median seconds, inputs per second and
// CPU seconds of the children, then the ratio of inputs per second (one process over the shards).
// Throws InputError when the list cannot be read or a child fails other than on an input (exit status
// other than 0 or 1).
void runBatchBench(const BatchBenchOptions& options, std::ostream& out);

}  // namespace facet
