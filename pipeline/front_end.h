// The front end of a draw, triangle by triangle: vertex stage → primitive assembly → clipping →
// divide + viewport → culling + setup → binning into screen tiles. Vertices, then chunks of triangles,
// are processed in parallel; each chunk sets up and bins its triangles into its own SetupChunk, in
// submission order, for the back end (back_end.h).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "bin.h"
#include "clip.h"
#include "depth_format.h"
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

// The vertex shader once per vertex, in chunks of `vertexChunk` (in parallel unless `inOrder`), then
// the viewport transform of every vertex inside the frustum (most of them), which the triangles
// sharing it reuse. `window` gets one WindowVertex per vertex (meaningful where the outcode is 0).
template <Shader S, class Observer>
void runVertexStage(std::span<const typename S::Attributes> vertices, const typename S::Uniforms& uniforms,
                    const DrawState& state, ThreadPool& pool, bool inOrder, std::size_t vertexChunk,
                    ShadedVertices& shaded, std::vector<WindowVertex>& window, Observer& observer) {
    prepareShadedVertices<S>(vertices.size(), shaded);
    window.resize(vertices.size());
    const std::size_t chunks = (vertices.size() + vertexChunk - 1) / vertexChunk;
    forEachItem(pool, inOrder, chunks, [&](std::size_t chunk, int) {
        const std::size_t begin = chunk * vertexChunk, end = std::min(begin + vertexChunk, vertices.size());
        shadeVertices<S>(vertices, uniforms, begin, end, shaded, clipDepthRange(state.depth.format));
        // Eight at a time (a group's lanes outside the frustum are computed too, and not read), then
        // the rest one by one.
        static_assert(kVertexBatch == 8, "the eight-lane toWindow takes a group of eight");
        std::size_t i = begin;
        for (; i + kVertexBatch <= end; i += kVertexBatch)
            toWindow(&shaded.positions[i], &shaded.outcodes[i], state.viewport, state.raster.subpixelBits,
                     state.depth.format, &window[i]);
        for (; i < end; ++i)
            if (shaded.outcodes[i] == 0)
                window[i] = toWindow(shaded.positions[i], state.viewport, state.raster.subpixelBits,
                                     state.depth.format);
    });
    if constexpr (Observer::enabled)
        for (std::size_t i = 0; i < shaded.size(); ++i)
            observer.onVertex(static_cast<std::uint32_t>(i), shaded.positions[i], shaded.varyingsOf(i),
                              shaded.varyingCount, shaded.outcodes[i]);
}

namespace detail {

// Tells the observer what a triangle culled for its facing would have covered: its setup with culling
// off, and the coverage decision at every sample of its bounding box (CoverageEvent::culled). Culling
// comes before the bounding box, so a culled triangle may also lie between pixel centres: its setup
// then has only the box, empty (TriangleSetup::boxEmpty), and there is no sample to show.
template <class Observer>
void observeCulled(std::uint32_t triangleIndex, const WindowTriangle& window, const DrawState& state,
                   Observer& observer) {
    DrawState unculled = state;
    unculled.raster.cull = CullMode::None;
    TriangleSetup wouldBe;
    float planes[3 * kMaxVaryingFloats];
    const TriangleFate wouldBeFate = setupTriangle(window, unculled, wouldBe, planes);
    wouldBe.triangle = triangleIndex;
    observer.onSetup(triangleIndex, window, TriangleFate::Culled, wouldBe);
    if (wouldBeFate != TriangleFate::Drawn) return;
    for (int y = wouldBe.minY; y <= wouldBe.maxY; ++y)
        for (int x = wouldBe.minX; x <= wouldBe.maxX; ++x) {
            CoverageEvent event = coverageAt(wouldBe, x, y);
            event.culled = true;
            observer.onCoverage(event);
        }
}

// Setup and binning of one window triangle (a whole triangle, or one fan piece of a clipped one) into
// `chunk`. One TriangleSetup serves every triangle of an unwatched draw: setupTriangle writes each of
// its fields for a triangle it draws, and only those are copied to the chunk (zeroing a fresh one per
// triangle cost ~30 instructions). An observer is shown a fresh one, even for a triangle not drawn.
template <class Observer>
struct SetupAndBin {
    const DrawState& state;
    const TileGrid& grid;
    SetupChunk& chunk;
    Observer& observer;
    int planeFloats;
    std::int64_t sampleReach;
    TriangleSetup reusedSetup;

