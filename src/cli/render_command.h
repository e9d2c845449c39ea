// facet render: an OBJ model or a scene file to an image, or to the frames of a turntable.
#pragma once

#include <CLI/CLI.hpp>

#include "cli/options.h"
#include "pipeline/names.h"
#include "shaders/shaders.h"

namespace facet::cli {

// Adds the `render` command and its options to `app`, filling `args` when it is parsed.
CLI::App* addRenderCommand(CLI::App& app, RenderArgs& args);

// Renders as the arguments ask; 0 on success. Throws InputError for bad input.
int render(const RenderArgs& args);

}  // namespace facet::cli
