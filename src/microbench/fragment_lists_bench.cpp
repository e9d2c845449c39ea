// Exact transparency's per-pixel fragment lists (pipeline/fragment_lists.h) against sorted blending, at
// 1920×1080 with eight full-screen transparent layers: blending draws them far to near; the lists take
// them in a shuffled order (append) and then composite every pixel's sorted list (resolve). Each
// iteration is one frame's transparent layers; the clear before it is not timed. The lists' memory is
// reported as counters.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "microbench/workload.h"
#include "pipeline/fragment_lists.h"
#include "pipeline/pipeline.h"

namespace facet::microbench {
namespace {

constexpr int kLayers = 8;

// One flat colour per layer (a flat varying: no interpolation touches it), positions in clip space.
struct LayerShader {
    struct Attributes {
        vec4 position;
        vec4 color;
    };
    struct Varyings {
        vec4 color;
    };
    static constexpr int kFlatVaryingFloats = 4;
    struct Uniforms {};
    static VertexOut<Varyings> vertex(const Attributes& in, const Uniforms&) {
        return {in.position, {in.color}};
    }
    static vec4 fragment(const Varyings& in, const Uniforms&) { return in.color; }
};

// The eight full-frame layers, far to near, each two triangles.
std::vector<std::vector<LayerShader::Attributes>> layersFarToNear() {
    std::vector<std::vector<LayerShader::Attributes>> layers(kLayers);
    const std::array<vec2, 4> corners = {vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, 1)};
    for (int k = 0; k < kLayers; ++k) {
        const float kf = static_cast<float>(k);
        const vec4 color(0.1f * kf, 0.5f, 1.0f - 0.1f * kf, 0.3f);
        for (const int c : {0, 1, 2, 0, 2, 3})
            layers[static_cast<std::size_t>(k)].push_back(
                {vec4(corners[static_cast<std::size_t>(c)], 0.8f - 0.2f * kf, 1.0f), color});
    }
    return layers;
}

// Transparent surfaces: depth test on, depth writes off, over blending or the lists.
DrawState transparentState(const Framebuffer& fb, FragmentOutput output) {
    DrawState state;
    state.viewport = {0, 0, fb.width(), fb.height()};
    state.raster.cull = CullMode::None;
    state.depth.writeEnabled = false;
    state.blend = BlendMode::Over;
    state.output = output;
    return state;
}

// Arguments: the output (0 sorted blending, 1 fragment lists: append and resolve), the thread count.
void BM_FragmentLists(benchmark::State& state) {
    const bool lists = state.range(0) == 1;
    const int threads = static_cast<int>(state.range(1));
    const std::vector<std::vector<LayerShader::Attributes>> farToNear = layersFarToNear();
    std::vector<std::vector<LayerShader::Attributes>> layers = farToNear;
    if (lists) {
        const std::array<int, kLayers> shuffled = {3, 7, 0, 5, 1, 6, 2, 4};
        for (int k = 0; k < kLayers; ++k)
            layers[static_cast<std::size_t>(k)] = farToNear[static_cast<std::size_t>(shuffled[k])];
    }
    const std::vector<std::uint32_t> indices = {0, 1, 2, 3, 4, 5};
    Framebuffer fb(kFrameWidth, kFrameHeight);
    DrawContext context(threads);
    const DrawState drawState =
        transparentState(fb, lists ? FragmentOutput::AppendToLists : FragmentOutput::Blend);
    FragmentListStats stats;
    for (auto _ : state) {
        state.PauseTiming();
        fb.clear(vec4(0, 0, 0, 1), 1.0f, context.pool);  // empties the lists too, keeping their memory
        state.ResumeTiming();
        for (const auto& layer : layers)
            draw<LayerShader>(drawState, {}, std::span<const LayerShader::Attributes>(layer),
                              std::span<const std::uint32_t>(indices), fb, context);
        if (lists) stats = resolveFragmentLists(fb, context.pool);
        benchmark::ClobberMemory();
    }
    state.SetLabel(joined({lists ? "--transparency exact (lists, shuffled order)" : "sorted blending",
                           knob("--threads", static_cast<long>(threads))}));
    state.SetItemsProcessed(state.iterations() * std::int64_t{kLayers} * kFrameWidth * kFrameHeight);
    if (lists) {
        state.counters["fragments"] = static_cast<double>(stats.fragments);
        state.counters["bytes_held"] = static_cast<double>(stats.bytesHeld);
    }
}
BENCHMARK(BM_FragmentLists)
    ->ArgNames({"lists", "threads"})
    ->Args({0, 1})
    ->Args({1, 1})
    ->Args({0, 2})
    ->Args({1, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace facet::microbench
