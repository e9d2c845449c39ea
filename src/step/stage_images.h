// The stage images of `facet step --stages DIR`: the whole frame after each stage of the pipeline, from
// the wireframe the rasterizer receives to the final image and the frame built up triangle by triangle.
// Every one comes from the renderer's own renderFrame: watched by an observer (pipeline/observer.h) for
// what happens between the stages, or run on a copy of the prepared scene with some uniforms changed
// (one lighting term, fog off, per-pixel shading, fewer triangles). There is no second pipeline.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include "io/image_io.h"
#include "render/renderer.h"
#include "shaders/shaders.h"
#include "step/screens.h"

namespace facet::step {

struct StageImageOptions {
    // LightingTerm bits (facet render's --only): the terms of the final image, its build-up and the
    // frame before fog; the term images are those of these terms.
    std::uint8_t terms = kAllTerms;
    int buildFrames = 8;  // frames of the build-up, the last of them the final image; 0: none
    // Threads of the renders no observer watches (0: one per hardware thread). The images are the same
    // bytes with any count: observed frames run on the calling thread, the others are deterministic.
    int threads = 0;
    // writeStageImages writes each image this many times larger, every pixel a scale × scale block
    // (nearest neighbour), for slides: the pixels stay sharp squares. renderStageImages ignores it.
    int scale = 1;
};

// Receives each stage image in pipeline order: what it is (`image.file` its file name), its pixels, and
// how an 8-bit file encodes them: prepared.encoding for colour images, as facet render writes them;
// kLinearEncoding for data (ids, counts, depth, normals, fog factors), so a pixel's code is its value.
using StageImageSink = std::function<void(const StageImage& image, const LinearImage& pixels, ColorEncoding)>;

// Renders the stage images of `prepared` one at a time into `sink`, in pipeline order:
//   wireframe, triangles, overdraw, depth, normals;
//   emission, ambient, diffuse, specular (those in options.terms);
//   before-fog, fog-factor (only when the scene has fog); layers (only with transparent objects);
//   final; build-001 ... (options.buildFrames of them, fewer when the scene has fewer triangles).
void renderStageImages(const PreparedScene& prepared, const StageImageOptions& options,
                       const StageImageSink& sink);

// Writes the stage images as PNG files into `dir` (created if missing; each file written to a temporary
// name and renamed into place by writeImage), options.scale times larger, and returns them in pipeline
// order. Throws InputError when the folder or a file cannot be written.
std::vector<StageImage> writeStageImages(const PreparedScene& prepared, const std::filesystem::path& dir,
                                         const StageImageOptions& options);

// The memory renderStageImages (and writeStageImages at options.scale) holds at once for a width x
// height image: the framebuffer (Framebuffer::bytesFor), the recorder's per-pixel planes (its images of
// triangles, normals and fog factors, its counts and wire bits), the stage being written with its depth
// distances, a colour render, and the magnified copy. `facet step` checks it against the memory limit
// before any work (base/memory_limit.h).
std::uint64_t stageImagesBytes(int width, int height, int scale);

// `image` with every pixel repeated as a `scale` × `scale` block (scale ≥ 1).
LinearImage magnified(const LinearImage& image, int scale);

// The colour scales the images use (for legends and tests).
// A triangle's colour in the id image: a hash of its draw and its number in the draw, each channel in
// [0.3, 1] so that no triangle is as dark as the black of "no triangle".
vec3 triangleIdColor(std::uint32_t draw, std::uint32_t triangle);
// The wireframe's edges: drawn, removed by clipping, culled for facing away (black: no edge).
inline constexpr vec3 kDrawnEdgeColor{1.0f, 1.0f, 1.0f};
inline constexpr vec3 kRemovedEdgeColor{1.0f, 0.2f, 0.1f};
inline constexpr vec3 kCulledEdgeColor{0.3f, 0.3f, 0.3f};
// A count on the heat scale from 1 (blue) through cyan, green and yellow to maxCount (red); 0 is black.
vec3 heatColor(std::uint32_t count, std::uint32_t maxCount);

}  // namespace facet::step
