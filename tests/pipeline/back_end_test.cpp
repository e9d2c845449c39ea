// The back end's fragment queue: what keeps every pixel's fragments in submission order.
#include "back_end.h"

#include <random>

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace facet
