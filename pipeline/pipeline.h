// The pipeline, every stage in order on one screen:
//
//   front end, per triangle:  vertex stage → primitive assembly → clipping → divide + viewport
//                             → culling + setup → binning into screen tiles          (front_end.h)
//   back end, per tile:       rasterization (8×8 blocks) → depth test → interpolation
//                             → fragment shader → blending (or, for exact transparency, appending
//                             to per-pixel fragment lists that resolveFragmentLists() composites)
//                                                                                     (back_end.h)
//
// Each stage is a plain function in its own file; draw() is the only place that knows their order, and
// it hands every stage's output to an Observer between stages (observer.h). Vertices and chunks of
// triangles are processed in parallel; then tiles are, each drawing its triangles in submission order,
// so the image is the same bytes for any number of threads or any tile size.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "back_end.h"
#include "bin.h"
#include "draw_plan.h"
#include "fragment_lists.h"
#include "fragment_lists_resolve.h"
#include "framebuffer.h"
#include "front_end.h"
#include "observer.h"
#include "shader.h"
#include "state.h"
#include "thread_pool.h"

namespace facet {

// The worker threads and buffers draws use, kept by the caller and reused, so that drawing allocates
// nothing per triangle or fragment (and, once warmed up, nothing per draw). The image a draw produces
// does not depend on the number of threads nor on the tile size.
struct DrawContext {
    explicit DrawContext(int threads = 0, int tileSize = kDefaultTileSize)
        : pool(threads), tileSize(tileSize) {}
    ThreadPool pool;
    int tileSize;  // pixels, a multiple of kBlockSize
    ShadedVertices shaded;
    std::vector<WindowVertex> window;  // viewport transform of each vertex that needs no clipping
    std::vector<SetupChunk> chunks;
    std::vector<std::uint32_t> activeTiles;  // the tiles a batch's triangles touch, in tile order
    std::vector<DrawStats> threadStats;      // back-end counters, one per thread
    std::uint64_t drawsStarted = 0;          // draws begun with this context: the next draw's id
};

// Work sizes: vertices are shaded in chunks of kVertexChunk, triangles set up in chunks of
// kTriangleChunk, and at most kChunksPerBatch chunks are binned before their tiles are drawn, which
// bounds the memory held in setups whatever the size of the mesh.
inline constexpr std::size_t kVertexChunk = 8192;
inline constexpr std::size_t kTriangleChunk = 2048;
inline constexpr std::size_t kChunksPerBatch = 8;

// Checks a draw's state and the mesh's indices; throws std::invalid_argument naming the problem.
void validateDraw(const DrawState& state, const Framebuffer& target, std::size_t vertexCount,
                  std::span<const std::uint32_t> indices, int tileSize);

// Draws an indexed triangle list: indices[3t], indices[3t+1], indices[3t+2] make triangle t.
// The caller owns `context` (reuse it across draws). Returns counters for the draw.
// With an enabled Observer everything runs on the calling thread, so hooks see a stable order:
// the draw's start, the front end in triangle order, then tile by tile each triangle's coverage and
// fragments in triangle order, then the draw's end.
template <Shader S, class Observer = NullObserver>
DrawStats draw(const DrawState& state, const typename S::Uniforms& uniforms,
               std::span<const typename S::Attributes> vertices, std::span<const std::uint32_t> indices,
               Framebuffer& target, DrawContext& context, Observer&& observer = Observer{}) {
    using Watcher = std::remove_reference_t<Observer>;
    constexpr bool inOrder = Watcher::enabled;  // observed draws run on the calling thread, in order
    validateDraw(state, target, vertices.size(), indices, context.tileSize);
    if constexpr (Watcher::enabled)
        if (state.samples > 1)
            throw std::invalid_argument("a multisampled draw cannot be observed: draw it with one sample");
    const DrawPlan plan = planDraw(state);
    const std::uint64_t drawId = context.drawsStarted++;
    if constexpr (Watcher::enabled) observer.onDrawBegin(drawId, state);
    if (plan.output == FragmentOutput::AppendToLists) {
        target.fragmentLists().prepare(target.width(), target.height(), context.tileSize);
        target.fragmentLists().useFormats(plan.depthFormat, plan.colorBuffer);
    }

    runVertexStage<S>(vertices, uniforms, state, context.pool, inOrder, kVertexChunk, context.shaded,
                      context.window, observer);
    DrawStats total;
    total.vertices = context.shaded.size();
    total.triangles = indices.size() / 3;
    const TileGrid grid = makeTileGrid(state.viewport, context.tileSize);
    context.threadStats.assign(static_cast<std::size_t>(context.pool.threads()), DrawStats{});
    for (std::size_t batchStart = 0; batchStart < total.triangles;
         batchStart += kTriangleChunk * kChunksPerBatch) {
        const std::size_t batchEnd = std::min(total.triangles, batchStart + kTriangleChunk * kChunksPerBatch);
        const std::size_t chunkCount = setupBatch(indices, batchStart, batchEnd, kTriangleChunk, state, grid,
                                                  context.shaded, context.window, flatVaryingFloats<S>(),
                                                  context.pool, inOrder, context.chunks, observer);
        const std::span<const SetupChunk> chunks(context.chunks.data(), chunkCount);
        total.tilesDrawn += drawBatchTiles<S>(grid, chunks, plan, uniforms, target, context.pool, inOrder,
                                              context.activeTiles, context.threadStats, observer);
        for (const SetupChunk& chunk : chunks)
            total += chunk.stats;
    }
    for (const DrawStats& s : context.threadStats)
        total += s;
    if constexpr (Watcher::enabled) observer.onDrawEnd(drawId, total);
    return total;
}

}  // namespace facet
