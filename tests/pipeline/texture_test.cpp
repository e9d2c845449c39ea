// Texture sampling (texture.h) against hand values: orientation (v = 0 is the image's bottom row), texel
// centres at (i + ½)/size, bilinear weights, repeat wrapping, and the 8-bit code tables.
#include "texture.h"

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

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

// The bilinear filter's pair of wrapped indices, ⌊u⌋ and ⌊u⌋ + 1, by integer remainder below 2^24: the
// same as fmod's wrapTexel for every integer-valued coordinate, negative, at the texture's edge, at
// and beyond 2^24 (where u + 1 rounds back to u). Breaks caught: the second index not wrapped to 0 at
// the last texel, a negative remainder left negative, or the exact-integer bound set too high.
TEST(Texture, WrappedIndexPairsMatchFmod) {
    for (const int n : {1, 3, 4, 256, 1000, 4096}) {
        std::vector<float> coordinates;
        for (int i = -3 * n - 2; i <= 3 * n + 2; ++i)
            coordinates.push_back(static_cast<float>(i));
        for (const float big : {16777214.0f, 16777215.0f, 16777216.0f, 16777218.0f, 3e9f, 1e20f})
            for (const float sign : {1.0f, -1.0f})
                coordinates.push_back(sign * big);
        for (const float i : coordinates) {
            int first = -1, second = -1;
            detail::wrapTexelPair(i, n, first, second);
            EXPECT_EQ(first, detail::wrapTexel(i, n)) << i << " mod " << n;
            EXPECT_EQ(second, detail::wrapTexel(i + 1.0f, n)) << i << " + 1 mod " << n;
        }
    }
}

// An 8-bit texture decodes R, G and B through colorFromCode and alpha by alphaFromCode, and samples like
// the float texture of its decoded values.
// Breaks caught: alpha decoded with the colour table, or a channel read from the wrong code.
TEST(Texture, EightBitCodesDecodeThroughTheirTables) {
    Texture codes;
    codes.width = 2;
    codes.height = 1;
    codes.codes = {{10, 200, 255, 128}, {0, 64, 3, 255}};
    for (int i = 0; i < 256; ++i)
        codes.colorFromCode[static_cast<std::size_t>(i)] =
            std::pow(i / 255.0f, 2.2f);  // any curve but identity
    const vec4 first = codes.texel(0, 0);
    EXPECT_EQ(first, vec4(codes.colorFromCode[10], codes.colorFromCode[200], codes.colorFromCode[255],
                          alphaFromCode(128)));
    Texture decoded;
    decoded.width = 2;
    decoded.height = 1;
    decoded.texels = {codes.texel(0, 0), codes.texel(1, 0)};
    EXPECT_EQ(decoded.texels[1], vec4(0.0f, codes.colorFromCode[64], codes.colorFromCode[3], 1.0f));
    for (const vec2 uv : {vec2(0.25f, 0.5f), vec2(0.5f, 0.5f), vec2(0.9f, 0.3f)})
        EXPECT_EQ(sampleBilinear(codes, uv), sampleBilinear(decoded, uv));
    EXPECT_EQ(codes.bytes(), 8u);
}

// Alpha codes are code · (1/255), the value an image library reads for them as float, with 255 exactly
// opaque; they rise with the code, so re-encoding a mip level's alpha finds the nearest.
// Breaks caught: 255 left at the product (0.99999994 or 1.0000001, a translucent or over-opaque texel),
// a division where the libraries multiply (a last-bit difference from a float read of the same file),
// or the opaque case tested on the wrong code.
TEST(Texture, AlphaCodesAreTheirShareOf255AndOpaqueAtTheTop) {
    EXPECT_EQ(alphaFromCode(0), 0.0f);
    EXPECT_EQ(alphaFromCode(255), 1.0f);
    EXPECT_LT(alphaFromCode(254), 1.0f);
    for (int code = 1; code < 255; ++code) {
        EXPECT_EQ(alphaFromCode(code), static_cast<float>(code) * (1.0f / 255.0f)) << code;
        EXPECT_GT(alphaFromCode(code), alphaFromCode(code - 1)) << code;
    }
}

TEST(Texture, EmptyIsWhiteAndNonFiniteCoordinatesAreBlack) {
    EXPECT_EQ(sampleBilinear(Texture{}, {0.5f, 0.5f}), vec4(1.0f));
    const Texture t = floatTexture(2, 2, [](int, int) { return 1.0f; });
    EXPECT_EQ(sampleBilinear(t, {std::numeric_limits<float>::quiet_NaN(), 0.5f}), vec4(0.0f));
    EXPECT_EQ(sampleBilinear(t, {0.5f, std::numeric_limits<float>::infinity()}), vec4(0.0f));
}

// ---- Nearest, mip chains and trilinear ------------------------------------------------------------

