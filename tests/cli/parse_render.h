// `facet render WORDS...` parsed into RenderArgs as the program parses it, for tests of the batch and
// the render command that call them in-process.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/render_command.h"

namespace facet::cli {

inline RenderArgs parseRender(std::vector<std::string> words) {
    CLI::App app;
    RenderArgs args;
    addRenderCommand(app, args);
    words.insert(words.begin(), "render");
    app.parse(std::vector<std::string>(words.rbegin(), words.rend()));  // CLI11 takes them last first
    return args;
}

}  // namespace facet::cli
