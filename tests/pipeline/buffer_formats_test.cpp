// The depth and colour buffer formats (depth_format.h, blend.h's roundToColorBuffer): the values each
// stores, checked against hand computations; reversed Z's clipping; z-fighting of two parallel planes
// for each depth format and near/far ratio, against the resolution a double-precision formula predicts
// (the table printed here is the one in docs/trade.md); and blending in an 8-bit or half colour buffer.
#include <cpuid.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <immintrin.h>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "../support/test_shaders.h"
#include "blend.h"
#include "clip.h"
#include "depth_format.h"

namespace facet {
namespace {

using testing::ClipSpaceColorShader;
using Unorm16 = DepthFormatOf<DepthBufferFormat::Unorm16>;
using Unorm24 = DepthFormatOf<DepthBufferFormat::Unorm24>;
using Reversed = DepthFormatOf<DepthBufferFormat::ReversedFloat>;

// Unorm codes: round(z·(2^N − 1)). 0.5·65535 = 32767.5 rounds to 32768; 0.5·(2^24 − 1) = 8388607.5 to
// 8388608; 2/3 (as a float, 0.66666669) · (2^24 − 1) = 11184810.3 to 11184810. Out of [0, 1] clamps.
// Breaks if the code is truncated instead of rounded (32767), scaled by 2^N (32768 but 65536 for 1),
// or not clamped.
TEST(DepthBufferFormats, UnormStoresTheRoundedCode) {
    EXPECT_EQ(Unorm16::store(0.5f), 32768.0f);
    EXPECT_EQ(Unorm16::store(1.0f), 65535.0f);
    EXPECT_EQ(Unorm16::store(0.0f), 0.0f);
    EXPECT_EQ(Unorm16::store(1.0f / 65535.0f * 0.49f), 0.0f);
    EXPECT_EQ(Unorm16::store(1.0f / 65535.0f * 0.51f), 1.0f);
    EXPECT_EQ(Unorm16::store(1.5f), 65535.0f);
    EXPECT_EQ(Unorm16::store(-0.5f), 0.0f);
    EXPECT_EQ(Unorm24::store(0.5f), 8388608.0f);
    EXPECT_EQ(Unorm24::store(2.0f / 3.0f), 11184810.0f);
    EXPECT_EQ(Unorm24::store(1.0f), 16777215.0f);
    EXPECT_EQ(Unorm16::kClear, 65535.0f);
    EXPECT_EQ(Unorm24::kClear, 16777215.0f);
    EXPECT_EQ(Reversed::kClear, 0.0f);
    EXPECT_EQ(DepthFormat::kClear, 1.0f);
    EXPECT_EQ(Unorm16::kResolution, 1.0f / 65535.0f);
    // The fragment is converted before the compare: 0.50000001 and 0.5 are the same code, so Less fails.
    EXPECT_FALSE(Unorm16::passes(CompareOp::Less, 0.5f, Unorm16::store(0.5000076f)));
    EXPECT_TRUE(DepthFormat::passes(CompareOp::Less, 0.5f, DepthFormat::store(0.5000076f)));
}

// The eight-lane store (add-and-remove 2^23) gives the one-lane std::nearbyint's codes, ties included.
// Breaks if either rounds differently (half away from zero in one of them, say).
TEST(DepthBufferFormats, EightLaneCodesAgreeWithOneLane) {
    for (int start = 0; start < 4096; start += 8) {
        Float8 z;
        for (int lane = 0; lane < 8; ++lane)
            z[lane] = float(start + lane) / 4095.0f + (lane % 2 ? 0.5f / 65535.0f : 0.0f);
        const Float8 codes16 = Unorm16::store(z), codes24 = Unorm24::store(z);
        for (int lane = 0; lane < 8; ++lane) {
            EXPECT_EQ(codes16[lane], Unorm16::store(z[lane])) << z[lane];
            EXPECT_EQ(codes24[lane], Unorm24::store(z[lane])) << z[lane];
        }
    }
}

// Reversed Z's window depth is NDC z itself (no (z + 1)/2), clamped to [0, 1]; the others keep OpenGL's.
// Breaks if reversed Z halved like OpenGL (0.75 for NDC 0.5).
TEST(DepthBufferFormats, ReversedWindowDepthIsNdcDepth) {
    EXPECT_EQ(Reversed::windowDepth(1.0f, 0.0f, 1.0f), 1.0f);
    EXPECT_EQ(Reversed::windowDepth(0.5f, 0.0f, 1.0f), 0.5f);
    EXPECT_EQ(Reversed::windowDepth(1e-30f, 0.0f, 1.0f), 1e-30f);  // the float precision kept near 0
    EXPECT_EQ(Reversed::windowDepth(-0.1f, 0.0f, 1.0f), 0.0f);
    EXPECT_EQ(DepthFormat::windowDepth(0.5f, 0.0f, 1.0f), 0.75f);
    EXPECT_EQ(toWindow({0, 0, 0.25f, 1}, {0, 0, 4, 4}, 8, DepthBufferFormat::ReversedFloat).z, 0.25f);
    EXPECT_EQ(toWindow({0, 0, 0.25f, 1}, {0, 0, 4, 4}, 8, DepthBufferFormat::Unorm16).z, 0.625f);
}

// Reversed Z clips to 0 ≤ z ≤ w, the near plane at z = w: a point at z = 1.5w is beyond the near plane,
// one at z = −0.1w beyond the far plane, and a triangle crossing z = 0 is cut there. Breaks if clipping
// kept −w ≤ z ≤ w under reversed Z (the point at −0.1w would be drawn, behind the far plane).
TEST(DepthBufferFormats, ReversedZClipsToZeroToW) {
    const ClipDepthRange reversed = ClipDepthRange::ReversedZeroToW;
    EXPECT_EQ(computeOutcode({0, 0, 0.5f, 1}, reversed), 0);
    EXPECT_EQ(computeOutcode({0, 0, 1.5f, 1}, reversed), kClipNear);
    EXPECT_EQ(computeOutcode({0, 0, -0.1f, 1}, reversed), kClipFar);
    EXPECT_EQ(computeOutcode({0, 0, -0.1f, 1}), 0);
    ClipPolygon polygon;
    polygon.count = 3;
    polygon.vertices[0].position = {-0.5f, -0.5f, 0.5f, 1};
    polygon.vertices[1].position = {0.5f, -0.5f, 0.5f, 1};
    polygon.vertices[2].position = {0, 0.5f, -0.5f, 1};
    clipPolygon(polygon, kClipFar, reversed);
    ASSERT_EQ(polygon.count, 4);
    for (int i = 0; i < polygon.count; ++i)
        EXPECT_GE(polygon.vertices[i].position.z, 0.0f);
}

// ---- z-fighting ----------------------------------------------------------------------------------

// Two parallel planes, tilted so that their depth spans ±18% across the view (every pixel sees its own
// depth), at eye distance d and d·(1 + gap); the far one (green) is drawn first, then the near one
// (red). Returns the share of pixels where the near one loses: the planes' depths stored as the same
// value (or both as the far plane's).
double zFightShare(DepthBufferFormat format, double near, double far, double d, double gap) {
    constexpr int kSide = 64;
    constexpr double kFovy = 40.0;
    Framebuffer fb(kSide, kSide);
    fb.clearColor(vec4(0.0f));
    fb.clearDepth(depthClearValue(format));
    glm::dmat4 clipFromEye = glm::perspective(glm::radians(kFovy), 1.0, near, far);
    if (format == DepthBufferFormat::ReversedFloat) {
        glm::dmat4 reversed(1.0);  // z' = (w − z)/2, as the renderer's drawnClipFromView
        reversed[2][2] = -0.5;
        reversed[3][2] = 0.5;
        clipFromEye = reversed * clipFromEye;
    }
    const mat4 clipFromEyeF(clipFromEye);  // rounded to float once, as the renderer's uniforms
    const double t = std::tan(glm::radians(kFovy) / 2.0);
    auto plane = [&](double distance, vec4 color) {
        std::vector<ClipSpaceColorShader::Attributes> v;
        for (vec2 corner : {vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1)}) {
            const double x = 1.2 * d * t * corner.x, y = 1.2 * d * t * corner.y;
            const double z = -(distance + 0.15 * y / t);
            v.push_back({clipFromEyeF * vec4(float(x), float(y), float(z), 1.0f), color});
        }
        return v;
    };
    DrawState state = testing::stateFor(fb);
    state.depth.format = format;
    state.depth.compare = nearerPasses(format, CompareOp::Less);
    const vec4 green(0, 1, 0, 1), red(1, 0, 0, 1);
    testing::drawTriangles<ClipSpaceColorShader>(state, plane(d * (1.0 + gap), green), fb);
    testing::drawTriangles<ClipSpaceColorShader>(state, plane(d, red), fb);
    // The near plane loses where the far one's depth stored the same value, and also where both
    // stored the clear value (the far plane's), so that neither was drawn.
    int nearLoses = 0;
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x)
            nearLoses += !(fb.color(x, y).r > 0.5f);  // interpolation may leave red a rounding off 1
    return double(nearLoses) / (kSide * kSide);
}

