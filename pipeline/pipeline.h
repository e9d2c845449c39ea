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

    // For drawRun: each draw's set-up chunks, plan and front-end counters, and each thread's vertices.
    struct RunDrawSlot {
        std::vector<SetupChunk> chunks;
        std::size_t chunkCount = 0;
        DrawPlan plan;
        DrawStats frontEnd;
    };
    struct RunVertexScratch {
        ShadedVertices shaded;
        std::vector<WindowVertex> window;
    };
    std::vector<RunDrawSlot> runSlots;
    std::vector<RunVertexScratch> runVertices;
};

// Work sizes: vertices are shaded in chunks of kVertexChunk, triangles set up in chunks of
// kTriangleChunk, and at most kChunksPerBatch chunks are binned before their tiles are drawn, which
// bounds the memory held in setups whatever the size of the mesh (65,536 triangles: ~17 MB with the
// built-in surface shader's varyings).
// Each batch draws every tile it touches once more, fetching its pixels into a cache again and, with
// two threads, often from the other core's: 32 chunks a batch rather than 8 made Lost Empire's frame
// ~6% faster on two threads and the bunny's ~2%, and left one thread's unchanged.
inline constexpr std::size_t kVertexChunk = 8192;
inline constexpr std::size_t kTriangleChunk = 2048;
inline constexpr std::size_t kChunksPerBatch = 32;

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

// One draw of a run (drawRun): what draw() takes, by reference (alive for the call).
template <Shader S>
struct RunDraw {
    const DrawState* state = nullptr;
    const typename S::Uniforms* uniforms = nullptr;
    std::span<const typename S::Attributes> vertices;
    std::span<const std::uint32_t> indices;
};

// Whether a draw may join a run: small enough that draw() would shade its vertices and set up its
// triangles on one thread anyway (one chunk of each).
inline bool fitsInRun(std::size_t vertexCount, std::size_t indexCount) {
    return vertexCount <= kVertexChunk && indexCount / 3 <= kTriangleChunk;
}

// Draws consecutive small draws of one shader with the bytes draw() would give one after another, as
// two jobs of the pool instead of two or three per draw: first the draws' front ends, one draw per
// item (each on one thread, as draw() runs a draw this small), then the back end, tile by tile, each
// tile drawing every draw's triangles in draw order, so that every pixel still sees its fragments in
// submission order. A frame of many draws of a few triangles each (Lost Empire's 4,064 sorted
// transparent runs) otherwise joins the pool per draw and runs every front end on the calling thread.
// Every draw must fit in a run (fitsInRun) and have the first one's viewport; checked, with each draw's
// state and indices as draw() checks them, before anything is drawn (std::invalid_argument). Not
// observable: an observer watches draw() by draw(). Returns the draws' counters summed.
template <Shader S>
DrawStats drawRun(std::span<const RunDraw<S>> draws, Framebuffer& target, DrawContext& context) {
    if (draws.empty()) return {};
    const Viewport& viewport = draws.front().state->viewport;
    for (const RunDraw<S>& d : draws) {
        validateDraw(*d.state, target, d.vertices.size(), d.indices, context.tileSize);
        if (!fitsInRun(d.vertices.size(), d.indices.size()))
            throw std::invalid_argument("drawRun: a draw of more than " + std::to_string(kVertexChunk) +
                                        " vertices or " + std::to_string(kTriangleChunk) +
                                        " triangles: draw it with draw()");
        if (!samePixels(d.state->viewport, viewport))
            throw std::invalid_argument("drawRun: the draws of a run must share one viewport");
    }
    const TileGrid grid = makeTileGrid(viewport, context.tileSize);
    if (context.runSlots.size() < draws.size()) context.runSlots.resize(draws.size());
    const auto threads = static_cast<std::size_t>(context.pool.threads());
    if (context.runVertices.size() < threads) context.runVertices.resize(threads);
    for (std::size_t i = 0; i < draws.size(); ++i) {
        const DrawPlan plan = planDraw(*draws[i].state);
        context.runSlots[i].plan = plan;
        if (plan.output == FragmentOutput::AppendToLists) {
            target.fragmentLists().prepare(target.width(), target.height(), context.tileSize);
            target.fragmentLists().useFormats(plan.depthFormat, plan.colorBuffer);
        }
    }
    context.drawsStarted += draws.size();

    // The front ends: vertex stage, then setup and binning into the draw's own chunk.
    context.pool.parallelFor(draws.size(), [&](std::size_t i, int thread) {
        const RunDraw<S>& d = draws[i];
        DrawContext::RunVertexScratch& scratch = context.runVertices[static_cast<std::size_t>(thread)];
        DrawContext::RunDrawSlot& slot = context.runSlots[i];
        NullObserver observer;
        constexpr bool kOneThread = true;  // this item is the draw's whole front end
        runVertexStage<S>(d.vertices, *d.uniforms, *d.state, context.pool, kOneThread, kVertexChunk,
                          scratch.shaded, scratch.window, observer);
        const std::size_t triangles = d.indices.size() / 3;
        slot.chunkCount = setupBatch(d.indices, 0, triangles, kTriangleChunk, *d.state, grid, scratch.shaded,
                                     scratch.window, flatVaryingFloats<S>(), context.pool, kOneThread,
                                     slot.chunks, observer);
        slot.frontEnd = DrawStats{};
        slot.frontEnd.vertices = scratch.shaded.size();
        slot.frontEnd.triangles = triangles;
        for (std::size_t c = 0; c < slot.chunkCount; ++c)
            slot.frontEnd += slot.chunks[c].stats;
    });

    // The back end: every tile some draw touches, each draw's triangles in draw order.
    std::vector<std::uint32_t>& tiles = context.activeTiles;
    tiles.clear();
    for (std::size_t i = 0; i < draws.size(); ++i) {
        const DrawContext::RunDrawSlot& slot = context.runSlots[i];
        detail::appendTouchedTiles({slot.chunks.data(), slot.chunkCount}, tiles);
    }
    detail::sortUniqueTiles(tiles);
    context.threadStats.assign(threads, DrawStats{});
    context.pool.parallelFor(tiles.size(), [&](std::size_t active, int thread) {
        const std::uint32_t tile = tiles[active];
        DrawStats& stats = context.threadStats[static_cast<std::size_t>(thread)];
        for (std::size_t i = 0; i < draws.size(); ++i) {
            const DrawContext::RunDrawSlot& slot = context.runSlots[i];
            const std::span<const SetupChunk> chunks(slot.chunks.data(), slot.chunkCount);
            const bool touched = std::any_of(chunks.begin(), chunks.end(), [&](const SetupChunk& chunk) {
                return !chunk.bins[tile].empty();
            });
            if (!touched) continue;
            NullObserver observer;
            detail::drawTileOfChunks<S>(grid, tile, chunks, slot.plan, *draws[i].uniforms, target, stats,
                                        observer);
            ++stats.tilesDrawn;
        }
    });

    DrawStats total;
    for (std::size_t i = 0; i < draws.size(); ++i)
        total += context.runSlots[i].frontEnd;
    for (const DrawStats& s : context.threadStats)
        total += s;
    return total;
}

}  // namespace facet
