// The back end's fragment queue: what keeps every pixel's fragments in submission order.
#include "back_end.h"

#include <bit>
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

// The back end queues a block row's passing fragments eight lanes at a time (queueRow) where it once
// queued them one by one (queueFragment); the slots must be the same, since they decide which fragments
// share a batch. For every mask of columns that fits the room left in queues filled 0–7 deep, both ways
// are compared slot by slot, with the live-slot mask and the pixel filter.
// Breaks caught: the columns packed out of order or from the wrong lanes (a fragment gets another
// column's depth or barycentrics), the live-slot mask not shifted past the slots already queued, the
// filter bits not rotated by the row's first column, a slot's triangle or planes left stale.
TEST(FragmentQueue, QueueingARowFillsTheSlotsOfQueueingItsFragmentsOneByOne) {
    TriangleSetup earlier, setup;
    earlier.triangle = 3;
    setup.triangle = 41;
    const float earlierPlanes[3] = {}, planes[3] = {};
    Float8 z, b1, b2;
    for (int lane = 0; lane < kBlockSize; ++lane) {
        z[lane] = 0.1f * static_cast<float>(lane + 1);
        b1[lane] = 1.0f / static_cast<float>(lane + 2);
        b2[lane] = -0.5f * static_cast<float>(lane);
    }
    int compared = 0;
    for (int already = 0; already < kBlockSize; ++already)
        for (unsigned columns = 1; columns < 256; ++columns) {
            if (std::popcount(columns) > kBlockSize - already) continue;
            for (const int rowX : {16, 21}) {
                const int rowY = 13;
                detail::FragmentQueue one, wide;
                for (int i = 0; i < already; ++i)
                    for (detail::FragmentQueue* q : {&one, &wide})
                        detail::queueFragment(*q, earlier, earlierPlanes, 40 + i, 2, 0.5f, 0.25f, 0.25f);
                for (int lane = 0; lane < kBlockSize; ++lane)
                    if ((columns >> lane) & 1u)
                        detail::queueFragment(one, setup, planes, rowX + lane, rowY, z[lane], b1[lane],
                                              b2[lane]);
                detail::queueRow(wide, setup, planes, rowX, rowY, z, b1, b2, columns);
                ASSERT_EQ(wide.count, one.count);
                ASSERT_EQ(wide.batch.mask, one.batch.mask) << "columns " << columns << ", after " << already;
                ASSERT_EQ(wide.pixelsMod8, one.pixelsMod8) << "columns " << columns << ", first x " << rowX;
                for (int slot = 0; slot < one.count; ++slot) {
                    SCOPED_TRACE(::testing::Message()
                                 << "columns " << columns << ", after " << already << ", slot " << slot);
                    EXPECT_EQ(wide.x[slot], one.x[slot]);
                    EXPECT_EQ(wide.y[slot], one.y[slot]);
                    EXPECT_EQ(wide.z[slot], one.z[slot]);
                    EXPECT_EQ(wide.b1[slot], one.b1[slot]);
                    EXPECT_EQ(wide.b2[slot], one.b2[slot]);
                    EXPECT_EQ(wide.triangle[slot], one.triangle[slot]);
                    EXPECT_EQ(wide.setups[slot], one.setups[slot]);
                    EXPECT_EQ(wide.planes[slot], one.planes[slot]);
                }
                ++compared;
            }
        }
    EXPECT_GT(compared, 2000);
}

// Splitting a row between a full queue and the next: the lowest k set bits of a mask, checked against
// clearing the lowest bit one at a time. Breaks caught: the k-th bit itself dropped or one bit too many
// kept (a fragment queued twice, or lost, when a row straddles a full queue).
TEST(FragmentQueue, LowestSetBitsKeepsExactlyTheFirstK) {
    for (unsigned mask = 0; mask < 256; ++mask)
        for (int k = 0; k <= kBlockSize; ++k) {
            unsigned expected = 0, rest = mask;
            for (int i = 0; i < k && rest; ++i) {
                expected |= rest & (~rest + 1u);
                rest &= rest - 1u;
            }
            ASSERT_EQ(lowestSetBits(mask, k), expected) << "mask " << mask << ", k " << k;
        }
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
