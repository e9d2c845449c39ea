#include "viewport.h"

#include <cmath>

#include <gtest/gtest.h>

namespace facet {
namespace {

TEST(Viewport, MapsNdcCornersToWindowCorners) {
    const Viewport vp{10, 20, 200, 100, 0.0f, 1.0f};
    const WindowVertex topLeft = toWindow({-2, 2, -2, 2}, vp, 8);  // NDC (−1, 1, −1)
    EXPECT_FLOAT_EQ(topLeft.window.x, 10.0f);
    EXPECT_FLOAT_EQ(topLeft.window.y, 20.0f);  // window y grows downwards: NDC y = +1 is the top row
    EXPECT_FLOAT_EQ(topLeft.z, 0.0f);
    EXPECT_FLOAT_EQ(topLeft.invW, 0.5f);
    const WindowVertex bottomRight = toWindow({4, -4, 4, 4}, vp, 8);  // NDC (1, −1, 1)
    EXPECT_FLOAT_EQ(bottomRight.window.x, 210.0f);
    EXPECT_FLOAT_EQ(bottomRight.window.y, 120.0f);
    EXPECT_FLOAT_EQ(bottomRight.z, 1.0f);
    EXPECT_EQ(bottomRight.xFixed, 210 * kFixedOne);
    EXPECT_EQ(bottomRight.yFixed, 120 * kFixedOne);
}

TEST(Viewport, DepthRangeAndClamp) {
    const Viewport vp{0, 0, 10, 10, 0.25f, 0.75f};
    EXPECT_FLOAT_EQ(toWindow({0, 0, 0, 1}, vp, 8).z, 0.5f);
    // Slightly in front of the near plane after clipping's rounding: clamped into the range.
    EXPECT_FLOAT_EQ(toWindow({0, 0, -1.0001f, 1}, vp, 8).z, 0.25f);
}

TEST(Viewport, SnapsToNearestSubpixel) {
    const Viewport vp{0, 0, 256, 256};
    // NDC x = 1/512 − 1 → window x = 0.5/256·256/… = exactly 0.5 px: 128/256 in fixed point.
    const WindowVertex v = toWindow({-1.0f + 1.0f / 256.0f, 0, 0, 1}, vp, 8);
    EXPECT_EQ(v.xFixed, 128);
    EXPECT_EQ(toWindow({-1.0f + 1.0f / 256.0f, 0, 0, 1}, vp, 0).xFixed, 0);  // 0.5 rounds to even: 0
}

TEST(Viewport, SnappingFollowsSubpixelBits) {
    Viewport vp{0, 0, 100, 100};
    // NDC x = 0.00123 → window x = 50.0615 px.
    const vec4 clip{0.00123f, 0.0f, 0.0f, 1.0f};
    EXPECT_EQ(toWindow(clip, vp, 8).xFixed, std::llround(50.0615 * 256));  // 1/256 px
    EXPECT_EQ(toWindow(clip, vp, 4).xFixed, 50 * 256 + 16 * 1);            // nearest 1/16 px: 50 + 1/16
    EXPECT_EQ(toWindow(clip, vp, 0).xFixed, 50 * 256);                     // whole pixels
}

}  // namespace
}  // namespace facet
