// The plumbing of draw(): that the state a caller sets reaches the stage that uses it, and that the
// back end calls the stages' formulas with the right operands. Each test fails when one line of that
// plumbing is broken (the break is named above the test); the stages' formulas have their own tests.
#include <cmath>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "../support/test_shaders.h"
#include "pipeline.h"

namespace facet {
namespace {

using testing::ClipSpaceColorShader;
using testing::CountingShader;

struct WindowPoint {
    double x, y, depth;  // window pixels (y down) and window depth
};

// The depth at (px, py) of the plane through three window points, solved in double (Cramer's rule).
double planeDepthAt(const WindowPoint p[3], double px, double py) {
    const double ax = p[1].x - p[0].x, ay = p[1].y - p[0].y, az = p[1].depth - p[0].depth;
    const double bx = p[2].x - p[0].x, by = p[2].y - p[0].y, bz = p[2].depth - p[0].depth;
    const double det = ax * by - ay * bx;
    const double s = ((px - p[0].x) * by - (py - p[0].y) * bx) / det;
    const double t = (ax * (py - p[0].y) - ay * (px - p[0].x)) / det;
    return p[0].depth + s * az + t * bz;
}

// A triangle with a different depth at each vertex: the depth draw() writes, and tests with, at every
// pixel is the plane through the vertices at the pixel's centre.
// Breaks caught: the back end's depth with dz1 and dz2 swapped, λ1 used for both, or λ2 for both.
TEST(DrawPlumbing, EarlyDepthIsThePlaneThroughTheVertices) {
    Framebuffer fb(32, 32);
    const WindowPoint corners[3] = {{2.5, 1.5, 0.1}, {29.5, 6.5, 0.65}, {8.5, 30.5, 0.95}};
    std::vector<ClipSpaceColorShader::Attributes> tilted;
    for (const WindowPoint& c : corners)
        tilted.push_back({testing::clipFromWindow(vec2(c.x, c.y), fb, static_cast<float>(2 * c.depth - 1)),
                          vec4(1, 0, 0, 1)});
    const std::vector<ClipSpaceColorShader::Attributes> fullScreenAtHalf = {
        {{-1, -1, 0, 1}, vec4(0, 1, 0, 1)},
        {{3, -1, 0, 1}, vec4(0, 1, 0, 1)},
        {{-1, 3, 0, 1}, vec4(0, 1, 0, 1)}};

    // The depth written: the plane, at every covered pixel.
    fb.clearColor(vec4(0));
    fb.clearDepth();
    const DrawState state = testing::stateFor(fb);
    testing::drawTriangles<ClipSpaceColorShader>(state, tilted, fb);
    int covered = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            if (fb.color(x, y) != vec4(1, 0, 0, 1)) continue;
            ++covered;
            EXPECT_NEAR(fb.depth(x, y), planeDepthAt(corners, x + 0.5, y + 0.5), 2e-6) << x << "," << y;
        }
    EXPECT_GT(covered, 300);

    // The depth tested: after a surface at depth ½, the triangle's pixels show it where its plane is
    // nearer than ½ and the surface elsewhere.
    const std::vector<vec4> alone = fb.colorPixels();
    fb.clearColor(vec4(0));
    fb.clearDepth();
    testing::drawTriangles<ClipSpaceColorShader>(state, fullScreenAtHalf, fb);
    testing::drawTriangles<ClipSpaceColorShader>(state, tilted, fb);
    int hidden = 0, shown = 0;
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            if (alone[static_cast<std::size_t>(y * 32 + x)] != vec4(1, 0, 0, 1)) continue;
            const double plane = planeDepthAt(corners, x + 0.5, y + 0.5);
            if (std::abs(plane - 0.5) < 1e-4) continue;
            EXPECT_EQ(fb.color(x, y), plane < 0.5 ? vec4(1, 0, 0, 1) : vec4(0, 1, 0, 1)) << x << "," << y;
            ++(plane < 0.5 ? shown : hidden);
        }
    EXPECT_GT(shown, 50);
    EXPECT_GT(hidden, 50);
}

// The pixels a right triangle covers, its legs on the top and left borders and its hypotenuse from
// (c, 0) to (0, c), drawn through draw() with the given sub-pixel bits. `clipped`: the same pixels as
// the window's part of a larger triangle, (−10, −10), (c + 10, −10), (−10, c + 10), which the left and
// top planes cut, so its corners come from the clipper and are snapped on the fan path.
int coveredPixels(float c, int subpixelBits, bool clipped) {
    Framebuffer fb(16, 16);
    fb.clearColor(vec4(0));
    DrawState state = testing::stateFor(fb);
    state.raster.subpixelBits = subpixelBits;
    state.blend = BlendMode::Additive;
    state.depth.testEnabled = false;
    const float o = clipped ? -10.0f : 0.0f;
    const std::vector<CountingShader::Attributes> v = {{testing::clipFromWindow({o, o}, fb)},
                                                       {testing::clipFromWindow({c - o, o}, fb)},
                                                       {testing::clipFromWindow({o, c - o}, fb)}};
    const DrawStats stats = testing::drawTriangles<CountingShader>(state, v, fb);
    EXPECT_EQ(stats.trianglesClipped, clipped ? 1u : 0u);
    int covered = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            covered += testing::hits(fb, x, y);
    return covered;
}

