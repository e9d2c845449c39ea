// The eight-lane bilinear sampler (texture.h) against the one-lane one it must equal bit for bit, and
// the lane helpers it is built on (wide.h's laneMaskOf, gather, gatherWords). Header-only on purpose:
// this file is also compiled alone for x86-64-v3 (facet_pipeline_avx2_tests), where the gathers are
// AVX2 instructions rather than the portable loops the baseline build tests.
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "texture.h"
#include "wide.h"

namespace facet {
namespace {

// Breaks caught: a lane bit read from the wrong position (laneBits out of order).
TEST(TextureLanes, LaneMaskOfSetsTheLanesOfItsBits) {
    for (unsigned bits : {0u, 1u, 0x80u, 0xa5u, 0xffu}) {
        const Int8 mask = laneMaskOf(bits);
        for (int lane = 0; lane < 8; ++lane)
            EXPECT_EQ(mask[lane], ((bits >> lane) & 1) ? -1 : 0) << "bits " << bits << ", lane " << lane;
        EXPECT_EQ(signMask(mask), bits);
    }
}

// Breaks caught: a gather scaled by the wrong element size, or reading the index's lane out of order;
// the 8-bit code lookup reading another entry than its code's.
TEST(TextureLanes, GathersReadTheIndexedElements) {
    std::vector<float> table(300);
    for (std::size_t i = 0; i < table.size(); ++i)
        table[i] = 0.5f + static_cast<float>(i);
    const std::uint8_t bytes[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 0xfe, 0xff, 0x80, 0x7f};
    const Int8 index = {299, 0, 7, 7, 1, 255, 2, 3};
    const Float8 floats = gather(table.data(), index);
    const Int8 words = gatherWords(bytes, index & 3);
    for (int lane = 0; lane < 8; ++lane) {
        EXPECT_EQ(floats[lane], table[static_cast<std::size_t>(index[lane])]) << "lane " << lane;
        const int at = 4 * (index[lane] & 3);
        const std::uint32_t expected = bytes[at] | bytes[at + 1] << 8 | bytes[at + 2] << 16 |
                                       static_cast<std::uint32_t>(bytes[at + 3]) << 24;  // little-endian
        EXPECT_EQ(static_cast<std::uint32_t>(words[lane]), expected) << "lane " << lane;
    }
    std::array<float, 256> codeTable;
    for (std::size_t code = 0; code < codeTable.size(); ++code)
        codeTable[code] = table[code];
    const Float8 decoded = lookupByteCodes(codeTable, index & 0xff);
    for (int lane = 0; lane < 8; ++lane)
        EXPECT_EQ(decoded[lane], table[static_cast<std::size_t>(index[lane] & 0xff)]) << "lane " << lane;
}

// An 8-bit texture with random codes, its colour decoded through a table that is not code/255, so
// that a channel decoded the wrong way or from the wrong byte shows.
Texture codedTexture(int width, int height, std::mt19937& random) {
    Texture t;
    t.width = width;
    t.height = height;
    t.codes.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    for (Texture::Codes& c : t.codes)
        for (std::uint8_t& channel : c)
            channel = static_cast<std::uint8_t>(random() & 0xffu);
    for (int code = 0; code < 256; ++code)
        t.colorFromCode[code] = std::pow(static_cast<float>(code) / 255.0f, 2.2f);
    return t;
}

Texture floatTexture(int width, int height, std::mt19937& random) {
    Texture t;
    t.width = width;
    t.height = height;
    std::uniform_real_distribution<float> value(-2.0f, 2.0f);
    t.texels.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
    for (vec4& texel : t.texels)
        texel = vec4(value(random), value(random), value(random), value(random));
    return t;
}

bool sameBits(float a, float b) {
    return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
}

// One lane's texture coordinate: mostly inside the texture (the gathering path), sometimes on the
// last texel's centre and beyond (wrapping), far outside, or not finite (each lane alone).
float coordinate(std::mt19937& random, int size, bool inside) {
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const float half = 0.5f / static_cast<float>(size);
    if (inside) return 1.5f * half + unit(random) * (1.0f - 3.0f * half);
    switch (random() % 8) {
        case 0:
            return 1.0f - half;  // the last texel's centre: its right neighbour wraps to 0
        case 1:
            return half * unit(random);  // left of the first centre: wraps to the last texel
        case 2:
            return -3.0f + 7.0f * unit(random);
        case 3:
            return 3.0e7f * (unit(random) - 0.5f);  // beyond 2^24 texels: wrapTexel's fmod
        case 4:
            return std::numeric_limits<float>::quiet_NaN();
        case 5:
            return random() % 2 ? std::numeric_limits<float>::infinity()
                                : -std::numeric_limits<float>::infinity();
        default:
            return unit(random);
    }
}

// Every alpha code computed eight at a time, as the eight-lane sampler does, gives the one-lane bits.
// Breaks caught: the opaque lanes chosen by another comparison, or a division where the one-lane
// function multiplies by 1/255 (a last-bit difference in some lanes).
TEST(TextureLanes, EightAlphaCodesGiveTheBitsOfOneAtATime) {
    for (int first = 0; first < 256; first += 8) {
        const Int8 codes = Int8{0, 1, 2, 3, 4, 5, 6, 7} + first;
        const Float8 alpha = alphaFromCode(codes);
        for (int lane = 0; lane < 8; ++lane)
            EXPECT_TRUE(sameBits(alpha[lane], alphaFromCode(first + lane))) << "code " << first + lane;
    }
}

// Breaks caught: the texel below taken one texel to the right (i01 = i00 + 1); the two weights or
// the two mixes swapped; a channel read from another byte or decoded through the other table; a dead
// lane not white; a batch with a lane that must wrap sampled without wrapping; a float texture's
// channel k read at 4·i + k − 1; under AddressSanitizer, a batch without live lanes reading texels a
// 1×1 texture does not have.
TEST(TextureLanes, EightLanesGiveTheBitsOfOneLaneAtATime) {
    std::mt19937 random(20261201);
    const int sizes[][2] = {{1, 1}, {2, 1}, {1, 3}, {2, 2}, {5, 4}, {64, 32}, {257, 130}};
    int batches = 0, gathered = 0;
    for (const auto& [width, height] : sizes)
        for (const bool coded : {true, false}) {
            const Texture t =
                coded ? codedTexture(width, height, random) : floatTexture(width, height, random);
            for (int b = 0; b < 400; ++b) {
                // Half the batches have every lane inside the texture (the gathering path); in the
                // rest each lane may be anywhere.
                const bool allInside = b % 2 == 0 && width > 1 && height > 1;
                Vec2x8 uv;
                for (int lane = 0; lane < 8; ++lane) {
                    const bool inside = allInside || random() % 4 != 0;
                    uv.x[lane] = coordinate(random, width, inside && width > 1);
                    uv.y[lane] = coordinate(random, height, inside && height > 1);
                }
                const unsigned live = b % 5 == 0 ? 0xffu : static_cast<unsigned>(random() & 0xffu);
                const Vec4x8 lanes8 = sampleBilinear(t, uv, live);
                ++batches;
                gathered += allInside;
                for (int lane = 0; lane < 8; ++lane) {
                    const vec4 expected =
                        (live >> lane) & 1 ? sampleBilinear(t, vec2(uv.x[lane], uv.y[lane])) : vec4(1.0f);
                    const vec4 got(lanes8.x[lane], lanes8.y[lane], lanes8.z[lane], lanes8.w[lane]);
                    for (int k = 0; k < 4; ++k)
                        ASSERT_TRUE(sameBits(got[k], expected[k]))
                            << width << "x" << height << (coded ? " codes" : " floats") << ", batch " << b
                            << ", lane " << lane << " (live " << ((live >> lane) & 1) << "), channel " << k
                            << ": uv (" << uv.x[lane] << ", " << uv.y[lane] << ") gives " << got[k]
                            << ", one lane gives " << expected[k];
                }
            }
        }
    EXPECT_GT(gathered, batches / 4);  // the gathering path was taken
}

// Breaks caught: an empty texture not answering white in every lane.
TEST(TextureLanes, AnEmptyTextureIsWhite) {
    const Texture empty;
    const Vec2x8 uv{splat(0.25f), splat(std::numeric_limits<float>::quiet_NaN())};
    const Vec4x8 texel = sampleBilinear(empty, uv, 0xffu);
    for (int lane = 0; lane < 8; ++lane)
        EXPECT_EQ(vec4(texel.x[lane], texel.y[lane], texel.z[lane], texel.w[lane]), vec4(1.0f));
}

}  // namespace
}  // namespace facet
