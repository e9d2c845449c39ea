// End-to-end properties of draw(): watertight coverage, robustness at the numerical extremes,
// the vertex/fragment stage contracts and the observer hooks.
#include "pipeline.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "../support/test_shaders.h"

namespace facet {
namespace {

using testing::ClipSpaceColorShader;
using testing::CountingShader;
using testing::FlatColorShader;
using testing::hits;

// piglit's overdraw test: a fan of triangles around a centre, drawn with additive blending, must hit
// every pixel inside it exactly once: a hole reads 0, a double hit reads 2.
void drawFan(Framebuffer& fb, vec2 centre, const std::vector<vec2>& rim, float w = 1.0f) {
    std::vector<CountingShader::Attributes> v;
    for (std::size_t i = 0; i < rim.size(); ++i) {
        const vec2 a = rim[i], b = rim[(i + 1) % rim.size()];
        for (vec2 p : {centre, a, b})
            v.push_back({testing::clipFromWindow(p, fb) * w});
    }
    DrawState state = testing::stateFor(fb);
    state.blend = BlendMode::Additive;
    state.depth.testEnabled = false;
    testing::drawTriangles<CountingShader>(state, v, fb);
}

TEST(PipelineCoverage, FanAlongTheWindowBorderCoversEveryPixelOnce) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> step(0.3f, 9.7f);
    for (int trial = 0; trial < 5; ++trial) {
        Framebuffer fb(97, 61);
        fb.clearColor(vec4(0));
        // Walk the border with random non-integer steps; the fan then covers the whole window.
        // Odd trials put the centre on a pixel centre and the rim on whole pixels, so many edges run
        // exactly through sample points and only the fill rule decides who owns them.
        const bool onGrid = trial % 2 == 1;
        auto next = [&] { return onGrid ? std::round(step(rng)) + 1.0f : step(rng); };
        std::vector<vec2> rim;
        const float W = 97, H = 61;
        for (float x = 0; x < W; x += next())
            rim.push_back({x, 0});
        for (float y = 0; y < H; y += next())
            rim.push_back({W, y});
        for (float x = W; x > 0; x -= next())
            rim.push_back({x, H});
        for (float y = H; y > 0; y -= next())
            rim.push_back({0, y});
        std::uniform_real_distribution<float> cx(5, W - 5), cy(5, H - 5);
        vec2 centre(cx(rng), cy(rng));
        if (onGrid) centre = glm::floor(centre) + 0.5f;
        drawFan(fb, centre, rim);
        for (int y = 0; y < fb.height(); ++y)
            for (int x = 0; x < fb.width(); ++x)
                ASSERT_EQ(hits(fb, x, y), 1) << "trial " << trial << " pixel " << x << "," << y;
    }
}

// Multisampling shades a partly covered pixel at a sample inside the triangle (the centroid rule:
// the first covered sample in the pattern's order), so its varyings are never extrapolated beyond the
// triangle. Red is λ of the apex (0 along the long edge opposite it, 1 at the apex): a pixel whose
// centre lies beyond that edge but with a sample inside would be shaded with a negative red. Breaks if
// the shading point stays the pixel centre for every pixel (Facet before the centroid rule), or if a
// partly covered pixel takes another pixel's centroid.
TEST(PipelineMultisampling, PartlyCoveredPixelsInterpolateInsideTheTriangle) {
    for (const int samples : {2, 4, 8, 16}) {
        SCOPED_TRACE(samples);
        Framebuffer fb(64, 48);
        fb.useSamples(samples);
        DrawContext context(1);
        fb.clear(vec4(0.5f), DepthFormat::kClear, context.pool);
        DrawState state = testing::stateFor(fb);
        state.samples = samples;
        const std::vector<ClipSpaceColorShader::Attributes> triangle = {
            {testing::clipFromWindow({1.3f, 3.1f}, fb), vec4(0.0f, 0.0f, 0.0f, 1.0f)},
            {testing::clipFromWindow({62.6f, 40.2f}, fb), vec4(0.0f, 0.0f, 0.0f, 1.0f)},
            {testing::clipFromWindow({6.4f, 46.7f}, fb), vec4(1.0f, 0.0f, 0.0f, 1.0f)}};
        testing::drawTriangles<ClipSpaceColorShader>(state, triangle, fb);
        int written = 0, partlyCovered = 0, extrapolated = 0;
        for (int y = 0; y < fb.height(); ++y)
            for (int x = 0; x < fb.width(); ++x) {
                int covered = 0;
                for (int s = 0; s < samples; ++s) {
                    const vec4 c = fb.sampleColors(x, y)[s];
                    if (c == vec4(0.5f)) continue;
                    ++covered;
                    extrapolated += c.r < 0.0f || c.r > 1.0f;
                }
                written += covered;
                partlyCovered += covered > 0 && covered < samples;
            }
        EXPECT_GT(written, 500 * samples);
        EXPECT_GT(partlyCovered, 40);
        EXPECT_EQ(extrapolated, 0);
    }
}

// The same around a circle much larger than the window: every triangle is clipped by the x/y planes,
// and the clipped pieces of neighbouring triangles must still meet without cracks or overlaps.
TEST(PipelineCoverage, FanLargerThanTheWindowCoversEveryPixelOnceThroughClipping) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> jitter(0.2f, 1.0f);
    for (int trial = 0; trial < 5; ++trial) {
        Framebuffer fb(80, 50);
        fb.clearColor(vec4(0));
        std::vector<vec2> rim;
        const vec2 centre(40.3f + trial, 24.7f - trial);
        const float radius = 400.0f;
        for (float angle = 0; angle < 2 * std::numbers::pi_v<float>; angle += 0.15f * jitter(rng))
            rim.push_back(centre + radius * vec2(std::cos(angle), std::sin(angle)));
        drawFan(fb, centre, rim, 1.0f + trial);  // w ≠ 1 too: the divide must not break the seams
        for (int y = 0; y < fb.height(); ++y)
            for (int x = 0; x < fb.width(); ++x)
                ASSERT_EQ(hits(fb, x, y), 1) << "trial " << trial << " pixel " << x << "," << y;
    }
}

