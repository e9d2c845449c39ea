#include "rasterize.h"

#include <bit>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "../support/patch_checks.h"
#include "triangle_setup.h"

namespace facet {
namespace {

using testing_support::fixedAt;

// Where a block may start along one axis: at a multiple of 8, or, when the triangle's pixels in the
// area span at most a block along it, anywhere a whole block stays inside the area.
void expectBlockStart(int start, int pixelsMin, int pixelsMax, int areaMin, int areaMax) {
    if (pixelsMax - pixelsMin < kBlockSize && areaMax - areaMin + 1 >= kBlockSize) {
        EXPECT_LE(start, pixelsMin);
        EXPECT_GE(start + kBlockSize - 1, pixelsMax);
        EXPECT_GE(start, areaMin);
        EXPECT_LE(start + kBlockSize - 1, areaMax);
    } else {
        EXPECT_EQ(start % kBlockSize, 0);
    }
}

// Walks `rect` block by block and counts how often each pixel is reported covered.
std::vector<int> walk(const TriangleSetup& setup, const PixelRect& rect, int width, int height) {
    std::vector<int> covered(static_cast<std::size_t>(width) * height, 0);
    const PixelRect pixels = rasterRect(setup, rect);
    rasterizeBlocks(setup, rect, [&](const CoverageBlock& b) {
        expectBlockStart(b.x, pixels.minX, pixels.maxX, rect.minX, rect.maxX);
        expectBlockStart(b.y, pixels.minY, pixels.maxY, rect.minY, rect.maxY);
        EXPECT_NE(b.mask, 0u);
        for (int bit = 0; bit < 64; ++bit) {
            if (!((b.mask >> bit) & 1)) continue;
            const int x = b.x + bit % kBlockSize, y = b.y + bit / kBlockSize;
            EXPECT_TRUE(x >= rect.minX && x <= rect.maxX && y >= rect.minY && y <= rect.maxY)
                << x << "," << y;
            if (x >= 0 && x < width && y >= 0 && y < height)
                ++covered[static_cast<std::size_t>(y) * width + x];
        }
        if (b.fullyCovered) {
            // Trivially accepted: every sample of the block really is inside.
            for (int bit = 0; bit < 64; ++bit) {
                if ((b.mask >> bit) & 1) {
                    EXPECT_TRUE(coversSample(setup, b.x + bit % kBlockSize, b.y + bit / kBlockSize));
                }
            }
        }
    });
    return covered;
}

// The block walk, with its trivial accept and reject, must report exactly the pixels the plain
// per-pixel test covers inside the bounds, each once, for random triangles of every size and for
// random sub-rectangles (tiles).
TEST(Rasterize, BlockWalkMatchesPerPixelOracleOnRandomTriangles) {
    std::mt19937 rng(20261124);
    const int width = 83, height = 61;
    DrawState state;
    state.viewport = {0, 0, width, height};
    state.raster.cull = CullMode::None;
    int trianglesChecked = 0, fullBlocksSeen = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        // Sizes from a pixel to several times the viewport.
        const float scale = std::ldexp(1.0f, static_cast<int>(rng() % 9)) * kFixedOne;
        std::uniform_real_distribution<float> offset(-0.5f * scale, 0.5f * scale);
        std::uniform_real_distribution<float> centreX(0, width * kFixedOne), centreY(0, height * kFixedOne);
        const float cx = centreX(rng), cy = centreY(rng);
        WindowTriangle t;
        for (auto& v : t.vertices)
            v = fixedAt(static_cast<std::int64_t>(cx + offset(rng)),
                        static_cast<std::int64_t>(cy + offset(rng)));
        TriangleSetup setup;
        if (setupTriangle(t, state, setup, nullptr) != TriangleFate::Drawn) continue;
        ++trianglesChecked;
        std::uniform_int_distribution<int> rx(0, width - 1), ry(0, height - 1);
        int x0 = rx(rng), x1 = rx(rng), y0 = ry(rng), y1 = ry(rng);
        const PixelRect rect =
            trial % 2 ? PixelRect{0, 0, width - 1, height - 1}
                      : PixelRect{std::min(x0, x1), std::min(y0, y1), std::max(x0, x1), std::max(y0, y1)};
        const std::vector<int> covered = walk(setup, rect, width, height);
        rasterizeBlocks(setup, rect, [&](const CoverageBlock& b) { fullBlocksSeen += b.fullyCovered; });
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const bool inside =
                    x >= std::max(rect.minX, setup.minX) && x <= std::min(rect.maxX, setup.maxX) &&
                    y >= std::max(rect.minY, setup.minY) && y <= std::min(rect.maxY, setup.maxY);
                ASSERT_EQ(covered[static_cast<std::size_t>(y) * width + x],
                          inside && coversSample(setup, x, y) ? 1 : 0)
                    << "trial " << trial << " pixel " << x << "," << y;
            }
    }
    EXPECT_GT(trianglesChecked, 2000);
    EXPECT_GT(fullBlocksSeen, 100);  // the trivial-accept path was exercised
}

