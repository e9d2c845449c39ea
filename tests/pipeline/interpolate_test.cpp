#include "interpolate.h"

#include <bit>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "../support/test_shaders.h"
#include "triangle_setup.h"

namespace facet {
namespace {

using testing::ClipSpaceColorShader;

// A floor plane seen in perspective: y = −1, z from −1 (near) to −9 (far), eye at the origin looking
// down −z, 90° vertical field of view. A varying carries the world z; at a pixel it must equal the z where
// the pixel's eye ray meets the plane (computed analytically), and the affine mode must not.
struct TiltedPlane {
    static constexpr int kSize = 64;
    Framebuffer fb{kSize, kSize};

    static mat4 projection() {
        // OpenGL perspective: fovy 90°, aspect 1, near 0.5, far 20.
        const float n = 0.5f, f = 20.0f;
        mat4 p(0.0f);
        p[0][0] = 1.0f;
        p[1][1] = 1.0f;
        p[2][2] = -(f + n) / (f - n);
        p[2][3] = -1.0f;
        p[3][2] = -2.0f * f * n / (f - n);
        return p;
    }

    void render(Interpolation mode) {
        fb.clearColor(vec4(0.0f));
        fb.clearDepth();
        DrawState state = testing::stateFor(fb);
        state.interpolation = mode;
        const mat4 P = projection();
        auto v = [&](float x, float z) {
            return ClipSpaceColorShader::Attributes{P * vec4(x, -1.0f, z, 1.0f), vec4(z, 0, 0, 1)};
        };
        testing::drawTriangles<ClipSpaceColorShader>(
            state, {v(-4, -1), v(4, -1), v(4, -9), v(-4, -1), v(4, -9), v(-4, -9)}, fb);
    }