// A fan of many tiny triangles (about 0.1 px² each) must still fill the pixel centres it covers:
// slivers are not culled for being small, only for zero area.
TEST(PipelineCoverage, TinyTrianglesLeaveNoHoles) {
    Framebuffer fb(16, 16);
    fb.clearColor(vec4(0));
    std::vector<vec2> rim;
    for (int i = 0; i < 2000; ++i) {
        const float angle = 2 * std::numbers::pi_v<float> * i / 2000;
        rim.push_back(vec2(8, 8) + 6.0f * vec2(std::cos(angle), std::sin(angle)));
    }
    drawFan(fb, {8, 8}, rim);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            const float r = glm::length(vec2(x + 0.5f, y + 0.5f) - vec2(8, 8));
            if (r < 5.9f) {
                EXPECT_EQ(hits(fb, x, y), 1) << x << "," << y;
            }
            if (r > 6.1f) {
                EXPECT_EQ(hits(fb, x, y), 0) << x << "," << y;
            }
            EXPECT_LE(hits(fb, x, y), 1);
        }
}

TEST(PipelineRobustness, NonFiniteVerticesDrawNothing) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    for (vec4 bad : {vec4(nan, 0, 0, 1), vec4(0, inf, 0, 1), vec4(-inf, 0, 0, 1), vec4(0, 0, 0, nan),
                     vec4(0, 0, inf, 1)}) {
        Framebuffer fb(16, 16);
        fb.clearColor(vec4(0));
        DrawState state = testing::stateFor(fb);
        std::vector<ClipSpaceColorShader::Attributes> v = {
            {bad, vec4(1)}, {{1, -1, 0, 1}, vec4(1)}, {{-1, 1, 0, 1}, vec4(1)}};
        const DrawStats stats = testing::drawTriangles<ClipSpaceColorShader>(state, v, fb);
        EXPECT_EQ(stats.trianglesRejected, 1u);
        EXPECT_EQ(stats.fragmentsShaded, 0u);
        for (const vec4& c : fb.colorPixels())
            ASSERT_EQ(c, vec4(0));
    }
}

