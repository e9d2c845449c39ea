// Texture coordinate derivatives through the back end (interpolate.h's interpolateDerivatives, asked
// for by a shader's kDerivativeVarying): the hand-computed level of detail of a quad whose texels span a
// known number of pixels, agreement with finite differences of the interpolated uv on a perspective
// triangle, and the same bits from the one-lane and the eight-lane interpolation.
#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "../support/test_shaders.h"
#include "pipeline.h"
#include "texture.h"

namespace facet {
namespace {

using testing::clipFromWindow;
using testing::drawTriangles;
using testing::levelNumberTexture;
using testing::stateFor;

// Writes uv's derivatives (∂u/∂x, ∂v/∂x, ∂u/∂y, ∂v/∂y) as the colour, or uv itself (showDerivatives
// off), so the framebuffer holds what the back end handed the fragment shader.
struct UvDerivativeShader {
    struct Attributes {
        vec4 position;
        vec2 uv;
    };
    struct Varyings {
        vec2 uv;
    };
    static constexpr int kDerivativeVarying = 0;
    struct Uniforms {
        bool showDerivatives = true;
    };
    static VertexOut<Varyings> vertex(const Attributes& in, const Uniforms&) {
        return {in.position, {in.uv}};
    }
    static vec4 fragment(const Varyings& in, const Uniforms&) { return vec4(in.uv, 0.0f, 1.0f); }
    static Vec4x8 fragmentBatch(const FragmentBatch& in, const Uniforms& u) {
        if (!u.showDerivatives) return {in.varyings[0], in.varyings[1], splat(0.0f), splat(1.0f)};
        return {in.uvDerivatives[0], in.uvDerivatives[1], in.uvDerivatives[2], in.uvDerivatives[3]};
    }
};

// A quad over the whole 32×32 framebuffer whose uv is the window position times (scale, scale/2).
std::vector<UvDerivativeShader::Attributes> scaledQuad(const Framebuffer& fb, float scale) {
    const auto corner = [&](float x, float y) {
        return UvDerivativeShader::Attributes{clipFromWindow(vec2(x, y), fb), vec2(x * scale, y * scale / 2)};
    };
    const float w = static_cast<float>(fb.width()), h = static_cast<float>(fb.height());
    return {corner(0, 0), corner(w, 0), corner(w, h), corner(0, 0), corner(w, h), corner(0, h)};
}

// One texel of a 64×64 texture across 4 pixels: ∂u/∂x = 1/256, λ = log2(64/256) = −2, level 0; four
// texels a pixel: ∂u/∂x = 1/16, λ = log2(64/16) = 2, level 2. v runs half as fast, down the rows.
// Breaks caught: the slopes per fixed-point unit, not per pixel (kFixedOne left out: λ off by 8), ∂/∂x
// and ∂/∂y swapped, or u's derivatives handed out as v's.
TEST(TextureLod, QuadWithKnownTexelsPerPixel) {
    Framebuffer fb(32, 32);
    const Texture texture = levelNumberTexture();
    for (const auto& [scale, lod] : {std::pair{1.0f / 256.0f, -2.0f}, std::pair{1.0f / 16.0f, 2.0f}}) {
        fb.clearColor(vec4(-1.0f));
        fb.clearDepth();
        drawTriangles<UvDerivativeShader>(stateFor(fb), scaledQuad(fb, scale), fb);
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) {
                const vec4 d = fb.color(x, y);
                ASSERT_NEAR(d.x, scale, 1e-6f * scale) << x << "," << y;      // ∂u/∂x
                ASSERT_NEAR(d.y, 0.0f, 1e-6f * scale) << x << "," << y;       // ∂v/∂x
                ASSERT_NEAR(d.z, 0.0f, 1e-6f * scale) << x << "," << y;       // ∂u/∂y
                ASSERT_NEAR(d.w, scale / 2, 1e-6f * scale) << x << "," << y;  // ∂v/∂y
                const vec2 dx(d.x, d.y), dy(d.z, d.w);
                ASSERT_NEAR(textureLod(texture, dx, dy), lod, 1e-5f);
                ASSERT_EQ(sampleTrilinear(texture, vec2(0.3f, 0.7f), dx, dy).r, std::max(lod, 0.0f));
            }
    }
}

// The corners of a triangle seen in perspective: window positions, w and uv.
struct PerspectiveCorner {
    vec2 window;
    float w;
    vec2 uv;
};
constexpr PerspectiveCorner kTilted[3] = {{{1.0f, 2.0f}, 1.0f, {0.1f, 0.2f}},
                                          {{62.0f, 6.0f}, 3.5f, {0.9f, 0.3f}},
                                          {{9.0f, 61.0f}, 1.8f, {0.4f, 1.1f}}};

std::vector<UvDerivativeShader::Attributes> tiltedTriangle(const Framebuffer& fb) {
    std::vector<UvDerivativeShader::Attributes> out;
    for (const PerspectiveCorner& c : kTilted)
        out.push_back({clipFromWindow(c.window, fb, 0.5f) * c.w, c.uv});
    return out;
}

// On a perspective triangle the derivatives match central differences of the interpolated uv,
// (uv(x + 1) − uv(x − 1))/2, to 1% of the largest derivative (the differences' own error, uv's
// curvature over two pixels, is below 0.3% here).
// Breaks caught: the quotient rule's a·W_x term dropped (the affine slope A_x·w), or the division by W
// (multiplication by w) left out.
TEST(TextureLod, DerivativesMatchFiniteDifferencesUnderPerspective) {
    Framebuffer uvImage(64, 64), derivatives(64, 64);
    for (Framebuffer* fb : {&uvImage, &derivatives}) {
        fb->clearColor(vec4(0.0f));
        fb->clearDepth();
    }
    drawTriangles<UvDerivativeShader>(stateFor(uvImage), tiltedTriangle(uvImage), uvImage, {false});
    drawTriangles<UvDerivativeShader>(stateFor(derivatives), tiltedTriangle(derivatives), derivatives,
                                      {true});
    const auto covered = [&](int x, int y) { return uvImage.color(x, y).w == 1.0f; };
    float largest = 0.0f;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            if (covered(x, y))
                for (int c = 0; c < 4; ++c)
                    largest = std::max(largest, std::abs(derivatives.color(x, y)[c]));
    ASSERT_GT(largest, 0.01f);
    int compared = 0;
    for (int y = 1; y < 63; ++y)
        for (int x = 1; x < 63; ++x) {
            if (!covered(x, y) || !covered(x - 1, y) || !covered(x + 1, y) || !covered(x, y - 1) ||
                !covered(x, y + 1))
                continue;
            const vec2 dx = 0.5f * (vec2(uvImage.color(x + 1, y)) - vec2(uvImage.color(x - 1, y)));
            const vec2 dy = 0.5f * (vec2(uvImage.color(x, y + 1)) - vec2(uvImage.color(x, y - 1)));
            const vec4 d = derivatives.color(x, y);
            EXPECT_NEAR(d.x, dx.x, 0.01f * largest) << x << "," << y;
            EXPECT_NEAR(d.y, dx.y, 0.01f * largest) << x << "," << y;
            EXPECT_NEAR(d.z, dy.x, 0.01f * largest) << x << "," << y;
            EXPECT_NEAR(d.w, dy.y, 0.01f * largest) << x << "," << y;
            ++compared;
        }
    EXPECT_GT(compared, 1000);
}

// Fragments interpolated one at a time (a row where one or two survive the depth test) get the same
// derivative bits as eight at a time: columns 1–3 of every four hidden behind nearer strips, the
// visible column's fragments go through the one-lane path, and match the unhidden draw exactly.
// Breaks caught: the one-lane path reading the wrong varying (&varyings[kUv + 1]) or its derivatives
// stored in the wrong order.
TEST(TextureLod, OneLaneAndEightLaneDerivativesAreTheSameBits) {
    Framebuffer wide(64, 64), narrow(64, 64);
    for (Framebuffer* fb : {&wide, &narrow}) {
        fb->clearColor(vec4(0.0f));
        fb->clearDepth();
    }
    const DrawState state = stateFor(wide);
    drawTriangles<UvDerivativeShader>(state, tiltedTriangle(wide), wide);
    std::vector<UvDerivativeShader::Attributes> strips;
    for (int x = 1; x < 64; x += 4) {
        const auto at = [&](float px, float py) {
            return UvDerivativeShader::Attributes{clipFromWindow(vec2(px, py), narrow, -0.9f), vec2(0.0f)};
        };
        const float left = static_cast<float>(x), right = static_cast<float>(x + 3);
        for (const vec2 p :
             {vec2(left, 0), vec2(right, 0), vec2(right, 64), vec2(left, 0), vec2(right, 64), vec2(left, 64)})
            strips.push_back(at(p.x, p.y));
    }
    drawTriangles<UvDerivativeShader>(state, strips, narrow, {false});
    drawTriangles<UvDerivativeShader>(state, tiltedTriangle(narrow), narrow);
    int compared = 0;
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; x += 4) {
            if (wide.color(x, y) == vec4(0.0f)) continue;
            const vec4 a = wide.color(x, y), b = narrow.color(x, y);
            EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << x << "," << y;
            ++compared;
        }
    EXPECT_GT(compared, 200);
}

}  // namespace
}  // namespace facet
