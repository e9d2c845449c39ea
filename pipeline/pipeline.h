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

    // For drawRun: each draw's set-up chunks and plan, written by the thread that ran the draw's front
    // end; each thread's vertices, front-end counters and (tile, draw) pairs, so that the calling thread
    // reads a few arrays instead of every draw's slot (on some machines a cache line the other core wrote
    // costs hundreds of nanoseconds).
    struct RunDrawSlot {
        std::vector<SetupChunk> chunks;
        std::size_t chunkCount = 0;
        DrawPlan plan;
    };
    struct alignas(64) RunThreadScratch {
        ShadedVertices shaded;
        std::vector<WindowVertex> window;
        DrawStats frontEnd;                  // summed over the draws this thread set up
        std::vector<std::uint64_t> touches;  // tile << 32 | draw, for each tile each of its draws touches
    };
    std::vector<RunDrawSlot> runSlots;
    std::vector<RunThreadScratch> runThreads;
    std::vector<std::uint64_t> runTouches;  // every thread's touches, sorted: by tile, then draw
    struct RunTile {
        std::uint32_t tile;
        std::uint32_t firstTouch, endTouch;  // its draws: runTouches[firstTouch, endTouch)
    };
    std::vector<RunTile> runTiles;
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

// Checks a draw's state (viewport, tile size, subpixel bits, samples); throws std::invalid_argument
// naming the problem.
void validateDrawState(const DrawState& state, const Framebuffer& target, int tileSize);

// Throws std::invalid_argument naming the first index ≥ vertexCount and its position, if there is one.
void throwIndexOutOfRange(std::size_t vertexCount, std::span<const std::uint32_t> indices);

// The largest of `indices` (0 for none): a loop without an early exit, which the compiler vectorises.
// Every draw of every frame pays it, so it is inline, and each instruction-set copy of the frame
// (src/render/frame_kernels) compiles it with its own vectors: out of line in pipeline.cpp's baseline
// copy (SSE2, which has no unsigned 32-bit max) it was 1.9% of the bunny's frame at 640×480.
inline std::uint32_t largestIndex(std::span<const std::uint32_t> indices) {
    std::uint32_t largest = 0;
    for (const std::uint32_t index : indices)
        largest = std::max(largest, index);
    return largest;
}

// Checks a draw's state and the mesh's indices; throws std::invalid_argument naming the problem.
inline void validateDraw(const DrawState& state, const Framebuffer& target, std::size_t vertexCount,
                         std::span<const std::uint32_t> indices, int tileSize) {
    validateDrawState(state, target, tileSize);
    if (!indices.empty() && largestIndex(indices) >= vertexCount) throwIndexOutOfRange(vertexCount, indices);
}

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

// drawRun cuts its draws into runs of at most kMaxRunCalls draws and kMaxRunTriangles triangles, so that
// the two runs it holds at a time take no more memory in set-ups than one big draw's batch.
inline constexpr std::size_t kMaxRunCalls = 64;
inline constexpr std::size_t kMaxRunTriangles = kTriangleChunk * kChunksPerBatch / 2;

// One past the last draw of the run that starts at draws[first].
template <Shader S>
std::size_t runEnd(std::span<const RunDraw<S>> draws, std::size_t first) {
    std::size_t end = first + 1, triangles = draws[first].indices.size() / 3;
    while (end < draws.size() && end - first < kMaxRunCalls) {
        triangles += draws[end].indices.size() / 3;
        if (triangles > kMaxRunTriangles) break;
        ++end;
    }
    return end;
}