    void operator()(std::uint32_t triangleIndex, const WindowTriangle& window) {
        TriangleSetup& setup = reusedSetup;
        if constexpr (Observer::enabled) setup = TriangleSetup{};
        float planes[3 * kMaxVaryingFloats];
        const TriangleFate fate = setupTriangle(window, state, setup, planes);
        setup.triangle = triangleIndex;
        if constexpr (Observer::enabled) {
            if (fate == TriangleFate::Culled)
                observeCulled(triangleIndex, window, state, observer);
            else
                observer.onSetup(triangleIndex, window, fate, setup);
        }
        if (fate != TriangleFate::Drawn) {
            countNotDrawn(fate);
            return;
        }
        ++chunk.stats.trianglesRasterized;
        const auto index = static_cast<std::uint32_t>(chunk.setups.size());
        setup.varyingPlaneOffset = static_cast<std::uint32_t>(chunk.varyingPlanes.size());
        chunk.setups.push_back(setup);
        chunk.varyingPlanes.insert(chunk.varyingPlanes.end(), planes, planes + planeFloats);
        binTriangle(grid, setup, index, chunk.bins, sampleReach, &chunk.touchedTiles);
    }

    void countNotDrawn(TriangleFate fate) {
        DrawStats& stats = chunk.stats;
        if (fate == TriangleFate::ZeroArea) ++stats.trianglesZeroArea;
        if (fate == TriangleFate::Culled) ++stats.trianglesCulled;
        if (fate == TriangleFate::MissesSamples) ++stats.trianglesMissingSamples;
    }
};

// A mesh's indices jump about its vertices: asks for triangle t + kVerticesAhead's window vertices,
// outcodes and varyings now, so that they are in cache when it comes (else each triangle waits on
// memory).
[[gnu::always_inline]] inline void prefetchVerticesAhead(std::span<const std::uint32_t> indices,
                                                         std::size_t t, std::size_t last,
                                                         const ShadedVertices& shaded,
                                                         std::span<const WindowVertex> windowVertices) {
    constexpr std::size_t kVerticesAhead = 8;
    if (t + kVerticesAhead < last) {
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t ahead = indices[3 * (t + kVerticesAhead) + k];
            __builtin_prefetch(&windowVertices[ahead]);
            __builtin_prefetch(&shaded.outcodes[ahead]);
            __builtin_prefetch(shaded.varyingsOf(ahead));
        }
    }
}

// Clipping of an assembled triangle that crosses at least one plane (outcodeOr ≠ 0), then the
// clipped polygon, convex, set up as a fan around its first vertex.
template <class Observer>
[[gnu::always_inline]] inline void clipAndSetUp(std::uint32_t triangleIndex, ClipPolygon& polygon,
                                                std::uint8_t outcodeOr, WindowTriangle& window,
                                                SetupAndBin<Observer>& setupAndBin) {
    const DrawState& state = setupAndBin.state;
    DrawStats& stats = setupAndBin.chunk.stats;
    ++stats.trianglesClipped;
    clipPolygon(polygon, outcodeOr, clipDepthRange(state.depth.format), state.depth.fromW);
    if constexpr (Observer::enabled) setupAndBin.observer.onClipped(triangleIndex, polygon);
    if (polygon.count == 0) {
        ++stats.trianglesRejected;
        if constexpr (Observer::enabled)
            setupAndBin.observer.onRejected(triangleIndex, TriangleFate::ClippedAway);
        return;
    }
    const int bits = state.raster.subpixelBits;
    const DepthBufferFormat depthFormat = state.depth.format;
    const WindowVertex firstVertex =
        toWindow(polygon.vertices[0].position, state.viewport, bits, depthFormat);
    WindowVertex previous = toWindow(polygon.vertices[1].position, state.viewport, bits, depthFormat);
    for (int k = 2; k < polygon.count; ++k) {
        const WindowVertex current =
            toWindow(polygon.vertices[k].position, state.viewport, bits, depthFormat);
        window.vertices = {firstVertex, previous, current};
        window.varyings = {polygon.vertices[0].varyings.data(), polygon.vertices[k - 1].varyings.data(),
                           polygon.vertices[k].varyings.data()};
        setupAndBin(triangleIndex, window);
        previous = current;
    }
}

}  // namespace detail

