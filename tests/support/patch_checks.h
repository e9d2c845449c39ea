// Checks of the patch walk (rasterize.h: patchCoverage; interpolate.h: barycentricLanes) for a lane
// type I, shared by the pipeline tests (eight lanes) and the AVX-512 test binary (sixteen).
#pragma once

#include <bit>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "interpolate.h"
#include "pipeline.h"
#include "rasterize.h"
#include "test_shaders.h"
#include "triangle_setup.h"

namespace facet::testing_support {

// A window vertex at fixed-point (xFixed, yFixed), 1/w = 1.
inline WindowVertex fixedAt(std::int64_t xFixed, std::int64_t yFixed) {
    WindowVertex v;
    v.xFixed = xFixed;
    v.yFixed = yFixed;
    v.invW = 1.0f;
    return v;
}

// A triangle of a few pixels is walked as one patch kColumns wide (4 or 8 columns by 2 or 1 rows of
// eight lanes, by 4 or 2 rows of sixteen): its coverage must be the per-pixel test's inside the rectangle,
// its unbiased edge values E₁, E₂ the exact ones, and its barycentrics the bits the block walk gives the same
// pixels, at any placement of the patch over the triangle's pixels and for rectangles that cut them (the
// triangle's part of a tile). Breaks caught: the fill rule's bias left out (a pixel on a right or bottom edge
// covered by both neighbouring triangles), columns and rows swapped in the lanes, a rectangle bound off by
// one, E rounded to float before it is divided by the area.
template <class I, int kColumns>
void expectPatchCoverageMatchesTheOracle() {
    constexpr int kRows = kPatchRows<I, kColumns>;
    std::mt19937 rng(20261207);
    const int width = 40, height = 30;
    DrawState state;
    state.viewport = {0, 0, width, height};
    state.raster.cull = CullMode::None;
    int checked = 0, coveredSeen = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        // Spread over about the patch's width and height, so that many fit it and some do not.
        const float scaleX = (0.5f + kColumns * static_cast<float>(rng() % 1000) / 1000.0f) * kFixedOne;
        const float scaleY = (0.5f + kRows * static_cast<float>(rng() % 1000) / 1000.0f) * kFixedOne;
        std::uniform_real_distribution<float> offsetX(-0.5f * scaleX, 0.5f * scaleX),
            offsetY(-0.5f * scaleY, 0.5f * scaleY);
        std::uniform_real_distribution<float> centreX(4 * kFixedOne, (width - 4) * kFixedOne),
            centreY(4 * kFixedOne, (height - 4) * kFixedOne);
        const float cx = centreX(rng), cy = centreY(rng);
        WindowTriangle t;
        for (auto& v : t.vertices)
            v = fixedAt(static_cast<std::int64_t>(cx + offsetX(rng)),
                        static_cast<std::int64_t>(cy + offsetY(rng)));
        TriangleSetup setup;
        if (setupTriangle(t, state, setup, nullptr) != TriangleFate::Drawn ||
            !fitsPatch(setup, kColumns, kRows))
            continue;
        // A tile that holds the triangle, or cuts it on a random side.
        PixelRect area{0, 0, width - 1, height - 1};
        if (trial % 2) {
            area.minX = setup.minX + static_cast<int>(rng() % 3) - 1;
            area.maxY = setup.maxY - static_cast<int>(rng() % 3) + 1;
        }
        const PixelRect rect = rasterRect(setup, area);
        if (rect.empty()) continue;
        // Any placement of the patch over the rectangle's pixels.
        const int x =
            rect.maxX - (kColumns - 1) + static_cast<int>(rng() % (kColumns - (rect.maxX - rect.minX)));
        const int y = rect.maxY - (kRows - 1) + static_cast<int>(rng() % (kRows - (rect.maxY - rect.minY)));
        I e1, e2;
        const unsigned mask = patchCoverage<I, kColumns>(setup, x, y, rect, e1, e2);
        const double inverse = 1.0 / static_cast<double>(setup.doubleArea);
        const auto b1 = barycentricLanes(e1, inverse), b2 = barycentricLanes(e2, inverse);
        const BlockBarycentrics block(setup, x, y);  // a block placed where the patch is
        ++checked;
        for (int lane = 0; lane < kColumns * kRows; ++lane) {
            const int px = x + lane % kColumns, py = y + lane / kColumns;
            const bool inRect = px >= rect.minX && px <= rect.maxX && py >= rect.minY && py <= rect.maxY;
            const bool expected = inRect && coversSample(setup, px, py);
            coveredSeen += expected;
            ASSERT_EQ((mask >> lane) & 1u, expected ? 1u : 0u)
                << "trial " << trial << " pixel " << px << "," << py;
            const SamplePoint p = samplePosition(px, py);
            ASSERT_EQ(e1[lane], setup.edges[1].at(p.x, p.y)) << "trial " << trial << " lane " << lane;
            ASSERT_EQ(e2[lane], setup.edges[2].at(p.x, p.y)) << "trial " << trial << " lane " << lane;
            Float8 blockB1, blockB2;
            block.row(lane / kColumns, blockB1, blockB2);
            ASSERT_EQ(std::bit_cast<std::uint32_t>(b1[lane]),
                      std::bit_cast<std::uint32_t>(blockB1[lane % kColumns]))
                << "trial " << trial << " lane " << lane;
            ASSERT_EQ(std::bit_cast<std::uint32_t>(b2[lane]),
                      std::bit_cast<std::uint32_t>(blockB2[lane % kColumns]))
                << "trial " << trial << " lane " << lane;
        }
    }
    EXPECT_GT(checked, 3000);
    EXPECT_GT(coveredSeen, 4000);
}