TEST(PipelineRobustness, VerticesAt1e30DrawNothingWhenOutsideAndStayFinite) {
    Framebuffer fb(16, 16);
    fb.clearColor(vec4(0));
    DrawState state = testing::stateFor(fb);
    // Wholly outside the frustum: rejected before clipping.
    std::vector<ClipSpaceColorShader::Attributes> outside = {
        {{1e30f, 1e30f, 0, 1}, vec4(1)}, {{2e30f, 1e30f, 0, 1}, vec4(1)}, {{1e30f, 3e30f, 0, 1}, vec4(1)}};
    DrawStats stats = testing::drawTriangles<ClipSpaceColorShader>(state, outside, fb);
    EXPECT_EQ(stats.fragmentsShaded, 0u);
    // One vertex far away, two on screen: clipped to the window, every written value finite, and the
    // covered area is the clipped wedge (nonzero): no crash, no NaN.
    std::vector<ClipSpaceColorShader::Attributes> mixed = {
        {{1e30f, 1e30f, 0, 1}, vec4(1)}, {{-1, -1, 0, 1}, vec4(1)}, {{1, -1, 0, 1}, vec4(1)}};
    stats = testing::drawTriangles<ClipSpaceColorShader>(state, mixed, fb);
    EXPECT_GT(stats.fragmentsWritten, 0u);
    for (const vec4& c : fb.colorPixels())
        for (int k = 0; k < 4; ++k)
            ASSERT_TRUE(std::isfinite(c[k]));
}

// A triangle 2^20 pixels across, mostly off screen: clipped and snapped without overflow (run under
// UBSan in CI) and covering exactly the pixels a float reference predicts.
TEST(PipelineRobustness, HugeTriangleClippedToASmallViewport) {
    Framebuffer fb(64, 64);
    fb.clearColor(vec4(0));
    DrawState state = testing::stateFor(fb);
    state.blend = BlendMode::Additive;
    state.depth.testEnabled = false;
    const float big = 1 << 20;
    const std::vector<vec2> corners = {{-big, -big}, {big, 30.3f}, {-big, big}};
    std::vector<CountingShader::Attributes> v;
    for (vec2 c : corners)
        v.push_back({testing::clipFromWindow(c, fb)});
    testing::drawTriangles<CountingShader>(state, v, fb);
    // The edge from (big, 30.3) to (−big, −big) and to (−big, big): near the window they are the lines
    // through (big, 30.3) with slopes ≈ ½ and ≈ −½ in y per x. Check pixels clearly away from the edges.
    auto edgeY = [&](vec2 a, vec2 b, float x) { return a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x); };
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const float px = x + 0.5f, py = y + 0.5f;
            const float upper = edgeY(corners[1], corners[0], px), lower = edgeY(corners[1], corners[2], px);
            if (py > upper + 0.01f && py < lower - 0.01f) {
                EXPECT_EQ(hits(fb, x, y), 1) << x << "," << y;
            }
            if (py < upper - 0.01f || py > lower + 0.01f) {
                EXPECT_EQ(hits(fb, x, y), 0) << x << "," << y;
            }
        }
}

TEST(PipelineRobustness, OddFramebufferSizesAndTheLastRowAndColumn) {
    for (auto [w, h] : {std::pair{1, 1}, {3, 7}, {4097, 1}, {1, 333}}) {
        Framebuffer fb(w, h);
        fb.clearColor(vec4(0));
        DrawState state = testing::stateFor(fb);
        state.blend = BlendMode::Additive;
        state.depth.testEnabled = false;
        // Two triangles making the full-screen quad: every pixel exactly once, the last row/column too.
        std::vector<CountingShader::Attributes> v = {{{-1, -1, 0, 1}}, {{1, -1, 0, 1}}, {{1, 1, 0, 1}},
                                                     {{-1, -1, 0, 1}}, {{1, 1, 0, 1}},  {{-1, 1, 0, 1}}};
        testing::drawTriangles<CountingShader>(state, v, fb);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                ASSERT_EQ(hits(fb, x, y), 1) << w << "x" << h << " pixel " << x << "," << y;
    }
}