// The smallest relative change of eye distance, Δd/d, that the format's stored depth resolves at
// distance d: the buffer's step in window depth divided by |dz_w/dd|·d, in double.
//   standard: z_w = f(d − n)/(d(f − n)), |dz_w/dd| = fn/(d²(f − n));
//   reversed: z_w = n(f − d)/(d(f − n)), the same slope;
//   step: 1/(2^N − 1) for unorm; the float spacing at z_w, 2^(⌊log2 z_w⌋ − 23), for float.
double relativeResolution(DepthBufferFormat format, double near, double far, double d) {
    const double slope = far * near / (d * d * (far - near));
    const double windowDepth = format == DepthBufferFormat::ReversedFloat
                                   ? near * (far - d) / (d * (far - near))
                                   : far * (d - near) / (d * (far - near));
    double step = 0;
    switch (format) {
        case DepthBufferFormat::Unorm16:
            step = 1.0 / 65535.0;
            break;
        case DepthBufferFormat::Unorm24:
            step = 1.0 / 16777215.0;
            break;
        default:
            step = std::ldexp(1.0, int(std::floor(std::log2(windowDepth))) - 23);
    }
    return step / (slope * d);
}

// The tolerance: a gap four times the resolution never fights (share 0: two depths that far apart
// cannot store the same value, whatever the rounding of the transform); a gap a quarter of it fights
// at most pixels (share > 1/2: the same value over about 1 − gap/resolution of them).
// The second holds only where the buffer's step is far coarser than the rounding of the float vertex
// transform (about 2^-24 of z_c, as large as the step of unorm24 and float): there the two planes'
// four corners round on their own, and whole planes tie or separate together (`fightsExpected` false).
void expectShareFitsResolution(double share, double resolution, double gap, bool fightsExpected,
                               const std::string& what) {
    if (resolution * 4.0 < gap) {
        EXPECT_EQ(share, 0.0) << what << ": resolution " << resolution;
    }
    if (fightsExpected && resolution > gap * 4.0) {
        EXPECT_GT(share, 0.5) << what << ": resolution " << resolution;
    }
}

