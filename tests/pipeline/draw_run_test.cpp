// drawRun: consecutive small draws drawn in runs, each run's back end sharing a job with the next run's
// front ends, must give the bytes and counters of the same draws drawn one by one with draw().
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "../support/test_shaders.h"
#include "draw_run.h"

namespace facet {
namespace {

using testing::FlatColorShader;

struct RandomDraw {
    DrawState state;
    FlatColorShader::Uniforms uniforms;
    std::vector<FlatColorShader::Attributes> vertices;
    std::vector<std::uint32_t> indices;
};

// Draws of a few overlapping triangles each, with states that differ from draw to draw: blending,
// depth test and write, the comparison, culling, and the uniforms (flat or smooth colour), so that a
// draw drawn out of order, skipped in a tile, or with another draw's plan or uniforms changes bytes.
std::vector<RandomDraw> randomDraws(const Framebuffer& fb, int count, std::mt19937& rng) {
    std::uniform_real_distribution<float> x(-20.0f, static_cast<float>(fb.width()) + 20.0f),
        y(-20.0f, static_cast<float>(fb.height()) + 20.0f), unit(0.0f, 1.0f), z(-0.9f, 0.9f);
    const BlendMode blends[] = {BlendMode::Replace, BlendMode::Over, BlendMode::Additive,
                                BlendMode::PremultipliedOver};
    const CompareOp compares[] = {CompareOp::Less, CompareOp::LessEqual, CompareOp::Greater};
    std::vector<RandomDraw> draws(static_cast<std::size_t>(count));
    for (RandomDraw& d : draws) {
        d.state = testing::stateFor(fb);
        d.state.blend = blends[rng() % 4];
        d.state.depth.testEnabled = rng() % 4 != 0;
        d.state.depth.writeEnabled = rng() % 3 != 0;
        d.state.depth.compare = compares[rng() % 3];
        d.state.raster.cull = rng() % 3 == 0 ? CullMode::Back : CullMode::None;
        d.uniforms.showSmooth = rng() % 2 == 0;
        const int triangles = 1 + static_cast<int>(rng() % 6);
        for (int t = 0; t < triangles; ++t) {
            // Some small (a few pixels), some across much of the framebuffer.
            const float size = rng() % 2 ? 6.0f : 60.0f;
            const vec2 centre(x(rng), y(rng));
            for (int k = 0; k < 3; ++k) {
                const vec2 p = centre + size * vec2(unit(rng) - 0.5f, unit(rng) - 0.5f);
                d.indices.push_back(static_cast<std::uint32_t>(d.vertices.size()));
                d.vertices.push_back({testing::clipFromWindow(p, fb, z(rng)),
                                      vec4(unit(rng), unit(rng), unit(rng), unit(rng))});
            }
        }
    }
    return draws;
}

std::vector<RunDraw<FlatColorShader>> asRun(const std::vector<RandomDraw>& draws) {
    std::vector<RunDraw<FlatColorShader>> run;
    for (const RandomDraw& d : draws)
        run.push_back({&d.state, &d.uniforms, d.vertices, d.indices});
    return run;
}

bool sameBytes(const Framebuffer& a, const Framebuffer& b) {
    if (std::memcmp(a.colorPixels().data(), b.colorPixels().data(), a.colorPixels().size() * sizeof(vec4)))
        return false;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            if (const float da = a.depth(x, y), db = b.depth(x, y); std::memcmp(&da, &db, sizeof da))
                return false;
    return true;
}

// Breaks caught: the back end drawing a tile's draws in another order than the run's, skipping a draw
// in a tile it touches (or in a part of a tile its triangles reach), runs not cut for many threads, drawing
// every draw with the first one's plan or uniforms, or a front end writing another draw's chunk; with more
// draws than one run takes (every other trial), a run's tiles drawn before its front ends have run, or the
// last run's not at all; counters summed wrongly. Not caught for certain: the run being drawn and the run
// being set up sharing a slot (a race between the threads, which shows only when they overlap on one draw).
TEST(DrawRun, GivesTheBytesAndCountersOfItsDrawsOneByOne) {
    std::mt19937 rng(1201);
    for (int trial = 0; trial < 6; ++trial) {
        Framebuffer one(150, 90), run(150, 90);
        const int drawCount = trial % 2 == 0 ? 40 : static_cast<int>(2 * runCallsFor(6, 1) + 30);
        const std::vector<RandomDraw> draws = randomDraws(one, drawCount, rng);
        DrawContext sequential(1);
        one.clear(vec4(0.1f, 0.2f, 0.3f, 1.0f), DepthFormat::kClear, sequential.pool);
        DrawStats expected;
        for (const RandomDraw& d : draws)
            expected += draw<FlatColorShader>(d.state, d.uniforms, std::span(d.vertices),
                                              std::span(d.indices), one, sequential);
        ASSERT_GT(expected.fragmentsWritten, 1000u);
        struct Setting {
            int threads, tileSize, cutFor;
        };
        // Cut for 6 or 16 threads, a run's busiest tiles are drawn in parts (cutRunTiles).
        for (const auto& [threads, tileSize, cutFor] : {Setting{1, kDefaultTileSize, 0},
                                                        {2, kDefaultTileSize, 0},
                                                        {2, 16, 0},
                                                        {2, kDefaultTileSize, 6},
                                                        {1, kDefaultTileSize, 16},
                                                        {2, kDefaultTileSize, 16}}) {
            SCOPED_TRACE(::testing::Message() << "trial " << trial << ", " << threads << " threads, tiles of "
                                              << tileSize << ", cut for " << cutFor);
            DrawContext context(threads, tileSize);
            context.cutForThreads = cutFor;
            run.clear(vec4(0.1f, 0.2f, 0.3f, 1.0f), DepthFormat::kClear, context.pool);
            const std::vector<RunDraw<FlatColorShader>> calls = asRun(draws);
            std::size_t runs = 0;
            const DrawStats stats = drawRun<FlatColorShader>(calls, run, context, &runs);
            const int tiles = makeTileGrid(draws.front().state.viewport, tileSize).count();
            const std::size_t runCalls = runCallsFor(cutFor > 0 ? cutFor : threads, tiles);  // 64; 192 for 6
            EXPECT_EQ(runs, (draws.size() + runCalls - 1) / runCalls);  // a few triangles each
            EXPECT_TRUE(sameBytes(one, run));
            EXPECT_EQ(stats.vertices, expected.vertices);
            EXPECT_EQ(stats.trianglesRasterized, expected.trianglesRasterized);
            EXPECT_EQ(stats.trianglesCulled, expected.trianglesCulled);
            EXPECT_EQ(stats.fragmentsShaded, expected.fragmentsShaded);
            EXPECT_EQ(stats.fragmentsDepthFailed, expected.fragmentsDepthFailed);
            EXPECT_EQ(stats.fragmentsWritten, expected.fragmentsWritten);
            if (tileSize == kDefaultTileSize) {
                EXPECT_EQ(stats.tilesDrawn, expected.tilesDrawn);
            }
            EXPECT_EQ(context.drawsStarted, draws.size());
            // The last run's items: tiles whole on one thread, the busiest in parts when cut for many.
            int widest = 1;
            for (const TilePart& part : context.tileParts)
                widest = std::max<int>(widest, part.side);
            if (cutFor == 16) {
                EXPECT_EQ(widest, 4);
            }
            if (threads == 1 && cutFor == 0) {
                EXPECT_EQ(widest, 1);
            }
        }
    }
}

// A draw too big for a run, or one with another viewport, is refused before anything is drawn.
TEST(DrawRun, RefusesADrawTooBigOrWithAnotherViewportAndDrawsNothing) {
    std::mt19937 rng(7);
    Framebuffer fb(64, 48), untouched(64, 48);
    std::vector<RandomDraw> draws = randomDraws(fb, 3, rng);
    DrawContext context(2);
    fb.clear(vec4(0.0f), DepthFormat::kClear, context.pool);
    untouched.clear(vec4(0.0f), DepthFormat::kClear, context.pool);

    draws[2].state.viewport.width = 32;
    EXPECT_THROW(drawRun<FlatColorShader>(asRun(draws), fb, context), std::invalid_argument);
    EXPECT_TRUE(sameBytes(fb, untouched));

    draws[2].state.viewport = draws[0].state.viewport;
    draws[1].indices.assign(3 * (kTriangleChunk + 1), 0u);
    EXPECT_THROW(drawRun<FlatColorShader>(asRun(draws), fb, context), std::invalid_argument);
    EXPECT_TRUE(sameBytes(fb, untouched));
    EXPECT_FALSE(fitsInRun(3, 3 * (kTriangleChunk + 1)));
    EXPECT_FALSE(fitsInRun(kVertexChunk + 1, 3));
    EXPECT_TRUE(fitsInRun(kVertexChunk, 3 * kTriangleChunk));
}

// Breaks caught: runs that do not grow with the threads, grow on one or two threads, outgrow the memory
// their tables of bins may take on a large image, or shrink below 64 draws on a huge one.
TEST(DrawRun, RunsGrowWithTheThreadsWithinTheirMemory) {
    constexpr int k1080pTiles = 30 * 17, k4kTiles = 60 * 34, k8kTiles = 120 * 68;  // tiles of 64
    EXPECT_EQ(runCallsFor(1, k1080pTiles), kMaxRunCalls);
    EXPECT_EQ(runCallsFor(2, k1080pTiles), kMaxRunCalls);
    EXPECT_EQ(runCallsFor(16, k1080pTiles), 8 * kMaxRunCalls);
    const std::size_t at4k = runCallsFor(16, k4kTiles);
    EXPECT_LT(at4k, 8 * kMaxRunCalls);
    EXPECT_LE(2 * at4k * k4kTiles * sizeof(std::vector<std::uint32_t>), kRunBinTablesBytes);
    EXPECT_GT(2 * (at4k + 1) * k4kTiles * sizeof(std::vector<std::uint32_t>), kRunBinTablesBytes);
    EXPECT_EQ(runCallsFor(16, k8kTiles), kMaxRunCalls);
}

}  // namespace
}  // namespace facet