// A patch's edge values are 32-bit, so a triangle is walked as patches only when its edges are short,
// not merely its box: the box of a long sliver that reaches beyond the viewport is cut to a few pixels.
// Break caught: fitsPatch deciding by the (clamped) box alone, whose edge values then wrap in 32 bits.
TEST(Rasterize, APatchNeedsShortEdgesNotJustASmallBox) {
    DrawState state;
    state.viewport = {0, 0, 16, 16};
    state.raster.cull = CullMode::None;
    WindowTriangle small, sliver;
    small.vertices = {fixedAt(2 * kFixedOne, 2 * kFixedOne), fixedAt(5 * kFixedOne, 3 * kFixedOne),
                      fixedAt(3 * kFixedOne, 8 * kFixedOne)};
    // Reaches 3000 pixels left of the viewport; its box inside it is 3 × 3 pixels.
    sliver.vertices = {fixedAt(-3000 * kFixedOne, 2 * kFixedOne), fixedAt(3 * kFixedOne, 2 * kFixedOne),
                       fixedAt(-3000 * kFixedOne, 5 * kFixedOne)};
    TriangleSetup smallSetup, sliverSetup;
    ASSERT_EQ(setupTriangle(small, state, smallSetup, nullptr), TriangleFate::Drawn);
    ASSERT_EQ(setupTriangle(sliver, state, sliverSetup, nullptr), TriangleFate::Drawn);
    ASSERT_LT(sliverSetup.maxX - sliverSetup.minX, kNarrowPatch);
    ASSERT_LT(sliverSetup.maxY - sliverSetup.minY, 8);
    EXPECT_TRUE(fitsPatch(smallSetup, kNarrowPatch, 8));
    EXPECT_FALSE(fitsPatch(smallSetup, kNarrowPatch, 4));  // six rows
    EXPECT_FALSE(fitsPatch(smallSetup, 2, 8));             // four columns
    EXPECT_FALSE(fitsPatch(sliverSetup, kWidePatch, 8));
}

// A triangle of a few pixels is walked as one patch: its coverage, edge values and barycentrics against
// the per-pixel test and the block walk (support/patch_checks.h; the sixteen-lane patch in the
// AVX-512 test binary).
TEST(Rasterize, PatchCoverageMatchesThePerPixelTestWithEightLanes) {
    testing_support::expectPatchCoverageMatchesTheOracle<Int8, kNarrowPatch>();
}

// The same for a wide patch, eight columns by one row of eight lanes.
TEST(Rasterize, WidePatchCoverageMatchesThePerPixelTestWithEightLanes) {
    testing_support::expectPatchCoverageMatchesTheOracle<Int8, kWidePatch>();
}

// Edges thousands of pixels long overflow the 32-bit lanes of a crossed block; those blocks take the
// 64-bit path, which must agree with the oracle just the same.
TEST(Rasterize, LongEdgesTakeTheWidePathAndStayExact) {
    std::mt19937 rng(77);
    const int width = 16000, height = 16000;
    DrawState state;
    state.viewport = {0, 0, width, height};
    state.raster.cull = CullMode::None;
    std::uniform_int_distribution<std::int64_t> coord(0, std::int64_t{width} * kFixedOne);
    int checked = 0;
    for (int trial = 0; trial < 40; ++trial) {
        WindowTriangle t;
        for (auto& v : t.vertices)
            v = fixedAt(coord(rng), coord(rng));
        TriangleSetup setup;
        if (setupTriangle(t, state, setup, nullptr) != TriangleFate::Drawn) continue;
        // Look at a 96×96 window around the middle of the first edge, which the edge crosses.
        const int cx = static_cast<int>((t.vertices[0].xFixed + t.vertices[1].xFixed) / 2 / kFixedOne);
        const int cy = static_cast<int>((t.vertices[0].yFixed + t.vertices[1].yFixed) / 2 / kFixedOne);
        const PixelRect rect{std::max(cx - 48, 0), std::max(cy - 48, 0), std::min(cx + 47, width - 1),
                             std::min(cy + 47, height - 1)};
        std::set<std::pair<int, int>> walked;
        rasterizeBlocks(setup, rect, [&](const CoverageBlock& b) {
            for (int bit = 0; bit < 64; ++bit)
                if ((b.mask >> bit) & 1) walked.insert({b.x + bit % kBlockSize, b.y + bit / kBlockSize});
        });
        for (int y = rect.minY; y <= rect.maxY; ++y)
            for (int x = rect.minX; x <= rect.maxX; ++x) {
                const bool inside = x >= setup.minX && x <= setup.maxX && y >= setup.minY && y <= setup.maxY;
                ASSERT_EQ(walked.count({x, y}) == 1, inside && coversSample(setup, x, y))
                    << "trial " << trial;
            }
        ++checked;
    }
    EXPECT_GT(checked, 30);
}