constexpr DepthBufferFormat kFormats[] = {DepthBufferFormat::Unorm16, DepthBufferFormat::Unorm24,
                                          DepthBufferFormat::Float, DepthBufferFormat::ReversedFloat};

// For far = 1000, planes at d = 500 with a relative gap of 1e-4, near = far·ratio for ratios 1e-1 … 1e-7:
// each format's share of z-fighting pixels agrees with its resolution (expectShareFitsResolution), and
// the table (docs/trade.md) is printed. Breaks if a format's stored depth is coarser or finer than it
// should be (unorm scaled by 2^8 fewer codes, reversed Z halved like OpenGL, the unorm compare made on
// unrounded depths).
TEST(DepthBufferFormats, ZFightingFollowsEachFormatsResolution) {
    const double far = 1000.0, d = 500.0, gap = 1e-4;
    std::printf(
        "near/far   unorm16  unorm24  float  reversed-float   (share of pixels where the near plane "
        "loses)\n");
    for (int exponent = 1; exponent <= 7; ++exponent) {
        const double ratio = std::pow(10.0, -exponent);
        const double near = far * ratio;
        std::printf("1e-%d    ", exponent);
        for (DepthBufferFormat format : kFormats) {
            const double share = zFightShare(format, near, far, d, gap);
            std::printf(" %6.1f%%", 100.0 * share);
            expectShareFitsResolution(
                share, relativeResolution(format, near, far, d), gap, format == DepthBufferFormat::Unorm16,
                std::string(nameOf(format)) + " near/far 1e-" + std::to_string(exponent));
        }
        std::printf("\n");
    }
}