    // The world z where the eye ray through pixel (x, y)'s centre hits the plane y = −1.
    static float analyticZ(int, int y) {
        // The ray is t·(x_ndc, y_ndc, −1) for a 90° field of view; it meets y = −1 at t = −1/y_ndc.
        const float yNdc = 1.0f - 2.0f * (y + 0.5f) / kSize;
        return 1.0f / yNdc;
    }
};

TEST(Interpolate, PerspectiveCorrectMatchesTheAnalyticPlane) {
    TiltedPlane scene;
    scene.render(Interpolation::PerspectiveCorrect);
    int checked = 0;
    for (int y = 40; y < 64; y += 3)
        for (int x = 24; x < 40; x += 5) {
            const vec4 c = scene.fb.color(x, y);
            if (c.a == 0.0f) continue;
            const float expected = TiltedPlane::analyticZ(x, y);
            EXPECT_NEAR(c.r, expected, 1e-4f * std::abs(expected)) << "pixel " << x << "," << y;
            ++checked;
        }
    EXPECT_GT(checked, 20);
}

TEST(Interpolate, AffineDeviatesFromTheAnalyticPlane) {
    TiltedPlane scene;
    scene.render(Interpolation::Affine);
    float worstRelativeError = 0.0f;
    for (int y = 40; y < 64; y += 3)
        for (int x = 24; x < 40; x += 5) {
            const vec4 c = scene.fb.color(x, y);
            if (c.a == 0.0f) continue;
            const float expected = TiltedPlane::analyticZ(x, y);
            worstRelativeError = std::max(worstRelativeError, std::abs(c.r - expected) / std::abs(expected));
        }
    EXPECT_GT(worstRelativeError, 0.05f);  // several per cent off: the affine warp is visible
}

TEST(Interpolate, DepthIsAffineInScreenSpace) {
    TriangleSetup s;
    s.z0 = 0.2f;
    s.dz1 = 0.4f;
    s.dz2 = -0.1f;
    EXPECT_FLOAT_EQ(interpolateDepth(s, 0.0f, 0.0f), 0.2f);
    EXPECT_FLOAT_EQ(interpolateDepth(s, 1.0f, 0.0f), 0.6f);
    EXPECT_FLOAT_EQ(interpolateDepth(s, 0.5f, 0.5f), 0.35f);
}

TEST(Interpolate, PerspectiveFormulaOnHandValues) {
    // a0 = 2 at w0 = 1, a1 = 10 at w1 = 4, a2 = 6 at w2 = 2; planes hold a/w and differences.
    TriangleSetup s;
    s.perspective = true;
    s.varyingCount = 1;
    s.invW0 = 1.0f;
    s.dInvW1 = 0.25f - 1.0f;
    s.dInvW2 = 0.5f - 1.0f;
    const float planes[3] = {2.0f, 10.0f / 4 - 2.0f, 6.0f / 2 - 2.0f};
    float out[1];
    // Halfway from v0 to v1 on screen: (a0/w0 + a1/w1)/2 ÷ (1/w0 + 1/w1)/2 = (2 + 2.5)/2 ÷ (1 + 0.25)/2
    // = 3.6, not the affine midpoint 6: the far vertex (w = 4) weighs less.
    interpolateVaryings(s, planes, 0.5f, 0.0f, out);
    EXPECT_FLOAT_EQ(out[0], 3.6f);
    interpolateVaryings(s, planes, 0.0f, 1.0f, out);
    EXPECT_FLOAT_EQ(out[0], 6.0f);
}

// The planes setupTriangle writes are the planes interpolateVaryings reads: at each vertex (λ = the
// vertex's weights) every varying comes back as that vertex gave it, the flat ones as the provoking
// vertex gave them, for five varyings (two flat), affine and perspective-correct, either orientation.
// Breaks caught: setup and interpolation disagreeing on where a varying's three numbers lie (the
// rows of types.h against triples); the differences taken to the wrong vertex; a flat varying
// interpolated.
TEST(Interpolate, SetUpPlanesGiveEachVertexItsVaryings) {
    const float varyings[3][5] = {{7, 8, 1, 2, 3}, {-7, -8, 4, 5, 6}, {0.5f, 9, -1, -2, 10}};
    for (const bool perspective : {false, true})
        for (const bool flipped : {false, true}) {
            WindowTriangle t;
            const std::int64_t xs[3] = {10, 90, 30}, ys[3] = {10, 20, flipped ? -60 : 80};
            const float invW[3] = {1.0f, 0.5f, 0.25f};
            for (int i = 0; i < 3; ++i) {
                t.vertices[i] = {xs[i] * kFixedOne, ys[i] * kFixedOne, 0.5f, invW[i],
                                 vec2(float(xs[i]), float(ys[i]))};
                t.varyings[i] = varyings[i];
            }
            t.varyingCount = 5;
            t.flatVaryingCount = 2;
            t.provokingVaryings = varyings[0];
            DrawState state;
            state.viewport = {0, 0, 128, 128};
            state.raster.cull = CullMode::None;
            state.interpolation = perspective ? Interpolation::PerspectiveCorrect : Interpolation::Affine;
            TriangleSetup setup;
            float planes[3 * 5];
            ASSERT_EQ(setupTriangle(t, state, setup, planes), TriangleFate::Drawn);
            // The setup may have swapped v1 and v2 to make the orientation positive: find each vertex
            // by its λ = E_i(vertex) / 2·area.
            for (int vertex = 0; vertex < 3; ++vertex) {
                const float b1 =
                    static_cast<float>(static_cast<double>(setup.edges[1].at(t.vertices[vertex].xFixed,
                                                                             t.vertices[vertex].yFixed)) /
                                       static_cast<double>(setup.doubleArea));
                const float b2 =
                    static_cast<float>(static_cast<double>(setup.edges[2].at(t.vertices[vertex].xFixed,
                                                                             t.vertices[vertex].yFixed)) /
                                       static_cast<double>(setup.doubleArea));
                float out[5];
                interpolateVaryings(setup, planes, b1, b2, out);
                for (int k = 0; k < 5; ++k) {
                    const float expected = k < 2 ? varyings[0][k] : varyings[vertex][k];
                    EXPECT_NEAR(out[k], expected, 1e-5f * (1.0f + std::abs(expected)))
                        << "vertex " << vertex << ", varying " << k
                        << (perspective ? ", perspective" : ", affine") << (flipped ? ", flipped" : "");
                }
            }
        }
}

// A triangle walked as a patch gets its barycentrics from its lanes' exact edge values
// (barycentricLanes); the block walk from BlockBarycentrics' rows. A pixel must get the same bits
// either way, whichever walk the triangle's size chooses.
// Breaks caught: E rounded to float before the multiplication, or 1/(2·area) taken in float.
TEST(Interpolate, PatchBarycentricsAreTheBlockWalksBits) {
    std::mt19937 rng(11);
    std::uniform_int_distribution<std::int64_t> coordinate(0, 12 * kFixedOne),
        nearby(-3 * kFixedOne, 3 * kFixedOne);
    DrawState state;
    state.viewport = {0, 0, 32, 32};
    state.raster.cull = CullMode::None;
    int compared = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        const std::int64_t cx = coordinate(rng) + 8 * kFixedOne, cy = coordinate(rng) + 8 * kFixedOne;
        WindowTriangle t;
        for (WindowVertex& v : t.vertices) {
            v.xFixed = cx + nearby(rng);
            v.yFixed = cy + nearby(rng);
            v.invW = 1.0f;
        }
        TriangleSetup setup;
        if (setupTriangle(t, state, setup, nullptr) != TriangleFate::Drawn) continue;
        const int x = setup.minX, y = setup.minY;
        const BlockBarycentrics block(setup, x, y);
        const double inverse = 1.0 / static_cast<double>(setup.doubleArea);
        for (int rowPair = 0; rowPair < 4; rowPair += 2) {
            Int8 e1, e2;  // rows rowPair and rowPair + 1 of the block's first four columns
            for (int lane = 0; lane < 8; ++lane) {
                const SamplePoint p = samplePosition(x + lane % 4, y + rowPair + lane / 4);
                e1[lane] = static_cast<std::int32_t>(setup.edges[1].at(p.x, p.y));
                e2[lane] = static_cast<std::int32_t>(setup.edges[2].at(p.x, p.y));
            }
            const Float8 b1 = barycentricLanes(e1, inverse), b2 = barycentricLanes(e2, inverse);
            for (int row = 0; row < 2; ++row) {
                Float8 blockB1, blockB2;
                block.row(rowPair + row, blockB1, blockB2);
                for (int column = 0; column < 4; ++column) {
                    ASSERT_EQ(std::bit_cast<std::uint32_t>(b1[row * 4 + column]),
                              std::bit_cast<std::uint32_t>(blockB1[column]))
                        << "trial " << trial;
                    ASSERT_EQ(std::bit_cast<std::uint32_t>(b2[row * 4 + column]),
                              std::bit_cast<std::uint32_t>(blockB2[column]))
                        << "trial " << trial;
                    ++compared;
                }
            }
        }
    }
    EXPECT_GT(compared, 20000);
}

// The back end interpolates a row's fragments eight at a time or one at a time depending on how many
// survived the depth test, so both lane widths must give the same bits for depth, 1/w and every
// varying, perspective-correct or affine, flat or not.
// Break caught: an approximate reciprocal (or any other shortcut) in the eight-lane path only.
TEST(Interpolate, OneLaneAndEightLanesGiveTheSameBits) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> value(-10.0f, 10.0f), invW(0.01f, 3.0f), lambda(0.0f, 1.0f);
    for (int trial = 0; trial < 200; ++trial) {
        TriangleSetup s;
        s.perspective = trial % 2 == 0;
        s.varyingCount = 5;
        s.flatVaryingCount = trial % 3 == 0 ? 2 : 0;
        s.z0 = lambda(rng);
        s.dz1 = value(rng) * 0.05f;
        s.dz2 = value(rng) * 0.05f;
        const float w0 = invW(rng), w1 = invW(rng), w2 = invW(rng);
        s.invW0 = w0;
        s.dInvW1 = w1 - w0;
        s.dInvW2 = w2 - w0;
        float planes[3 * 5];
        for (float& p : planes)
            p = value(rng);
        Float8 b1, b2;
        for (int lane = 0; lane < 8; ++lane) {
            b1[lane] = lambda(rng);
            b2[lane] = (1.0f - b1[lane]) * lambda(rng);
        }
        FragmentBatch wide;
        interpolateVaryings(s, planes, b1, b2, wide);
        const Float8 depth = interpolateDepth(s, b1, b2), weight = interpolateInvW(s, b1, b2);
        for (int lane = 0; lane < 8; ++lane) {
            float narrow[5];
            interpolateVaryings(s, planes, b1[lane], b2[lane], narrow);
            for (int k = 0; k < 5; ++k)
                ASSERT_EQ(std::bit_cast<std::uint32_t>(narrow[k]),
                          std::bit_cast<std::uint32_t>(wide.varyings[k][lane]))
                    << "trial " << trial << " lane " << lane << " varying " << k;
            ASSERT_EQ(std::bit_cast<std::uint32_t>(interpolateDepth(s, b1[lane], b2[lane])),
                      std::bit_cast<std::uint32_t>(depth[lane]));
            ASSERT_EQ(std::bit_cast<std::uint32_t>(interpolateInvW(s, b1[lane], b2[lane])),
                      std::bit_cast<std::uint32_t>(weight[lane]));
        }
    }
}

}  // namespace
}  // namespace facet