// An 8-bit texture with sRGB-decoding colour tables, its codes from `codes(x, y)`.
template <class Codes>
Texture srgbTexture(int width, int height, Codes codes) {
    Texture t;
    t.width = width;
    t.height = height;
    for (int i = 0; i < 256; ++i) {
        const float c = static_cast<float>(i) / 255.0f;
        t.colorFromCode[static_cast<std::size_t>(i)] =
            c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
    }
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            t.codes.push_back(codes(x, y));
    return t;
}

// GL_NEAREST: anywhere inside texel (x, y)'s square, the texel itself, unblended.
// Breaks caught: the bilinear −½ kept (a point left of a centre reads the texel to its left), or
// rounding instead of floor.
TEST(Texture, NearestReturnsTheTexelContainingUv) {
    const Texture t = floatTexture(4, 3, [](int x, int y) { return static_cast<float>(10 * y + x); });
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x)
            for (const vec2 inside : {vec2(0.1f, 0.1f), vec2(0.9f, 0.2f), vec2(0.3f, 0.85f)}) {
                // Row y of the file spans v from 1 − (y + 1)/3 to 1 − y/3.
                const vec2 uv((x + inside.x) / 4.0f, 1.0f - (y + inside.y) / 3.0f);
                EXPECT_EQ(sampleNearest(t, uv).r, static_cast<float>(10 * y + x)) << x << "," << y;
            }
    // Wrapped: u = −0.1 is in the last column, v = 1.1 in the bottom row.
    EXPECT_EQ(sampleNearest(t, {-0.1f, 1.1f}).r, 23.0f);
}

// Floor halving to 1×1, as OpenGL sizes levels (§8.14.3).
// Breaks caught: rounding odd sides up (5 → 3), or stopping when one side reaches 1.
TEST(Texture, MipLevelSizes) {
    Texture odd = floatTexture(5, 3, [](int, int) { return 0.0f; });
    buildMipChain(odd);
    ASSERT_EQ(odd.levelCount(), 3);
    EXPECT_EQ(std::pair(odd.level(1).width, odd.level(1).height), std::pair(2, 1));
    EXPECT_EQ(std::pair(odd.level(2).width, odd.level(2).height), std::pair(1, 1));

    Texture square = srgbTexture(64, 64, [](int, int) { return Texture::Codes{1, 2, 3, 4}; });
    buildMipChain(square);
    ASSERT_EQ(square.levelCount(), 7);
    for (int level = 0; level < 7; ++level) {
        EXPECT_EQ(square.level(level).width, 64 >> level);
        EXPECT_EQ(square.level(level).height, 64 >> level);
        // Kept in the file's form: 8-bit codes, 4 bytes a texel.
        EXPECT_TRUE(square.level(level).texels.empty());
    }
    // 4/3 of level 0, less the rounding of the small levels.
    EXPECT_EQ(square.bytes(), 4u * (64 * 64 + 32 * 32 + 16 * 16 + 8 * 8 + 4 * 4 + 2 * 2 + 1));
}

// A level-1 texel is the mean of its 2×2 level-0 texels in linear light: black and white codes average
// to linear ½ (code 188 re-encoded), not to code 128 (linear 0.216).
// Breaks caught: averaging the 8-bit codes rather than their linear values, or re-encoding with the
// linear table (code/255) instead of the texture's own.
TEST(Texture, MipTexelIsTheLinearMeanOfItsFour) {
    // Columns alternate black and white; alpha codes 0, 255 average to ½ as well (not sRGB-decoded).
    Texture t = srgbTexture(4, 2, [](int x, int) {
        const std::uint8_t c = (x % 2) ? 255 : 0;
        return Texture::Codes{c, c, static_cast<std::uint8_t>(x * 60), c};
    });
    buildMipChain(t);
    const Texture& level1 = t.level(1);
    for (int x = 0; x < 2; ++x) {
        const vec4 mean =
            0.25f * (t.texel(2 * x, 0) + t.texel(2 * x + 1, 0) + t.texel(2 * x, 1) + t.texel(2 * x + 1, 1));
        const vec4 got = level1.texel(x, 0);
        // Within half a code step of the mean (re-encoding to 8 bits rounds): steps near ½ are ≈ 0.004.
        for (int c = 0; c < 4; ++c)
            EXPECT_NEAR(got[c], mean[c], 0.003f) << "channel " << c << " texel " << x;
    }
    EXPECT_EQ(level1.codes[0][0], 188);  // linear ½: code 188 decodes to 0.5029, 187 to 0.4969

    // Float textures keep the mean itself.
    Texture f = floatTexture(2, 2, [](int x, int y) { return static_cast<float>(1 + x + 2 * y); });
    buildMipChain(f);
    EXPECT_EQ(f.level(1).texel(0, 0).r, 2.5f);
}

