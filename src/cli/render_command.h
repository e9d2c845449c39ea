// facet render: an OBJ model or a scene file to an image, or to the frames of a turntable; several
// inputs are a batch, several rendered at once in one process (cli/batch.h).
#pragma once

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/options.h"
#include "io/image_file.h"
#include "pipeline/names.h"
#include "pipeline/pipeline.h"
#include "reference/reference.h"
#include "shaders/shaders.h"

namespace facet::cli {

// Adds the `render` command and its options to `app`, filling `args` when it is parsed.
CLI::App* addRenderCommand(CLI::App& app, RenderArgs& args);

// Renders as the arguments ask, one input or a batch; 0 on success (a batch: 1 when an input failed).
// Throws InputError for bad input (in a batch: for a bad command line or list only).
int render(const RenderArgs& args);

// What the command line alone decides about the images, the same for every input: checked before any
// model is loaded (renderSettings throws InputError), so that a typo in --frames does not wait for a
// large model, nor start writing images.
struct RenderSettings {
    int firstFrame = 0, lastFrame = 0;  // --frames; 0, 0 without
    float turntable = 0.0f;             // degrees over the frames
    bool reference = false;             // --renderer reference
    facet::ReferenceOptions referenceOptions;
    std::uint8_t terms = facet::kAllTerms;            // --only
    int pngCompression = facet::kFastPngCompression;  // --png-compression
};
RenderSettings renderSettings(const RenderArgs& args);

// What one input's render wrote and cost.
struct RenderedInput {
    std::vector<std::filesystem::path> written;  // the frames' images, each followed by its terms'
    int width = 0, height = 0;
    std::size_t triangles = 0;
    std::size_t degenerateSkipped = 0;
    std::uint64_t fragmentsShaded = 0;  // the rasterizer's, over all frames
    double milliseconds = 0;            // loading, rendering and writing
};

// Loads args.input and renders it to args.output (no placeholders left) on `context`'s threads, with
// its own scene, framebuffer and frame memory: the same bytes as any other run with these arguments.
// --stats lines go to `out`, "facet: warning: " lines to `warnings`. Throws InputError for bad input.
// It is inputScene then renderScene.
RenderedInput renderInput(const RenderArgs& args, const RenderSettings& settings, facet::DrawContext& context,
                          std::ostream& out, std::ostream& warnings);

// The first step of renderInput: the scene of args.input (a scene file read, or an OBJ named, not yet
// parsed) with the command line's options, and its image's destination checked. Cheap: the models'
// triangles are read by renderScene, so a batch can weigh an input's memory before loading it.
facet::Scene inputScene(const RenderArgs& args);

// The rest of renderInput: `scene` (from inputScene(args)) loaded, prepared, rendered and written.
RenderedInput renderScene(const RenderArgs& args, const RenderSettings& settings, const facet::Scene& scene,
                          facet::DrawContext& context, std::ostream& out, std::ostream& warnings);

// The image of one lighting term next to the output (--components): "out/spot.png" + "diffuse" ->
// "out/spot-diffuse.png".
std::filesystem::path componentPath(const std::filesystem::path& output, std::string_view term);

}  // namespace facet::cli
