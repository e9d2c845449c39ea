#include "bin.h"

#include <algorithm>
#include <random>

#include <gtest/gtest.h>

#include "../support/test_shaders.h"
#include "rasterize.h"
#include "triangle_setup.h"

namespace facet {
namespace {

TEST(TileGrid, CoversTheViewportWithTilesOnMultiplesOfTheTileSize) {
    const TileGrid grid = makeTileGrid(Viewport{10, 70, 150, 20}, 64);
    EXPECT_EQ(grid.columns, 3);  // x 10..159: tiles 0, 1, 2
    EXPECT_EQ(grid.rows, 1);     // y 70..89: all in tile row 1 (64..127)
    EXPECT_EQ(grid.firstRow, 1);
    int pixels = 0;
    for (int t = 0; t < grid.count(); ++t) {
        const PixelRect r = grid.tileRect(t);
        if (!r.empty()) pixels += (r.maxX - r.minX + 1) * (r.maxY - r.minY + 1);
    }
    EXPECT_EQ(pixels, 150 * 20);
}

// A pixel's tile is its coordinate divided by the tile size, by a shift for powers of two only.
// Breaks caught: the shift off by one; a shift used for a size that is not a power of two.
TEST(TileGrid, TileOfIsTheQuotientForEverySize) {
    for (int size : {8, 16, 24, 32, 40, 64, 96, 128, 256}) {
        const TileGrid grid = makeTileGrid(Viewport{0, 0, 4000, 10}, size);
        EXPECT_EQ(grid.tileShift >= 0, (size & (size - 1)) == 0) << size;
        for (int p = 0; p < 4000; ++p)
            ASSERT_EQ(grid.tileOf(p), p / size) << "pixel " << p << ", tiles of " << size;
    }
}

// A tile cut side × side: its parts inside the viewport tile its pixels exactly once, each part a
// multiple of kBlockSize wide and high unless the viewport clips it, and one part counts the tile.
// Breaks caught: parts overlapping or leaving a gap (a part's size or origin off by one), a part
// outside the viewport handed out, no part or two parts counting the tile, a cut that leaves parts
// narrower than a block (24-pixel tiles) or one capped below 4 parts a side (64-pixel tiles).
TEST(TileGrid, PartsOfATileCoverItsPixelsOnce) {
    EXPECT_EQ(makeTileGrid(Viewport{0, 0, 100, 100}, 64).maxPartsPerSide(), 4);
    EXPECT_EQ(makeTileGrid(Viewport{0, 0, 100, 100}, 32).maxPartsPerSide(), 4);
    EXPECT_EQ(makeTileGrid(Viewport{0, 0, 100, 100}, 16).maxPartsPerSide(), 2);
    EXPECT_EQ(makeTileGrid(Viewport{0, 0, 100, 100}, 24).maxPartsPerSide(), 1);
    EXPECT_EQ(makeTileGrid(Viewport{0, 0, 100, 100}, 8).maxPartsPerSide(), 1);
    for (const int tileSize : {64, 32, 16}) {
        // The viewport starts and ends inside tiles, so edge tiles have parts wholly outside it.
        const TileGrid grid = makeTileGrid(Viewport{37, 5, 150, 90}, tileSize);
        for (int side = 1; side <= grid.maxPartsPerSide(); side *= 2)
            for (int tile = 0; tile < grid.count(); ++tile) {
                SCOPED_TRACE(::testing::Message()
                             << "tiles of " << tileSize << ", tile " << tile << ", side " << side);
                std::vector<TilePart> parts;
                appendTileParts(grid, 7, tile, side, parts);
                const PixelRect whole = grid.tileRect(tile);
                std::vector<int> hits(static_cast<std::size_t>(grid.area.maxX + 1) * (grid.area.maxY + 1));
                int counting = 0;
                for (const TilePart& part : parts) {
                    EXPECT_EQ(part.tile, 7u);
                    EXPECT_EQ(part.side, side);
                    counting += part.first;
                    const PixelRect r = grid.tilePartRect(tile, part.side, part.part);
                    ASSERT_FALSE(r.empty());
                    if (r.minX > whole.minX) {
                        EXPECT_EQ(r.minX % kBlockSize, 0);
                    }
                    if (r.minY > whole.minY) {
                        EXPECT_EQ(r.minY % kBlockSize, 0);
                    }
                    for (int y = r.minY; y <= r.maxY; ++y)
                        for (int x = r.minX; x <= r.maxX; ++x)
                            ++hits[static_cast<std::size_t>(y) * (grid.area.maxX + 1) + x];
                }
                EXPECT_EQ(counting, 1);
                for (int y = 0; y <= grid.area.maxY; ++y)
                    for (int x = 0; x <= grid.area.maxX; ++x) {
                        const bool inTile =
                            x >= whole.minX && x <= whole.maxX && y >= whole.minY && y <= whole.maxY;
                        ASSERT_EQ(hits[static_cast<std::size_t>(y) * (grid.area.maxX + 1) + x],
                                  inTile ? 1 : 0)
                            << "pixel " << x << ", " << y;
                    }
            }
    }
}

// A tile is cut while a part would hold more than 1/(2·threads) of the back end's work, never on one
// thread, never past maxSide. Breaks caught: the share compared the wrong way or without the factor 2,
// a cut on one thread, the side grown past maxSide or by one instead of doubled.
TEST(TileGrid, ATileIsCutWhileAPartHoldsMoreThanItsShare) {
    EXPECT_EQ(tilePartsPerSide(900, 1000, 1, 4), 1);    // one thread: nothing to share
    EXPECT_EQ(tilePartsPerSide(31, 1000, 16, 4), 1);    // 31 · 32 ≤ 1000
    EXPECT_EQ(tilePartsPerSide(32, 1000, 16, 4), 2);    // 32 · 32 > 1000
    EXPECT_EQ(tilePartsPerSide(125, 1000, 16, 4), 2);   // 125 · 32 ≤ 4 · 1000
    EXPECT_EQ(tilePartsPerSide(126, 1000, 16, 4), 4);   // 126 · 32 > 4 · 1000
    EXPECT_EQ(tilePartsPerSide(1000, 1000, 16, 4), 4);  // a part never smaller than a quarter side
    EXPECT_EQ(tilePartsPerSide(1000, 1000, 16, 2), 2);  // capped by the tile size
    EXPECT_EQ(tilePartsPerSide(300, 1000, 2, 4), 2);    // 300 · 4 > 1000, ≤ 4 · 1000
}

// Every pixel a triangle covers lies in a tile the triangle was binned into, for tiles whose size is a
// power of two and tiles whose size is not.
TEST(Bin, EveryCoveredPixelIsInABinnedTile) {
    std::mt19937 rng(5);
    DrawState state;
    state.viewport = {0, 0, 300, 200};
    state.raster.cull = CullMode::None;
    std::uniform_real_distribution<float> coord(-100.0f, 400.0f);
    for (int trial = 0; trial < 600; ++trial) {
        const TileGrid grid = makeTileGrid(state.viewport, trial % 2 ? 24 : 32);
        WindowTriangle t;
        for (auto& v : t.vertices) {
            v.xFixed = static_cast<std::int64_t>(coord(rng) * kFixedOne);
            v.yFixed = static_cast<std::int64_t>(coord(rng) * kFixedOne);
        }
        TriangleSetup setup;
        if (setupTriangle(t, state, setup, nullptr) != TriangleFate::Drawn) continue;
        std::vector<std::vector<std::uint32_t>> bins(static_cast<std::size_t>(grid.count()));
        binTriangle(grid, setup, 0, bins);
        for (int tile = 0; tile < grid.count(); ++tile) {
            int covered = 0;
            rasterizeBlocks(setup, grid.tileRect(tile),
                            [&](const CoverageBlock& b) { covered += b.mask != 0; });
            if (covered) {
                EXPECT_EQ(bins[tile].size(), 1u) << "trial " << trial << " tile " << tile;
            }
        }
    }
}

// The image does not depend on the number of threads, the number the work is cut for (chunks of
// vertices and triangles) nor on the tile size: the same bytes.
TEST(Bin, SameBytesForAnyThreadCountAndTileSize) {
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-1.3f, 1.3f);
    std::vector<testing::ClipSpaceColorShader::Attributes> vertices;
    for (int i = 0; i < 3 * 2000; ++i) {
        // A mix of small triangles and a few large ones crossing many tiles and the frustum.
        const float size = i % 300 < 3 ? 1.0f : 0.05f;
        const vec2 centre(u(rng), u(rng));
        vertices.push_back({vec4(centre + size * vec2(u(rng), u(rng)), u(rng) * 0.9f, 1.0f),
                            vec4(u(rng), u(rng), u(rng), 0.5f)});
    }
    std::vector<std::uint32_t> indices(vertices.size());
    for (std::size_t i = 0; i < indices.size(); ++i)
        indices[i] = static_cast<std::uint32_t>(i);
    auto render = [&](int threads, int tileSize, BlendMode blend, int cutFor = 0) {
        Framebuffer fb(317, 211);
        fb.clearColor(vec4(0));
        DrawState state = testing::stateFor(fb);
        state.blend = blend;
        DrawContext context(threads, tileSize);
        context.cutForThreads = cutFor;
        draw<testing::ClipSpaceColorShader>(
            state, {}, std::span<const testing::ClipSpaceColorShader::Attributes>(vertices),
            std::span<const std::uint32_t>(indices), fb, context);
        return std::make_pair(fb.colorPixels(), fb.depthPixels());
    };
    for (BlendMode blend : {BlendMode::Replace, BlendMode::Over}) {
        const auto reference = render(1, 64, blend);
        for (auto [threads, tileSize] : {std::pair{2, 64}, {7, 64}, {1, 8}, {2, 16}, {7, 32}, {3, 1024}}) {
            const auto image = render(threads, tileSize, blend);
            EXPECT_TRUE(image.first == reference.first) << threads << " threads, tile " << tileSize;
            EXPECT_TRUE(image.second == reference.second) << threads << " threads, tile " << tileSize;
        }
        // 2,000 triangles of 6,000 vertices: one chunk of each on one thread, 6 and 8 cut for 7, 6 and 8
        // cut for 64 (the smallest chunks).
        // Cut for 5 and 64, the busiest of the 20 tiles are drawn in 4 or 16 parts (drawBatchTiles).
        for (auto [threads, cutFor] : {std::pair{1, 64}, {2, 5}, {3, 64}}) {
            const auto image = render(threads, 64, blend, cutFor);
            EXPECT_TRUE(image.first == reference.first) << threads << " threads cut for " << cutFor;
            EXPECT_TRUE(image.second == reference.second) << threads << " threads cut for " << cutFor;
        }
    }
}

// The back end of a draw cut for many threads draws its busiest tiles in parts, and whole on one thread.
// Breaks caught: drawBatchTiles ignoring the threads it is cut for (every tile whole), or cutting for one
// thread; a tile's parts not all handed out.
TEST(Bin, ADrawCutForManyThreadsDrawsItsBusiestTilesInParts) {
    Framebuffer fb(200, 130);  // 4 × 3 tiles of 64
    std::vector<testing::ClipSpaceColorShader::Attributes> vertices;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-0.9f, 0.9f);
    for (int t = 0; t < 300; ++t) {
        // Small triangles, a third of them around the centre: the tiles there hold far more than the rest.
        const vec2 centre = t % 3 == 0 ? 0.1f * vec2(u(rng), u(rng)) : vec2(u(rng), u(rng));
        for (int k = 0; k < 3; ++k)
            vertices.push_back({vec4(centre + 0.05f * vec2(u(rng), u(rng)), 0.0f, 1.0f), vec4(1.0f)});
    }
    std::vector<std::uint32_t> indices(vertices.size());
    for (std::size_t i = 0; i < indices.size(); ++i)
        indices[i] = static_cast<std::uint32_t>(i);
    for (const int cutFor : {1, 16}) {
        DrawContext context(1);
        context.cutForThreads = cutFor;
        fb.clearColor(vec4(0));
        const DrawStats stats = draw<testing::ClipSpaceColorShader>(
            testing::stateFor(fb), {}, std::span<const testing::ClipSpaceColorShader::Attributes>(vertices),
            std::span<const std::uint32_t>(indices), fb, context);
        std::size_t tilesCounted = 0;
        int widest = 1;
        for (const TilePart& part : context.tileParts) {
            tilesCounted += part.first;
            widest = std::max<int>(widest, part.side);
        }
        EXPECT_EQ(tilesCounted, stats.tilesDrawn) << "cut for " << cutFor;
        EXPECT_EQ(widest, cutFor == 1 ? 1 : 4) << "cut for " << cutFor;
        if (cutFor == 16) {
            EXPECT_GT(context.tileParts.size(), stats.tilesDrawn + 3 * 4);
        }
    }
}

