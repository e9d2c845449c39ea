// The pipeline where fixed point and float are stretched: a triangle far from the window's origin, and
// fans of long slivers. Each case is checked against a double-precision computation of what the
// rasterizer should produce, with the tolerance stated where it is not exact.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "../support/test_shaders.h"
#include "pipeline.h"

namespace facet {
namespace {

using testing::ClipSpaceColorShader;
using testing::CountingShader;
using testing::hits;

// One small triangle in perspective (its corners at w = 1, 2 and 4), with a colour per corner.
struct SmallTriangle {
    glm::dvec2 corner[3] = {{0.25, 0.5}, {13.75, 2.25}, {3.5, 11.75}};  // window pixels from its origin
    double w[3] = {1.0, 2.0, 4.0};
    vec4 color[3] = {{1, 0, 0, 1}, {0, 1, 0, 0.5f}, {0, 0, 1, 0.25f}};
};

// Draws the triangle with its origin at window (ox, oy) into `fb`. The clip coordinates are exact
// in float: window positions are multiples of 1/4 and the framebuffer sides powers of two, so
// 2x/width − 1 and its product with w lose nothing, and both placements start from the same
// geometry to the last bit.
void drawSmallTriangle(Framebuffer& fb, const SmallTriangle& t, int ox, int oy) {
    std::vector<ClipSpaceColorShader::Attributes> v;
    for (int i = 0; i < 3; ++i) {
        const vec2 window(static_cast<float>(ox + t.corner[i].x), static_cast<float>(oy + t.corner[i].y));
        const vec4 clip = testing::clipFromWindow(window, fb) * static_cast<float>(t.w[i]);
        v.push_back({clip, t.color[i]});
    }
    testing::drawTriangles<ClipSpaceColorShader>(testing::stateFor(fb), v, fb);
}

// The colour a perspective-correct rasterizer gives the pixel centre (px + ½, py + ½) of the
// triangle's own frame, in double: λ from the signed areas, then a = Σ λᵢ aᵢ/wᵢ ÷ Σ λᵢ/wᵢ.
// Returns false when the centre is outside (or within 1e-9 px² of an edge, where the fill rule
// decides and the test does not).
bool expectedColor(const SmallTriangle& t, double px, double py, glm::dvec4& color) {
    const glm::dvec2 p(px + 0.5, py + 0.5);
    auto edge = [](glm::dvec2 a, glm::dvec2 b, glm::dvec2 q) {
        return (b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x);
    };
    const double area = edge(t.corner[0], t.corner[1], t.corner[2]);
    const double l0 = edge(t.corner[1], t.corner[2], p) / area;
    const double l1 = edge(t.corner[2], t.corner[0], p) / area;
    const double l2 = edge(t.corner[0], t.corner[1], p) / area;
    if (std::min({l0, l1, l2}) * std::abs(area) < 1e-9) return false;
    const double q0 = l0 / t.w[0], q1 = l1 / t.w[1], q2 = l2 / t.w[2];
    color = (q0 * glm::dvec4(t.color[0]) + q1 * glm::dvec4(t.color[1]) + q2 * glm::dvec4(t.color[2])) /
            (q0 + q1 + q2);
    return true;
}

// The same triangle at (10, 10) and at (16000, 16000) — near the far corner of the largest viewport,
// where a window coordinate needs 22 of its fixed-point bits — gives the same interpolated colours,
// each within 2e-6 of the double-precision value. Tolerance: the float barycentrics and the
// perspective divide carry a few ulps of the colours (about 1e-7 each); a pipeline that lost precision
// with distance from the origin (say, interpolating from window coordinates in float) would be off by
// about 16000 · 2^-24 ≈ 1e-3 per unit of colour gradient at the far corner.
TEST(PipelineExtremes, ASmallTriangleFarFromTheOriginInterpolatesAsNearIt) {
    const SmallTriangle triangle;
    constexpr int kFar = 16000;
    struct Placement {
        int width, height, ox, oy;
    };
    const Placement placements[] = {
        {64, 64, 10, 10},        // near the origin
        {16384, 32, kFar, 10},   // far along x (a 16384 × 16384 buffer would be 5 GB)
        {32, 16384, 10, kFar}};  // far along y
    std::vector<std::vector<vec4>> colors;
    for (const Placement& at : placements) {
        SCOPED_TRACE(::testing::Message() << "origin " << at.ox << "," << at.oy);
        Framebuffer fb(at.width, at.height);
        fb.clearColor(vec4(-1.0f));
        drawSmallTriangle(fb, triangle, at.ox, at.oy);
        std::vector<vec4> seen;
        int inside = 0;
        for (int y = 0; y < 14; ++y)
            for (int x = 0; x < 14; ++x) {
                const vec4 c = fb.color(at.ox + x, at.oy + y);
                seen.push_back(c);
                glm::dvec4 expected;
                if (!expectedColor(triangle, x, y, expected)) continue;
                ++inside;
                for (int k = 0; k < 4; ++k)
                    ASSERT_NEAR(c[k], expected[k], 2e-6) << "pixel " << x << "," << y << " channel " << k;
            }
        EXPECT_GT(inside, 50);
        colors.push_back(seen);
    }
    // And the far placements agree with the near one pixel for pixel (coverage included).
    for (std::size_t i = 0; i < colors[0].size(); ++i) {
        for (int k = 0; k < 4; ++k) {
            EXPECT_NEAR(colors[1][i][k], colors[0][i][k], 2e-6) << "pixel " << i;
            EXPECT_NEAR(colors[2][i][k], colors[0][i][k], 2e-6) << "pixel " << i;
        }
    }
}

// A fan of 6000 slivers, each as long as the window (about 90 px) and a few thousandths of a pixel
// wide at its end, covers every pixel exactly once: no hole where a sliver misses every centre, no
// double hit where two claim the same centre. The rim runs along two opposite window edges only, so
// every triangle is long and thin.
TEST(PipelineExtremes, AFanOfLongSliversCoversEveryPixelOnce) {
    Framebuffer fb(64, 64);
    fb.clearColor(vec4(0));
    std::vector<vec2> rim;
    const int steps = 3000;
    for (int i = 0; i <= steps; ++i)
        rim.push_back({64.0f * i / steps, 0.0f});  // the top edge, left to right
    rim.push_back({64.0f, 64.0f});
    for (int i = steps; i >= 0; --i)
        rim.push_back({64.0f * i / steps, 64.0f});  // the bottom edge, right to left
    std::vector<CountingShader::Attributes> v;
    const vec2 centre(31.37f, 32.61f);
    for (std::size_t i = 0; i < rim.size(); ++i) {
        const vec2 a = rim[i], b = rim[(i + 1) % rim.size()];
        for (vec2 p : {centre, a, b})
            v.push_back({testing::clipFromWindow(p, fb)});
    }
    DrawState state = testing::stateFor(fb);
    state.blend = BlendMode::Additive;
    state.depth.testEnabled = false;
    testing::drawTriangles<CountingShader>(state, v, fb);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x)
            ASSERT_EQ(hits(fb, x, y), 1) << "pixel " << x << "," << y;
}

}  // namespace
}  // namespace facet