// The hypotenuse's ends at 8.03 px lie between 1/16-pixel positions: with 8 sub-pixel bits they stay
// at 8.03 and the pixels with x + y ≤ 7 are inside (36); snapped to 1/16 or whole pixels they move to
// 8, the hypotenuse runs through the centres with x + y = 7, which a right edge does not take (28).
// Breaks caught: draw() ignoring RasterState::subpixelBits (snapping with 8 bits whatever the state),
// for the vertices no plane clips or for the clipped polygon's fan.
TEST(DrawPlumbing, SubpixelBitsReachTheSnapping) {
    for (bool clipped : {false, true}) {
        EXPECT_EQ(coveredPixels(8.03f, 8, clipped), 36) << (clipped ? "clipped" : "whole");
        EXPECT_EQ(coveredPixels(8.03f, 4, clipped), 28) << (clipped ? "clipped" : "whole");
        EXPECT_EQ(coveredPixels(8.03f, 0, clipped), 28) << (clipped ? "clipped" : "whole");
    }
}

// Two small triangles of one draw on the same pixels, the nearer first: the farther one's fragments
// fail the depth test against the nearer one's, although the nearer ones may still wait in the back
// end's queue of eight when the farther ones are tested.
// Break caught: the queue not shaded (its depths not written) before a pixel it holds is tested again.
TEST(DrawPlumbing, QueuedFragmentsReachTheDepthBufferBeforeTheirPixelIsTestedAgain) {
    Framebuffer fb(16, 16);
    fb.clearColor(vec4(0));
    fb.clearDepth();
    const vec4 red(1, 0, 0, 1), green(0, 1, 0, 1);
    std::vector<ClipSpaceColorShader::Attributes> v;
    for (const auto& [z, color] : {std::pair{-0.5f, red}, std::pair{0.5f, green}})
        for (vec2 p : {vec2(4, 4), vec2(6.6f, 4), vec2(4, 6.6f)})  // three pixels: fewer than eight
            v.push_back({testing::clipFromWindow(p, fb, z), color});
    const DrawStats stats = testing::drawTriangles<ClipSpaceColorShader>(testing::stateFor(fb), v, fb);
    EXPECT_EQ(stats.fragmentsWritten, 3u);
    EXPECT_EQ(stats.fragmentsDepthFailed, 3u);
    EXPECT_EQ(fb.color(4, 4), red);
    EXPECT_EQ(fb.color(5, 4), red);
    EXPECT_EQ(fb.color(4, 5), red);
}

// OpenGL: with GL_DEPTH_TEST disabled the depth buffer is not written, even with the depth mask on;
// with the test enabled and Always it is.
// Break caught: the back end writing depth whenever writeEnabled, without testEnabled.
TEST(DrawPlumbing, NoDepthWriteWithoutTheDepthTest) {
    Framebuffer fb(4, 4);
    fb.clearColor(vec4(0));
    fb.clearDepth(0.25f);
    DrawState state = testing::stateFor(fb);
    state.depth.testEnabled = false;
    state.depth.writeEnabled = true;
    const std::vector<ClipSpaceColorShader::Attributes> v = {
        {{-1, -1, 0.5f, 1}, vec4(1)}, {{3, -1, 0.5f, 1}, vec4(1)}, {{-1, 3, 0.5f, 1}, vec4(1)}};
    testing::drawTriangles<ClipSpaceColorShader>(state, v, fb);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            EXPECT_EQ(fb.color(x, y), vec4(1));  // drawn at 0.75, behind the stored 0.25: no test ran
            EXPECT_EQ(fb.depth(x, y), 0.25f);
        }
    state.depth.testEnabled = true;
    state.depth.compare = CompareOp::Always;
    testing::drawTriangles<ClipSpaceColorShader>(state, v, fb);
    EXPECT_EQ(fb.depth(2, 2), 0.75f);
}