// Front end for triangles [first, last): assembly, clipping, viewport, setup, binning into `chunk`
// (which the caller has emptied). `window` holds the viewport transform of every vertex no plane clips.
// The first flatVaryingCount varyings are flat (shader.h, flatVaryingFloats).
template <class Observer>
void setupTriangles(std::span<const std::uint32_t> indices, std::size_t first, std::size_t last,
                    const DrawState& state, const TileGrid& grid, const ShadedVertices& shaded,
                    std::span<const WindowVertex> windowVertices, int flatVaryingCount, SetupChunk& chunk,
                    Observer& observer) {
    constexpr bool kObserving = Observer::enabled;
    const int varyingCount = shaded.varyingCount;
    detail::SetupAndBin<Observer> setupAndBin{
        state, grid, chunk, observer, 3 * varyingCount, sampleReachFixed(state.samples), {}};
    for (std::size_t t = first; t < last; ++t) {
        const auto triangleIndex = static_cast<std::uint32_t>(t);
        const std::array<std::uint32_t, 3> i = {indices[3 * t], indices[3 * t + 1], indices[3 * t + 2]};
        detail::prefetchVerticesAhead(indices, t, last, shaded, windowVertices);

        // Primitive assembly and trivial reject.
        const std::uint8_t outcodeAnd = shaded.outcodes[i[0]] & shaded.outcodes[i[1]] & shaded.outcodes[i[2]];
        const std::uint8_t outcodeOr = shaded.outcodes[i[0]] | shaded.outcodes[i[1]] | shaded.outcodes[i[2]];
        const TriangleFate rejected = trivialReject(outcodeAnd, outcodeOr);
        if (rejected != TriangleFate::Drawn) {
            ++chunk.stats.trianglesRejected;
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
            // Trivially inside: no clipping, the vertices' window positions are ready. Unwatched, a
            // triangle of zero area or culled for its facing is counted from its area alone, before
            // it is gathered (setupTriangle decides the same first; an observer is shown its setup).
            if constexpr (!kObserving) {
                const TriangleFate fate = areaFate(
                    signedDoubleArea(windowVertices[i[0]], windowVertices[i[1]], windowVertices[i[2]]),
                    state.raster);
                if (fate != TriangleFate::Drawn) {
                    setupAndBin.countNotDrawn(fate);
                    continue;
                }
            }
            for (int k = 0; k < 3; ++k) {
                window.vertices[k] = windowVertices[i[k]];
                window.varyings[k] = shaded.varyingsOf(i[k]);
            }
            setupAndBin(triangleIndex, window);
            continue;
        }
        detail::clipAndSetUp(triangleIndex, polygon, outcodeOr, window, setupAndBin);
    }
}

// The front end for one batch of triangles [batchStart, batchEnd): chunks of `triangleChunk` triangles
// set up and binned in parallel (unless `inOrder`), chunk c into chunks[c]. Returns the chunk count.
template <class Observer>
std::size_t setupBatch(std::span<const std::uint32_t> indices, std::size_t batchStart, std::size_t batchEnd,
                       std::size_t triangleChunk, const DrawState& state, const TileGrid& grid,
                       const ShadedVertices& shaded, std::span<const WindowVertex> windowVertices,
                       int flatVaryingCount, ThreadPool& pool, bool inOrder, std::vector<SetupChunk>& chunks,
                       Observer& observer) {
    const std::size_t chunkCount = (batchEnd - batchStart + triangleChunk - 1) / triangleChunk;
    if (chunks.size() < chunkCount) chunks.resize(chunkCount);
    forEachItem(pool, inOrder, chunkCount, [&](std::size_t c, int) {
        SetupChunk& chunk = chunks[c];
        chunk.setups.clear();
        chunk.varyingPlanes.clear();
        // Only the bins the last batch filled hold anything; a new grid size starts them all afresh.
        if (chunk.bins.size() != static_cast<std::size_t>(grid.count())) {
            chunk.bins.assign(static_cast<std::size_t>(grid.count()), {});
        } else {
            for (const std::uint32_t tile : chunk.touchedTiles)
                chunk.bins[tile].clear();
        }
        chunk.touchedTiles.clear();
        chunk.stats = DrawStats{};
        const std::size_t first = batchStart + c * triangleChunk;
        setupTriangles(indices, first, std::min(first + triangleChunk, batchEnd), state, grid, shaded,
                       windowVertices, flatVaryingCount, chunk, observer);
    });
    return chunkCount;
}

}  // namespace facet