TEST(PipelineRobustness, InvalidDrawsAreRefusedWithAReason) {
    Framebuffer fb(8, 8);
    DrawContext scratch;
    DrawState state = testing::stateFor(fb);
    std::vector<CountingShader::Attributes> v = {{{0, 0, 0, 1}}, {{1, 0, 0, 1}}, {{0, 1, 0, 1}}};
    std::vector<std::uint32_t> badIndices = {0, 1, 3};
    EXPECT_THROW(draw<CountingShader>(state, {}, std::span<const CountingShader::Attributes>(v),
                                      std::span<const std::uint32_t>(badIndices), fb, scratch),
                 std::invalid_argument);
    state.viewport.width = 9;
    std::vector<std::uint32_t> indices = {0, 1, 2};
    EXPECT_THROW(draw<CountingShader>(state, {}, std::span<const CountingShader::Attributes>(v),
                                      std::span<const std::uint32_t>(indices), fb, scratch),
                 std::invalid_argument);
}

// Breaks caught: the largest index missing one position of a vectorised loop (its head or its tail, any
// length), an index equal to the vertex count let through, the message not naming index and position.
// The loop is the copy this test is compiled with; the renderer's instruction-set copies compile the
// same source (the bytes tests of FACET_ISA compare their images, not their refusals).
TEST(PipelineRobustness, EveryIndexIsCheckedAndTheFirstBadOneNamed) {
    for (std::size_t count = 1; count <= 70; ++count)
        for (std::size_t at = 0; at < count; ++at) {
            std::vector<std::uint32_t> indices(count, 5u);
            indices[at] = 9u;
            ASSERT_EQ(largestIndex(indices), 9u) << count << " indices, the largest at " << at;
        }
    EXPECT_EQ(largestIndex({}), 0u);

    Framebuffer fb(8, 8);
    DrawContext scratch;
    const DrawState state = testing::stateFor(fb);
    std::vector<CountingShader::Attributes> v = {{{0, 0, 0, 1}}, {{1, 0, 0, 1}}, {{0, 1, 0, 1}}};
    std::vector<std::uint32_t> indices = {0, 1, 2, 2, 1, 0, 0, 1, 2};
    EXPECT_NO_THROW(draw<CountingShader>(state, {}, std::span<const CountingShader::Attributes>(v),
                                         std::span<const std::uint32_t>(indices), fb, scratch));
    indices[7] = 3;  // the vertex count: one past the last vertex
    indices[8] = 4;
    try {
        draw<CountingShader>(state, {}, std::span<const CountingShader::Attributes>(v),
                             std::span<const std::uint32_t>(indices), fb, scratch);
        FAIL() << "an index out of range was drawn";
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "index 3 at position 7 is out of range (3 vertices)");
    }
}

// The vertex shader runs once per vertex of an indexed mesh, however many triangles share it.
struct CountingVertexShader {
    struct Attributes {
        vec4 position;
    };
    struct Varyings {};
    struct Uniforms {
        int* vertexCalls;
        int* fragmentCalls;
    };
    static VertexOut<Varyings> vertex(const Attributes& in, const Uniforms& u) {
        ++*u.vertexCalls;
        return {in.position, {}};
    }
    static std::optional<vec4> fragment(const Varyings&, const Uniforms& u) {
        ++*u.fragmentCalls;
        return std::nullopt;  // discards everything
    }
};

