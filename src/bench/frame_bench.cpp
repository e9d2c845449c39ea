// facet bench: whole frames of a model timed, medians printed.
#include <algorithm>
#include <chrono>
#include <iomanip>
#include <optional>
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
    if (options.shader) scene.shader = options.shader;
    scene.uniforms.insert(scene.uniforms.end(), options.uniforms.begin(), options.uniforms.end());
    return scene;
}

namespace {

// The same scene drawn by the built-in per-pixel Blinn-Phong shader: no shader of one's own anywhere.
Scene builtInBlinnPhong(Scene scene) {
    scene.shader.reset();
    scene.uniforms.clear();
    scene.lighting.model = ReflectionModel::BlinnPhong;
    scene.lighting.shading = ShadingFrequency::Phong;
    for (ObjectSpec& object : scene.objects) {
        object.shader.reset();
        object.reflection.reset();
        object.shading.reset();
    }
    return scene;
}

// --shader: the shader's frames and the built-in's, taking turns frame by frame (a shared machine
// drifts), each with its own framebuffer and memory.
void runShaderBench(const BenchOptions& options, const Scene& scene, std::ostream& out) {
    using Clock = std::chrono::steady_clock;
    struct Side {
        const char* label;
        PreparedScene prepared;
        Framebuffer framebuffer;
        FrameMemory memory;
        DrawStats stats;
        std::vector<double> wallMs, cpuMs;
    };
    Side sides[2] = {{"shader", prepareScene(scene), Framebuffer(scene.width, scene.height), {}, {}, {}, {}},
                     {"built-in",
                      prepareScene(builtInBlinnPhong(scene)),
                      Framebuffer(scene.width, scene.height),
                      {},
                      {},
                      {},
                      {}}};
    const std::string label = scene.shader ? scene.shader->source.filename().string() : "the scene's shaders";
    DrawContext context(options.threads);
    for (Side& side : sides)  // warm-up: caches, buffers, threads
        side.stats = renderFrame(side.prepared, side.framebuffer, context, side.memory).draw;
    for (int i = 0; i < options.frames; ++i) {
        for (int k = 0; k < 2; ++k) {
            Side& side = sides[(i + k) % 2];  // each goes first every other round
            const double cpuStart = processCpuMs();
            const auto start = Clock::now();
            side.stats = renderFrame(side.prepared, side.framebuffer, context, side.memory).draw;
            side.wallMs.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
            side.cpuMs.push_back(processCpuMs() - cpuStart);
        }
    }
    out << std::fixed << std::setprecision(2);
    out << "model      " << options.model.string() << "\n";
    out << "image      " << scene.width << "x" << scene.height << ", " << context.pool.threads()
        << (context.pool.threads() == 1 ? " thread" : " threads") << "\n";
    out << coreHandoffLine(context.pool.threads());
    out << "code       compiled for " << describeFrameKernels() << "\n";
    out << "triangles  " << sides[0].prepared.triangleCount << "\n";
    out << "frames     " << options.frames << " of each, taking turns, after 1 warm-up each\n";
    for (const Side& side : sides) {
        const std::string name = &side == &sides[0] ? label : "built-in per-pixel Blinn-Phong";
        out << (&side == &sides[0] ? "shader     " : "built-in   ") << name << ": median "
            << median(side.wallMs) << " ms/frame (min "
            << *std::min_element(side.wallMs.begin(), side.wallMs.end()) << "), CPU " << median(side.cpuMs)
            << " ms/frame; fragments " << side.stats.fragmentsShaded << " shaded, "
            << side.stats.fragmentsWritten << " written\n";
    }
    const double wallRatio = median(sides[0].wallMs) / median(sides[1].wallMs);
    const double cpuRatio = median(sides[0].cpuMs) / median(sides[1].cpuMs);
    out << std::setprecision(3);
    out << "ratio      " << wallRatio << "x the built-in's frame (wall-clock medians), " << cpuRatio
        << "x (CPU time medians)\n";
}

}  // namespace

