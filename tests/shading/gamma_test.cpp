// The 8-bit encoding of a linear value (shading/gamma.h): the codes the image writer, `facet compare`
// and the conformance tests all take.
#include "shading/gamma.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include <gtest/gtest.h>

namespace facet {
namespace {

TEST(Quantize8, RoundsAsTheImageWriterDoes) {
    EXPECT_EQ(encodeChannel(0.5f, kLinearEncoding), 128);  // 127.5 rounds up
    EXPECT_EQ(encodeChannel(0.5f, kSrgbEncoding), 188);    // 1.055·0.5^(1/2.4) − 0.055 = 0.73536 → 187.5
    EXPECT_EQ(encodeChannel(0.0031308f * 0.5f, kSrgbEncoding), 5);  // the linear toe: 12.92 c · 255 = 5.16
    EXPECT_EQ(encodeChannel(-1.0f, kSrgbEncoding), 0);
    EXPECT_EQ(encodeChannel(std::nanf(""), kLinearEncoding), 0);
    EXPECT_EQ(encodeChannel(7.0f, kSrgbEncoding), 255);
    EXPECT_EQ(encodeChannel(1.0f, kLinearEncoding), 255);
}

// The gl preset rounds a value exactly halfway between two codes to the even one, as Mesa's float →
// unorm8 (_mesa_lroundevenf) does; Facet's rounds it up. 0.5 is 127.5 codes: 128 either way (even);
// 2.5/255 and 4.5/255 (their products with 255 are exactly 2.5 and 4.5 in float): 2 and 4, not 3 and 5;
// 3.5/255: 4 under both.
TEST(Quantize8, GlPresetRoundsHalfToEven) {
    EXPECT_EQ(encodeChannel(0.5f, kGlEncoding), 128);
    // (k + ½, the even neighbour, the one above)
    const int cases[][3] = {{5, 2, 3}, {9, 4, 5}, {7, 4, 4}, {253, 126, 127}};
    for (const auto& [twiceHalf, even, up] : cases) {
        const float half = float(twiceHalf) / 2.0f;
        const float value = half / 255.0f;
        ASSERT_EQ(value * 255.0f, half);  // exactly halfway, after the float product
        EXPECT_EQ(encodeChannel(value, kGlEncoding), even) << half;
        EXPECT_EQ(encodeChannel(value, kLinearEncoding), up) << half;
        EXPECT_EQ(toByte(value, Rounding::HalfToEven), even) << half;  // alpha alike
    }
    // Away from halves, both round to nearest.
    EXPECT_EQ(encodeChannel(2.6f / 255.0f, kGlEncoding), 3);
    EXPECT_EQ(encodeChannel(2.4f / 255.0f, kGlEncoding), 2);
}

// The three transfer curves on hand-computed values, and each one's inverse round-trips every code.
TEST(EncodeChannel, SrgbPowerAndLinearCurves) {
    const ColorEncoding power{TransferCurve::Power, 2.2f};
    EXPECT_EQ(encodeChannel(0.5f, kSrgbEncoding), 188);    // 1.055·0.5^(1/2.4) − 0.055 = 0.7354
    EXPECT_EQ(encodeChannel(0.5f, power), 186);            // 0.5^(1/2.2) = 0.7297
    EXPECT_EQ(encodeChannel(0.5f, kLinearEncoding), 128);  // 127.5 rounds up
    EXPECT_EQ(encodeChannel(0.2f, ColorEncoding{TransferCurve::Power, 1.0f}), 51);
    for (const ColorEncoding& e : {kSrgbEncoding, power, kLinearEncoding}) {
        EXPECT_EQ(encodeChannel(-0.5f, e), 0);
        EXPECT_EQ(encodeChannel(2.0f, e), 255);
        EXPECT_EQ(encodeChannel(std::nanf(""), e), 0);
    }
    for (int code = 0; code < 256; ++code) {
        const float unit = static_cast<float>(code) / 255.0f;
        EXPECT_EQ(encodeChannel(srgbToLinear(unit), kSrgbEncoding), code);
        EXPECT_EQ(encodeChannel(std::pow(unit, 2.2f), power), code);
        EXPECT_EQ(encodeChannel(unit, kLinearEncoding), code);
    }
}

// ChannelEncoder (the image writer's tables) gives encodeChannel's code for every float tried: all
// floats within 4096 steps of each code's first value, 2^16 spread over [0, 1], and the edges (zero,
// negatives, NaN, infinity, one and above), for each curve and rounding. Breaks caught: a threshold
// off by one float (the bisection keeping `below`), a bucket starting one code too high, the step-up
// loop comparing with > instead of >=, or NaN not mapped to 0.
TEST(ChannelEncoder, GivesEncodeChannelsCodeForEveryFloat) {
    const ColorEncoding encodings[] = {kSrgbEncoding,
                                       kLinearEncoding,
                                       kGlEncoding,
                                       {TransferCurve::Power, 2.2f},
                                       {TransferCurve::Power, 1.8f, Rounding::HalfToEven},
                                       {TransferCurve::Srgb, 2.2f, Rounding::HalfToEven}};
    for (const ColorEncoding& encoding : encodings) {
        const ChannelEncoder encode(encoding);
        std::size_t mismatches = 0;
        const auto check = [&](float value) {
            if (encode(value) != encodeChannel(value, encoding) && mismatches++ < 5)
                ADD_FAILURE() << "curve " << int(encoding.curve) << ", " << value << " (bits "
                              << std::bit_cast<std::uint32_t>(value) << "): table " << int(encode(value))
                              << ", encodeChannel " << int(encodeChannel(value, encoding));
        };
        for (const float edge : {0.0f, -0.0f, -1.0f, 1.0f, 1.5f, 1e30f, std::nanf(""), INFINITY, -INFINITY,
                                 std::numeric_limits<float>::denorm_min(), std::nextafter(1.0f, 0.0f)})
            check(edge);
        for (int k = 0; k <= 65536; ++k)
            check(float(k) / 65536.0f);
        for (int code = 1; code < 256; ++code) {
            // Around the first float with this code (by bisection on encodeChannel alone).
            std::uint32_t low = 0, bits = 0x3F800000u;
            while (bits - low > 1) {
                const std::uint32_t middle = low + (bits - low) / 2;
                (encodeChannel(std::bit_cast<float>(middle), encoding) >= code ? bits : low) = middle;
            }
            for (std::uint32_t b = bits > 4096 ? bits - 4096 : 0; b < bits + 4096 && b <= 0x3F800000u; ++b)
                check(std::bit_cast<float>(b));
        }
        EXPECT_EQ(mismatches, 0u);
    }
}

}  // namespace
}  // namespace facet