TEST(PipelineStages, VertexShaderOncePerVertexAndDiscardWritesNothing) {
    Framebuffer fb(16, 16);
    fb.clearColor(vec4(0.5f));
    fb.clearDepth(1.0f);
    int vertexCalls = 0, fragmentCalls = 0;
    // A quad from 4 vertices and 6 indices.
    std::vector<CountingVertexShader::Attributes> v = {
        {{-1, -1, 0, 1}}, {{1, -1, 0, 1}}, {{1, 1, 0, 1}}, {{-1, 1, 0, 1}}};
    std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3};
    DrawContext scratch;
    const DrawStats stats = draw<CountingVertexShader>(testing::stateFor(fb), {&vertexCalls, &fragmentCalls},
                                                       std::span<const CountingVertexShader::Attributes>(v),
                                                       std::span<const std::uint32_t>(indices), fb, scratch);
    EXPECT_EQ(vertexCalls, 4);
    EXPECT_EQ(fragmentCalls, 16 * 16);
    EXPECT_EQ(stats.fragmentsDiscarded, 256u);
    EXPECT_EQ(stats.fragmentsWritten, 0u);
    for (const vec4& c : fb.colorPixels())
        ASSERT_EQ(c, vec4(0.5f));
    for (float d : fb.depthPixels())
        ASSERT_EQ(d, 1.0f);  // a discarded fragment writes no depth
}

// The back end visits only the tiles some triangle touches: a small triangle costs one tile, not the
// whole framebuffer's, and its pixels are the same as when it is drawn among triangles covering every tile.
TEST(PipelineStages, OnlyTheTilesTrianglesTouchAreDrawn) {
    Framebuffer alone(4 * kDefaultTileSize, 3 * kDefaultTileSize), among(alone.width(), alone.height());
    const vec2 corner(1.5f * kDefaultTileSize, 1.25f * kDefaultTileSize);  // inside tile (1, 1)
    const std::vector<ClipSpaceColorShader::Attributes> small = {
        {testing::clipFromWindow(corner, alone), vec4(1, 0, 0, 1)},
        {testing::clipFromWindow(corner + vec2(20, 0), alone), vec4(0, 1, 0, 1)},
        {testing::clipFromWindow(corner + vec2(0, 20), alone), vec4(0, 0, 1, 1)}};
    for (Framebuffer* fb : {&alone, &among}) {
        fb->clearColor(vec4(0));
        fb->clearDepth(1.0f);
    }
    DrawState state = testing::stateFor(alone);
    state.depth.testEnabled = false;
    state.blend = BlendMode::Additive;
    const DrawStats smallStats = testing::drawTriangles<ClipSpaceColorShader>(state, small, alone);
    EXPECT_EQ(smallStats.tilesDrawn, 1u);
    EXPECT_GT(smallStats.fragmentsWritten, 100u);

    // The same triangle after two covering the whole framebuffer in black (adding nothing).
    std::vector<ClipSpaceColorShader::Attributes> both;
    for (const vec2 p : {vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1)})
        both.push_back({testing::clipFromWindow(p * vec2(among.width(), among.height()), among), vec4(0)});
    both.insert(both.end(), small.begin(), small.end());
    const DrawStats bothStats = testing::drawTriangles<ClipSpaceColorShader>(state, both, among);
    EXPECT_EQ(bothStats.tilesDrawn, 12u);
    EXPECT_EQ(alone.colorPixels(), among.colorPixels());
}

// Varyings of several types arrive interpolated: at a vertex sitting on a pixel centre they are exact.
struct MixedVaryingShader {
    struct Attributes {
        vec4 position;
        vec3 normal;
        vec2 uv;
        float weight;
    };
    struct Varyings {
        vec3 normal;
        vec2 uv;
        float weight;
    };
    struct Uniforms {};
    static VertexOut<Varyings> vertex(const Attributes& in, const Uniforms&) {
        return {in.position, {in.normal, in.uv, in.weight}};
    }
    static vec4 fragment(const Varyings& in, const Uniforms&) { return vec4(in.uv, in.weight, in.normal.z); }
};

