// facet bench: frames, transparency modes, the sorter, or Facet against Mesa's llvmpipe, timed.
#pragma once

#include <CLI/CLI.hpp>

#include "bench/bench.h"

namespace facet::cli {

// Adds the `bench` command and its options to `app`, filling `options` when it is parsed.
CLI::App* addBenchCommand(CLI::App& app, facet::BenchOptions& options);

// Runs the mode the options choose (`command` tells which options were given); 0 on success. Throws
// InputError for bad input or options that do not go together.
int bench(facet::BenchOptions& options, const CLI::App& command);

}  // namespace facet::cli