// Two triangles of one draw, each with its own vertex colours: every pixel shows its own triangle's
// colours, so each setup reads its own varying planes.
// Break caught: SetupChunk::planesOf ignoring the setup's offset (every setup reading the first planes).
TEST(DrawPlumbing, EachTriangleInterpolatesItsOwnVaryings) {
    Framebuffer fb(16, 8);
    fb.clearColor(vec4(0));
    const vec4 red(1, 0, 0, 1), blue(0, 0, 1, 1);
    std::vector<ClipSpaceColorShader::Attributes> v;
    for (vec2 p : {vec2(0, 0), vec2(8, 0), vec2(0, 8)})
        v.push_back({testing::clipFromWindow(p, fb), red});
    for (vec2 p : {vec2(8, 0), vec2(16, 0), vec2(8, 8)})
        v.push_back({testing::clipFromWindow(p, fb), blue});
    testing::drawTriangles<ClipSpaceColorShader>(testing::stateFor(fb), v, fb);
    EXPECT_EQ(fb.color(1, 1), red);
    EXPECT_EQ(fb.color(9, 1), blue);
    EXPECT_EQ(fb.color(10, 3), blue);
}

// A draw's blend mode reaches the output merger: a quad of each mode over a known colour gives what
// blend() gives for that mode.
// Break caught: the back end blending every Blend draw with one fixed mode.
TEST(DrawPlumbing, TheDrawsBlendModeReachesTheOutputMerger) {
    const vec4 destination(0.25f, 0.5f, 0.75f, 0.5f), source(0.5f, 0.25f, 1.0f, 0.25f);
    for (BlendMode mode : {BlendMode::Replace, BlendMode::Additive, BlendMode::Over,
                           BlendMode::PremultipliedOver, BlendMode::Multiply}) {
        Framebuffer fb(4, 4);
        fb.clearColor(destination);
        DrawState state = testing::stateFor(fb);
        state.blend = mode;
        const std::vector<ClipSpaceColorShader::Attributes> v = {
            {{-1, -1, 0, 1}, source}, {{3, -1, 0, 1}, source}, {{-1, 3, 0, 1}, source}};
        testing::drawTriangles<ClipSpaceColorShader>(state, v, fb);
        EXPECT_EQ(fb.color(2, 1), blend(mode, source, destination)) << mode;
    }
}

// Breaks caught: the division rounded down (117,456 / 64 → 1835, which leaves a 65th chunk of one
// vertex), either bound not applied, one thread cut like many.
TEST(DrawPlumbing, ChunksShrinkWithTheThreadsDownToTheSmallest) {
    EXPECT_EQ(chunkSize(117'456, 1, kMinVertexChunk, kVertexChunk), kVertexChunk);
    EXPECT_EQ(chunkSize(117'456, 2, kMinVertexChunk, kVertexChunk), kVertexChunk);
    EXPECT_EQ(chunkSize(117'456, 16, kMinVertexChunk, kVertexChunk), 1836u);  // 117,456 / 64, rounded up
    EXPECT_EQ(chunkSize(5'000, 16, kMinVertexChunk, kVertexChunk), kMinVertexChunk);
    EXPECT_EQ(chunkSize(10'000, 4, kMinTriangleChunk, kTriangleChunk), 625u);
    EXPECT_EQ(chunkSize(0, 8, kMinTriangleChunk, kTriangleChunk), kMinTriangleChunk);
}

// The threads a context's work is cut for reach the vertex stage and the set-up: a trace of a draw on one
// thread shows the items.
// Breaks caught: draw() cutting for the pool's threads whatever DrawContext::cutForThreads says, or
// either stage keeping its largest chunk.
TEST(DrawPlumbing, TheThreadsToCutForSizeTheDrawsItems) {
    Framebuffer fb(64, 64);
    std::vector<ClipSpaceColorShader::Attributes> vertices(20'000);
    for (std::size_t i = 0; i < vertices.size(); ++i)
        vertices[i] = {
            vec4(0.001f * static_cast<float>(i % 7), 0.002f * static_cast<float>(i % 5), 0.5f, 1.0f),
            vec4(1.0f)};
    std::vector<std::uint32_t> indices(3 * 10'000);
    for (std::size_t i = 0; i < indices.size(); ++i)
        indices[i] = static_cast<std::uint32_t>(i % vertices.size());
    const auto itemsOfFirstTwoJobs = [&](int cutFor) {
        DrawContext context(1);
        context.cutForThreads = cutFor;
        PoolTrace trace;
        context.pool.startTrace(trace);
        draw<ClipSpaceColorShader>(testing::stateFor(fb), {}, std::span(std::as_const(vertices)),
                                   std::span(std::as_const(indices)), fb, context);
        context.pool.stopTrace();
        return trace.jobs.size() < 2 ? std::pair{0u, 0u}
                                     : std::pair{trace.jobs[0].items, trace.jobs[1].items};
    };
    EXPECT_EQ(itemsOfFirstTwoJobs(0), (std::pair{3u, 5u}));     // chunks of 8192 vertices, 2048 triangles
    EXPECT_EQ(itemsOfFirstTwoJobs(16), (std::pair{20u, 40u}));  // chunks of 1024 vertices, 256 triangles
}

}  // namespace
}  // namespace facet