TEST(Rasterize, OddBoundsAndTheLastRowAndColumn) {
    for (auto [width, height] : {std::pair{1, 1}, {3, 7}, {4097, 1}}) {
        DrawState state;
        state.viewport = {0, 0, width, height};
        state.raster.cull = CullMode::None;
        // A triangle much larger than the viewport covers every pixel once, including the last ones.
        WindowTriangle t;
        t.vertices = {fixedAt(-5 * kFixedOne, -5 * kFixedOne), fixedAt(3 * width * kFixedOne, -5 * kFixedOne),
                      fixedAt(-5 * kFixedOne, 3 * height * kFixedOne + 20 * kFixedOne)};
        TriangleSetup setup;
        ASSERT_EQ(setupTriangle(t, state, setup, nullptr), TriangleFate::Drawn);
        const std::vector<int> covered = walk(setup, {0, 0, width - 1, height - 1}, width, height);
        for (int v : covered)
            ASSERT_EQ(v, 1) << width << "x" << height;
    }
}

// A triangle a few pixels across that straddles the corner of four aligned blocks is walked as one
// block placed over it; near the area's right and bottom edges the block is moved back inside the area
// (the back end loads and stores whole block rows, which must stay in the tile).
TEST(Rasterize, ASmallTriangleIsOneBlockPlacedInsideTheArea) {
    DrawState state;
    state.viewport = {0, 0, 64, 64};
    state.raster.cull = CullMode::None;
    const auto smallTriangleAt = [&](int x, int y) {
        WindowTriangle t;
        t.vertices = {fixedAt(x * kFixedOne, y * kFixedOne), fixedAt((x + 5) * kFixedOne, y * kFixedOne),
                      fixedAt(x * kFixedOne, (y + 5) * kFixedOne)};
        TriangleSetup setup;
        EXPECT_EQ(setupTriangle(t, state, setup, nullptr), TriangleFate::Drawn);
        return setup;
    };
    struct Case {
        int x, y;            // the triangle's corner
        PixelRect area;      // the tile
        int blockX, blockY;  // the one block expected
    };
    for (const Case& c : {Case{6, 5, {0, 0, 63, 63}, 6, 5}, Case{29, 29, {0, 0, 31, 31}, 24, 24},
                          Case{12, 13, {8, 8, 15, 15}, 8, 8}}) {
        const TriangleSetup setup = smallTriangleAt(c.x, c.y);
        int blocks = 0, pixels = 0;
        rasterizeBlocks(setup, c.area, [&](const CoverageBlock& b) {
            ++blocks;
            pixels += std::popcount(b.mask);
            EXPECT_EQ(b.x, c.blockX);
            EXPECT_EQ(b.y, c.blockY);
        });
        EXPECT_EQ(blocks, 1) << c.x << "," << c.y;
        int expected = 0;
        for (int y = c.area.minY; y <= c.area.maxY; ++y)
            for (int x = c.area.minX; x <= c.area.maxX; ++x)
                expected += coversSample(setup, x, y);
        EXPECT_EQ(pixels, expected) << c.x << "," << c.y;
        EXPECT_GT(pixels, 0);
    }
}

TEST(Rasterize, EmptyBoundsVisitNothing) {
    TriangleSetup setup;  // default bounds are empty (max < min)
    int visits = 0;
    rasterizeBlocks(setup, PixelRect{0, 0, 100, 100}, [&](const CoverageBlock&) { ++visits; });
    EXPECT_EQ(visits, 0);
}

TEST(Rasterize, RectMaskSelectsThePixelsInside) {
    EXPECT_EQ(rectMask(0, 0, {0, 0, 7, 7}), ~std::uint64_t{0});
    EXPECT_EQ(rectMask(8, 0, {0, 0, 7, 7}), 0u);
    EXPECT_EQ(rectMask(0, 0, {1, 0, 2, 0}), 0b110u);                  // row 0, columns 1–2
    EXPECT_EQ(rectMask(0, 0, {0, 7, 0, 7}), std::uint64_t{1} << 56);  // row 7, column 0
    EXPECT_EQ(std::popcount(rectMask(16, 8, {18, 9, 30, 12})), 6 * 4);
}

// Every rectangle with corners from two pixels before the block to two after it, bit by bit against
// "is the pixel inside". Breaks caught: the rows' span one row short or long, rows shifted by the
// first row twice, the columns' bits not copied to every kept row.
TEST(Rasterize, RectMaskAgreesWithTestingEachPixel) {
    const int bx = 16, by = 8;
    for (int minY = by - 2; minY <= by + 9; ++minY)
        for (int maxY = minY - 1; maxY <= by + 9; ++maxY)
            for (int minX = bx - 2; minX <= bx + 9; ++minX)
                for (int maxX = minX - 1; maxX <= bx + 9; ++maxX) {
                    const PixelRect rect{minX, minY, maxX, maxY};
                    std::uint64_t expected = 0;
                    for (int row = 0; row < kBlockSize; ++row)
                        for (int column = 0; column < kBlockSize; ++column) {
                            const int x = bx + column, y = by + row;
                            if (x >= minX && x <= maxX && y >= minY && y <= maxY)
                                expected |= std::uint64_t{1} << (row * kBlockSize + column);
                        }
                    ASSERT_EQ(rectMask(bx, by, rect), expected)
                        << "rect " << minX << "," << minY << " – " << maxX << "," << maxY;
                }
}

}  // namespace
}  // namespace facet
