// The pipeline, every stage in order on one screen:
//
//   front end, per triangle:  vertex stage → primitive assembly → clipping → divide + viewport
//                             → culling + setup → binning into screen tiles
//   back end, per tile:       rasterization (8×8 blocks) → depth test → interpolation
//                             → fragment shader → blending (or, for exact transparency, appending
//                             to per-pixel fragment lists that resolveFragmentLists() composites)
//
// Each stage is a plain function in its own file; draw() is the only place that knows their order, and
// it hands every stage's output to an Observer between stages (observer.h). Vertices and chunks of
// triangles are processed in parallel; then tiles are, each drawing its triangles in submission order,
// so the image is the same bytes for any number of threads or any tile size.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "bin.h"
#include "blend.h"
#include "clip.h"
#include "depth_test.h"
#include "fragment_lists.h"
#include "fragment_stage.h"
#include "framebuffer.h"
#include "interpolate.h"
#include "observer.h"
#include "primitive_assembly.h"
#include "rasterize.h"
#include "shader.h"
#include "state.h"
#include "thread_pool.h"
#include "triangle_setup.h"
#include "vertex_stage.h"
#include "viewport.h"

namespace facet {

// The front end's output for one chunk of consecutive triangles: their setups, and for every tile the
// setups that may touch it, in submission order.
struct SetupChunk {
    std::vector<TriangleSetup> setups;
    std::vector<float> varyingPlanes;              // 3 · varyingCount floats per setup, in order
    std::vector<std::vector<std::uint32_t>> bins;  // per tile: indices into setups
    DrawStats stats;
    ClipPolygon polygon;  // clipping scratch
};

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

namespace detail {

// Front end for triangles [first, last): assembly, clipping, viewport, setup, binning into `chunk`.
// The first flatVaryingCount varyings are flat (shader.h, flatVaryingFloats).
template <class Observer>
void setupTriangles(std::span<const std::uint32_t> indices, std::size_t first, std::size_t last,
                    const DrawState& state, const TileGrid& grid, const DrawContext& context,
                    int flatVaryingCount, SetupChunk& chunk, Observer& observer) {
    constexpr bool kObserving = Observer::enabled;
    const ShadedVertices& shaded = context.shaded;
    const int varyingCount = shaded.varyingCount;
    const int planeFloats = 3 * varyingCount;
    DrawStats& stats = chunk.stats;

    // Setup and binning of one window triangle (a whole triangle, or one fan piece of a clipped one).
    auto setupAndBin = [&](std::uint32_t triangleIndex, const WindowTriangle& window) {
        TriangleSetup setup;
        float planes[3 * kMaxVaryingFloats];
        const TriangleFate fate = setupTriangle(window, state, setup, planes);
        setup.triangle = triangleIndex;
        if constexpr (kObserving) observer.onSetup(triangleIndex, window, fate, setup);
        if (fate != TriangleFate::Drawn) {
            if (fate == TriangleFate::ZeroArea) ++stats.trianglesZeroArea;
            if (fate == TriangleFate::Culled) ++stats.trianglesCulled;
            if (fate == TriangleFate::MissesSamples) ++stats.trianglesMissingSamples;
            return;
        }
        ++stats.trianglesRasterized;
        const auto index = static_cast<std::uint32_t>(chunk.setups.size());
        chunk.setups.push_back(setup);
        chunk.varyingPlanes.insert(chunk.varyingPlanes.end(), planes, planes + planeFloats);
        binTriangle(grid, setup, index, chunk.bins);
    };

    for (std::size_t t = first; t < last; ++t) {
        const auto triangleIndex = static_cast<std::uint32_t>(t);
        const std::array<std::uint32_t, 3> i = {indices[3 * t], indices[3 * t + 1], indices[3 * t + 2]};

        // Primitive assembly and trivial reject.
        const std::uint8_t outcodeAnd = shaded.outcodes[i[0]] & shaded.outcodes[i[1]] & shaded.outcodes[i[2]];
        const std::uint8_t outcodeOr = shaded.outcodes[i[0]] | shaded.outcodes[i[1]] | shaded.outcodes[i[2]];
        const TriangleFate rejected = trivialReject(outcodeAnd, outcodeOr);
        if (rejected != TriangleFate::Drawn) {
            ++stats.trianglesRejected;
            if constexpr (kObserving) observer.onRejected(triangleIndex, rejected);
            continue;
        }
        ClipPolygon& polygon = chunk.polygon;
        if (kObserving || outcodeOr != 0) {
            assembleTriangle(shaded, i, polygon);
            if constexpr (kObserving) observer.onAssembled(triangleIndex, polygon);
        }

        WindowTriangle window;
        window.varyingCount = varyingCount;
        window.flatVaryingCount = flatVaryingCount;
        window.provokingVaryings =
            shaded.varyingsOf(i[state.raster.provokingVertex == ProvokingVertex::Last ? 2 : 0]);
        if (outcodeOr == 0) {
            // Trivially inside: no clipping, the vertices' window positions are ready.
            for (int k = 0; k < 3; ++k) {
                window.vertices[k] = context.window[i[k]];
                window.varyings[k] = shaded.varyingsOf(i[k]);
            }
            setupAndBin(triangleIndex, window);
            continue;
        }

        // Clipping: the triangle crosses at least one plane.
        ++stats.trianglesClipped;
        clipPolygon(polygon, outcodeOr);
        if constexpr (kObserving) observer.onClipped(triangleIndex, polygon);
        if (polygon.count == 0) {
            ++stats.trianglesRejected;
            if constexpr (kObserving) observer.onRejected(triangleIndex, TriangleFate::ClippedAway);
            continue;
        }

        // The clipped polygon is convex: a fan around its first vertex.
        const int bits = state.raster.subpixelBits;
        const WindowVertex firstVertex = toWindow(polygon.vertices[0].position, state.viewport, bits);
        WindowVertex previous = toWindow(polygon.vertices[1].position, state.viewport, bits);
        for (int k = 2; k < polygon.count; ++k) {
            const WindowVertex current = toWindow(polygon.vertices[k].position, state.viewport, bits);
            window.vertices = {firstVertex, previous, current};
            window.varyings = {polygon.vertices[0].varyings.data(), polygon.vertices[k - 1].varyings.data(),
                               polygon.vertices[k].varyings.data()};
            setupAndBin(triangleIndex, window);
            previous = current;
        }
    }
    // The planes vector has stopped growing: point every setup at its planes.
    for (std::size_t k = 0; k < chunk.setups.size(); ++k)
        chunk.setups[k].varyingPlanes = chunk.varyingPlanes.data() + k * planeFloats;
}

// Fragments that passed the depth test, waiting to be shaded eight at a time: the fragments of tiny
// triangles share a batch. Their varyings are interpolated on the way in (each with its own triangle's
// planes), so a batch may mix triangles of one draw. No two queued fragments share a pixel: before a
// fragment is depth-tested at a pixel that holds a queued one, the queue is shaded, so every pixel
// still sees its fragments in submission order, and the image does not depend on how fragments were
// grouped.
struct FragmentQueue {
    int count = 0;
    int x[kBlockSize], y[kBlockSize];
    float z[kBlockSize];
    std::uint32_t triangle[kBlockSize];
    FragmentBatch batch;              // interpolated varyings, lane = queue slot
    FragmentLists::TileWriter lists;  // the tile's fragment lists, for AppendToLists draws