void runBench(const BenchOptions& options, std::ostream& out) {
    const Scene scene = benchScene(options);
    if (options.shader) return runShaderBench(options, scene, out);
    const PreparedScene prepared = prepareScene(scene);

    Framebuffer framebuffer(scene.width, scene.height);
    DrawContext context(options.threads);
    context.cutForThreads = options.cutFor;
    // Frames as a loop of frames draws them (facet render --frames): the plan's buffers and the transparent
    // triangles' order kept from one frame to the next, so that sorting starts from the last order
    // rather than from scratch, and nothing is allocated per frame.
    FrameMemory memory;
    DrawStats stats =
        renderFrame(prepared, framebuffer, context, memory).draw;  // warm-up: caches, buffers, threads
    // The CPU time a frame costs on N threads is set against one thread's, measured here on frames taking
    // turns with the N-thread ones (a shared machine drifts): what waiting and sharing the work cost.
    const bool againstOneThread = context.pool.threads() > 1;
    std::optional<DrawContext> oneThread;
    Framebuffer oneThreadFramebuffer(againstOneThread ? scene.width : 1, againstOneThread ? scene.height : 1);
    FrameMemory oneThreadMemory;
    if (againstOneThread) {
        oneThread.emplace(1);
        renderFrame(prepared, oneThreadFramebuffer, *oneThread, oneThreadMemory);
    }

    using Clock = std::chrono::steady_clock;
    std::vector<double> frameMs, clearMs, cpuMs, oneThreadCpuMs;
    for (int i = 0; i < options.frames; ++i) {
        const double cpuStart = processCpuMs();
        const auto start = Clock::now();
        stats = renderFrame(prepared, framebuffer, context, memory).draw;
        const auto end = Clock::now();
        cpuMs.push_back(processCpuMs() - cpuStart);
        frameMs.push_back(std::chrono::duration<double, std::milli>(end - start).count());
        if (againstOneThread) {
            const double oneStart = processCpuMs();
            renderFrame(prepared, oneThreadFramebuffer, *oneThread, oneThreadMemory);
            oneThreadCpuMs.push_back(processCpuMs() - oneStart);
        }
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
        << (context.pool.threads() == 1 ? " thread" : " threads");
    if (context.threadsToCutFor() != context.pool.threads())
        out << " (work cut for " << context.threadsToCutFor() << ")";
    out << ", built-in Blinn-Phong shader\n";
    out << coreHandoffLine(context.pool.threads());
    out << "code       compiled for " << describeFrameKernels() << "\n";
    const Antialiasing aa = scene.pipeline.antialiasing;
    out << "samples    " << samplesPerPixel(aa) << " per pixel (--aa " << nameOf(aa) << ")\n";
    out << "triangles  " << prepared.triangleCount << " (" << stats.trianglesRasterized
        << " rasterized after culling and clipping; " << stats.patchWalks
        << " walks of a triangle over a tile done as one patch of a few pixels)\n";
    out << "fragments  " << stats.fragmentsShaded << " shaded, " << stats.fragmentsWritten << " written, "
        << stats.fragmentsDepthFailed << " rejected by the depth test\n";
    out << "frames     " << options.frames << " timed after 1 warm-up\n";
    out << "ms/frame   median " << median(frameMs) << "  min "
        << *std::min_element(frameMs.begin(), frameMs.end()) << "  max "
        << *std::max_element(frameMs.begin(), frameMs.end()) << "\n";
    out << "cpu/frame  median " << median(cpuMs) << " ms (every thread's CPU time)";
    if (againstOneThread)
        out << "; one thread: " << median(oneThreadCpuMs) << " ms, ratio " << std::setprecision(2)
            << median(cpuMs) / median(oneThreadCpuMs)
            << " (1.00: the threads cost no CPU time beyond the work; one-thread frames taking turns)";
    out << "\n";
    out << "full clear median " << median(clearMs)
        << " ms (colour + depth, every pixel; a frame clears only the 64×64 cells the previous one drew "
           "into, each as its tile is first drawn)\n";
}

}  // namespace facet
