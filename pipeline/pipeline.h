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
// it hands every stage's output to an Observer between stages (observer.h); drawRun (draw_run.h) runs
// the same stages for many small draws at once. Vertices and chunks of triangles are processed in
// parallel; then tiles are, each drawing its triangles in submission order, so the image is the same
// bytes for any number of threads or any tile size.
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
    // The number of threads a draw cuts its vertices and triangles for (chunkSize); 0: the pool's. Only
    // the sizes of the pool's items change, never the image: a trace on one thread cut for 16 shows the
    // items a 16-thread frame would run (facet bench --scaling predicts from it).
    int cutForThreads = 0;
    int threadsToCutFor() const { return cutForThreads > 0 ? cutForThreads : pool.threads(); }
    ShadedVertices shaded;
    std::vector<WindowVertex> window;  // viewport transform of each vertex that needs no clipping
    std::vector<SetupChunk> chunks;
    std::vector<std::uint32_t> activeTiles;  // the tiles a batch's triangles touch, in tile order
    std::vector<TilePart> tileParts;         // a batch's or a run's back-end items
    std::vector<std::uint32_t> tileWeights;  // per tile of the grid, 0 between batches
    std::vector<DrawStats> threadStats;      // back-end counters, one per thread
    std::uint64_t drawsStarted = 0;          // draws begun with this context: the next draw's id

    // For drawRun (draw_run.h): each draw's set-up chunks and plan, written by the thread that ran the draw's
    // front end; each thread's vertices, front-end counters and (tile, draw) pairs, so that the calling
    // thread reads a few arrays instead of every draw's slot (on some machines a cache line the other core
    // wrote costs hundreds of nanoseconds).
    struct RunDrawSlot {
        std::vector<SetupChunk> chunks;
        std::size_t chunkCount = 0;
        DrawPlan plan;
        PixelRect bounds;  // the pixels its set-up triangles' bounding boxes cover
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

// Work sizes: vertices are shaded in chunks of at most kVertexChunk, triangles set up in chunks of at
// most kTriangleChunk, and at most kBatchTriangles triangles are binned before their tiles are drawn, which
// bounds the memory held in setups whatever the size of the mesh (~17 MB with the built-in surface
// shader's varyings).
// Each batch draws every tile it touches once more, fetching its pixels into a cache again and, with
// two threads, often from the other core's: batches of 65,536 triangles rather than 16,384 made Lost
// Empire's frame ~6% faster on two threads and the bunny's ~2%, and left one thread's unchanged.
inline constexpr std::size_t kVertexChunk = 8192;
inline constexpr std::size_t kTriangleChunk = 2048;
inline constexpr std::size_t kBatchTriangles = 32 * kTriangleChunk;
// A draw is cut into at least kItemsPerThread chunks per thread where its size allows (down to chunks of
// kMinVertexChunk vertices and kMinTriangleChunk triangles, below which an item's own cost shows): a job
// of items lasts at least its longest item, so a mesh of 117,000 vertices in chunks of 8192 keeps 15 of
// 16 threads busy for one chunk's time and leaves the 16th idle, where chunks of 1836 keep all 16 busy
// for a quarter of it. With k items per thread, taken by the threads as they free up, a job ends at most
// one item (a k-th of a thread's share) later than an even split would.
inline constexpr std::size_t kMinVertexChunk = 1024;
inline constexpr std::size_t kMinTriangleChunk = 256;
inline constexpr std::size_t kItemsPerThread = 4;

// The chunk size for `count` vertices or triangles on `threads` threads: count / (kItemsPerThread ·
// threads) rounded up, within [smallest, largest]; `largest` on one thread.
inline std::size_t chunkSize(std::size_t count, int threads, std::size_t smallest, std::size_t largest) {
    if (threads <= 1) return largest;
    const std::size_t items = kItemsPerThread * static_cast<std::size_t>(threads);
    return std::clamp((count + items - 1) / items, smallest, largest);
}

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

// The target ready for a draw of `plan`: the fragment lists sized and told the formats, for a draw
// that appends to them.
inline void prepareTarget(const DrawPlan& plan, Framebuffer& target, const DrawContext& context) {
    if (plan.output != FragmentOutput::AppendToLists) return;
    target.fragmentLists().prepare(target.width(), target.height(), context.tileSize);
    target.fragmentLists().useFormats(plan.depthFormat, plan.colorBuffer);
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
    checkWalkCompiled<S>(plan, Watcher::enabled);
    const std::uint64_t drawId = context.drawsStarted++;
    if constexpr (Watcher::enabled) observer.onDrawBegin(drawId, state);
    prepareTarget(plan, target, context);

    // Vertex stage, every vertex once.
    // Observed draws run on one thread: the largest chunks, so that hooks see the same items as ever.
    const int threads = inOrder ? 1 : context.threadsToCutFor();
    runVertexStage<S>(vertices, uniforms, state, context.pool, inOrder,
                      chunkSize(vertices.size(), threads, kMinVertexChunk, kVertexChunk), context.shaded,
                      context.window, observer);
    DrawStats total;
    total.vertices = context.shaded.size();
    total.triangles = indices.size() / 3;
    const std::size_t triangleChunk = chunkSize(total.triangles, threads, kMinTriangleChunk, kTriangleChunk);
    const TileGrid grid = makeTileGrid(state.viewport, context.tileSize);
    context.threadStats.assign(static_cast<std::size_t>(context.pool.threads()), DrawStats{});
    for (std::size_t batchStart = 0; batchStart < total.triangles; batchStart += kBatchTriangles) {
        const std::size_t batchEnd = std::min(total.triangles, batchStart + kBatchTriangles);
        // Primitive assembly → clipping → divide and viewport → culling and setup → binning.
        const std::size_t chunkCount = setupBatch(indices, batchStart, batchEnd, triangleChunk, state, grid,
                                                  context.shaded, context.window, flatVaryingFloats<S>(),
                                                  context.pool, inOrder, context.chunks, observer);
        const std::span<const SetupChunk> chunks(context.chunks.data(), chunkCount);
        // The back end, tile by tile.
        total.tilesDrawn += drawBatchTiles<S>(grid, chunks, plan, uniforms, target, context.pool, inOrder,
                                              threads, context.activeTiles, context.tileParts,
                                              context.tileWeights, context.threadStats, observer);
        for (const SetupChunk& chunk : chunks)
            total += chunk.stats;
    }
    for (const DrawStats& s : context.threadStats)
        total += s;
    if constexpr (Watcher::enabled) observer.onDrawEnd(drawId, total);
    return total;
}

}  // namespace facet