TEST(PipelineStages, VaryingStructsRoundTripThroughTheFlatArray) {
    static_assert(kVaryingFloatCount<MixedVaryingShader::Varyings> == 6);
    Framebuffer fb(8, 8);
    fb.clearColor(vec4(0));
    // Vertex 0 at the centre of pixel (0, 0), with w = 2 to exercise the perspective divide.
    const vec4 p0 = testing::clipFromWindow({0.5f, 0.5f}, fb) * 2.0f;
    std::vector<MixedVaryingShader::Attributes> v = {
        {p0, {0, 0, 0.25f}, {0.125f, 0.75f}, 3.5f},
        {testing::clipFromWindow({8, 0}, fb), {0, 0, 1}, {1, 1}, 1},
        {testing::clipFromWindow({0, 8}, fb), {0, 0, 1}, {1, 1}, 1}};
    testing::drawTriangles<MixedVaryingShader>(testing::stateFor(fb), v, fb);
    const vec4 c = fb.color(0, 0);
    EXPECT_NEAR(c.x, 0.125f, 1e-6f);
    EXPECT_NEAR(c.y, 0.75f, 1e-6f);
    EXPECT_NEAR(c.z, 3.5f, 1e-6f);
    EXPECT_NEAR(c.w, 0.25f, 1e-6f);
}

struct RecordingObserver : NullObserver {
    static constexpr bool enabled = true;
    int vertices = 0, assembled = 0, clipped = 0, setups = 0;
    std::vector<TriangleFate> rejections;
    std::vector<FragmentEvent> fragments;
    void onVertex(std::uint32_t, const vec4&, const float*, int, std::uint8_t) { ++vertices; }
    void onAssembled(std::uint32_t, const ClipPolygon&) { ++assembled; }
    void onClipped(std::uint32_t, const ClipPolygon&) { ++clipped; }
    void onSetup(std::uint32_t, const WindowTriangle&, TriangleFate, const TriangleSetup&) { ++setups; }
    void onRejected(std::uint32_t, TriangleFate fate) { rejections.push_back(fate); }
    void onFragment(const FragmentEvent& e) { fragments.push_back(e); }
};

// Flat varyings take the provoking vertex's value, bit for bit, on every pixel: the last vertex by
// default (OpenGL), the first when asked (Direct3D, Vulkan), and still that vertex's value on every
// fan piece of a triangle that clipping cut up (clipping must not make a new provoking vertex).
TEST(PipelineStages, FlatVaryingsTakeTheProvokingVertexValueExactly) {
    const vec4 colors[3] = {vec4(0.1f, 0.2f, 0.3f, 1.0f), vec4(0.7f, 0.11f, 0.13f, 1.0f),
                            vec4(0.123456f, 0.654321f, 0.999f, 0.5f)};
    for (ProvokingVertex provoking : {ProvokingVertex::Last, ProvokingVertex::First}) {
        for (bool clipped : {false, true}) {
            Framebuffer fb(40, 30);
            fb.clearColor(vec4(-1.0f));
            DrawState state = testing::stateFor(fb);
            state.raster.provokingVertex = provoking;
            state.depth.testEnabled = false;  // the second draw covers the same pixels
            // Perspective: different w at each vertex, so interpolating would not give a constant.
            // The clipped case pokes vertex 1 far out through the left and near planes.
            std::vector<FlatColorShader::Attributes> v = {
                {testing::clipFromWindow({3, 2}, fb) * 1.0f, colors[0]},
                {clipped ? vec4(-30.0f, 0.5f, -4.0f, 2.0f) : testing::clipFromWindow({37, 5}, fb) * 3.0f,
                 colors[1]},
                {testing::clipFromWindow({20, 27}, fb) * 0.5f, colors[2]},
            };
            const DrawStats stats = testing::drawTriangles<FlatColorShader>(state, v, fb);
            EXPECT_EQ(stats.trianglesClipped, clipped ? 1u : 0u);
            const vec4 expected = colors[provoking == ProvokingVertex::Last ? 2 : 0];
            int covered = 0;
            for (int y = 0; y < fb.height(); ++y)
                for (int x = 0; x < fb.width(); ++x) {
                    if (fb.color(x, y).r == -1.0f) continue;
                    ++covered;
                    ASSERT_EQ(fb.color(x, y), expected) << "pixel " << x << ", " << y;
                }
            EXPECT_GT(covered, 100);

            // The same triangle with the colour interpolated is not constant.
            fb.clearColor(vec4(-1.0f));
            testing::drawTriangles<FlatColorShader>(state, v, fb, {.showSmooth = true});
            int differing = 0;
            for (int y = 0; y < fb.height(); ++y)
                for (int x = 0; x < fb.width(); ++x)
                    if (fb.color(x, y).r != -1.0f && fb.color(x, y) != expected) ++differing;
            EXPECT_GT(differing, 50);
        }
    }
}