// The cases of the issue: at the same near/far, unorm16 fights where unorm24 does not; float with near
// 0.1 and far 1e4 cannot separate a gap of 1e-5 at d = 100 (its resolution there is 6e-5 relative),
// while reversed float separates 1e-6 (about 1.2e-7 relative at any distance). Breaks if reversed Z is
// dropped (the reversed-float plane pair would fight like float's) or unorm24 stored 16 bits.
TEST(DepthBufferFormats, ZFightingCasesOfTheIssue) {
    EXPECT_GT(zFightShare(DepthBufferFormat::Unorm16, 0.1, 100.0, 10.0, 2.5e-4), 0.5);
    EXPECT_EQ(zFightShare(DepthBufferFormat::Unorm24, 0.1, 100.0, 10.0, 2.5e-4), 0.0);
    EXPECT_NEAR(relativeResolution(DepthBufferFormat::Float, 0.1, 1e4, 100.0), 6e-5, 1e-5);
    EXPECT_GT(zFightShare(DepthBufferFormat::Float, 0.1, 1e4, 100.0, 1e-5), 0.5);
    EXPECT_LT(relativeResolution(DepthBufferFormat::ReversedFloat, 0.1, 1e4, 100.0), 2.5e-7);
    EXPECT_EQ(zFightShare(DepthBufferFormat::ReversedFloat, 0.1, 1e4, 100.0, 1e-6), 0.0);
}

// ---- colour buffer -------------------------------------------------------------------------------

// Ten full-screen layers of grey 0.61 at alpha 0.5, blended over black: in an 8-bit buffer each step is
// rounded to a multiple of 1/255, as the hand computation here does, and the result differs from the
// float buffer's. Breaks if the 8-bit buffer is not rounded after a blend (or only at the end).
TEST(ColorBufferFormats, EightBitBlendingRoundsAfterEveryLayer) {
    auto layers = [](ColorBufferFormat format) {
        Framebuffer fb(16, 8);
        fb.clearColor(vec4(0.0f));
        DrawState state = testing::stateFor(fb);
        state.blend = BlendMode::Over;
        state.depth.testEnabled = false;  // every layer at the same depth is blended
        state.colorBuffer = format;
        std::vector<ClipSpaceColorShader::Attributes> quad;
        for (vec2 p : {vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1)})
            quad.push_back({vec4(p, 0.0f, 1.0f), vec4(0.61f, 0.61f, 0.61f, 0.5f)});
        for (int layer = 0; layer < 10; ++layer)
            testing::drawTriangles<ClipSpaceColorShader>(state, quad, fb);
        return fb.color(3, 5);
    };
    double c = 0.0, a = 0.0;  // by hand: c = 0.5·0.61 + 0.5·c, then round(c·255)/255; likewise alpha
    for (int layer = 0; layer < 10; ++layer) {
        c = std::round((0.5 * 0.61 + 0.5 * c) * 255.0) / 255.0;
        a = std::round((0.5 + 0.5 * a) * 255.0) / 255.0;
    }
    const vec4 eightBit = layers(ColorBufferFormat::Unorm8);
    EXPECT_EQ(eightBit.r, float(std::round(c * 255.0)) / 255.0f);
    EXPECT_EQ(eightBit.a, float(std::round(a * 255.0)) / 255.0f);
    EXPECT_NE(layers(ColorBufferFormat::Float).r, eightBit.r);
}

// What F16C's conversion (round to nearest even) gives, back as a float. Compiled for F16C whatever the
// build's level: the tests that call it skip on a CPU without it.
[[gnu::target("f16c")]] float f16c(float x) {
    return _cvtsh_ss(_cvtss_sh(x, _MM_FROUND_TO_NEAREST_INT));
}

bool cpuHasF16c() {  // CPUID leaf 1, ECX bit 29
    unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
    return __get_cpuid(1, &eax, &ebx, &ecx, &edx) && (ecx & bit_F16C);
}

