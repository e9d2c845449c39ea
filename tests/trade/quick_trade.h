// A trade small enough for a unit test, for the tests of the trade's verdicts and rankings.
#pragma once

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "cli/trade_command.h"
#include "trade/trade.h"

namespace facet::testing_support {

// The trade of the scene file `scene` turning `knobs`: one frame, one round, one thread, one ray per
// pixel, quietly; the presets' rows too when `presets`.
inline TradeResult quickTrade(const std::filesystem::path& scene, const std::string& knobs,
                              const std::filesystem::path& outputDir, bool presets = true) {
    cli::SceneArgs args;
    args.input = scene.string();
    TradeOptions options;
    options.knobs = knobs;
    options.frames = 1;
    options.rounds = 1;
    options.threads = 1;
    options.referenceSamples = 1;
    options.presets = presets;
    options.outputDir = outputDir;
    options.progress = false;
    std::ostringstream log;
    return runTrade([&](const std::vector<std::string>& words) { return cli::sceneWithWords(args, words); },
                    options, log);
}

}  // namespace facet::testing_support
