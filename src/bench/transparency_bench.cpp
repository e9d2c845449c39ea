// facet bench --transparency: the transparency modes side by side on a turntable.
#include <chrono>
#include <iomanip>
#include <ostream>
#include <vector>

#include "bench/bench.h"
#include "bench/process_stats.h"
#include "render/renderer.h"

namespace facet {

void runTransparencyBench(const BenchOptions& options, std::ostream& out) {
    Scene scene = benchScene(options);
    scene.pipeline.cull = CullMode::None;  // see-through: the back faces show
    for (ObjectSpec& object : scene.objects)
        object.material.opacity = 0.5f;
    PreparedScene prepared = prepareScene(scene);
    Framebuffer framebuffer(scene.width, scene.height);
    DrawContext context(options.threads);

    out << "Transparency modes on a turntable of " << options.model.string()
        << ", every surface at opacity 0.5, culling off,\n"
        << scene.width << "x" << scene.height << ", " << context.pool.threads()
        << (context.pool.threads() == 1 ? " thread" : " threads") << ", " << options.degreesPerFrame
        << " deg per frame, " << options.frames << " frames after 1 warm-up; medians of wall-clock ms.\n";
    out << prepared.transparentTriangles.size() << " transparent triangles.\n\n";
    out << std::fixed << std::setprecision(2);
    out << "  mode        ms/frame   sort ms   resolve ms   draws   fragments stored   longest list   lists "
           "hold\n";

    for (const EnumName<TransparencyMode>& mode : kTransparencyModeNames) {
        prepared.scene.transparency.mode = mode.value;
        FrameMemory memory;
        setTurntable(prepared, 0.0f);
        FrameStats stats = renderFrame(prepared, framebuffer, context, memory);  // warm-up
        std::vector<double> frameMs, sortMs, resolveMs;
        for (int frame = 1; frame <= options.frames; ++frame) {
            setTurntable(prepared, options.degreesPerFrame * static_cast<float>(frame));
            const auto start = std::chrono::steady_clock::now();
            stats = renderFrame(prepared, framebuffer, context, memory);
            frameMs.push_back(
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
            sortMs.push_back(stats.sortMilliseconds);
            resolveMs.push_back(stats.resolveMilliseconds);
        }
        out << "  " << std::left << std::setw(10) << mode.name << std::right << std::setw(10)
            << median(frameMs) << std::setw(10) << median(sortMs) << std::setw(13) << median(resolveMs)
            << std::setw(8) << stats.transparentRuns << std::setw(19) << stats.fragmentLists.fragments
            << std::setw(15) << stats.fragmentLists.longestList << std::setw(9) << std::setprecision(1)
            << static_cast<double>(stats.fragmentLists.bytesHeld) / (1024.0 * 1024.0) << " MiB"
            << std::setprecision(2) << "\n";
    }
    out << "\nsorted: back to front by insertion sort from the previous frame's order; unsorted: file order "
           "(wrong "
           "where\nsurfaces overlap, the floor under the other two); exact: per-pixel lists sorted by depth, "
           "right even "
           "where\ntriangles intersect. The colour and depth buffers ("
        << std::setprecision(1) << static_cast<double>(scene.width) * scene.height * 20.0 / (1024.0 * 1024.0)
        << " MiB) are the same for all three.\n";
}

}  // namespace facet