// Half: 1/3 is stored as half(1/3) = 0.333251953125, every value as the hardware conversion rounds it
// (subnormals and ties included), and beyond the largest half, 65504, clamped there: never Inf. Breaks
// if the half rounding truncates (0.33300781), keeps 12 bits, or lets 65520 overflow to infinity.
TEST(ColorBufferFormats, HalfRoundsLikeTheHardwareAndNeverOverflows) {
    if (!cpuHasF16c()) GTEST_SKIP() << "this CPU has no F16C to compare with";
    EXPECT_EQ(roundToHalf(1.0f / 3.0f), 0.333251953125f);
    EXPECT_EQ(roundToHalf(1.0f / 3.0f), f16c(1.0f / 3.0f));
    for (float x : {0.0f, 1.0f, 0.1f, 2049.0f, 2051.0f, 1e-5f, 3e-8f, 6e-8f, 1e-7f, -0.7f, 65503.0f, 65519.0f,
                    1.0f + 0x1p-11f, 1.0f + 3 * 0x1p-11f})
        EXPECT_EQ(roundToHalf(x), f16c(x)) << x;
    EXPECT_EQ(roundToHalf(65520.0f), 65504.0f);
    EXPECT_EQ(roundToHalf(1e30f), 65504.0f);
    EXPECT_EQ(roundToHalf(-1e30f), -65504.0f);
    EXPECT_EQ(roundToHalf(INFINITY), 65504.0f);

    // The four-channel rounding through F16C (what the frame's AVX2 and AVX-512 copies use,
    // render/frame_kernels.h) is roundToHalf on every channel, over float bit patterns spread across
    // the whole range — subnormals, ties, the overflow clamp, ±Inf and NaN included. Catches a clamp
    // that turns NaN into a number or lets Inf through.
    for (std::uint64_t bits = 0; bits <= 0xffffffffull; bits += 0x10001) {
        const float x = std::bit_cast<float>(static_cast<std::uint32_t>(bits));
        const vec4 four = roundToHalfF16c(vec4(x, -x, x * 0.5f, 1.0f));
        const vec4 one(roundToHalf(x), roundToHalf(-x), roundToHalf(x * 0.5f), 1.0f);
        for (int k = 0; k < 4; ++k)
            if (std::isnan(one[k]) ? !std::isnan(four[k]) : four[k] != one[k]) {
                ADD_FAILURE() << "channel " << k << " of " << x << ": " << four[k] << " != " << one[k];
                return;
            }
    }
    EXPECT_TRUE(std::isnan(roundToHalfF16c(vec4(NAN)).r));
    EXPECT_EQ(roundToHalfF16c(vec4(INFINITY)).g, 65504.0f);
    EXPECT_EQ(roundToHalfF16c(vec4(-INFINITY)).b, -65504.0f);
    EXPECT_TRUE(std::isnan(roundToColorBuffer<ColorBufferFormat::Half>(vec4(NAN)).r));
    EXPECT_EQ(roundToColorBuffer<ColorBufferFormat::Half>(vec4(INFINITY)).g, 65504.0f);
    EXPECT_EQ(roundToColorBuffer<ColorBufferFormat::Half>(vec4(-INFINITY)).b, -65504.0f);

    // Through the pipeline: a Replace draw into a half buffer stores the rounded values.
    Framebuffer fb(8, 8);
    fb.clearColor(vec4(0.0f));
    DrawState state = testing::stateFor(fb);
    state.colorBuffer = ColorBufferFormat::Half;
    std::vector<ClipSpaceColorShader::Attributes> quad;
    for (vec2 p : {vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1)})
        quad.push_back({vec4(p, 0.0f, 1.0f), vec4(1.0f / 3.0f, 1e6f, 0.1f, 1.0f)});
    testing::drawTriangles<ClipSpaceColorShader>(state, quad, fb);
    EXPECT_EQ(fb.color(4, 4), vec4(f16c(1.0f / 3.0f), 65504.0f, f16c(0.1f), 1.0f));
}

// Exact transparency's resolve writes through the same rounding: one fragment of grey 0.61 at alpha
// 0.5 over black, resolved into an 8-bit buffer, is round(0.305·255)/255. Breaks if the resolve blends
// without rounding.
TEST(ColorBufferFormats, FragmentListResolveRoundsToo) {
    Framebuffer fb(8, 8);
    fb.clearColor(vec4(0.0f));
    DrawState state = testing::stateFor(fb);
    state.blend = BlendMode::Over;
    state.output = FragmentOutput::AppendToLists;
    state.colorBuffer = ColorBufferFormat::Unorm8;
    std::vector<ClipSpaceColorShader::Attributes> quad;
    for (vec2 p : {vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1)})
        quad.push_back({vec4(p, 0.0f, 1.0f), vec4(0.61f, 0.61f, 0.61f, 0.5f)});
    DrawContext context(1);
    std::vector<std::uint32_t> indices = {0, 1, 2, 3, 4, 5};
    draw<ClipSpaceColorShader>(state, {}, std::span<const ClipSpaceColorShader::Attributes>(quad),
                               std::span<const std::uint32_t>(indices), fb, context);
    resolveFragmentLists(fb, context.pool);
    EXPECT_EQ(fb.color(2, 2).r, std::round(0.5f * 0.61f * 255.0f) / 255.0f);
}

}  // namespace
}  // namespace facet