    // Does a queued fragment sit in row y, at a column of [x, x + 8) whose bit is set in `columns`?
    bool holdsAny(int rowY, int firstX, unsigned columns) const {
        bool found = false;
        for (int i = 0; i < count; ++i) {
            const unsigned column = static_cast<unsigned>(x[i] - firstX);
            found |= y[i] == rowY && column < kBlockSize && ((columns >> column) & 1u);
        }
        return found;
    }
};

// The fragment shader, then the depth write and blending (or appending to the fragment lists) for the
// queued fragments. The back end is compiled once for each FragmentOutput, and draw() chooses per draw,
// so the blending loop is exactly what it would be without fragment lists.
template <Shader S, FragmentOutput kOutput, class Observer>
void shadeQueue(FragmentQueue& queue, const DrawState& state, const typename S::Uniforms& uniforms,
                Framebuffer& target, DrawStats& stats, Observer& observer) {
    constexpr bool kObserving = Observer::enabled;
    const int n = queue.count;
    if (n == 0) return;
    queue.count = 0;

    // The fragment shader: eight lanes at once when the shader can.
    vec4 shaded[kBlockSize];
    unsigned kept = (1u << n) - 1;
    stats.fragmentsShaded += static_cast<unsigned>(n);
    if constexpr (BatchShader<S>) {
        queue.batch.mask = kept;
        const Vec4x8 c = S::fragmentBatch(queue.batch, uniforms);
        for (int lane = 0; lane < n; ++lane)
            shaded[lane] = vec4(c.x[lane], c.y[lane], c.z[lane], c.w[lane]);
    } else {
        float varyings[kMaxVaryingFloats];
        for (int lane = 0; lane < n; ++lane) {
            for (int k = 0; k < kVaryingFloatCount<typename S::Varyings>; ++k)
                varyings[k] = queue.batch.varyings[k][lane];
            shaded[lane] = vec4(0.0f);  // what a discarded lane holds (never read)
            if (!shadeFragment<S>(varyings, uniforms, shaded[lane])) kept &= ~(1u << lane);
        }
    }

    // Depth write, then blending into the colour buffer or appending to the pixel's fragment list.
    const DepthState depth = state.depth;
    for (int lane = 0; lane < n; ++lane) {
        const int x = queue.x[lane], y = queue.y[lane];
        FragmentEvent event;
        if constexpr (kObserving) {
            event = FragmentEvent{x, y, queue.triangle[lane], queue.z[lane], target.depth(x, y)};
            event.colorBefore = event.colorAfter = target.color(x, y);
        }
        if (!(kept & (1u << lane))) {
            ++stats.fragmentsDiscarded;
            if constexpr (kObserving) {
                event.fate = FragmentFate::Discarded;
                observer.onFragment(event);
            }
            continue;
        }
        if (depth.testEnabled && depth.writeEnabled) target.depth(x, y) = queue.z[lane];
        if constexpr (kOutput == FragmentOutput::AppendToLists) {
            const bool stored = queue.lists.append(x, y, shaded[lane], queue.z[lane], state.blend);
            stats.fragmentsStored += stored;
            if constexpr (kObserving) event.fate = stored ? FragmentFate::Stored : FragmentFate::Dropped;
        } else {
            vec4& destination = target.color(x, y);
            destination = blend(state.blend, shaded[lane], destination);
            ++stats.fragmentsWritten;
            if constexpr (kObserving) {
                event.fate = FragmentFate::Written;
                event.colorAfter = destination;
            }
        }
        if constexpr (kObserving) {
            event.shaded = shaded[lane];
            observer.onFragment(event);
        }
    }
}

// The covered pixels of one block: barycentrics, depth, and the depth test (before shading: the shader
// cannot change depth, so testing early gives the same image and skips hidden fragments). Fragments
// that pass go to the queue, which is shaded whenever it holds eight.
template <Shader S, FragmentOutput kOutput, class Observer>
void depthTestBlock(const TriangleSetup& setup, const CoverageBlock& block, FragmentQueue& queue,
                    const DrawState& state, const typename S::Uniforms& uniforms, Framebuffer& target,
                    DrawStats& stats, Observer& observer) {
    constexpr bool kObserving = Observer::enabled;
    const DepthState depth = state.depth;

    // Barycentrics from the exact edge values: λᵢ = Eᵢ / (2·area). The edge values at the block's first
    // sample and their per-pixel steps are integers below 2^47, exact in double.
    const double invArea = 1.0 / static_cast<double>(setup.doubleArea);
    const std::int64_t px = std::int64_t{block.x} * kFixedOne + kFixedOne / 2;
    const std::int64_t py = std::int64_t{block.y} * kFixedOne + kFixedOne / 2;
    const double e1 = static_cast<double>(setup.edges[1].at(px, py));
    const double e2 = static_cast<double>(setup.edges[2].at(px, py));
    const double e1x = static_cast<double>(setup.edges[1].a * kFixedOne);
    const double e1y = static_cast<double>(setup.edges[1].b * kFixedOne);
    const double e2x = static_cast<double>(setup.edges[2].a * kFixedOne);
    const double e2y = static_cast<double>(setup.edges[2].b * kFixedOne);

    for (int row = 0; row < kBlockSize; ++row) {
        const unsigned rowMask = static_cast<unsigned>(block.mask >> (row * kBlockSize)) & 0xffu;
        if (!rowMask) continue;
        const int y = block.y + row;

        // Barycentrics and depth for the row's eight lanes.
        Float8 b1{}, b2{};
        for (int lane = 0; lane < kBlockSize; ++lane) {
            b1[lane] = static_cast<float>((e1 + lane * e1x + row * e1y) * invArea);
            b2[lane] = static_cast<float>((e2 + lane * e2x + row * e2y) * invArea);
        }
        const Float8 z = setup.z0 + b1 * setup.dz1 + b2 * setup.dz2;

        // A queued fragment at one of these pixels must reach the framebuffer before they are tested.
        if (queue.count && queue.holdsAny(y, block.x, rowMask))
            shadeQueue<S, kOutput>(queue, state, uniforms, target, stats, observer);

        float* depthRow = &target.depth(block.x, y);
        unsigned passed = rowMask;
        if (depth.testEnabled) {
            if (block.x + kBlockSize <= target.width()) {
                // Eight stored depths at once (the row lies inside the framebuffer).
                Float8 stored;
                std::memcpy(&stored, depthRow, sizeof stored);
                const Int8 pass = depthTestPasses(depth.compare, z, stored);
                passed &= signMask(pass);
            } else {
                for (int lane = 0; lane < kBlockSize; ++lane)
                    if ((rowMask >> lane) & 1u)
                        if (!depthTestPasses(depth.compare, z[lane], depthRow[lane])) passed &= ~(1u << lane);
            }
        }
        // Varyings for the row's eight lanes at once when several fragments survived; one by one when a
        // sliver of a triangle left one or two (the same formula either way: interpolate.h).
        FragmentBatch rowVaryings;
        const bool wideRow = std::popcount(passed) > 2;
        if (wideRow) interpolateVaryings(setup, b1, b2, rowVaryings);
        for (int lane = 0; lane < kBlockSize; ++lane) {
            if (!(rowMask & (1u << lane))) continue;
            if (!(passed & (1u << lane))) {
                ++stats.fragmentsDepthFailed;
                if constexpr (kObserving) {
                    FragmentEvent event{block.x + lane, y, setup.triangle, z[lane], depthRow[lane]};
                    event.colorBefore = event.colorAfter = target.color(block.x + lane, y);
                    event.fate = FragmentFate::DepthFailed;
                    observer.onFragment(event);
                }
                continue;
            }
            const int slot = queue.count++;
            queue.x[slot] = block.x + lane;
            queue.y[slot] = y;
            queue.z[slot] = z[lane];
            queue.triangle[slot] = setup.triangle;
            if (wideRow) {
                for (int k = 0; k < setup.varyingCount; ++k)
                    queue.batch.varyings[k][slot] = rowVaryings.varyings[k][lane];
            } else {
                float varyings[kMaxVaryingFloats];
                interpolateVaryings(setup, b1[lane], b2[lane], varyings);
                for (int k = 0; k < setup.varyingCount; ++k)
                    queue.batch.varyings[k][slot] = varyings[k];
            }
            if (queue.count == kBlockSize)
                shadeQueue<S, kOutput>(queue, state, uniforms, target, stats, observer);
        }
    }
}

}  // namespace detail

// Draws an indexed triangle list: indices[3t], indices[3t+1], indices[3t+2] make triangle t.
// The caller owns `context` (reuse it across draws). Returns counters for the draw.
// With an enabled Observer everything runs on the calling thread, so hooks see a stable order:
// the front end in triangle order, then fragments tile by tile, each tile in triangle order.
template <Shader S, class Observer = NullObserver>
DrawStats draw(const DrawState& state, const typename S::Uniforms& uniforms,
               std::span<const typename S::Attributes> vertices, std::span<const std::uint32_t> indices,
               Framebuffer& target, DrawContext& context, Observer&& observer = Observer{}) {
    using ObserverType = std::remove_reference_t<Observer>;
    constexpr bool kObserving = ObserverType::enabled;
    validateDraw(state, target, vertices.size(), indices, context.tileSize);
    const bool appending = state.output == FragmentOutput::AppendToLists;
    if (appending) target.fragmentLists().prepare(target.width(), target.height(), context.tileSize);
    ThreadPool& pool = context.pool;
    auto forEach = [&](std::size_t count, const auto& body) {
        if constexpr (kObserving) {
            for (std::size_t item = 0; item < count; ++item)
                body(item, 0);
        } else {
            pool.parallelFor(count, body);
        }
    };

    // Vertex stage: the vertex shader once per vertex, then the viewport transform for every vertex
    // inside the frustum (most of them), which the triangles sharing it then reuse.
    ShadedVertices& shaded = context.shaded;
    prepareShadedVertices<S>(vertices.size(), shaded);
    context.window.resize(vertices.size());
    const std::size_t vertexChunks = (vertices.size() + kVertexChunk - 1) / kVertexChunk;
    forEach(vertexChunks, [&](std::size_t chunk, int) {
        const std::size_t begin = chunk * kVertexChunk, end = std::min(begin + kVertexChunk, vertices.size());
        shadeVertices<S>(vertices, uniforms, begin, end, shaded);
        for (std::size_t i = begin; i < end; ++i)
            if (shaded.outcodes[i] == 0)
                context.window[i] = toWindow(shaded.positions[i], state.viewport, state.raster.subpixelBits);
    });
    if constexpr (kObserving)
        for (std::size_t i = 0; i < shaded.size(); ++i)
            observer.onVertex(static_cast<std::uint32_t>(i), shaded.positions[i], shaded.varyingsOf(i),
                              shaded.varyingCount, shaded.outcodes[i]);

    DrawStats total;
    total.vertices = shaded.size();
    total.triangles = indices.size() / 3;
    const TileGrid grid = makeTileGrid(state.viewport, context.tileSize);
    context.threadStats.assign(static_cast<std::size_t>(pool.threads()), DrawStats{});
    const std::size_t triangleCount = indices.size() / 3;
    for (std::size_t batchStart = 0; batchStart < triangleCount;
         batchStart += kTriangleChunk * kChunksPerBatch) {
        // Front end: chunks of triangles in parallel, each binning into its own lists.
        const std::size_t batchEnd = std::min(triangleCount, batchStart + kTriangleChunk * kChunksPerBatch);
        const std::size_t chunkCount = (batchEnd - batchStart + kTriangleChunk - 1) / kTriangleChunk;
        if (context.chunks.size() < chunkCount) context.chunks.resize(chunkCount);
        forEach(chunkCount, [&](std::size_t c, int) {
            SetupChunk& chunk = context.chunks[c];
            chunk.setups.clear();
            chunk.varyingPlanes.clear();
            chunk.bins.resize(static_cast<std::size_t>(grid.count()));
            for (auto& bin : chunk.bins)
                bin.clear();
            chunk.stats = DrawStats{};
            const std::size_t first = batchStart + c * kTriangleChunk;
            detail::setupTriangles(indices, first, std::min(first + kTriangleChunk, batchEnd), state, grid,
                                   context, flatVaryingFloats<S>(), chunk, observer);
        });

        // Back end: tiles in parallel; inside a tile, chunk after chunk, so triangles keep their order.
        // The back end is compiled for each FragmentOutput (shadeQueue): the choice is made per tile.
        auto drawTile = [&](auto output, std::size_t tile, int thread) {
            constexpr FragmentOutput kOutput = decltype(output)::value;
            const PixelRect rect = grid.tileRect(static_cast<int>(tile));
            DrawStats& stats = context.threadStats[static_cast<std::size_t>(thread)];
            detail::FragmentQueue queue;
            if constexpr (kOutput == FragmentOutput::AppendToLists)
                queue.lists = target.fragmentLists().writer(rect.minX, rect.minY);
            for (std::size_t c = 0; c < chunkCount; ++c) {
                const SetupChunk& chunk = context.chunks[c];
                const std::vector<std::uint32_t>& bin = chunk.bins[tile];
                for (std::size_t k = 0; k < bin.size(); ++k) {
                    // Setups were written by the front end a while ago: ask for the next one early.
                    if (k + 1 < bin.size()) {
                        const TriangleSetup& next = chunk.setups[bin[k + 1]];
                        __builtin_prefetch(&next);
                        __builtin_prefetch(reinterpret_cast<const char*>(&next) + 64);
                        __builtin_prefetch(reinterpret_cast<const char*>(&next) + 128);
                        __builtin_prefetch(next.varyingPlanes);
                    }
                    const TriangleSetup& setup = chunk.setups[bin[k]];
                    rasterizeBlocks(setup, rect, [&](const CoverageBlock& block) {
                        detail::depthTestBlock<S, kOutput>(setup, block, queue, state, uniforms, target,
                                                           stats, observer);
                    });
                }
            }
            detail::shadeQueue<S, kOutput>(queue, state, uniforms, target, stats, observer);
        };
        // Only the tiles some triangle touches: a draw of a few triangles (such as a short run of the
        // transparent pass) then costs little more than its triangles, and a single tile is drawn on
        // the calling thread without waking the pool.
        context.activeTiles.clear();
        for (int tile = 0; tile < grid.count(); ++tile)
            for (std::size_t c = 0; c < chunkCount; ++c)
                if (!context.chunks[c].bins[static_cast<std::size_t>(tile)].empty()) {
                    context.activeTiles.push_back(static_cast<std::uint32_t>(tile));
                    break;
                }
        total.tilesDrawn += context.activeTiles.size();
        forEach(context.activeTiles.size(), [&](std::size_t active, int thread) {
            const std::size_t tile = context.activeTiles[active];
            if (appending)
                drawTile(std::integral_constant<FragmentOutput, FragmentOutput::AppendToLists>{}, tile,
                         thread);
            else
                drawTile(std::integral_constant<FragmentOutput, FragmentOutput::Blend>{}, tile, thread);
        });
        for (std::size_t c = 0; c < chunkCount; ++c)
            total += context.chunks[c].stats;
    }
    for (const DrawStats& s : context.threadStats)
        total += s;
    return total;
}

}  // namespace facet
