// facet compare: one model or scene drawn by Facet and by OpenGL (Mesa), the pixels compared.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/options.h"
#include "oracle/mesa_peer.h"

namespace facet::cli {

struct CompareArgs {
    SceneArgs scene;                          // input, size and lighting choices as for render
    std::optional<facet::MesaDriver> driver;  // absent: softpipe, the conformance oracle
    std::optional<std::string> facetImage, mesaImage, diffImage;
    // --reference: against the exact reference renderer instead of OpenGL.
    bool reference = false;
    std::optional<std::string> shadowMapSizes;  // "256,512": the shadow-map table's sizes
    std::optional<std::string> csv;             // the shadow-map table as CSV
    std::optional<std::string> referenceImage;  // the reference's image
    // --against MODEL (with --shader): the shader of one's own against the built-in reflection model,
    // both per pixel, with the rasterizer alone.
    std::optional<facet::ReflectionModel> against;
    bool noTrace = false;  // --no-trace: with --against, no side-by-side trace of the first pixel
};

// Adds the `compare` command and its options to `app`, filling `args` when it is parsed.
CLI::App* addCompareCommand(CLI::App& app, CompareArgs& args);

// Renders with both and prints how they agree: 0 when they do, kImagesDiffer when not. Throws
// InputError for bad input.
int compare(const CompareArgs& args);

// "256,512,1024": the --shadow-map-sizes list, each from 16 to kMaxShadowMapSize. Throws InputError.
std::vector<int> parseShadowMapSizes(const std::string& text);

}  // namespace facet::cli
