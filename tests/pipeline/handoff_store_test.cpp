// Streamed stores (handoff_store.h): what the front end hands other threads must hold the bytes plain
// stores would, whether it was streamed or not.
#include "handoff_store.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "../support/test_shaders.h"
#include "front_end.h"
#include "pipeline.h"

namespace facet {
namespace {

// Field by field: a set-up's padding bytes hold whatever its copy left there.
bool sameSetup(const TriangleSetup& a, const TriangleSetup& b) {
    for (int i = 0; i < 3; ++i)
        if (a.edges[i].a != b.edges[i].a || a.edges[i].b != b.edges[i].b || a.edges[i].c != b.edges[i].c ||
            a.edges[i].bias != b.edges[i].bias)
            return false;
    const auto bits = [](float f) { return std::bit_cast<std::uint32_t>(f); };
    return a.doubleArea == b.doubleArea && a.frontFacing == b.frontFacing && a.perspective == b.perspective &&
           a.minX == b.minX && a.minY == b.minY && a.maxX == b.maxX && a.maxY == b.maxY &&
           a.triangle == b.triangle && bits(a.z0) == bits(b.z0) && bits(a.dz1) == bits(b.dz1) &&
           bits(a.dz2) == bits(b.dz2) && bits(a.invW0) == bits(b.invW0) && bits(a.dInvW1) == bits(b.dInvW1) &&
           bits(a.dInvW2) == bits(b.dInvW2) && a.varyingCount == b.varyingCount &&
           a.flatVaryingCount == b.flatVaryingCount && a.varyingPlaneOffset == b.varyingPlaneOffset;
}

// Breaks caught: a streamed copy of too few words (a loop bound of bytes/8) or past the end (≤).
TEST(HandoffStore, AStreamedCopyWritesEveryByteAndNoMore) {
    TriangleSetup setup;
    unsigned char pattern[sizeof setup];
    for (std::size_t i = 0; i < sizeof pattern; ++i)
        pattern[i] = static_cast<unsigned char>(i * 7 + 1);
    std::memcpy(&setup, pattern, sizeof setup);

    // Room for two, filled with a marker: the copy goes into the first.
    alignas(TriangleSetup) unsigned char room[2 * sizeof(TriangleSetup)];
    std::memset(room, 0xab, sizeof room);
    copyStreamed(room, &setup, sizeof setup);
    finishStreamedStores();
    EXPECT_EQ(std::memcmp(room, pattern, sizeof pattern), 0);
    for (std::size_t i = sizeof setup; i < sizeof room; ++i)
        ASSERT_EQ(room[i], 0xab) << "byte " << i << " past the copy";

    // One value in place.
    TriangleSetup stored;
    storeMaybeStreamed(stored, setup, true);
    finishStreamedStores();
    EXPECT_EQ(std::memcmp(&stored, pattern, sizeof pattern), 0);
}

// Breaks caught: a streamed append that does not grow the vector, overwrites its last elements, or
// copies fewer values than asked (an odd count of floats, as planes of a varying count of 7 are).
TEST(HandoffStore, StreamedAndPlainAppendsGiveTheSameVector) {
    std::vector<float> values(21);
    for (std::size_t i = 0; i < values.size(); ++i)
        values[i] = 0.5f * static_cast<float>(i) - 3.0f;
    UnfilledVector<float> streamed, plain;
    for (int round = 0; round < 3; ++round) {
        appendMaybeStreamed(streamed, values.data(), values.size(), true);
        appendMaybeStreamed(plain, values.data(), values.size(), false);
    }
    finishStreamedStores();
    ASSERT_EQ(streamed.size(), 3 * values.size());
    EXPECT_TRUE(std::equal(streamed.begin(), streamed.end(), plain.begin(), plain.end()));
}

// The front end with more threads than one streams its vertices' varyings and window positions and
// its set-ups and planes; with one it stores them plainly. A mesh of several vertex chunks and
// triangle chunks (some triangles clipped, some culled) must give the same chunks either way.
// Breaks caught: a streamed window position or varying stored for another vertex or cut short, a
// set-up or its planes appended streamed at the wrong place or not at all, binning of a streamed
// set-up reading what was not written yet.
TEST(HandoffStore, TheFrontEndOnSeveralThreadsHandsOnWhatOneThreadDoes) {
    using testing::FlatColorShader;
    Framebuffer fb(300, 200);
    DrawState state = testing::stateFor(fb);
    state.raster.cull = CullMode::Back;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> x(-40.0f, 340.0f), y(-40.0f, 240.0f), unit(0.0f, 1.0f),
        z(-1.2f, 1.2f);
    const std::size_t triangles = kVertexChunk / 3 * 2 + 100;  // three vertex chunks, many set-up chunks
    std::vector<FlatColorShader::Attributes> vertices;
    std::vector<std::uint32_t> indices;
    for (std::size_t t = 0; t < triangles; ++t) {
        const vec2 centre(x(rng), y(rng));
        for (int k = 0; k < 3; ++k) {
            const vec2 p = centre + 12.0f * vec2(unit(rng) - 0.5f, unit(rng) - 0.5f);
            indices.push_back(static_cast<std::uint32_t>(vertices.size()));
            vertices.push_back(
                {testing::clipFromWindow(p, fb, z(rng)), vec4(unit(rng), unit(rng), unit(rng), 1)});
        }
    }
    const FlatColorShader::Uniforms uniforms;
    const TileGrid grid = makeTileGrid(state.viewport, kDefaultTileSize);

    struct FrontEnd {
        ShadedVertices shaded;
        std::vector<WindowVertex> window;
        std::vector<SetupChunk> chunks;
        std::size_t chunkCount = 0;
    };
    const auto run = [&](int threads) {
        ThreadPool pool(threads);
        NullObserver observer;
        FrontEnd out;
        runVertexStage<FlatColorShader>(vertices, uniforms, state, pool, false, kVertexChunk, out.shaded,
                                        out.window, observer);
        out.chunkCount = setupBatch(std::span<const std::uint32_t>(indices), 0, triangles, kTriangleChunk,
                                    state, grid, out.shaded, out.window, flatVaryingFloats<FlatColorShader>(),
                                    pool, false, out.chunks, observer);
        return out;
    };
    const FrontEnd one = run(1);
    for (int threads : {2, 3}) {
        const FrontEnd several = run(threads);
        ASSERT_EQ(several.shaded.varyings, one.shaded.varyings) << threads << " threads";
        for (std::size_t v = 0; v < vertices.size(); ++v) {
            if (one.shaded.outcodes[v] != 0) continue;  // clipped: its window position is never read
            ASSERT_EQ(std::memcmp(&several.window[v], &one.window[v], sizeof(WindowVertex)), 0)
                << "vertex " << v;
        }
        ASSERT_EQ(several.chunkCount, one.chunkCount);
        ASSERT_GT(one.chunkCount, 2u);
        for (std::size_t c = 0; c < one.chunkCount; ++c) {
            const SetupChunk &a = one.chunks[c], &b = several.chunks[c];
            ASSERT_EQ(b.setups.size(), a.setups.size()) << "chunk " << c;
            ASSERT_GT(a.setups.size(), 0u);
            for (std::size_t i = 0; i < a.setups.size(); ++i)
                ASSERT_TRUE(sameSetup(b.setups[i], a.setups[i])) << "chunk " << c << ", set-up " << i;
            EXPECT_TRUE(std::equal(a.varyingPlanes.begin(), a.varyingPlanes.end(), b.varyingPlanes.begin(),
                                   b.varyingPlanes.end()))
                << "chunk " << c;
            EXPECT_EQ(b.bins, a.bins) << "chunk " << c;
            EXPECT_EQ(b.stats.trianglesRasterized, a.stats.trianglesRasterized);
            EXPECT_EQ(b.stats.trianglesClipped, a.stats.trianglesClipped);
        }
    }
}

}  // namespace
}  // namespace facet
