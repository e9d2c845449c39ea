// Runs of draws: many consecutive small draws of one shader drawn with the bytes draw() would give
// one after another, in runs of one front-end job and one back-end job each instead of two or three
// jobs per draw (drawRun). The same stages as draw() (pipeline.h), in the same order per draw.
#pragma once

#include <algorithm>
#include <climits>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "pipeline.h"

namespace facet {

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

// drawRun cuts its draws into runs of at most runCallsFor(threads, tiles) draws and kMaxRunTriangles
// triangles, so that the two runs it holds at a time take no more memory in set-ups than one big draw's
// batch. Each run is one job of the pool (its tiles and the next run's front ends), and a job lasts at least
// its longest item: with many threads, a run of 64 draws of a few triangles each is too little work to share
// (its largest tile or front end is a good part of it), so runs grow with the threads: kMaxRunCalls
// draws per two threads, as far as the two runs' tables of bins (one per draw, a std::vector per tile:
// 12 KB a draw at 1920×1080 in tiles of 64) fit in kRunBinTablesBytes, and never below kMaxRunCalls.
inline constexpr std::size_t kMaxRunCalls = 64;
inline constexpr std::size_t kMaxRunTriangles = kBatchTriangles / 2;
inline constexpr std::size_t kRunBinTablesBytes = std::size_t{16} << 20;
inline std::size_t runCallsFor(int threads, int tiles) {
    const std::size_t wanted = kMaxRunCalls * static_cast<std::size_t>(std::max(1, threads / 2));
    const std::size_t fitting = kRunBinTablesBytes / (2 * static_cast<std::size_t>(std::max(1, tiles)) *
                                                      sizeof(std::vector<std::uint32_t>));
    return std::max(kMaxRunCalls, std::min(wanted, fitting));
}

// One past the last draw of the run that starts at draws[first], of at most maxCalls draws.
template <Shader S>
std::size_t runEnd(std::span<const RunDraw<S>> draws, std::size_t first, std::size_t maxCalls) {
    std::size_t end = first + 1, triangles = draws[first].indices.size() / 3;
    while (end < draws.size() && end - first < maxCalls) {
        triangles += draws[end].indices.size() / 3;
        if (triangles > kMaxRunTriangles) break;
        ++end;
    }
    return end;
}

// Checks each draw of a run as draw() checks it, and that it fits in a run and shares the first one's
// viewport; throws std::invalid_argument naming the problem.
template <Shader S>
void validateRun(std::span<const RunDraw<S>> draws, const Framebuffer& target, const DrawContext& context) {
    const Viewport& viewport = draws.front().state->viewport;
    for (const RunDraw<S>& d : draws) {
        validateDraw(*d.state, target, d.vertices.size(), d.indices, context.tileSize);
        checkWalkCompiled<S>(planDraw(*d.state), false);
        if (!fitsInRun(d.vertices.size(), d.indices.size()))
            throw std::invalid_argument("drawRun: a draw of more than " + std::to_string(kVertexChunk) +
                                        " vertices or " + std::to_string(kTriangleChunk) +
                                        " triangles: draw it with draw()");
        if (!samePixels(d.state->viewport, viewport))
            throw std::invalid_argument("drawRun: the draws of a run must share one viewport");
    }
}

namespace detail {

// The context's scratch for runs of up to maxCalls of `draws` on `threads` threads, emptied, and the target
// ready for each draw (prepareTarget).
template <Shader S>
void startRun(std::span<const RunDraw<S>> draws, Framebuffer& target, DrawContext& context,
              std::size_t threads, std::size_t maxCalls) {
    if (context.runSlots.size() < 2 * maxCalls) context.runSlots.resize(2 * maxCalls);
    if (context.runThreads.size() < threads) context.runThreads.resize(threads);
    for (std::size_t t = 0; t < threads; ++t) {
        context.runThreads[t].frontEnd = DrawStats{};
        context.runThreads[t].touches.clear();
    }
    for (const RunDraw<S>& d : draws)
        prepareTarget(planDraw(*d.state), target, context);
    context.drawsStarted += draws.size();
    context.threadStats.assign(threads, DrawStats{});
}

// Draw i's front end, one item on one thread (this item is the draw's whole front end): vertex stage →
// primitive assembly, clipping, setup and binning into its slot's chunks; the thread notes the tiles
// the draw touches.
template <Shader S>
void runFrontEnd(const RunDraw<S>& d, std::size_t i, DrawContext::RunDrawSlot& slot,
                 DrawContext::RunThreadScratch& scratch, const TileGrid& grid, DrawContext& context) {
    slot.plan = planDraw(*d.state);
    NullObserver observer;
    constexpr bool kOneThread = true;
    runVertexStage<S>(d.vertices, *d.uniforms, *d.state, context.pool, kOneThread, kVertexChunk,
                      scratch.shaded, scratch.window, observer);
    const std::size_t triangles = d.indices.size() / 3;
    slot.chunkCount =
        setupBatch(d.indices, 0, triangles, kTriangleChunk, *d.state, grid, scratch.shaded, scratch.window,
                   flatVaryingFloats<S>(), context.pool, kOneThread, slot.chunks, observer);
    scratch.frontEnd.vertices += scratch.shaded.size();
    scratch.frontEnd.triangles += triangles;
    PixelRect& bounds = slot.bounds;
    bounds = {INT_MAX, INT_MAX, INT_MIN, INT_MIN};  // empty until a triangle widens it
    for (std::size_t c = 0; c < slot.chunkCount; ++c) {
        const SetupChunk& chunk = slot.chunks[c];
        for (const TriangleSetup& setup : chunk.setups) {
            bounds.minX = std::min(bounds.minX, setup.minX);
            bounds.minY = std::min(bounds.minY, setup.minY);
            bounds.maxX = std::max(bounds.maxX, setup.maxX);
            bounds.maxY = std::max(bounds.maxY, setup.maxY);
        }
        scratch.frontEnd += chunk.stats;
        for (const std::uint32_t tile : chunk.touchedTiles)
            scratch.touches.push_back(std::uint64_t{tile} << 32 | i);
    }
}

// After a run's front ends: each tile they touch and its draws, in draw order (a tile appears once per
// draw however many of the draw's triangles touch it), from every thread's notes.
inline void gatherRunTiles(DrawContext& context, std::size_t threads) {
    std::vector<std::uint64_t>& touches = context.runTouches;
    std::vector<DrawContext::RunTile>& tiles = context.runTiles;
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
}

// The run's back-end items, in tile order: each tile of context.runTiles whole, or, when `mayCut`, in
// parts (tilePartsPerSide: the draws touching it against the run's (tile, draw) pairs).
inline void cutRunTiles(DrawContext& context, const TileGrid& grid, int threads, bool mayCut) {
    std::vector<TilePart>& parts = context.tileParts;
    parts.clear();
    const int maxSide = mayCut ? grid.maxPartsPerSide() : 1;
    for (std::size_t r = 0; r < context.runTiles.size(); ++r) {
        const DrawContext::RunTile& tile = context.runTiles[r];
        const int side =
            tilePartsPerSide(tile.endTouch - tile.firstTouch, context.runTouches.size(), threads, maxSide);
        appendTileParts(grid, static_cast<std::uint32_t>(r), static_cast<int>(tile.tile), side, parts);
    }
}

}  // namespace detail

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
    validateRun(draws, target, context);
    const TileGrid grid = makeTileGrid(draws.front().state->viewport, context.tileSize);
    const auto threads = static_cast<std::size_t>(context.pool.threads());
    const std::size_t maxCalls = runCallsFor(context.threadsToCutFor(), grid.count());
    detail::startRun(draws, target, context, threads, maxCalls);

