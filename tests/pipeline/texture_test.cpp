// Texture sampling (texture.h) against hand values: orientation (v = 0 is the image's bottom row), texel
// centres at (i + ½)/size, bilinear weights, repeat wrapping, and the 8-bit code tables.
#include "texture.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace facet {
namespace {

// A float texture whose texel (x, y) holds `value(x, y)` in red (rows as stored: row 0 is the file's top).
template <class Value>
Texture floatTexture(int width, int height, Value value) {
    Texture t;
    t.width = width;
    t.height = height;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            t.texels.push_back(vec4(value(x, y), 0.0f, 0.0f, 1.0f));
    return t;
}

// Breaks caught: v = uv.y · height (the image upside down).
TEST(Texture, VZeroIsTheBottomRowOfTheImage) {
    // Two rows: the file's top row (row 0) holds 1, its bottom row (row 1) holds 2.
    const Texture t = floatTexture(1, 2, [](int, int y) { return y == 0 ? 1.0f : 2.0f; });
    EXPECT_EQ(sampleBilinear(t, {0.5f, 0.25f}).r, 2.0f);  // the centre of the bottom texel
    EXPECT_EQ(sampleBilinear(t, {0.5f, 0.75f}).r, 1.0f);  // the centre of the top texel
}

// Breaks caught: texel centres at i/size (the −½ dropped), or at (i + 1)/size.
TEST(Texture, TexelCentresReturnTheTexelExactly) {
    const Texture t = floatTexture(4, 3, [](int x, int y) { return static_cast<float>(10 * y + x); });
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) {
            const vec2 uv((x + 0.5f) / 4.0f, 1.0f - (y + 0.5f) / 3.0f);
            // Exact but for the rounding of uv to float (a texel off centre by ½ would be off by ½ or 5).
            EXPECT_NEAR(sampleBilinear(t, uv).r, static_cast<float>(10 * y + x), 1e-4f) << x << "," << y;
        }
}

// Between four texel centres the value is the bilinear blend, weight s across and r down.
// Breaks caught: the weights swapped (s for r), or one weight taken as 1 − s.
TEST(Texture, BilinearWeights) {
    // Corner values 1, 2 (top row), 4, 8 (bottom row) of a 2×2 texture: all four weights show.
    const float corner[2][2] = {{1, 2}, {4, 8}};
    const Texture t = floatTexture(2, 2, [&](int x, int y) { return corner[y][x]; });
    for (const auto& [s, r] : {std::pair{0.25f, 0.5f}, std::pair{0.75f, 0.125f}, std::pair{0.5f, 0.875f}}) {
        // From the top-left texel's centre (¼, ¾ in uv), s across and r down (towards v = ¼).
        const vec2 uv(0.25f + 0.5f * s, 0.75f - 0.5f * r);
        const float expected = (1 - r) * ((1 - s) * corner[0][0] + s * corner[0][1]) +
                               r * ((1 - s) * corner[1][0] + s * corner[1][1]);
        EXPECT_FLOAT_EQ(sampleBilinear(t, uv).r, expected) << s << ", " << r;
    }
}

// GL_REPEAT: u and v wrap with period 1, and between the last and first texel centres the blend wraps
// round the edge.
// Breaks caught: clamping instead of wrapping, or a negative coordinate wrapped to the wrong texel.
TEST(Texture, RepeatWrapping) {
    const Texture t = floatTexture(4, 2, [](int x, int y) { return static_cast<float>(x + 4 * y); });
    // Coordinates in 1/64ths: adding whole numbers to them is exact in float.
    for (const vec2 uv : {vec2(0.375f, 0.25f), vec2(0.59375f, 0.90625f), vec2(0.125f, 0.703125f)}) {
        const float value = sampleBilinear(t, uv).r;
        EXPECT_EQ(sampleBilinear(t, uv + vec2(1, 0)).r, value);
        EXPECT_EQ(sampleBilinear(t, uv - vec2(2, 0)).r, value);
        EXPECT_EQ(sampleBilinear(t, uv + vec2(0, 3)).r, value);
        EXPECT_EQ(sampleBilinear(t, uv - vec2(0, 1)).r, value);
    }
    // u = 0 lies halfway between the centres of the last texel (3 in the bottom row: 7) and the first (4).
    EXPECT_FLOAT_EQ(sampleBilinear(t, {0.0f, 0.25f}).r, 0.5f * (7 + 4));
    // v = 0 lies halfway between the bottom row and, wrapped, the top row.
    EXPECT_FLOAT_EQ(sampleBilinear(t, {0.125f, 0.0f}).r, 0.5f * (4 + 0));
}

// An 8-bit texture decodes R, G and B through colorFromCode and alpha through alphaFromCode, and samples
// like the float texture of its decoded values.
// Breaks caught: alpha decoded with the colour table, or a channel read from the wrong code.
TEST(Texture, EightBitCodesDecodeThroughTheirTables) {
    Texture codes;
    codes.width = 2;
    codes.height = 1;
    codes.codes = {{10, 200, 255, 128}, {0, 64, 3, 255}};
    for (int i = 0; i < 256; ++i) {
        codes.colorFromCode[static_cast<std::size_t>(i)] =
            std::pow(i / 255.0f, 2.2f);  // any curve but identity
        codes.alphaFromCode[static_cast<std::size_t>(i)] = i / 255.0f;
    }
    const vec4 first = codes.texel(0, 0);
    EXPECT_EQ(first, vec4(codes.colorFromCode[10], codes.colorFromCode[200], codes.colorFromCode[255],
                          128 / 255.0f));
    Texture decoded;
    decoded.width = 2;
    decoded.height = 1;
    decoded.texels = {codes.texel(0, 0), codes.texel(1, 0)};
    EXPECT_EQ(decoded.texels[1], vec4(0.0f, codes.colorFromCode[64], codes.colorFromCode[3], 1.0f));
    for (const vec2 uv : {vec2(0.25f, 0.5f), vec2(0.5f, 0.5f), vec2(0.9f, 0.3f)})
        EXPECT_EQ(sampleBilinear(codes, uv), sampleBilinear(decoded, uv));
    EXPECT_EQ(codes.bytes(), 8u);
}

TEST(Texture, EmptyIsWhiteAndNonFiniteCoordinatesAreBlack) {
    EXPECT_EQ(sampleBilinear(Texture{}, {0.5f, 0.5f}), vec4(1.0f));
    const Texture t = floatTexture(2, 2, [](int, int) { return 1.0f; });
    EXPECT_EQ(sampleBilinear(t, {std::numeric_limits<float>::quiet_NaN(), 0.5f}), vec4(0.0f));
    EXPECT_EQ(sampleBilinear(t, {0.5f, std::numeric_limits<float>::infinity()}), vec4(0.0f));
}

}  // namespace
}  // namespace facet
