#include "bench.h"

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <ostream>
#include <vector>

#include "errors.h"
#include "renderer.h"

namespace facet {

namespace {

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace

void runBench(const BenchOptions& options, std::ostream& out) {
    if (options.frames < 1) throw InputError("--frames must be at least 1");
    const bool isScene = options.model.extension() == ".json";
    Scene scene = isScene ? loadScene(options.model) : sceneForModel(options.model);
    scene.width = options.width;
    scene.height = options.height;
    const PreparedScene prepared = prepareScene(scene);

    Framebuffer framebuffer(scene.width, scene.height);
    DrawContext context(options.threads);
    DrawStats stats = renderFrame(prepared, framebuffer, context);  // warm-up: caches, buffers, threads

    using Clock = std::chrono::steady_clock;
    std::vector<double> frameMs, clearMs;
    for (int i = 0; i < options.frames; ++i) {
        const auto start = Clock::now();
        stats = renderFrame(prepared, framebuffer, context);
        const auto end = Clock::now();
        frameMs.push_back(std::chrono::duration<double, std::milli>(end - start).count());

        const auto clearStart = Clock::now();
        framebuffer.clearColor(prepared.clearColor);
        framebuffer.clearDepth(1.0f);
        clearMs.push_back(std::chrono::duration<double, std::milli>(Clock::now() - clearStart).count());
    }

    out << std::fixed << std::setprecision(2);
    out << "model      " << options.model.string() << "\n";
    out << "image      " << scene.width << "x" << scene.height << ", " << context.pool.threads()
        << (context.pool.threads() == 1 ? " thread" : " threads") << ", built-in Blinn-Phong shader\n";
    out << "triangles  " << prepared.triangleCount << " (" << stats.trianglesRasterized
        << " rasterized after culling and clipping)\n";
    out << "fragments  " << stats.fragmentsShaded << " shaded, " << stats.fragmentsWritten << " written, "
        << stats.fragmentsDepthFailed << " rejected by the depth test\n";
    out << "frames     " << options.frames << " timed after 1 warm-up\n";
    out << "ms/frame   median " << median(frameMs) << "  min "
        << *std::min_element(frameMs.begin(), frameMs.end()) << "  max "
        << *std::max_element(frameMs.begin(), frameMs.end()) << "\n";
    out << "clear only median " << median(clearMs) << " ms (colour + depth)\n";
}

}  // namespace facet