    // Draw i's chunks and plan: two consecutive runs span at most 2 · maxCalls draws, so the run being
    // drawn and the run being set up never share a slot. One thread runs a job's items in order (the
    // tiles, then the next front ends), so it reuses the slots the last run left in its caches.
    const std::size_t slotCount = threads > 1 ? 2 * maxCalls : maxCalls;
    const auto slotOf = [&](std::size_t i) -> DrawContext::RunDrawSlot& {
        return context.runSlots[i % slotCount];
    };
    const auto frontEnd = [&](std::size_t i, int thread) {
        detail::runFrontEnd(draws[i], i, slotOf(i), context.runThreads[static_cast<std::size_t>(thread)],
                            grid, context);
    };
    // The back end of one tile of a run, or of a part of it: each draw that touches the tile (and, in a
    // part, whose triangles' bounds reach the part), in draw order.
    const auto backEnd = [&](const TilePart& part, int thread) {
        DrawStats& stats = context.threadStats[static_cast<std::size_t>(thread)];
        const DrawContext::RunTile& tile = context.runTiles[part.tile];
        const PixelRect rect = grid.tilePartRect(static_cast<int>(tile.tile), part.side, part.part);
        for (std::uint32_t e = tile.firstTouch; e < tile.endTouch; ++e) {
            const auto i = static_cast<std::size_t>(context.runTouches[e] & 0xffffffffu);
            const DrawContext::RunDrawSlot& slot = slotOf(i);
            if (part.first) ++stats.tilesDrawn;
            if (part.side > 1 && !overlaps(slot.bounds, rect)) continue;
            NullObserver observer;
            detail::drawTileOfChunks<S>(rect, part.side > 1, tile.tile, {slot.chunks.data(), slot.chunkCount},
                                        slot.plan, *draws[i].uniforms, target, stats, observer);
        }
    };
    // A tile's fragment list has one writer (FragmentLists::writer): a run with a draw that appends to
    // lists draws its tiles whole.
    const auto mayCutTiles = [&](std::size_t runFirst, std::size_t runEnd) {
        for (std::size_t i = runFirst; i < runEnd; ++i)
            if (slotOf(i).plan.output == FragmentOutput::AppendToLists) return false;
        return true;
    };

    // The first run's front ends alone; then each job draws one run's tiles (first: they are the bigger
    // items) and sets up the next run.
    std::size_t first = 0, end = runEnd(draws, 0, maxCalls);
    context.pool.parallelFor(end, frontEnd);
    while (first < draws.size()) {
        detail::gatherRunTiles(context, threads);
        detail::cutRunTiles(context, grid, context.threadsToCutFor(), mayCutTiles(first, end));
        if (runs) ++*runs;
        const std::size_t nextFirst = end,
                          nextEnd = nextFirst < draws.size() ? runEnd(draws, nextFirst, maxCalls) : end;
        const std::size_t tileItems = context.tileParts.size();
        context.pool.parallelFor(tileItems + (nextEnd - nextFirst), [&](std::size_t item, int thread) {
            if (item < tileItems)
                backEnd(context.tileParts[item], thread);
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