// Draws consecutive small draws of one shader with the bytes draw() would give one after another, in
// runs (runEnd) of one front-end job and one back-end job each instead of two or three jobs per draw:
// first the run's front ends, one draw per item (each on one thread, as draw() runs a draw this small),
// then its back end, tile by tile, each tile drawing the run's triangles in draw order, so that every
// pixel still sees its fragments in submission order. Each run's back end shares a job with the next
// run's front ends (which, on more than one thread, write the other of two sets of chunks), so that
// neither waits for the other's last items. A frame of many draws of a few triangles each (Lost Empire's
// 4,064 sorted transparent draws) otherwise joins the pool per draw and runs every front end on the calling
// thread. Every draw must fit in a run (fitsInRun) and have the first one's viewport; checked, with each
// draw's state and indices as draw() checks them, before anything is drawn (std::invalid_argument). Not
// observable: an observer watches draw() by draw(). Returns the draws' counters summed; `runs`, when
// given, gets the number of runs.
template <Shader S>
DrawStats drawRun(std::span<const RunDraw<S>> draws, Framebuffer& target, DrawContext& context,
                  std::size_t* runs = nullptr) {
    if (runs) *runs = 0;
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
    if (context.runSlots.size() < 2 * kMaxRunCalls) context.runSlots.resize(2 * kMaxRunCalls);
    const auto threads = static_cast<std::size_t>(context.pool.threads());
    if (context.runThreads.size() < threads) context.runThreads.resize(threads);
    for (std::size_t t = 0; t < threads; ++t) {
        context.runThreads[t].frontEnd = DrawStats{};
        context.runThreads[t].touches.clear();
    }
    for (const RunDraw<S>& d : draws) {
        const DrawPlan plan = planDraw(*d.state);
        if (plan.output == FragmentOutput::AppendToLists) {
            target.fragmentLists().prepare(target.width(), target.height(), context.tileSize);
            target.fragmentLists().useFormats(plan.depthFormat, plan.colorBuffer);
        }
    }
    context.drawsStarted += draws.size();
    context.threadStats.assign(threads, DrawStats{});

    // Draw i's chunks and plan: two consecutive runs span at most 2 · kMaxRunCalls draws, so the run being
    // drawn and the run being set up never share a slot. One thread runs a job's items in order (the
    // tiles, then the next front ends), so it reuses the slots the last run left in its caches.
    const std::size_t slotCount = threads > 1 ? 2 * kMaxRunCalls : kMaxRunCalls;
    const auto slotOf = [&](std::size_t i) -> DrawContext::RunDrawSlot& {
        return context.runSlots[i % slotCount];
    };
    // Draw i's front end: vertex stage, then setup and binning into its slot's chunk; the thread notes
    // the tiles the draw touches.
    const auto frontEnd = [&](std::size_t i, int thread) {
        const RunDraw<S>& d = draws[i];
        DrawContext::RunThreadScratch& scratch = context.runThreads[static_cast<std::size_t>(thread)];
        DrawContext::RunDrawSlot& slot = slotOf(i);
        slot.plan = planDraw(*d.state);
        NullObserver observer;
        constexpr bool kOneThread = true;  // this item is the draw's whole front end
        runVertexStage<S>(d.vertices, *d.uniforms, *d.state, context.pool, kOneThread, kVertexChunk,
                          scratch.shaded, scratch.window, observer);
        const std::size_t triangles = d.indices.size() / 3;
        slot.chunkCount = setupBatch(d.indices, 0, triangles, kTriangleChunk, *d.state, grid, scratch.shaded,
                                     scratch.window, flatVaryingFloats<S>(), context.pool, kOneThread,
                                     slot.chunks, observer);
        scratch.frontEnd.vertices += scratch.shaded.size();
        scratch.frontEnd.triangles += triangles;
        for (std::size_t c = 0; c < slot.chunkCount; ++c) {
            const SetupChunk& chunk = slot.chunks[c];
            scratch.frontEnd += chunk.stats;
            for (const std::uint32_t tile : chunk.touchedTiles)
                scratch.touches.push_back(std::uint64_t{tile} << 32 | i);
        }
    };
    // After a run's front ends: each tile they touch and its draws, in draw order (a tile appears once
    // per draw however many of the draw's triangles touch it).
    std::vector<std::uint64_t>& touches = context.runTouches;
    std::vector<DrawContext::RunTile>& tiles = context.runTiles;
    const auto gatherTiles = [&] {
        touches.clear();
        for (std::size_t t = 0; t < threads; ++t) {
            std::vector<std::uint64_t>& own = context.runThreads[t].touches;
            touches.insert(touches.end(), own.begin(), own.end());
            own.clear();
        }
        std::sort(touches.begin(), touches.end());
        touches.erase(std::unique(touches.begin(), touches.end()), touches.end());
        tiles.clear();
        for (std::size_t e = 0; e < touches.size(); ++e) {
            const auto tile = static_cast<std::uint32_t>(touches[e] >> 32);
            if (tiles.empty() || tiles.back().tile != tile)
                tiles.push_back({tile, static_cast<std::uint32_t>(e), static_cast<std::uint32_t>(e)});
            ++tiles.back().endTouch;
        }
    };
    // One tile of a run: each draw that touches it, in draw order.
    const auto backEnd = [&](const DrawContext::RunTile& tile, int thread) {
        DrawStats& stats = context.threadStats[static_cast<std::size_t>(thread)];
        for (std::uint32_t e = tile.firstTouch; e < tile.endTouch; ++e) {
            const auto i = static_cast<std::size_t>(touches[e] & 0xffffffffu);
            const DrawContext::RunDrawSlot& slot = slotOf(i);
            NullObserver observer;
            detail::drawTileOfChunks<S>(grid, tile.tile, {slot.chunks.data(), slot.chunkCount}, slot.plan,
                                        *draws[i].uniforms, target, stats, observer);
            ++stats.tilesDrawn;
        }
    };

    // The first run's front ends alone; then each job draws one run's tiles (first: they are the bigger
    // items) and sets up the next run.
    std::size_t first = 0, end = runEnd(draws, 0);
    context.pool.parallelFor(end, frontEnd);
    while (first < draws.size()) {
        gatherTiles();
        if (runs) ++*runs;
        const std::size_t nextFirst = end,
                          nextEnd = nextFirst < draws.size() ? runEnd(draws, nextFirst) : end;
        const std::size_t tileItems = tiles.size();
        context.pool.parallelFor(tileItems + (nextEnd - nextFirst), [&](std::size_t item, int thread) {
            if (item < tileItems)
                backEnd(tiles[item], thread);
            else
                frontEnd(nextFirst + (item - tileItems), thread);
        });
        first = nextFirst;
        end = nextEnd;
    }

    DrawStats total;
    for (std::size_t t = 0; t < threads; ++t)
        total += context.runThreads[t].frontEnd;
    for (const DrawStats& s : context.threadStats)
        total += s;
    return total;
}

}  // namespace facet
