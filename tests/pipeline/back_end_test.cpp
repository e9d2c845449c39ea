// The back end's fragment queue: what keeps every pixel's fragments in submission order.
#include "back_end.h"

#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "../support/test_shaders.h"
#include "pipeline.h"

namespace facet {
namespace {

// Before a block row is depth-tested, the queue is shaded if it holds a fragment at one of the row's
// covered pixels; holdsAny answers that through a filter of pixel positions modulo 8 and then the
// slots. Fragments 8 apart alias in the filter, so the positions here are drawn from a 24×24 area to
// make aliases common (and half of the rows pass through a queued pixel), and every answer is compared with
// looking at each slot. Breaks caught: the filter's rotation by the row's first column going the wrong way or
// missing (a row whose pixel is queued answered "no", so that pixel's later fragment would be tested against
// a depth its earlier one has not yet written); remember() not called for a queued fragment.
TEST(FragmentQueue, HoldsAnyAgreesWithLookingAtEverySlot) {
    std::mt19937 rng(2026);
    std::uniform_int_distribution<int> coordinate(0, 23), slots(0, kBlockSize);
    int held = 0, notHeld = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        detail::FragmentQueue queue;
        const int count = slots(rng);
        for (int i = 0; i < count; ++i) {
            queue.x[i] = coordinate(rng);
            queue.y[i] = coordinate(rng);
            queue.remember(queue.x[i], queue.y[i]);
        }
        queue.count = count;
        // Half of the rows pass through a queued fragment's pixel.
        int rowY = coordinate(rng), firstX = coordinate(rng);
        if (count > 0 && trial % 2) {
            const int i = static_cast<int>(rng() % static_cast<unsigned>(count));
            rowY = queue.y[i];
            firstX = queue.x[i] - static_cast<int>(rng() % kBlockSize);
        }
        const unsigned columns = static_cast<unsigned>(rng()) & 0xffu;
        bool expected = false;
        for (int i = 0; i < count; ++i) {
            const int column = queue.x[i] - firstX;
            expected |=
                queue.y[i] == rowY && column >= 0 && column < kBlockSize && ((columns >> column) & 1u);
        }
        ASSERT_EQ(queue.holdsAny(rowY, firstX, columns), expected)
            << "trial " << trial << ": row " << rowY << ", first column " << firstX << ", columns "
            << columns;
        (expected ? held : notHeld) += 1;
    }
    EXPECT_GT(held, 1000);
    EXPECT_GT(notHeld, 1000);
}

// Fragments of many small triangles share the queue's batches, and are interpolated when a batch is
// shaded, each triangle's slots with that triangle's planes. A grid of tiny triangles, one per 4×4
// cell, each of one colour of its own at its three corners (so interpolation gives it exactly): every
// pixel holds the background or its own cell's colour, and most cells show theirs.
// Breaks caught: a batch interpolated with its first slot's triangle for every slot (the colour of a
// neighbouring cell), a later triangle's lanes not merged into the batch (a stale colour).
TEST(FragmentQueue, EachQueuedFragmentIsInterpolatedWithItsOwnTriangle) {
    constexpr int kCells = 16, kCell = 4;
    Framebuffer fb(kCells * kCell, kCells * kCell);
    const vec4 background(0.0f, 0.0f, 0.0f, 1.0f);
    fb.clearColor(background);
    const auto cellColor = [](int cx, int cy) {
        return vec4(static_cast<float>(cx + 1) / 32.0f, static_cast<float>(cy + 1) / 32.0f, 0.5f, 1.0f);
    };
    std::vector<testing::ClipSpaceColorShader::Attributes> vertices;
    for (int cy = 0; cy < kCells; ++cy)
        for (int cx = 0; cx < kCells; ++cx) {
            // Three or so pixels each, in different spots of their cells, so batches mix triangles.
            const vec2 corner(static_cast<float>(cx * kCell) + 0.25f * static_cast<float>((cx + cy) % 3),
                              static_cast<float>(cy * kCell) + 0.25f * static_cast<float>(cx % 2));
            for (vec2 p : {corner, corner + vec2(2.6f, 0.2f), corner + vec2(0.3f, 2.7f)})
                vertices.push_back({testing::clipFromWindow(p, fb), cellColor(cx, cy)});
        }
    testing::drawTriangles<testing::ClipSpaceColorShader>(testing::stateFor(fb), vertices, fb);
    int cellsShown = 0;
    for (int cy = 0; cy < kCells; ++cy)
        for (int cx = 0; cx < kCells; ++cx) {
            bool shown = false;
            for (int y = cy * kCell; y < (cy + 1) * kCell; ++y)
                for (int x = cx * kCell; x < (cx + 1) * kCell; ++x) {
                    const vec4 c = fb.color(x, y);
                    if (c == background) continue;
                    ASSERT_EQ(c, cellColor(cx, cy)) << "pixel " << x << ", " << y;
                    shown = true;
                }
            cellsShown += shown;
        }
    EXPECT_GT(cellsShown, kCells * kCells * 3 / 4);
}

}  // namespace
}  // namespace facet