TEST(PipelineObserver, SeesEveryStageAndEveryFragmentFate) {
    Framebuffer fb(4, 4);
    fb.clearColor(vec4(0));
    fb.clearDepth(1.0f);
    DrawState state = testing::stateFor(fb);
    // Triangle 0: covers the screen at depth 0.25 (written). Triangle 1: the same at depth 0.75 (fails
    // depth). Both reach past the right and top planes, so they are clipped too. Triangle 2: crosses the
    // near plane (clipped). Triangle 3: wholly left of the window (rejected before clipping).
    std::vector<ClipSpaceColorShader::Attributes> v = {
        {{-1, -1, -0.5f, 1}, vec4(1)}, {{3, -1, -0.5f, 1}, vec4(1)}, {{-1, 3, -0.5f, 1}, vec4(1)},
        {{-1, -1, 0.5f, 1}, vec4(1)},  {{3, -1, 0.5f, 1}, vec4(1)},  {{-1, 3, 0.5f, 1}, vec4(1)},
        {{-1, -1, -3, 1}, vec4(1)},    {{1, -1, 0.9f, 1}, vec4(1)},  {{-1, 1, 0.9f, 1}, vec4(1)},
        {{-5, 0, 0, 1}, vec4(1)},      {{-4, 0, 0, 1}, vec4(1)},     {{-5, 1, 0, 1}, vec4(1)}};
    std::vector<std::uint32_t> indices(v.size());
    for (std::size_t i = 0; i < v.size(); ++i)
        indices[i] = static_cast<std::uint32_t>(i);
    DrawContext scratch;
    RecordingObserver observer;
    draw<ClipSpaceColorShader>(state, {}, std::span<const ClipSpaceColorShader::Attributes>(v),
                               std::span<const std::uint32_t>(indices), fb, scratch, observer);
    EXPECT_EQ(observer.vertices, 12);
    EXPECT_EQ(observer.assembled, 3);
    EXPECT_EQ(observer.clipped, 3);
    ASSERT_EQ(observer.rejections.size(), 1u);
    EXPECT_EQ(observer.rejections[0], TriangleFate::OutsideFrustum);
    int fragmentsPerTriangle[3] = {};
    for (const FragmentEvent& e : observer.fragments) {
        ASSERT_LT(e.triangle, 3u);
        ++fragmentsPerTriangle[e.triangle];
        if (e.triangle == 0) {
            EXPECT_EQ(e.fate, FragmentFate::Written);
        }
        if (e.triangle == 1) {
            EXPECT_EQ(e.fate, FragmentFate::DepthFailed);
        }
        if (e.fate == FragmentFate::Written) {
            EXPECT_EQ(e.colorAfter, vec4(1));
        }
    }
    EXPECT_EQ(fragmentsPerTriangle[0], 16);
    EXPECT_EQ(fragmentsPerTriangle[1], 16);
    EXPECT_GT(fragmentsPerTriangle[2], 0);
}

// Drawing the same thing twice gives the same bytes.
TEST(PipelineDeterminism, SameInputSameBytes) {
    auto render = [] {
        Framebuffer fb(50, 40);
        fb.clearColor(vec4(0));
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> u(-1.5f, 1.5f);
        std::vector<ClipSpaceColorShader::Attributes> v;
        for (int i = 0; i < 300; ++i)
            v.push_back({vec4(u(rng), u(rng), u(rng) * 0.6f, 1.0f), vec4(u(rng), u(rng), u(rng), 1)});
        testing::drawTriangles<ClipSpaceColorShader>(testing::stateFor(fb), v, fb);
        return fb.colorPixels();
    };
    EXPECT_EQ(render(), render());
}

}  // namespace
}  // namespace facet
