// The observer hooks (observer.h) see what a pixel history needs, and watching never changes a byte:
// an observed draw gives the same framebuffer as an unobserved one.
#include <algorithm>
#include <map>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "../support/patch_checks.h"
#include "../support/test_shaders.h"
#include "pipeline.h"

namespace facet {
namespace {

using testing::ClipSpaceColorShader;
using testing::FlatColorShader;
using testing::RedDiscardingShader;

// Records every hook.
struct RecordingObserver : NullObserver {
    static constexpr bool enabled = true;
    std::vector<std::uint64_t> drawsBegun, drawsEnded;
    std::vector<DrawStats> endStats;
    std::vector<std::pair<std::uint32_t, TriangleFate>> setups;
    std::vector<CoverageEvent> coverage;
    std::vector<FragmentEvent> fragments;
    std::vector<ResolveEvent> resolves;
    std::vector<std::vector<ResolvedFragment>> resolvedLists;  // the spans' contents, kept

    void onDrawBegin(std::uint64_t id, const DrawState&) { drawsBegun.push_back(id); }
    void onDrawEnd(std::uint64_t id, const DrawStats& stats) {
        drawsEnded.push_back(id);
        endStats.push_back(stats);
    }
    void onSetup(std::uint32_t triangle, const WindowTriangle&, TriangleFate fate, const TriangleSetup&) {
        setups.emplace_back(triangle, fate);
    }
    void onCoverage(const CoverageEvent& e) { coverage.push_back(e); }
    void onFragment(const FragmentEvent& e) { fragments.push_back(e); }
    void onResolve(const ResolveEvent& e) {
        resolves.push_back(e);
        resolvedLists.emplace_back(e.fragments.begin(), e.fragments.end());
    }
};

// A shader with an eight-lane fragment function, so the observed draw goes through fragmentBatch too.
struct BatchColorShader : ClipSpaceColorShader {
    static Vec4x8 fragmentBatch(const FragmentBatch& in, const Uniforms&) {
        return {in.varyings[0], in.varyings[1], in.varyings[2], in.varyings[3]};
    }
};
static_assert(BatchShader<BatchColorShader>);

template <class S>
std::vector<typename S::Attributes> randomTriangles(std::mt19937& rng, int count) {
    std::uniform_real_distribution<float> u(-1.4f, 1.4f), c(0.0f, 1.0f);
    std::vector<typename S::Attributes> v;
    for (int i = 0; i < 3 * count; ++i)
        v.push_back({vec4(u(rng), u(rng), u(rng) * 0.8f, 1.0f), vec4(c(rng), c(rng), c(rng), c(rng))});
    return v;
}

template <class S>
void drawBoth(const DrawState& state, const std::vector<typename S::Attributes>& v, Framebuffer& plain,
              DrawContext& plainContext, Framebuffer& watched, DrawContext& watchedContext,
              RecordingObserver& observer) {
    std::vector<std::uint32_t> indices(v.size());
    for (std::size_t i = 0; i < indices.size(); ++i)
        indices[i] = static_cast<std::uint32_t>(i);
    const std::span<const typename S::Attributes> vertices(v);
    const DrawStats plainStats = draw<S>(state, {}, vertices, indices, plain, plainContext);
    const DrawStats watchedStats = draw<S>(state, {}, vertices, indices, watched, watchedContext, observer);
    EXPECT_EQ(plainStats.fragmentsShaded, watchedStats.fragmentsShaded);
    EXPECT_EQ(plainStats.fragmentsWritten, watchedStats.fragmentsWritten);
    EXPECT_EQ(plainStats.fragmentsStored, watchedStats.fragmentsStored);
    EXPECT_EQ(plainStats.trianglesCulled, watchedStats.trianglesCulled);
}

// Opaque draws of several shaders and states, then transparent AppendToLists draws and their resolve:
// the observed frame is the same bytes, colour and depth, as the unobserved one (which runs on three
// threads in small tiles).
// Break caught: the observed resolve of a one-fragment list blending it into the pixel twice.
TEST(Observer, WatchingChangesNoByte) {
    std::mt19937 rng(42);
    Framebuffer plain(61, 47), watched(61, 47);
    DrawContext plainContext(3, 16), watchedContext(1, 16);
    RecordingObserver observer;
    for (Framebuffer* fb : {&plain, &watched})
        fb->clear(vec4(0.1f, 0.2f, 0.3f, 1.0f), DepthFormat::kClear, plainContext.pool);

    DrawState state = testing::stateFor(plain);
    state.raster.cull = CullMode::Back;
    drawBoth<ClipSpaceColorShader>(state, randomTriangles<ClipSpaceColorShader>(rng, 40), plain, plainContext,
                                   watched, watchedContext, observer);
    state.raster.cull = CullMode::None;
    state.interpolation = Interpolation::Affine;
    state.depth.compare = CompareOp::LessEqual;
    drawBoth<RedDiscardingShader>(state, randomTriangles<RedDiscardingShader>(rng, 30), plain, plainContext,
                                  watched, watchedContext, observer);
    state.interpolation = Interpolation::PerspectiveCorrect;
    state.blend = BlendMode::Additive;
    drawBoth<BatchColorShader>(state, randomTriangles<BatchColorShader>(rng, 30), plain, plainContext,
                               watched, watchedContext, observer);
    state.raster.provokingVertex = ProvokingVertex::First;
    state.blend = BlendMode::Over;
    state.depth.writeEnabled = false;
    drawBoth<FlatColorShader>(state, randomTriangles<FlatColorShader>(rng, 30), plain, plainContext, watched,
                              watchedContext, observer);
    EXPECT_EQ(plain.colorPixels(), watched.colorPixels());
    EXPECT_EQ(plain.depthPixels(), watched.depthPixels());

    // Transparent draws into the fragment lists, each with its own blend mode, then the resolve.
    state.output = FragmentOutput::AppendToLists;
    for (BlendMode mode : {BlendMode::Over, BlendMode::PremultipliedOver, BlendMode::Multiply}) {
        state.blend = mode;
        drawBoth<ClipSpaceColorShader>(state, randomTriangles<ClipSpaceColorShader>(rng, 20), plain,
                                       plainContext, watched, watchedContext, observer);
    }
    const FragmentListStats plainLists = resolveFragmentLists(plain, plainContext.pool);
    const FragmentListStats watchedLists = resolveFragmentLists(watched, watchedContext.pool, observer);
    EXPECT_EQ(plainLists.fragments, watchedLists.fragments);
    EXPECT_GT(plainLists.longestList, 1u);
    EXPECT_EQ(plain.colorPixels(), watched.colorPixels());
    EXPECT_EQ(plain.depthPixels(), watched.depthPixels());
    EXPECT_EQ(observer.resolves.size(), plainLists.pixels);
    EXPECT_EQ(observer.drawsBegun, (std::vector<std::uint64_t>{0, 1, 2, 3, 4, 5, 6}));
    EXPECT_EQ(observer.drawsEnded, observer.drawsBegun);
}

// The watched back end chooses the depth coding and the colour buffer's rounding per fragment, where the
// unwatched one has a copy per choice: every depth format and colour buffer format gives the same bytes
// watched as not.
// Breaks caught: the watched copy storing depths as floats under a unorm format, or not rounding colours
// to a half or 8-bit colour buffer.
TEST(Observer, WatchingChangesNoByteInAnyBufferFormat) {
    for (DepthBufferFormat depthFormat : {DepthBufferFormat::Float, DepthBufferFormat::Unorm16,
                                          DepthBufferFormat::Unorm24, DepthBufferFormat::ReversedFloat})
        for (ColorBufferFormat colorFormat :
             {ColorBufferFormat::Float, ColorBufferFormat::Half, ColorBufferFormat::Unorm8}) {
            SCOPED_TRACE(std::to_string(static_cast<int>(depthFormat)) + " " +
                         std::to_string(static_cast<int>(colorFormat)));
            std::mt19937 rng(7);
            Framebuffer plain(37, 29), watched(37, 29);
            DrawContext plainContext(2, 16), watchedContext(1, 16);
            RecordingObserver observer;
            for (Framebuffer* fb : {&plain, &watched})
                fb->clear(roundToColorBuffer(colorFormat, vec4(0.1f, 0.2f, 0.3f, 1.0f)),
                          depthClearValue(depthFormat), plainContext.pool);
            DrawState state = testing::stateFor(plain);
            state.depth.format = depthFormat;
            state.depth.compare = nearerPasses(depthFormat, CompareOp::Less);
            state.colorBuffer = colorFormat;
            state.blend = BlendMode::Over;
            drawBoth<BatchColorShader>(state, randomTriangles<BatchColorShader>(rng, 40), plain, plainContext,
                                       watched, watchedContext, observer);
            EXPECT_EQ(plain.colorPixels(), watched.colorPixels());
            EXPECT_EQ(plain.depthPixels(), watched.depthPixels());
            if (depthFormat == DepthBufferFormat::Unorm16) {  // the codes are integers
                for (float d : watched.depthPixels())
                    ASSERT_EQ(d, std::round(d));
            }
            if (colorFormat == ColorBufferFormat::Unorm8) {  // the colours are multiples of 1/255
                for (const vec4& c : watched.colorPixels())
                    ASSERT_EQ(roundToUnorm8(c.r), c.r);
            }
        }
}

// Direct3D's example of the fill rule: the square (0,0)–(5,5) split along its diagonal, whose five
// pixel centres lie exactly on the shared edge. The observer sees each of them as a tie on the diagonal
// for both triangles, included by the one for which it is a left edge (the upper right) and excluded by
// the other, and
// the covered samples are exactly the fragments.
// Breaks caught: a tie reported from the biased edge value, or a top-left edge reported as not.
TEST(Observer, CoverageShowsTheFillRuleSettlingTies) {
    Framebuffer fb(8, 8);
    fb.clearColor(vec4(0));
    std::vector<ClipSpaceColorShader::Attributes> v;
    for (vec2 p : {vec2(0, 0), vec2(5, 0), vec2(5, 5), vec2(0, 0), vec2(5, 5), vec2(0, 5)})
        v.push_back({testing::clipFromWindow(p, fb), vec4(1)});
    std::vector<std::uint32_t> indices = {0, 1, 2, 3, 4, 5};
    DrawContext context;
    RecordingObserver observer;
    draw<ClipSpaceColorShader>(testing::stateFor(fb), {},
                               std::span<const ClipSpaceColorShader::Attributes>(v), indices, fb, context,
                               observer);

    std::map<std::pair<int, int>, int> coveredBy;  // pixel → triangles covering it
    int included = 0, excluded = 0;
    for (const CoverageEvent& e : observer.coverage) {
        EXPECT_FALSE(e.culled);
        const bool onDiagonal = e.x == e.y && e.x < 5;
        if (e.covered) ++coveredBy[{e.x, e.y}];
        if (!onDiagonal) {
            EXPECT_EQ(e.tiedEdges, 0) << e;
            continue;
        }
        ASSERT_EQ(std::popcount(static_cast<unsigned>(e.tiedEdges)), 1) << e;
        if (e.covered) {
            EXPECT_EQ(e.tiesIncluded(), e.tiedEdges) << e;
            EXPECT_EQ(e.triangle, 0u)
                << e;  // the upper-right triangle lies right of the diagonal: a left edge
            ++included;
        } else {
            EXPECT_EQ(e.tiesExcluded(), e.tiedEdges) << e;
            EXPECT_EQ(e.excludingEdges, e.tiedEdges) << e;
            ++excluded;
        }
    }
    EXPECT_EQ(included, 5);
    EXPECT_EQ(excluded, 5);
    EXPECT_EQ(coveredBy.size(), 25u);
    for (const auto& [pixel, count] : coveredBy)
        EXPECT_EQ(count, 1) << pixel.first << "," << pixel.second;
    // The covered samples are the fragments, pixel for pixel and triangle for triangle.
    std::vector<std::pair<int, std::uint32_t>> coveredSamples, fragmentSamples;
    for (const CoverageEvent& e : observer.coverage)
        if (e.covered) coveredSamples.emplace_back(e.y * 8 + e.x, e.triangle);
    for (const FragmentEvent& e : observer.fragments)
        fragmentSamples.emplace_back(e.y * 8 + e.x, e.triangle);
    std::sort(coveredSamples.begin(), coveredSamples.end());
    std::sort(fragmentSamples.begin(), fragmentSamples.end());
    EXPECT_EQ(coveredSamples, fragmentSamples);
}

// Unwatched, the front end counts a triangle of zero area or culled for its facing from its area alone,
// before gathering it; watched, setupTriangle decides. Both must give the same fates and image under
// every cull mode and front face, with degenerate triangles (two vertices alike) among the rest.
// Breaks caught: the unwatched early test ignoring the cull mode or the front face (culling back faces
// under CullMode::Front or None), or counting a zero-area triangle as culled.
TEST(Observer, UnwatchedDrawsCullAndCountAsWatchedOnesDo) {
    std::mt19937 rng(7);
    std::vector<ClipSpaceColorShader::Attributes> v = randomTriangles<ClipSpaceColorShader>(rng, 60);
    for (std::size_t t = 0; t < v.size(); t += 9)  // every third triangle: its last vertex on its first
        v[t + 2].position = v[t].position;
    std::vector<std::uint32_t> indices(v.size());
    for (std::size_t i = 0; i < indices.size(); ++i)
        indices[i] = static_cast<std::uint32_t>(i);
    for (CullMode cull : {CullMode::None, CullMode::Back, CullMode::Front})
        for (FrontFace front : {FrontFace::CounterClockwise, FrontFace::Clockwise}) {
            Framebuffer plain(40, 30), watched(40, 30);
            DrawContext context;
            for (Framebuffer* fb : {&plain, &watched})
                fb->clear(vec4(0.0f), DepthFormat::kClear, context.pool);
            DrawState state = testing::stateFor(plain);
            state.raster.cull = cull;
            state.raster.frontFace = front;
            RecordingObserver observer;
            const std::span<const ClipSpaceColorShader::Attributes> vertices(v);
            const DrawStats plainStats =
                draw<ClipSpaceColorShader>(state, {}, vertices, indices, plain, context);
            const DrawStats watchedStats =
                draw<ClipSpaceColorShader>(state, {}, vertices, indices, watched, context, observer);
            SCOPED_TRACE(::testing::Message()
                         << "cull " << static_cast<int>(cull) << ", front face " << static_cast<int>(front));
            EXPECT_EQ(plainStats.trianglesCulled, watchedStats.trianglesCulled);
            EXPECT_EQ(plainStats.trianglesZeroArea, watchedStats.trianglesZeroArea);
            EXPECT_EQ(plainStats.trianglesMissingSamples, watchedStats.trianglesMissingSamples);
            EXPECT_EQ(plainStats.trianglesRasterized, watchedStats.trianglesRasterized);
            EXPECT_GT(watchedStats.trianglesZeroArea, 0u);
            if (cull == CullMode::None)
                EXPECT_EQ(watchedStats.trianglesCulled, 0u);
            else
                EXPECT_GT(watchedStats.trianglesCulled, 0u);
            EXPECT_EQ(plain.colorPixels(), watched.colorPixels());
        }
}

// A triangle a few pixels wide and up to eight tall is drawn as a stack of patches when unwatched, block
// by block when watched: the same bytes (support/patch_checks.h, also run for sixteen lanes in the
// AVX-512 test binary).
TEST(PatchWalk, TinyTrianglesDrawTheBytesOfTheBlockWalk) {
    testing_support::expectPatchWalkDrawsTheBlockWalksBytes();
}

// Which walk a triangle takes goes by its size: up to four pixels wide a narrow patch, up to eight a
// wide one, wider the block walk; each of them two rows tall.
// Breaks caught: triangles wider than a narrow patch left to the block walk; a triangle wider than a
// wide patch walked as one (its pixels beyond the eighth column lost).
TEST(PatchWalk, ATriangleUpToEightPixelsWideIsWalkedAsPatches) {
    for (const auto& [width, patchWalks] : {std::pair{3.0f, 1u}, {6.0f, 1u}, {12.0f, 0u}}) {
        SCOPED_TRACE(::testing::Message() << "a triangle " << width << " pixels wide");
        Framebuffer fb(32, 16);
        DrawContext context(1, 16);
        fb.clear(vec4(0.0f), 1.0f, context.pool);
        DrawState state = testing::stateFor(fb);
        state.raster.cull = CullMode::None;
        const vec4 white(1.0f);
        const std::vector<ClipSpaceColorShader::Attributes> v = {
            {testing::clipFromWindow(vec2(4.2f, 4.3f), fb), white},
            {testing::clipFromWindow(vec2(4.2f + width, 4.6f), fb), white},
            {testing::clipFromWindow(vec2(4.4f, 5.9f), fb), white}};
        const std::vector<std::uint32_t> indices = {0, 1, 2};
        const DrawStats stats = draw<ClipSpaceColorShader>(state, {}, v, indices, fb, context);
        EXPECT_GT(stats.fragmentsShaded, 0u);
        EXPECT_EQ(stats.patchWalks, patchWalks);
    }
}

// A back-facing triangle culled by the draw is still shown to the observer: the setup it would have had
// and the samples it would have covered, which are the ones it covers when culling is off.
// Break caught: the would-be setup made with the draw's own culling (so nothing is shown).
TEST(Observer, CulledTrianglesShowWhatTheyWouldHaveCovered) {
    Framebuffer fb(16, 16);
    fb.clearColor(vec4(0));
    // Clockwise on the screen: a back face under the default counter-clockwise front face.
    std::vector<ClipSpaceColorShader::Attributes> v;
    for (vec2 p : {vec2(1, 1), vec2(13, 2), vec2(4, 14)})
        v.push_back({testing::clipFromWindow(p, fb), vec4(1)});
    std::vector<std::uint32_t> indices = {0, 1, 2};
    DrawState state = testing::stateFor(fb);
    state.raster.cull = CullMode::Back;
    DrawContext context;
    RecordingObserver culled, drawn;
    const DrawStats stats = draw<ClipSpaceColorShader>(
        state, {}, std::span<const ClipSpaceColorShader::Attributes>(v), indices, fb, context, culled);
    EXPECT_EQ(stats.trianglesCulled, 1u);
    EXPECT_TRUE(culled.fragments.empty());
    ASSERT_EQ(culled.setups.size(), 1u);
    EXPECT_EQ(culled.setups[0].second, TriangleFate::Culled);
    state.raster.cull = CullMode::None;
    draw<ClipSpaceColorShader>(state, {}, std::span<const ClipSpaceColorShader::Attributes>(v), indices, fb,
                               context, drawn);
    std::vector<int> wouldCover, covers;
    for (const CoverageEvent& e : culled.coverage) {
        EXPECT_TRUE(e.culled);
        if (e.covered) wouldCover.push_back(e.y * 16 + e.x);
    }
    for (const FragmentEvent& e : drawn.fragments)
        covers.push_back(e.y * 16 + e.x);
    std::sort(wouldCover.begin(), wouldCover.end());
    std::sort(covers.begin(), covers.end());
    EXPECT_GT(covers.size(), 40u);
    EXPECT_EQ(wouldCover, covers);
}

// A back face between pixel centres is culled before its bounding box is known: the observer is still
// told (a Culled setup, its box empty) and is shown no sample, since there is none to show.
// Breaks caught: observeCulled returning before onSetup when the unculled setup draws nothing (the
// triangle vanishes from the step mode), or showing coverage of a setup that was never made.
TEST(Observer, CulledTriangleBetweenPixelCentresIsShownWithNoSamples) {
    Framebuffer fb(16, 16);
    fb.clearColor(vec4(0));
    std::vector<ClipSpaceColorShader::Attributes> v;
    for (vec2 p : {vec2(3.6f, 3.6f), vec2(4.4f, 3.6f), vec2(3.6f, 4.4f)})  // clockwise: a back face
        v.push_back({testing::clipFromWindow(p, fb), vec4(1)});
    std::vector<std::uint32_t> indices = {0, 1, 2};
    DrawState state = testing::stateFor(fb);
    state.raster.cull = CullMode::Back;
    DrawContext context;
    RecordingObserver observer;
    const DrawStats stats = draw<ClipSpaceColorShader>(
        state, {}, std::span<const ClipSpaceColorShader::Attributes>(v), indices, fb, context, observer);
    EXPECT_EQ(stats.trianglesCulled, 1u);
    EXPECT_EQ(stats.trianglesMissingSamples, 0u);
    ASSERT_EQ(observer.setups.size(), 1u);
    EXPECT_EQ(observer.setups[0].second, TriangleFate::Culled);
    EXPECT_TRUE(observer.coverage.empty());
    EXPECT_TRUE(observer.fragments.empty());
}

// Each fragment carries its barycentrics, 1/w and interpolated varyings: exact at a vertex sitting on a
// pixel centre, and everywhere the varyings the shader received (the written colour is the varying).
// Breaks caught: the event's varyings taken from another queue slot, or its λ from another lane.
TEST(Observer, FragmentsCarryTheirInterpolation) {
    Framebuffer fb(8, 8);
    fb.clearColor(vec4(0));
    fb.clearDepth();
    const vec4 c0(0.125f, 0.25f, 0.5f, 1.0f);
    std::vector<ClipSpaceColorShader::Attributes> v = {
        {testing::clipFromWindow({0.5f, 0.5f}, fb, -0.5f) * 2.0f, c0},
        {testing::clipFromWindow({8, 0}, fb, -0.5f), vec4(1, 0, 0, 1)},
        {testing::clipFromWindow({0, 8}, fb, -0.5f), vec4(0, 1, 0, 1)},
        // The same triangle again, behind: every fragment fails the depth test.
        {testing::clipFromWindow({0.5f, 0.5f}, fb, 0.5f) * 2.0f, c0},
        {testing::clipFromWindow({8, 0}, fb, 0.5f), vec4(1, 0, 0, 1)},
        {testing::clipFromWindow({0, 8}, fb, 0.5f), vec4(0, 1, 0, 1)}};
    std::vector<std::uint32_t> indices = {0, 1, 2, 3, 4, 5};
    DrawContext context;
    RecordingObserver observer;
    draw<ClipSpaceColorShader>(testing::stateFor(fb), {},
                               std::span<const ClipSpaceColorShader::Attributes>(v), indices, fb, context,
                               observer);
    int written = 0, failed = 0;
    std::map<int, vec4> writtenVaryings;
    for (const FragmentEvent& e : observer.fragments) {
        ASSERT_EQ(e.varyingCount, 4);
        const vec4 varyings(e.varyings[0], e.varyings[1], e.varyings[2], e.varyings[3]);
        // λ at the pixel's centre in screen space, from the window positions (0.5, 0.5), (8, 0), (0, 8);
        // 1/w is affine in it, from 1/w = ½, 1, 1.
        // (x, y) − v0 = λ1·(7.5, −0.5) + λ2·(−0.5, 7.5), solved by Cramer's rule (determinant 56).
        const float dx = e.x, dy = e.y;
        const float lambda1 = (7.5f * dx + 0.5f * dy) / 56.0f, lambda2 = (0.5f * dx + 7.5f * dy) / 56.0f;
        EXPECT_NEAR(e.barycentrics.y, lambda1, 1e-5f) << e;
        EXPECT_NEAR(e.barycentrics.z, lambda2, 1e-5f) << e;
        EXPECT_NEAR(e.barycentrics.x + e.barycentrics.y + e.barycentrics.z, 1.0f, 1e-6f);
        EXPECT_NEAR(e.invW, 0.5f * e.barycentrics.x + e.barycentrics.y + e.barycentrics.z, 1e-6f) << e;
        if (e.x == 0 && e.y == 0) {
            EXPECT_EQ(e.barycentrics, vec3(1, 0, 0)) << e;
            EXPECT_EQ(e.invW, 0.5f) << e;
            EXPECT_EQ(varyings, c0) << e;
        }
        if (e.fate == FragmentFate::Written) {
            EXPECT_EQ(varyings, e.shaded) << e;
            writtenVaryings[e.y * 8 + e.x] = varyings;
            ++written;
        } else {
            ASSERT_EQ(e.fate, FragmentFate::DepthFailed) << e;
            EXPECT_EQ(varyings, writtenVaryings[e.y * 8 + e.x]) << e;  // the same triangle's varyings
            ++failed;
        }
    }
    EXPECT_GT(written, 20);
    EXPECT_EQ(failed, written);
}

// The resolve of a pixel's list: its fragments farthest first, each with its blend mode, the colour
// after each step, the last one the pixel's final colour.
// Break caught: the event listing fragments in submission order instead of compositing order.
TEST(Observer, ResolveShowsTheCompositingOrder) {
    Framebuffer fb(4, 4);
    DrawContext context(1);
    fb.clear(vec4(0, 0, 0, 1), DepthFormat::kClear, context.pool);
    DrawState state = testing::stateFor(fb);
    state.output = FragmentOutput::AppendToLists;
    state.depth.writeEnabled = false;
    struct Layer {
        float z;
        vec4 color;
        BlendMode mode;
    };
    const Layer layers[3] = {{0.0f, vec4(1, 0, 0, 0.5f), BlendMode::Over},
                             {0.6f, vec4(0, 1, 0, 0.5f), BlendMode::Additive},
                             {-0.4f, vec4(0.5f, 0.5f, 0.5f, 1), BlendMode::Multiply}};
    for (const Layer& layer : layers) {
        state.blend = layer.mode;
        const std::vector<ClipSpaceColorShader::Attributes> v = {{{-1, -1, layer.z, 1}, layer.color},
                                                                 {{3, -1, layer.z, 1}, layer.color},
                                                                 {{-1, 3, layer.z, 1}, layer.color}};
        testing::drawTriangles<ClipSpaceColorShader>(state, v, fb);
    }
    RecordingObserver observer;
    resolveFragmentLists(fb, context.pool, observer);
    ASSERT_EQ(observer.resolves.size(), 16u);
    for (std::size_t i = 0; i < observer.resolves.size(); ++i) {
        const ResolveEvent& e = observer.resolves[i];
        const std::vector<ResolvedFragment>& list = observer.resolvedLists[i];
        EXPECT_EQ(e.colorBefore, vec4(0, 0, 0, 1));
        ASSERT_EQ(list.size(), 3u);
        EXPECT_EQ(list[0].submission, 1u);  // z 0.6: farthest
        EXPECT_EQ(list[1].submission, 0u);
        EXPECT_EQ(list[2].submission, 2u);  // z −0.4: nearest
        EXPECT_EQ(list[0].blend, BlendMode::Additive);
        EXPECT_EQ(list[2].blend, BlendMode::Multiply);
        vec4 c = e.colorBefore;
        for (const ResolvedFragment& f : list) {
            c = blend(f.blend, f.color, c);
            EXPECT_EQ(f.colorAfter, c);
        }
        EXPECT_EQ(fb.color(e.x, e.y), c);
    }
}

}  // namespace
}  // namespace facet
