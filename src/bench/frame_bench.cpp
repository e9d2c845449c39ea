// facet bench: whole frames of a model timed, medians printed.
#include <algorithm>
#include <chrono>
#include <iomanip>
#include <ostream>
#include <vector>

#include "base/errors.h"
#include "bench/bench.h"
#include "bench/process_stats.h"
#include "render/frame_kernels.h"
#include "render/renderer.h"

namespace facet {

Scene benchScene(const BenchOptions& options) {
    if (options.frames < 1) throw InputError("--frames must be at least 1");
    Scene scene = loadSceneOrModel(options.model);
    scene.width = options.width;
    scene.height = options.height;
    if (options.antialiasing) scene.pipeline.antialiasing = *options.antialiasing;
    return scene;
}

void runBench(const BenchOptions& options, std::ostream& out) {
    const Scene scene = benchScene(options);
    const PreparedScene prepared = prepareScene(scene);

    Framebuffer framebuffer(scene.width, scene.height);
    DrawContext context(options.threads);
    // Frames as a loop of frames draws them (facet render --frames): the plan's buffers and the transparent
    // triangles' order kept from one frame to the next, so that sorting starts from the last order
    // rather than from scratch, and nothing is allocated per frame.
    FrameMemory memory;
    DrawStats stats =
        renderFrame(prepared, framebuffer, context, memory).draw;  // warm-up: caches, buffers, threads

    using Clock = std::chrono::steady_clock;
    std::vector<double> frameMs, clearMs;
    for (int i = 0; i < options.frames; ++i) {
        const auto start = Clock::now();
        stats = renderFrame(prepared, framebuffer, context, memory).draw;
        const auto end = Clock::now();
        frameMs.push_back(std::chrono::duration<double, std::milli>(end - start).count());
    }
    // A clear of every pixel, on a framebuffer of its own (one that held the frame would write only
    // the cells the frame drew into, and spare the next frame's clear): the colour alternates, so no
    // cell already holds it.
    Framebuffer cleared(scene.width, scene.height);
    for (int i = 0; i < options.frames; ++i) {
        const vec4 color = i % 2 ? prepared.clearColor : vec4(1.0f) - prepared.clearColor;
        const auto clearStart = Clock::now();
        cleared.clear(color, 1.0f, context.pool);
        cleared.finishClear(context.pool);  // no draw writes the cells: all of them now
        clearMs.push_back(std::chrono::duration<double, std::milli>(Clock::now() - clearStart).count());
    }

    out << std::fixed << std::setprecision(2);
    out << "model      " << options.model.string() << "\n";
    out << "image      " << scene.width << "x" << scene.height << ", " << context.pool.threads()
        << (context.pool.threads() == 1 ? " thread" : " threads") << ", built-in Blinn-Phong shader\n";
    out << coreHandoffLine(context.pool.threads());
    out << "code       compiled for " << describeFrameKernels() << "\n";
    const Antialiasing aa = scene.pipeline.antialiasing;
    out << "samples    " << samplesPerPixel(aa) << " per pixel (--aa " << nameOf(aa) << ")\n";
    out << "triangles  " << prepared.triangleCount << " (" << stats.trianglesRasterized
        << " rasterized after culling and clipping)\n";
    out << "fragments  " << stats.fragmentsShaded << " shaded, " << stats.fragmentsWritten << " written, "
        << stats.fragmentsDepthFailed << " rejected by the depth test\n";
    out << "frames     " << options.frames << " timed after 1 warm-up\n";
    out << "ms/frame   median " << median(frameMs) << "  min "
        << *std::min_element(frameMs.begin(), frameMs.end()) << "  max "
        << *std::max_element(frameMs.begin(), frameMs.end()) << "\n";
    out << "full clear median " << median(clearMs)
        << " ms (colour + depth, every pixel; a frame clears only the 64×64 cells the previous one drew "
           "into, each as its tile is first drawn)\n";
}

}  // namespace facet