// A constant texture is the same constant on every level, odd sides included: each new texel's
// weights sum to 1.
// Breaks caught: an odd side's footprint weights not divided by its length n/m (a brighter level), or
// the odd last texel left out (weights summing to less than 1).
TEST(Texture, ConstantTextureStaysConstantOnEveryLevel) {
    for (const auto& [width, height] :
         {std::pair{5, 3}, std::pair{7, 7}, std::pair{64, 1}, std::pair{3, 1}}) {
        Texture t = srgbTexture(width, height, [](int, int) { return Texture::Codes{77, 200, 3, 128}; });
        buildMipChain(t);
        for (int level = 1; level < t.levelCount(); ++level)
            for (const Texture::Codes& c : t.level(level).codes)
                EXPECT_EQ(c, (Texture::Codes{77, 200, 3, 128}))
                    << width << "x" << height << " level " << level;
        Texture f = floatTexture(width, height, [](int, int) { return 0.3f; });
        buildMipChain(f);
        for (int level = 1; level < f.levelCount(); ++level)
            for (const vec4& texel : f.level(level).texels)
                EXPECT_NEAR(texel.r, 0.3f, 1e-6f) << width << "x" << height << " level " << level;
    }
}

// An odd side: 3 texels halve to 1, which covers all three equally (area weighting), and 5 to 2, the
// middle texel shared: (a + b + ½c)/2.5 and (½c + d + e)/2.5.
// Breaks caught: the odd texel dropped (a 2-texel box), or given to one side only.
TEST(Texture, OddSidesWeighEveryTexelByItsArea) {
    Texture three =
        floatTexture(3, 1, [](int x, int) { return static_cast<float>(1 << (3 * x)); });  // 1, 8, 64
    buildMipChain(three);
    EXPECT_NEAR(three.level(1).texel(0, 0).r, (1 + 8 + 64) / 3.0f, 1e-4f);
    Texture five = floatTexture(5, 1, [](int x, int) { return static_cast<float>(x * x); });  // 0 1 4 9 16
    buildMipChain(five);
    EXPECT_NEAR(five.level(1).texel(0, 0).r, (0 + 1 + 0.5f * 4) / 2.5f, 1e-5f);
    EXPECT_NEAR(five.level(1).texel(1, 0).r, (0.5f * 4 + 9 + 16) / 2.5f, 1e-5f);
}

// λ = log2 ρ with ρ the footprint's longer side in texels (§8.14.1); trilinear picks and blends the two
// levels around λ, level 0 alone when magnifying, the last level beyond it.
// Breaks caught: ρ from the shorter side (min for max), the texture's size left out of ρ, or the
// blend weight reversed (the coarser level weighted by 1 − frac).
TEST(Texture, TrilinearLevelOfDetail) {
    Texture t = floatTexture(16, 8, [](int, int) { return 0.0f; });
    buildMipChain(t);
    // One texel per 4 pixels across: λ = −2.
    EXPECT_FLOAT_EQ(textureLod(t, {1.0f / 64.0f, 0.0f}, {0.0f, 1.0f / 32.0f}), -2.0f);
    // x: 2 texels a pixel, y: 8: the longer side wins, λ = 3.
    EXPECT_FLOAT_EQ(textureLod(t, {2.0f / 16.0f, 0.0f}, {0.0f, 8.0f / 8.0f}), 3.0f);
    // Distinct levels: level l holds l everywhere.
    for (int level = 0; level < t.levelCount(); ++level)
        for (vec4& texel : level == 0 ? t.texels : t.mipLevels[static_cast<std::size_t>(level - 1)].texels)
            texel.r = static_cast<float>(level);
    const vec2 uv(0.3f, 0.6f);
    EXPECT_EQ(sampleTrilinear(t, uv, {1.0f / 64.0f, 0.0f}, {0.0f, 0.0f}).r, 0.0f);  // λ = −2: level 0
    EXPECT_FLOAT_EQ(sampleTrilinear(t, uv, {4.0f / 16.0f, 0.0f}, {0.0f, 0.0f}).r, 2.0f);  // λ = 2
    // λ = log2 6 = 2.585: 0.415 of level 2 and 0.585 of level 3.
    EXPECT_NEAR(sampleTrilinear(t, uv, {6.0f / 16.0f, 0.0f}, {0.0f, 0.0f}).r, std::log2(6.0f), 1e-5f);
    EXPECT_EQ(sampleTrilinear(t, uv, {0.0f, 0.0f}, {0.0f, 1000.0f}).r, 4.0f);  // beyond the 1×1 level
    EXPECT_EQ(sampleTrilinear(t, uv, {0.0f, 0.0f}, {0.0f, 0.0f}).r, 0.0f);     // a point: level 0
}

}  // namespace
}  // namespace facet