// A draw of more triangles than one batch (kBatchTriangles: set up and binned, then
// drawn, before the next batch is set up) gives the bytes of the same triangles drawn as draws of one
// chunk each, which never span a batch. The triangles overlap and blend over each other, so an order
// changed, a triangle dropped or drawn twice shows. Breaks caught: a batch's end computed from one chunk
// instead of a batch's (triangles dropped), the last partial batch skipped.
TEST(Bin, ADrawOfSeveralBatchesMatchesItsTrianglesInChunkSizedDraws) {
    const std::size_t triangles = 2 * kBatchTriangles + 777;  // two batches and a part
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<testing::ClipSpaceColorShader::Attributes> vertices;
    for (std::size_t i = 0; i < 3 * triangles; ++i) {
        const vec2 centre(u(rng) * 0.8f, u(rng) * 0.8f);
        vertices.push_back({vec4(centre + 0.15f * vec2(u(rng), u(rng)), u(rng) * 0.9f, 1.0f),
                            vec4(0.5f + 0.5f * u(rng), 0.5f + 0.5f * u(rng), 0.5f + 0.5f * u(rng), 0.3f)});
    }
    std::vector<std::uint32_t> indices(vertices.size());
    for (std::size_t i = 0; i < indices.size(); ++i)
        indices[i] = static_cast<std::uint32_t>(i);
    const std::span<const testing::ClipSpaceColorShader::Attributes> allVertices(vertices);
    const std::span<const std::uint32_t> allIndices(indices);
    auto render = [&](std::size_t trianglesPerDraw) {
        Framebuffer fb(61, 47);
        fb.clearColor(vec4(0));
        DrawState state = testing::stateFor(fb);
        state.blend = BlendMode::Over;
        state.depth.testEnabled = false;  // every triangle blends: the order of all of them shows
        DrawContext context(2);
        for (std::size_t first = 0; first < triangles; first += trianglesPerDraw) {
            const std::size_t count = std::min(trianglesPerDraw, triangles - first);
            // Each triangle has its own three vertices (indices 0, 1, 2, …): a draw takes only its own.
            draw<testing::ClipSpaceColorShader>(state, {}, allVertices.subspan(3 * first, 3 * count),
                                                allIndices.first(3 * count), fb, context);
        }
        return fb.colorPixels();
    };
    EXPECT_TRUE(render(triangles) == render(kTriangleChunk));
}

