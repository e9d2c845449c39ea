// facet render: an OBJ model or a scene file to an image, or to the frames of a turntable.
#pragma once

#include <CLI/CLI.hpp>

#include "cli/options.h"
#include "pipeline/names.h"
#include "shaders/shaders.h"

namespace facet {

// The lighting terms (shaders.h's LightingTerm bits) by the names the command line uses, in the order
// component images are written; kAllTerms, their sum, is the main image and has no name.
inline constexpr EnumName<LightingTerm> kLightingTermNames[] = {{kEmissionTerm, "emission"},
                                                                {kAmbientTerm, "ambient"},
                                                                {kDiffuseTerm, "diffuse"},
                                                                {kSpecularTerm, "specular"}};
constexpr std::span<const EnumName<LightingTerm>> enumNames(LightingTerm) {
    return kLightingTermNames;
}

}  // namespace facet

namespace facet::cli {

// Adds the `render` command and its options to `app`, filling `args` when it is parsed.
CLI::App* addRenderCommand(CLI::App& app, RenderArgs& args);

// Renders as the arguments ask; 0 on success. Throws InputError for bad input.
int render(const RenderArgs& args);

}  // namespace facet::cli