// Any observer makes a draw watched, and a watched draw walks blocks only.
struct WatchingObserver : NullObserver {
    static constexpr bool enabled = true;
};

// A triangle of a few pixels is drawn as a stack of patches (back_end.h: drawAsPatches: 4×4 or 8×2
// pixels in the AVX-512 build, 4×2 or 8×1 elsewhere) when unwatched, and block by block when watched, so
// the two must give the same bytes: overlapping tiny triangles, a third of them flat strips wider than a
// narrow patch, drawn with the depth test and replaced colours, by a shader that discards, then blended
// additively (whose float sums depend on the order each pixel's fragments arrive in), on one thread and
// on three. Breaks caught: the queue not shaded before a patch whose pixel holds a queued fragment (a
// pixel's fragments blended out of order), a patch's second half left out of the depth test or its depth
// write, a wide patch's row stored as a narrow one's two half rows, the patch placed outside the tile, the
// second patch of a stack left out.
inline void expectPatchWalkDrawsTheBlockWalksBytes() {
    using testing::ClipSpaceColorShader;
    using testing::RedDiscardingShader;
    std::mt19937 rng(99);
    Framebuffer probe(40, 30);
    std::uniform_real_distribution<float> centreX(2.0f, 38.0f), centreY(2.0f, 28.0f), spread(-2.0f, 2.0f),
        depth(-0.9f, 0.9f), channel(0.0f, 1.0f);
    std::vector<ClipSpaceColorShader::Attributes> v;
    for (int t = 0; t < 600; ++t) {
        // Half of them piled on a 6×6 square, so that pixels see many fragments; each slanted in depth.
        const vec2 centre = t % 2 ? vec2(centreX(rng), centreY(rng))
                                  : vec2(17.0f, 13.0f) + 0.5f * vec2(spread(rng), spread(rng));
        const float z = depth(rng);
        const vec4 color(channel(rng), channel(rng), channel(rng), 1.0f);
        for (int k = 0; k < 3; ++k) {
            // Every third triangle five to eight pixels wide and one or two rows tall: its vertices 3
            // pixels apart along x.
            const bool wide = t % 3 == 0;
            const vec2 offset =
                wide ? vec2(3.0f * static_cast<float>(k - 1) + 0.4f * spread(rng), 0.3f * spread(rng))
                     : vec2(spread(rng), 1.8f * spread(rng));
            v.push_back({testing::clipFromWindow(centre + offset, probe, z + 0.02f * spread(rng)), color});
        }
    }
    std::vector<std::uint32_t> indices(v.size());
    for (std::size_t i = 0; i < indices.size(); ++i)
        indices[i] = static_cast<std::uint32_t>(i);
    const std::span<const ClipSpaceColorShader::Attributes> vertices(v);
    for (const DepthBufferFormat depthFormat : {DepthBufferFormat::Float, DepthBufferFormat::Unorm16,
                                                DepthBufferFormat::Unorm24, DepthBufferFormat::ReversedFloat})
        for (const int threads : {1, 3}) {
            SCOPED_TRACE(::testing::Message() << "depth format " << static_cast<int>(depthFormat) << ", "
                                              << threads << " threads");
            Framebuffer plain(40, 30), watched(40, 30);
            DrawContext plainContext(threads, 16), watchedContext(1, 16);
            for (Framebuffer* fb : {&plain, &watched})
                fb->clear(vec4(0.0f), depthClearValue(depthFormat), plainContext.pool);
            DrawState state = testing::stateFor(plain);
            state.raster.cull = CullMode::None;
            state.depth.format = depthFormat;
            state.depth.compare = nearerPasses(depthFormat, CompareOp::Less);
            WatchingObserver observer;
            std::uint64_t patchWalks = 0;
            auto drawBothWays = [&]<class S>(S) {
                const DrawStats plainStats = draw<S>(state, {}, vertices, indices, plain, plainContext);
                const DrawStats watchedStats =
                    draw<S>(state, {}, vertices, indices, watched, watchedContext, observer);
                EXPECT_EQ(plainStats.fragmentsShaded, watchedStats.fragmentsShaded);
                EXPECT_EQ(plainStats.fragmentsDepthFailed, watchedStats.fragmentsDepthFailed);
                EXPECT_EQ(watchedStats.patchWalks, 0u);
                patchWalks += plainStats.patchWalks;
            };
            // A shader that may discard writes depth when shaded, not when tested: a pixel's next
            // fragment must not be tested before its queued one is shaded.
            drawBothWays(RedDiscardingShader{});
            state.depth.compare = nearerPasses(depthFormat, CompareOp::LessEqual);
            drawBothWays(ClipSpaceColorShader{});
            state.blend = BlendMode::Additive;
            state.depth.testEnabled = false;
            drawBothWays(ClipSpaceColorShader{});
            EXPECT_GT(patchWalks, 300u) << "the tiny triangles were not walked as patches";
            EXPECT_EQ(plain.colorPixels(), watched.colorPixels());
            EXPECT_EQ(plain.depthPixels(), watched.depthPixels());
        }
}

}  // namespace facet::testing_support
