// facet trade: the speed–accuracy trade of a model or scene (src/trade/): every knob setting timed and
// scored against the exact reference renderer.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/options.h"
#include "trade/trade.h"

namespace facet::cli {

struct TradeArgs {
    SceneArgs scene;  // the baseline: input, size, camera and every knob as for render
    std::string knobs;
    int frames = 9;
    int rounds = 3;
    int referenceSamples = 4;
    std::optional<std::string> outputDir;  // absent: out/trade-<scene name>/
    bool quiet = false;
    bool noPresets = false;  // --no-presets: only the baseline and the knobs
};

// Adds the `trade` command and its options to `app`, filling `args` when it is parsed.
CLI::App* addTradeCommand(CLI::App& app, TradeArgs& args);

// The scene of `args` with `words` (render's options, like {"--shading", "flat"}) applied on top,
// through the render command's own parser: what the trade renders for each setting. Throws InputError
// for words the parser refuses.
facet::Scene sceneWithWords(const SceneArgs& args, const std::vector<std::string>& words);

// Runs the trade as the arguments ask, prints the table; 0 on success. Throws InputError for bad input.
int trade(const TradeArgs& args);

}  // namespace facet::cli
