// facet step: the step-through teaching mode. One pixel and one triangle of exactly the frame `facet
// render` would draw with the same options, traced through every stage (src/step/).
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/options.h"

namespace facet::cli {

struct StepArgs : SceneArgs {
    std::optional<std::string> pixel;  // "X,Y"
    std::optional<long long> triangle;
    bool print = false;
    bool notation = false;  // print the notation table instead of the walk
    std::optional<std::string> json;
    std::optional<std::string> stages;
    std::optional<int> stageScale;  // --stage-scale N: the --stages images N times larger
    std::optional<std::string> html;
    std::optional<int> htmlStep;
    std::optional<std::string> htmlRegion;  // "X,Y,W,H"
    std::optional<std::string> versus;
    bool stats = false;
    std::optional<std::string> screen;  // --screen ID: print only this screen
    std::optional<std::string> format;  // --format text|markdown|latex
    std::string commandLine;            // as typed, for the web page to show
};

// The options of --versus (`options`, as typed) parsed as the command's own and applied over `base`:
// the second setting of the comparison. Throws InputError for options CLI11 refuses or an input.
// "--shader builtin" stands for the built-in shaders (no shader of one's own, no --uniform); so do
// empty options when `base` has --shader (the user's shader against the built-in one).
SceneArgs versusArgs(const SceneArgs& base, const std::string& options);

// The name --versus gives the built-in shaders: --shader builtin.
inline constexpr const char* kBuiltInShaders = "builtin";

// Whether `args` (of versusArgs) ask for the built-in shaders.
bool wantsBuiltInShaders(const SceneArgs& args);

// Adds the `step` command and its options to `app`, filling `args` when it is parsed.
CLI::App* addStepCommand(CLI::App& app, StepArgs& args);

// Runs it: the interactive walk on a terminal, else the screens to standard output (--print), and
// the files asked for. Throws InputError for bad input.
int step(const StepArgs& args);

}  // namespace facet::cli
