#include "viewport.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "clip.h"

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

// The vertex stage's eight-at-a-time viewport transform gives toWindow's bits, lane by lane: positions
// inside the frustum (up to its planes, w from tiny to large), ties between subpixels, every subpixel
// precision, viewports off the origin and of the largest size, the depth formats and reversed depth
// ranges; in a group that mixes them with lanes outside the frustum (NaN, behind the eye), the lanes
// inside still get their bits (breaks caught: the rounding of a tie or of a negative coordinate, the int64
// halves of a snapped coordinate for some precision, reversed Z's depth mapping, the depth clamp, a field in
// the wrong word of WindowVertex).
TEST(Viewport, EightAtOnceMatchOneAtATimeBitForBit) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), logW(-6.0f, 3.0f);
    std::vector<vec4> positions = {{-1, 1, -1, 1},
                                   {1, -1, 1, 1},
                                   {-1.0f + 1.0f / 256.0f, 0, 0, 1},
                                   {1e-9f, -1e-9f, 1e-9f, 1e-9f},
                                   {0.0f, -0.0f, -0.0f, 1.0f}};
    // Window x at a multiple of half a pixel (and of half of every finer subpixel): ties to round.
    for (int k = -16; k <= 16; ++k)
        positions.push_back({k / 64.0f, -k / 128.0f, k / 16.0f, 1.0f});
    while (positions.size() % 8 != 0 || positions.size() < 800) {
        const float w = std::pow(10.0f, logW(rng));
        positions.push_back({unit(rng) * w, unit(rng) * w, unit(rng) * w, w});
    }
    const Viewport viewports[] = {{0, 0, 1920, 1080, 0.0f, 1.0f},
                                  {-50, 30, 333, 77, 0.25f, 0.75f},
                                  {7, 5, kMaxViewportSide, kMaxViewportSide, 1.0f, 0.0f}};
    for (const Viewport& viewport : viewports)
        for (const DepthBufferFormat format :
             {DepthBufferFormat::Float, DepthBufferFormat::ReversedFloat, DepthBufferFormat::Unorm24})
            for (int bits = 0; bits <= kFixedFractionBits; ++bits)
                for (std::size_t group = 0; group < positions.size(); group += 8) {
                    const std::uint8_t inside[8] = {};
                    WindowVertex eight[8];
                    toWindow(&positions[group], inside, viewport, bits, format, eight);
                    for (std::size_t lane = 0; lane < 8; ++lane) {
                        const WindowVertex one = toWindow(positions[group + lane], viewport, bits, format);
                        const vec4& p = positions[group + lane];
                        SCOPED_TRACE(testing::Message() << p.x << ", " << p.y << ", " << p.z << ", " << p.w
                                                        << ", " << bits << " subpixel bits, viewport "
                                                        << viewport.width << "x" << viewport.height);
                        EXPECT_EQ(eight[lane].xFixed, one.xFixed);
                        EXPECT_EQ(eight[lane].yFixed, one.yFixed);
                        EXPECT_EQ(std::bit_cast<std::uint32_t>(eight[lane].z),
                                  std::bit_cast<std::uint32_t>(one.z));
                        EXPECT_EQ(std::bit_cast<std::uint32_t>(eight[lane].invW),
                                  std::bit_cast<std::uint32_t>(one.invW));
                        EXPECT_EQ(std::bit_cast<std::uint64_t>(eight[lane].window),
                                  std::bit_cast<std::uint64_t>(one.window));
                    }
                }
    // A group mixing lanes inside and outside the frustum: the outside ones (NaN, behind the eye, beside
    // it) are computed from a stand-in position and not read; the inside ones are exact.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    vec4 mixed[8] = {{0.5f, 0.5f, 0.5f, 1.0f},
                     {nan, 0, 0, 1},
                     {0, 0, 0, -1},
                     {0.25f, -0.5f, 0, 2.0f},
                     {5, 0, 0, 1},
                     {0, 0, 0, 0},
                     {0, nan, 0, 1},
                     {-0.5f, 0.5f, 0.9f, 1.0f}};
    std::uint8_t codes[8];
    computeOutcodes(mixed, codes);
    WindowVertex eight[8];
    toWindow(mixed, codes, viewports[0], 8, DepthBufferFormat::Float, eight);
    for (const int lane : {0, 3, 7}) {
        ASSERT_EQ(codes[lane], 0);
        const WindowVertex one = toWindow(mixed[lane], viewports[0], 8);
        EXPECT_EQ(eight[lane].xFixed, one.xFixed) << lane;
        EXPECT_EQ(eight[lane].yFixed, one.yFixed) << lane;
        EXPECT_EQ(eight[lane].z, one.z) << lane;
    }
}

}  // namespace
}  // namespace facet
