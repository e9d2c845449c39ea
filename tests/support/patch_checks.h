// Checks of the patch walk (rasterize.h: patchCoverage; interpolate.h: barycentricLanes) for a lane
// type I, shared by the pipeline tests (eight lanes) and the AVX-512 test binary (sixteen).
#pragma once

#include <bit>
#include <cstdint>
#include <random>

#include <gtest/gtest.h>

#include "interpolate.h"
#include "rasterize.h"
#include "triangle_setup.h"

namespace facet::testing_support {

// A triangle of a few pixels is walked as one patch (4 columns by 2 rows of lanes, or 4 by 4 with
// sixteen): its coverage must be the per-pixel test's inside the rectangle, its unbiased edge values
// E₁, E₂ the exact ones, and its barycentrics the bits the block walk gives the same pixels, at any
// placement of the patch over the triangle's pixels and for rectangles that cut them (the triangle's
// part of a tile).
// Breaks caught: the fill rule's bias left out (a pixel on a right or bottom edge covered by both
// neighbouring triangles), columns and rows swapped in the lanes, a rectangle bound off by one, E
// rounded to float before it is divided by the area.
inline WindowVertex patchTestVertex(std::int64_t xFixed, std::int64_t yFixed) {
    WindowVertex v;
    v.xFixed = xFixed;
    v.yFixed = yFixed;
    v.invW = 1.0f;
    return v;
}

template <class I>
void expectPatchCoverageMatchesTheOracle() {
    constexpr int kRows = kPatchRows<I>;
    std::mt19937 rng(20261207);
    const int width = 40, height = 30;
    DrawState state;
    state.viewport = {0, 0, width, height};
    state.raster.cull = CullMode::None;
    int checked = 0, coveredSeen = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        const float scale = (0.5f + 4.0f * static_cast<float>(rng() % 1000) / 1000.0f) * kFixedOne;
        std::uniform_real_distribution<float> offset(-0.5f * scale, 0.5f * scale);
        std::uniform_real_distribution<float> centreX(4 * kFixedOne, (width - 4) * kFixedOne),
            centreY(4 * kFixedOne, (height - 4) * kFixedOne);
        const float cx = centreX(rng), cy = centreY(rng);
        WindowTriangle t;
        for (auto& v : t.vertices)
            v = patchTestVertex(static_cast<std::int64_t>(cx + offset(rng)),
                                static_cast<std::int64_t>(cy + offset(rng)));
        TriangleSetup setup;
        if (setupTriangle(t, state, setup, nullptr) != TriangleFate::Drawn || !fitsPatch(setup, kRows))
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
        const int x = rect.maxX - (kPatchColumns - 1) +
                      static_cast<int>(rng() % (kPatchColumns - (rect.maxX - rect.minX)));
        const int y = rect.maxY - (kRows - 1) + static_cast<int>(rng() % (kRows - (rect.maxY - rect.minY)));
        I e1, e2;
        const unsigned mask = patchCoverage(setup, x, y, rect, e1, e2);
        const double inverse = 1.0 / static_cast<double>(setup.doubleArea);
        const auto b1 = barycentricLanes(e1, inverse), b2 = barycentricLanes(e2, inverse);
        const BlockBarycentrics block(setup, x, y);  // a block placed where the patch is
        ++checked;
        for (int lane = 0; lane < kPatchColumns * kRows; ++lane) {
            const int px = x + lane % kPatchColumns, py = y + lane / kPatchColumns;
            const bool inRect = px >= rect.minX && px <= rect.maxX && py >= rect.minY && py <= rect.maxY;
            const bool expected = inRect && coversSample(setup, px, py);
            coveredSeen += expected;
            ASSERT_EQ((mask >> lane) & 1u, expected ? 1u : 0u)
                << "trial " << trial << " pixel " << px << "," << py;
            const SamplePoint p = samplePosition(px, py);
            ASSERT_EQ(e1[lane], setup.edges[1].at(p.x, p.y)) << "trial " << trial << " lane " << lane;
            ASSERT_EQ(e2[lane], setup.edges[2].at(p.x, p.y)) << "trial " << trial << " lane " << lane;
            Float8 blockB1, blockB2;
            block.row(lane / kPatchColumns, blockB1, blockB2);
            ASSERT_EQ(std::bit_cast<std::uint32_t>(b1[lane]),
                      std::bit_cast<std::uint32_t>(blockB1[lane % kPatchColumns]))
                << "trial " << trial << " lane " << lane;
            ASSERT_EQ(std::bit_cast<std::uint32_t>(b2[lane]),
                      std::bit_cast<std::uint32_t>(blockB2[lane % kPatchColumns]))
                << "trial " << trial << " lane " << lane;
        }
    }
    EXPECT_GT(checked, 3000);
    EXPECT_GT(coveredSeen, 4000);
}

}  // namespace facet::testing_support
