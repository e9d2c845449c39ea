// Sixteen lanes (pipeline/wide.h's Floatx16, the AVX-512 copy's): every function the shaders call on
// sixteen lanes gives, lane by lane, the bits its eight-lane version gives each half (which the other
// tests hold to the one-lane version), so a pixel is the same whether it was shaded eight or sixteen at
// a time. Compiled alone for x86-64-v4 (facet_sixteen_lane_tests) and run only on a CPU with AVX-512.
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "../support/patch_checks.h"
#include "shaders/shaders.h"
#include "shaders/user_shader.h"

#if !FACET_SIXTEEN_LANES
#error "compiled for an instruction set with 512-bit registers (tests/CMakeLists.txt)"
#endif

namespace facet {
namespace {

using namespace glsl;

constexpr float kInf = std::numeric_limits<float>::infinity();

std::uint32_t bits(float v) {
    return std::bit_cast<std::uint32_t>(v);
}

// Values with negatives, both zeros, tiny and huge ones, infinities and NaN, sixteen at every offset.
const std::vector<float>& spread() {
    static const std::vector<float> values = {-kInf, -3e38f,  -1e30f, -1000.5f,     -7.3f,  -2.5f, -1.0f,
                                              -0.5f, -1e-30f, -0.0f,  0.0f,         1e-30f, 1e-7f, 0.1f,
                                              0.25f, 0.5f,    0.75f,  1.0f,         1.5f,   2.5f,  7.3f,
                                              42.0f, 1e30f,   kInf,   std::nanf("")};
    return values;
}
Floatx16 sixteen(int first, int stride = 1) {
    Floatx16 r;
    for (int lane = 0; lane < 16; ++lane)
        r[lane] = spread()[static_cast<std::size_t>(first + lane * stride) % spread().size()];
    return r;
}

// The same bits, or both NaN: which of two NaN operands a product passes on (and so the sign of the
// NaN) follows the order the compiler puts them in, its choice in each copy of the code.
void expectSameLanes(Floatx16 got, Float8 low, Float8 high, const char* name, int first) {
    for (int lane = 0; lane < 16; ++lane) {
        const float expected = lane < 8 ? low[lane] : high[lane - 8];
        if (std::isnan(expected) && std::isnan(got[lane])) continue;
        EXPECT_EQ(bits(got[lane]), bits(expected)) << name << " at offset " << first << ", lane " << lane;
    }
}

// f on sixteen lanes against f on each half as eight, over every offset of the spread.
template <class Fn>
void expectUnary(const char* name, Fn f) {
    for (int first = 0; first < static_cast<int>(spread().size()); ++first) {
        const Floatx16 x = sixteen(first);
        expectSameLanes(f(x), f(lowHalf(x)), f(highHalf(x)), name, first);
    }
}
template <class Fn>
void expectBinary(const char* name, Fn f) {
    for (int first = 0; first < static_cast<int>(spread().size()); ++first) {
        const Floatx16 a = sixteen(first), b = sixteen(first * 2 + 1, 3);
        expectSameLanes(f(a, b), f(lowHalf(a), lowHalf(b)), f(highHalf(a), highHalf(b)), name, first);
    }
}

// Breaks caught: a sixteen-lane function that computes otherwise than the eight-lane one (another
// order of operations, a fused multiply-add, a comparison that treats NaN or −0 differently, a loop
// over eight lanes only, the AVX-512 reciprocal square root estimate in place of the AVX one).
TEST(SixteenLanes, ScalarFunctionsGiveTheEightLaneBitsOfEachHalf) {
    expectUnary("sqrt", [](auto x) { return sqrt(x); });
    expectUnary("abs", [](auto x) { return abs(x); });
    expectUnary("floor", [](auto x) { return floor(x); });
    expectUnary("ceil", [](auto x) { return ceil(x); });
    expectUnary("fract", [](auto x) { return fract(x); });
    expectUnary("sign", [](auto x) { return sign(x); });
    expectUnary("sin", [](auto x) { return sin(x); });
    expectUnary("saturate", [](auto x) { return saturate(x); });
    expectUnary("clamp", [](auto x) { return clamp(x, -1.0f, 2.0f); });
    expectUnary("step", [](auto x) { return step(0.5f, x); });
    expectUnary("smoothstep", [](auto x) { return smoothstep(0.0f, 2.0f, x); });
    expectUnary("fast log2", [](auto x) { return log2(abs(x)); });
    expectUnary("fast exp2", [](auto x) { return exp2(x); });
    expectUnary("fast pow", [](auto x) { return pow(abs(x), 12.5f); });
    expectUnary("exact pow", [](auto x) { return Maths<MathPrecision::Exact>::pow(abs(x), 12.5f); });
    expectUnary("fast 1/sqrt", [](auto x) { return fastInverseSqrt(abs(x)); });
    expectUnary("sRGB", [](auto x) { return linearToSrgb(x); });
    expectBinary("min", [](auto a, auto b) { return min(a, b); });
    expectBinary("max", [](auto a, auto b) { return max(a, b); });
    expectBinary("mod", [](auto a, auto b) { return mod(a, b); });
    expectBinary("mix", [](auto a, auto b) { return mix(a, b, saturate(b)); });
    expectBinary("pow per lane", [](auto a, auto b) { return pow(abs(a), b); });
    expectBinary("select", [](auto a, auto b) { return select(a < b, a, b); });
}

// Breaks caught: a vector function of sixteen lanes mixing up components, or normalising otherwise.
TEST(SixteenLanes, VectorFunctionsGiveTheEightLaneBitsOfEachHalf) {
    for (int first = 0; first < static_cast<int>(spread().size()); ++first) {
        const Vec3x16 a(sixteen(first), sixteen(first + 3, 5), sixteen(first + 7, 2));
        const Vec3x16 b(sixteen(first + 1, 7), sixteen(first + 2), sixteen(first + 11, 3));
        auto check = [&](const char* name, auto f) {
            const Vec3x16 got = f(a, b);
            const Vec3x8 low = f(lowHalf(a), lowHalf(b)), high = f(highHalf(a), highHalf(b));
            expectSameLanes(got.x, low.x, high.x, name, first);
            expectSameLanes(got.y, low.y, high.y, name, first);
            expectSameLanes(got.z, low.z, high.z, name, first);
        };
        check("normalize", [](const auto& u, const auto&) { return normalize(u); });
        check("safeNormalize", [](const auto& u, const auto&) {
            return safeNormalize<decltype(u.x), std::decay_t<decltype(u)>, Normalization::Fast>(u);
        });
        check("cross", [](const auto& u, const auto& v) { return cross(u, v); });
        check("reflect", [](const auto& u, const auto& v) { return reflect(u, normalize(v)); });
        check("mix", [](const auto& u, const auto& v) { return mix(u, v, 0.25f); });
        check("dot", [](const auto& u, const auto& v) {
            const auto d = dot(u, v);
            return std::decay_t<decltype(u)>(d, d, d);
        });
    }
}

// The lane helpers of sixteen lanes. Breaks caught: a mask bit read from the wrong lane, a sign mask
// of eight bits only, a gather that reads the index lanes out of order.
TEST(SixteenLanes, MasksAndGathersCoverAllSixteenLanes) {
    for (unsigned mask : {0u, 1u, 0x8000u, 0xa5c3u, 0xffffu}) {
        const Intx16 lanesOf = laneMaskOf<Floatx16>(mask);
        for (int lane = 0; lane < 16; ++lane)
            EXPECT_EQ(lanesOf[lane], ((mask >> lane) & 1) ? -1 : 0) << "mask " << mask << ", lane " << lane;
        EXPECT_EQ(signMask(lanesOf), mask);
    }
    float table[64];
    for (int i = 0; i < 64; ++i)
        table[i] = static_cast<float>(i) * 1.5f;
    Intx16 index;
    for (int lane = 0; lane < 16; ++lane)
        index[lane] = (lane * 7 + 3) % 64;
    const Floatx16 gathered = gather(table, index);
    const Intx16 words = gatherWords(table, index);
    for (int lane = 0; lane < 16; ++lane) {
        EXPECT_EQ(gathered[lane], table[index[lane]]) << "lane " << lane;
        EXPECT_EQ(words[lane], std::bit_cast<std::int32_t>(table[index[lane]])) << "lane " << lane;
    }
}

// Every 8-bit code through the 256-entry table lookup of sixteen lanes (eight permutes and a choice by
// the code's top three bits), each code in every lane. Breaks caught: an eighth of the table read from
// the wrong place, the choice by bit 5, 6 or 7 inverted or swapped, a lane's code taken from another.
TEST(SixteenLanes, ByteCodeLookupReadsEveryEntryInEveryLane) {
    std::array<float, 256> table;
    for (int code = 0; code < 256; ++code)
        table[static_cast<std::size_t>(code)] = static_cast<float>(code) * 1.5f + 0.25f;
    for (int start = 0; start < 256; ++start) {
        Intx16 code;
        for (int lane = 0; lane < 16; ++lane)
            code[lane] = (start + lane * 17) % 256;
        const Floatx16 looked = lookupByteCodes(table, code);
        for (int lane = 0; lane < 16; ++lane)
            ASSERT_EQ(looked[lane], table[static_cast<std::size_t>(code[lane])])
                << "code " << code[lane] << " in lane " << lane;
    }
}

// Breaks caught: sixteen-lane bilinear filtering that weighs, decodes or addresses texels otherwise
// than eight lanes (or one) do, or takes the gathering path where one lane would wrap.
TEST(SixteenLanes, BilinearSamplesGiveTheEightLaneBitsOfEachHalf) {
    std::mt19937 random(20261207);
    Texture coded, linear;
    coded.width = linear.width = 37;
    coded.height = linear.height = 21;
    for (int i = 0; i < coded.width * coded.height; ++i) {
        coded.codes.push_back({static_cast<std::uint8_t>(random()), static_cast<std::uint8_t>(random()),
                               static_cast<std::uint8_t>(random()), static_cast<std::uint8_t>(random())});
        linear.texels.push_back(vec4(static_cast<float>(random() % 1000) / 999.0f, 0.5f, 0.25f, 1.0f));
    }
    for (int code = 0; code < 256; ++code)
        coded.colorFromCode[static_cast<std::size_t>(code)] =
            std::pow(static_cast<float>(code) / 255.0f, 2.2f);
    std::uniform_real_distribution<float> inside(0.05f, 0.95f), anywhere(-1.5f, 2.5f);
    for (const Texture* t : {&coded, &linear})
        for (int b = 0; b < 200; ++b) {
            Vec2x16 uv;
            for (int lane = 0; lane < 16; ++lane) {
                uv.x[lane] = b % 2 ? inside(random) : anywhere(random);
                uv.y[lane] = b % 2 ? inside(random) : anywhere(random);
            }
            const unsigned live = b % 3 ? 0xffffu : static_cast<unsigned>(random() & 0xffffu);
            const Vec4x16 got = sampleBilinear(*t, uv, live);
            const Vec4x8 low = sampleBilinear(*t, lowHalf(uv), live & 0xffu);
            const Vec4x8 high = sampleBilinear(*t, highHalf(uv), live >> 8);
            expectSameLanes(got.x, low.x, high.x, "red", b);
            expectSameLanes(got.y, low.y, high.y, "green", b);
            expectSameLanes(got.z, low.z, high.z, "blue", b);
            expectSameLanes(got.w, low.w, high.w, "alpha", b);
        }
}

// The built-in per-pixel shader on sixteen lanes against eight, textured, lit by two lights, with fog
// and each reflection model. Breaks caught: a part of the lighting that takes sixteen lanes for eight
// (a texture lookup or a shadow test of one half only), or a live-lane mask cut to eight bits.
TEST(SixteenLanes, ThePerPixelShaderGivesTheEightLaneBitsOfEachHalf) {
    std::mt19937 random(7);
    Texture map;
    map.width = map.height = 8;
    for (int i = 0; i < 64; ++i)
        map.texels.push_back(
            vec4(static_cast<float>(i) / 64.0f, 0.5f, 1.0f - static_cast<float>(i) / 64.0f, 1.0f));
    SurfaceUniforms u;
    u.lightCount = 2;
    u.lights[0].position = vec3(2.0f, 3.0f, 1.0f);
    u.lights[1].kind = LightKind::Directional;
    u.lights[1].direction = normalize(vec3(1.0f, -0.5f, -2.0f));
    u.diffuseMap = &map;
    u.fog.mode = FogMode::Exponential;
    u.fog.density = 0.2f;
    std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
    for (const ReflectionModel model :
         {ReflectionModel::BlinnPhong, ReflectionModel::Phong, ReflectionModel::CookTorrance}) {
        u.reflection = model;
        PerPixelSurface::VaryingsT<Floatx16> in;
        Floatx16* floats = reinterpret_cast<Floatx16*>(&in);
        for (int k = 0; k < 8; ++k)
            for (int lane = 0; lane < 16; ++lane)
                floats[k][lane] = k == 2 ? -3.0f + coordinate(random) : coordinate(random);
        PerPixelSurface::VaryingsT<Float8> low, high;
        Float8* lowFloats = reinterpret_cast<Float8*>(&low);
        Float8* highFloats = reinterpret_cast<Float8*>(&high);
        for (int k = 0; k < 8; ++k) {
            lowFloats[k] = lowHalf(floats[k]);
            highFloats[k] = highHalf(floats[k]);
        }
        const unsigned live = 0xbeefu;
        const Vec4x16 got = PerPixelSurface::shade<Floatx16>(in, u, live);
        const Vec4x8 lowShaded = PerPixelSurface::shade<Float8>(low, u, live & 0xffu);
        const Vec4x8 highShaded = PerPixelSurface::shade<Float8>(high, u, live >> 8);
        const int name = static_cast<int>(model);
        expectSameLanes(got.x, lowShaded.x, highShaded.x, "red", name);
        expectSameLanes(got.y, lowShaded.y, highShaded.y, "green", name);
        expectSameLanes(got.z, lowShaded.z, highShaded.z, "blue", name);
        expectSameLanes(got.w, lowShaded.w, highShaded.w, "alpha", name);
    }
}

// The patch walk of the AVX-512 copy (4×4 or 8×2 pixels in sixteen lanes): coverage, edge values and
// barycentrics as the per-pixel test and the block walk give them (support/patch_checks.h).
TEST(SixteenLanes, PatchCoverageMatchesThePerPixelTest) {
    testing_support::expectPatchCoverageMatchesTheOracle<Intx16, kNarrowPatch>();
}
TEST(SixteenLanes, WidePatchCoverageMatchesThePerPixelTest) {
    testing_support::expectPatchCoverageMatchesTheOracle<Intx16, kWidePatch>();
}

// Tiny triangles drawn as 4×4 and 8×2 patches of sixteen lanes against the block walk: the same bytes.
TEST(SixteenLanes, PatchWalkDrawsTheBlockWalksBytes) {
    testing_support::expectPatchWalkDrawsTheBlockWalksBytes();
}

}  // namespace
}  // namespace facet