// A context reused from a large draw for a small one: the small draw's image is the one a fresh context
// gives. The front end empties only the bins the last batch filled, and the back end visits only the
// tiles the chunks list. Breaks caught: a bin left holding the large draw's triangles, a tile binned but
// not listed (never drawn), or a grid of another tile count reusing the old bins.
TEST(Bin, AReusedContextDrawsOnlyTheNewDrawsTiles) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.2f, 1.2f);
    std::vector<testing::ClipSpaceColorShader::Attributes> many;
    for (int i = 0; i < 3 * 3000; ++i)
        many.push_back({vec4(u(rng), u(rng), 0.5f * u(rng), 1.0f), vec4(u(rng), u(rng), u(rng), 1.0f)});
    const std::vector<testing::ClipSpaceColorShader::Attributes> few = {
        {vec4(-0.9f, -0.9f, 0.0f, 1.0f), vec4(1, 0, 0, 1)},
        {vec4(0.9f, -0.5f, 0.0f, 1.0f), vec4(0, 1, 0, 1)},
        {vec4(0.1f, 0.9f, 0.0f, 1.0f), vec4(0, 0, 1, 1)}};
    auto drawInto = [](Framebuffer& fb, const std::vector<testing::ClipSpaceColorShader::Attributes>& v,
                       DrawContext& context) {
        std::vector<std::uint32_t> indices(v.size());
        for (std::size_t i = 0; i < indices.size(); ++i)
            indices[i] = static_cast<std::uint32_t>(i);
        DrawState state = testing::stateFor(fb);
        state.depth.testEnabled = false;  // the later draw covers the earlier one wherever it lies
        draw<testing::ClipSpaceColorShader>(state, {},
                                            std::span<const testing::ClipSpaceColorShader::Attributes>(v),
                                            std::span<const std::uint32_t>(indices), fb, context);
    };
    for (const int threads : {1, 2}) {
        DrawContext reused(threads, 16);
        Framebuffer large(203, 157), small(203, 157), alone(203, 157);
        for (Framebuffer* fb : {&large, &small, &alone})
            fb->clearColor(vec4(0));
        drawInto(large, many, reused);
        drawInto(small, few, reused);
        drawInto(small, few, reused);  // twice: the second draw's bins hold only its own triangle
        DrawContext fresh(threads, 16);
        drawInto(alone, few, fresh);
        EXPECT_TRUE(small.colorPixels() == alone.colorPixels()) << threads << " threads";
        // A framebuffer of another size: a grid of another tile count, the same context.
        Framebuffer other(64, 48), otherAlone(64, 48);
        other.clearColor(vec4(0));
        otherAlone.clearColor(vec4(0));
        drawInto(other, few, reused);
        DrawContext fresh2(threads, 16);
        drawInto(otherAlone, few, fresh2);
        EXPECT_TRUE(other.colorPixels() == otherAlone.colorPixels()) << threads << " threads";
    }
}

}  // namespace
}  // namespace facet
