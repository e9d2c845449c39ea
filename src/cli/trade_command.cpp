#include "cli/trade_command.h"

#include <algorithm>
#include <iostream>

#include "base/errors.h"
#include "base/quote.h"
#include "io/output_path.h"

namespace facet::cli {

CLI::App* addTradeCommand(CLI::App& app, TradeArgs& args) {
    CLI::App* command = app.add_subcommand(
        "trade",
        "Time every accuracy knob and score it against the exact reference renderer (docs/trade.md)");
    addSceneOptions(*command, args.scene);
    std::string names;
    for (const facet::Knob& knob : facet::knobTable()) {
        if (!names.empty()) names += ",";
        names += knob.name;
    }
    command->add_option("--knobs", args.knobs, "Knobs to try, comma-separated (default all: " + names + ")");
    command
        ->add_option("--frames", args.frames,
                     "Timed frames per setting, split over the rounds; the median is reported (default 9)")
        ->check(wholeNumber(1, facet::kMaxTradeFrames));
    command
        ->add_option(
            "--rounds", args.rounds,
            "Time every setting in turn this many times (at most --frames), each a warm-up frame and "
            "a share of the frames, so that a busy spell of the machine is shared (default 3)")
        ->check(wholeNumber(1, facet::kMaxTradeRounds));
    command
        ->add_option(
            "--reference-samples", args.referenceSamples,
            "N×N rays per pixel of the reference image to start with (default 4); doubled, up to 16, "
            "while the reference's own estimated error is above a tenth of the baseline's")
        ->check(wholeNumber(1, facet::kMaxReferenceSamples));
    command->add_option("-o,--output", args.outputDir,
                        "Folder for trade.csv, chart.png and the images (default out/trade-NAME/)");
    command->add_flag(
        "--no-presets", args.noPresets,
        "Time and score only the baseline and the knobs, not the fast, default and best presets");
    command->add_flag("-q,--quiet", args.quiet,
                      "Print no progress and no table; warnings still go to standard error");
    return command;
}

facet::Scene sceneWithWords(const SceneArgs& args, const std::vector<std::string>& words) {
    facet::Scene scene = sceneFromArgs(args);
    if (words.empty()) return scene;
    // The words parsed as `facet render` parses its options, onto a fresh SceneArgs, then applied over
    // the user's choices (a second --shading on one command line would be refused by CLI11).
    CLI::App parser;
    SceneArgs setting;
    addSceneOptions(parser, setting);
    std::vector<std::string> reversed(words.rbegin(), words.rend());  // CLI11 takes them last first
    reversed.push_back(args.input);
    try {
        parser.parse(reversed);
    } catch (const CLI::ParseError& e) {
        std::string message = "the trade's setting";
        for (const std::string& word : words) {
            message += " ";
            message += word;
        }
        message += ": ";
        message += e.what();
        throw facet::InputError(message);
    }
    applyLightingOptions(setting, scene);
    return scene;
}

int trade(const TradeArgs& args) {
    // The trade scores whole images against the reference's whole image.
    if (args.scene.only)
        throw facet::InputError(
            "--only does not go with facet trade (it scores the whole image; use facet render "
            "--only for one term)");
    facet::TradeOptions options;
    options.knobs = args.knobs;
    facet::selectKnobs(options.knobs);  // a typo fails before the model is loaded
    options.frames = args.frames;
    options.rounds = args.rounds;
    options.threads = args.scene.threads;
    options.referenceSamples = args.referenceSamples;
    options.progress = !args.quiet;
    options.presets = !args.noPresets;
    options.outputDir = args.outputDir
                            ? std::filesystem::path(*args.outputDir)
                            : std::filesystem::path("out") /
                                  ("trade-" + std::filesystem::path(args.scene.input).stem().string());
    if (options.outputDir.empty())
        throw facet::InputError("no output folder given: name one with -o, like -o out/trade");
    facet::checkOutputFolder(options.outputDir, "-o");  // before the minutes of measuring
    const facet::TradeResult result = facet::runTrade(
        [&](const std::vector<std::string>& words) { return sceneWithWords(args.scene, words); }, options,
        std::cerr);
    if (!args.quiet) {
        facet::printTradeTable(result, std::cout);  // the warnings under it
        std::cout << "facet: wrote " << (options.outputDir / "trade.csv").string() << ", "
                  << (options.outputDir / "chart.png").string() << " and " << 2 * result.rows.size() + 1
                  << " images (reference " << result.width << "x" << result.height << ", "
                  << result.referenceSamples << "x" << result.referenceSamples << " rays per pixel, "
                  << static_cast<long>(result.referenceMs + 0.5) << " ms)\n";
    } else {
        // The table that carries them is not printed: a blank image or a meaningless score must still
        // be said.
        for (const std::string& warning : result.warnings)
            std::cerr << "facet: warning: " << warning << "\n";
    }
    return 0;
}

}  // namespace facet::cli
