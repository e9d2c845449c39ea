// Exact transparency with per-pixel fragment lists (fragment_lists.h): AppendToLists draws and
// resolveFragmentLists() give the depth-sorted composite at every pixel, whatever the order of the
// draws, where transparent triangles intersect, for any thread count, with each fragment's blend mode.
#include "fragment_lists.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <new>
#include <optional>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include "../support/sanitizers.h"
#include "../support/test_shaders.h"
#include "pipeline.h"

// Allocation counting for the "no allocation per fragment once warmed up" test: every operator new in
// this test binary goes through here, which only adds the count. Not under AddressSanitizer, which
// brings its own operator new.
namespace {
std::atomic<long> gAllocations{0};
#if defined(FACET_TEST_ADDRESS_SANITIZER)
constexpr bool kCountingAllocations = false;
#else
constexpr bool kCountingAllocations = true;
#endif
}  // namespace

#if !defined(FACET_TEST_ADDRESS_SANITIZER)
// GCC pairs the operator new it sees inlined here with the free() in operator delete; both are ours.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
    gAllocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(size ? size : 1)) return p;
    throw std::bad_alloc();
}
void* operator new(std::size_t size, std::align_val_t align) {
    gAllocations.fetch_add(1, std::memory_order_relaxed);
    const std::size_t a = static_cast<std::size_t>(align);
    if (void* p = std::aligned_alloc(a, (std::max<std::size_t>(size, 1) + a - 1) / a * a)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
    std::free(p);
}
#pragma GCC diagnostic pop
#endif

namespace facet {
namespace {

using testing::ClipSpaceColorShader;
using testing::FlatColorShader;

// An axis-aligned quad in window pixels [x0, x1) × [y0, y1) at NDC depth z, one flat colour (exact:
// no interpolation touches it), as two triangles.
struct Quad {
    float x0, y0, x1, y1;
    float z;
    vec4 color;
};

void appendQuad(const Framebuffer& fb, const Quad& q, std::vector<FlatColorShader::Attributes>& v) {
    const vec2 corners[4] = {{q.x0, q.y0}, {q.x1, q.y0}, {q.x1, q.y1}, {q.x0, q.y1}};
    for (int k : {0, 1, 2, 0, 2, 3})
        v.push_back({testing::clipFromWindow(corners[k], fb, q.z), q.color});
}

template <Shader S>
DrawStats drawWith(const DrawState& state, const std::vector<typename S::Attributes>& vertices,
                   Framebuffer& fb, DrawContext& context, const typename S::Uniforms& uniforms = {}) {
    std::vector<std::uint32_t> indices(vertices.size());
    for (std::size_t i = 0; i < indices.size(); ++i)
        indices[i] = static_cast<std::uint32_t>(i);
    return draw<S>(state, uniforms, std::span<const typename S::Attributes>(vertices),
                   std::span<const std::uint32_t>(indices), fb, context);
}

DrawStats drawQuads(const DrawState& state, const std::vector<Quad>& quads, Framebuffer& fb,
                    DrawContext& context) {
    std::vector<FlatColorShader::Attributes> v;
    for (const Quad& q : quads)
        appendQuad(fb, q, v);
    return drawWith<FlatColorShader>(state, v, fb, context);
}

// Transparent surfaces: depth test on, depth writes off, fragments to the lists.
DrawState transparentState(const Framebuffer& fb, BlendMode mode = BlendMode::Over,
                           FragmentOutput output = FragmentOutput::AppendToLists) {
    DrawState state = testing::stateFor(fb);
    state.depth.writeEnabled = false;
    state.blend = mode;
    state.output = output;
    return state;
}

// Three overlapping quads, far to near: red α ½ (A), green α ½ (B), blue α ¼ (C), on a black
// transparent background. Where all three overlap, over far to near gives
//   A: (½, 0, 0, ½); B: ½·(0,1,0) + ½·A = (¼, ½, 0), α ¾; C: ¼·(0,0,1) + ¾·B = (3/16, 3/8, ¼), α 13/16.
// Every order of submission gives that with fragment lists; only the sorted order does with blending.
TEST(FragmentLists, ThreeOverlappingQuadsInEveryOrderGiveTheSortedComposite) {
    Framebuffer fb(100, 90);
    DrawContext context(2);
    const std::array<Quad, 3> quads = {Quad{10, 10, 70, 70, 0.6f, vec4(1, 0, 0, 0.5f)},
                                       Quad{30, 20, 90, 80, 0.0f, vec4(0, 1, 0, 0.5f)},
                                       Quad{20, 40, 60, 85, -0.6f, vec4(0, 0, 1, 0.25f)}};
    const vec4 all(0.1875f, 0.375f, 0.25f, 0.8125f), onlyA(0.5f, 0, 0, 0.5f), onlyB(0, 0.5f, 0, 0.5f),
        cOverB(0, 0.375f, 0.25f, 0.625f);
    std::array<int, 3> order = {0, 1, 2};
    int orders = 0, blendingRight = 0;
    do {
        for (FragmentOutput output : {FragmentOutput::AppendToLists, FragmentOutput::Blend}) {
            fb.clear(vec4(0), 1.0f, context.pool);
            for (int q : order) {
                const DrawStats stats = drawQuads(transparentState(fb, BlendMode::Over, output),
                                                  {quads[static_cast<std::size_t>(q)]}, fb, context);
                EXPECT_EQ(
                    output == FragmentOutput::AppendToLists ? stats.fragmentsStored : stats.fragmentsWritten,
                    stats.fragmentsShaded);
            }
            if (output == FragmentOutput::Blend) {
                blendingRight += fb.color(45, 55) == all;
                continue;
            }
            // Nothing reaches the colour buffer before the resolve.
            EXPECT_EQ(fb.color(45, 55), vec4(0));
            const FragmentListStats stats = resolveFragmentLists(fb, context.pool);
            EXPECT_EQ(fb.color(45, 55), all) << "order " << order[0] << order[1] << order[2];
            EXPECT_EQ(fb.color(15, 15), onlyA);
            EXPECT_EQ(fb.color(80, 30), onlyB);
            EXPECT_EQ(fb.color(50, 75), cOverB);
            EXPECT_EQ(fb.color(95, 5), vec4(0));
            EXPECT_EQ(stats.longestList, 3u);
            EXPECT_EQ(stats.fragments, 60u * 60 + 60 * 60 + 40 * 45);
            EXPECT_EQ(stats.dropped, 0u);
            EXPECT_GE(stats.bytesHeld, stats.fragments * sizeof(FragmentLists::Node));
        }
        ++orders;
    } while (std::next_permutation(order.begin(), order.end()));
    EXPECT_EQ(orders, 6);
    EXPECT_EQ(blendingRight, 1);  // blending is right only when submitted far to near
}

// Two triangles with the same outline crossing in depth: P is near on the left and far on the right,
// Q the opposite; they intersect along x = 48. No order of the two is right everywhere: sorted by
// centroid depth (Q's is farther), blending puts P over Q on both sides. The lists get each pixel
// right: nearer over farther, P over Q left of the line, Q over P right of it.
TEST(FragmentLists, IntersectingTrianglesAreRightAtEveryPixel) {
    Framebuffer fb(96, 80);
    DrawContext context(2);
    const vec2 a(4, 4), b(92, 4), c(4, 76);
    const vec4 red(1, 0, 0, 0.5f), green(0, 1, 0, 0.5f);
    // Window depth 0.2 at NDC −0.6 and 0.8 at NDC 0.6: P's depth 0.2 + 0.6·(x − 4)/88, Q's 0.8 − …
    std::vector<FlatColorShader::Attributes> q = {{testing::clipFromWindow(a, fb, 0.6f), green},
                                                  {testing::clipFromWindow(b, fb, -0.6f), green},
                                                  {testing::clipFromWindow(c, fb, 0.6f), green}};
    std::vector<FlatColorShader::Attributes> p = {{testing::clipFromWindow(a, fb, -0.6f), red},
                                                  {testing::clipFromWindow(b, fb, 0.6f), red},
                                                  {testing::clipFromWindow(c, fb, -0.6f), red}};
    std::vector<FlatColorShader::Attributes> sorted = q;  // far (by centroid) to near
    sorted.insert(sorted.end(), p.begin(), p.end());
    std::vector<FlatColorShader::Attributes> reversed = p;
    reversed.insert(reversed.end(), q.begin(), q.end());

    // On a transparent black background: Q over it is (0, ½, 0, ½), P over that (½, ¼, 0, ¾);
    // P over the background (½, 0, 0, ½), Q over that (¼, ½, 0, ¾).
    const vec4 pOverQ(0.5f, 0.25f, 0, 0.75f), qOverP(0.25f, 0.5f, 0, 0.75f);
    auto expected = [&](int x) { return x + 0.5f < 48.0f ? pOverQ : qOverP; };

    fb.clear(vec4(0), 1.0f, context.pool);
    drawWith<FlatColorShader>(transparentState(fb, BlendMode::Over, FragmentOutput::Blend), sorted, fb,
                              context);
    int covered = 0, rightLeft = 0, wrongRight = 0;
    for (int y = 0; y < fb.height(); ++y)
        for (int x = 0; x < fb.width(); ++x) {
            if (fb.color(x, y).a == 0.0f) continue;
            ++covered;
            if (x + 0.5f < 48.0f) rightLeft += fb.color(x, y) == expected(x);
            if (x + 0.5f > 48.0f) wrongRight += fb.color(x, y) != expected(x);
        }
    EXPECT_GT(covered, 2500);
    EXPECT_EQ(rightLeft + wrongRight, covered);  // sorted blending: the left half right, the right wrong
    EXPECT_GT(wrongRight, 500);

    for (const auto* vertices : {&sorted, &reversed}) {
        fb.clear(vec4(0), 1.0f, context.pool);
        drawWith<FlatColorShader>(transparentState(fb), *vertices, fb, context);
        resolveFragmentLists(fb, context.pool);
        int checked = 0;
        for (int y = 0; y < fb.height(); ++y)
            for (int x = 0; x < fb.width(); ++x) {
                if (fb.color(x, y).a == 0.0f) continue;
                ++checked;
                ASSERT_EQ(fb.color(x, y), expected(x)) << "pixel " << x << ", " << y;
            }
        EXPECT_EQ(checked, covered);
    }
}

// The depth test still runs against what opaque surfaces wrote: transparent fragments behind them are
// neither stored nor composited; depth writes follow DrawState::depth.writeEnabled.
TEST(FragmentLists, DepthTestAgainstOpaqueSurfacesRejectsHiddenFragments) {
    Framebuffer fb(100, 70);
    DrawContext context(2);
    fb.clear(vec4(0, 0, 0, 1), 1.0f, context.pool);
    const vec4 opaque(0.2f, 0.4f, 0.6f, 1.0f);
    drawQuads(testing::stateFor(fb), {Quad{0, 0, 50, 70, 0.0f, opaque}}, fb, context);  // window depth ½

    // Behind the opaque half (window depth 0.7): stored only on the right.
    DrawStats stats =
        drawQuads(transparentState(fb), {Quad{0, 0, 100, 70, 0.4f, vec4(1, 0, 0, 0.5f)}}, fb, context);
    EXPECT_EQ(stats.fragmentsDepthFailed, 50u * 70);
    EXPECT_EQ(stats.fragmentsStored, 50u * 70);
    EXPECT_TRUE(fb.fragmentLists().fragmentsAt(10, 10).empty());
    ASSERT_EQ(fb.fragmentLists().fragmentsAt(60, 10).size(), 1u);
    EXPECT_EQ(fb.depth(60, 10), 1.0f);  // writes off
    EXPECT_EQ(fb.depth(10, 10), 0.5f);

    // In front (window depth 0.3, writes on): stored everywhere, and it hides what comes after it.
    DrawState writing = transparentState(fb);
    writing.depth.writeEnabled = true;
    stats = drawQuads(writing, {Quad{25, 0, 75, 70, -0.4f, vec4(0, 0, 1, 0.5f)}}, fb, context);
    EXPECT_EQ(stats.fragmentsStored, 50u * 70);
    EXPECT_FLOAT_EQ(fb.depth(30, 10), 0.3f);
    stats = drawQuads(transparentState(fb), {Quad{0, 0, 100, 70, 0.0f, vec4(0, 1, 0, 0.5f)}}, fb, context);
    EXPECT_EQ(stats.fragmentsStored, 25u * 70);  // only x in [75, 100): in front of nothing
    EXPECT_EQ(stats.fragmentsDepthFailed, 75u * 70);

    resolveFragmentLists(fb, context.pool);
    EXPECT_EQ(fb.color(10, 10), opaque);                   // hidden red not composited
    EXPECT_EQ(fb.color(60, 10), vec4(0.25f, 0, 0.5f, 1));  // blue over red over black
    EXPECT_EQ(fb.color(30, 10), blend(BlendMode::Over, vec4(0, 0, 1, 0.5f), opaque));  // blue over opaque
    EXPECT_EQ(fb.color(90, 10), vec4(0.25f, 0.5f, 0, 1));  // green over red over black
}

// Equal depths composite in submission order, across draws and inside one draw: as blending would.
TEST(FragmentLists, EqualDepthsResolveInSubmissionOrder) {
    Framebuffer fb(70, 70);
    DrawContext context(2);
    const Quad red{0, 0, 70, 70, 0.2f, vec4(1, 0, 0, 0.5f)}, green{20, 20, 50, 50, 0.2f, vec4(0, 1, 0, 0.5f)};
    const vec4 greenOverRed(0.25f, 0.5f, 0, 1), redOverGreen(0.5f, 0.25f, 0, 1);
    for (bool oneDraw : {false, true})
        for (bool redFirst : {true, false}) {
            const std::vector<Quad> quads =
                redFirst ? std::vector<Quad>{red, green} : std::vector<Quad>{green, red};
            for (FragmentOutput output : {FragmentOutput::AppendToLists, FragmentOutput::Blend}) {
                fb.clear(vec4(0, 0, 0, 1), 1.0f, context.pool);
                const DrawState state = transparentState(fb, BlendMode::Over, output);
                if (oneDraw) {
                    drawQuads(state, quads, fb, context);
                } else {
                    for (const Quad& q : quads)
                        drawQuads(state, {q}, fb, context);
                }
                if (output == FragmentOutput::AppendToLists) resolveFragmentLists(fb, context.pool);
                EXPECT_EQ(fb.color(30, 30), redFirst ? greenOverRed : redOverGreen)
                    << output << (oneDraw ? ", one draw" : ", two draws");
                EXPECT_EQ(fb.color(5, 5), vec4(0.5f, 0, 0, 1));
            }
        }
}

// A scene of intersecting, randomly coloured triangles in several draws with different blend modes
// (built once, so that drawing it allocates nothing of its own).
struct RandomScene {
    std::vector<std::vector<ClipSpaceColorShader::Attributes>> layers;
    std::vector<std::uint32_t> indices;
};

RandomScene makeRandomScene(int layers) {
    RandomScene scene;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.3f, 1.3f), unit(0.0f, 1.0f);
    for (int layer = 0; layer < layers; ++layer) {
        auto& v = scene.layers.emplace_back();
        for (int i = 0; i < 3 * 60; ++i)
            v.push_back({vec4(u(rng), u(rng), u(rng) * 0.7f, 1.0f),
                         vec4(unit(rng), unit(rng), unit(rng), unit(rng))});
    }
    for (std::uint32_t i = 0; i < 3 * 60; ++i)
        scene.indices.push_back(i);
    return scene;
}

void drawRandomScene(const RandomScene& scene, Framebuffer& fb, DrawContext& context) {
    const BlendMode modes[] = {BlendMode::Over, BlendMode::Additive, BlendMode::PremultipliedOver,
                               BlendMode::Multiply};
    for (std::size_t layer = 0; layer < scene.layers.size(); ++layer)
        draw<ClipSpaceColorShader>(transparentState(fb, modes[layer % 4]), {},
                                   std::span<const ClipSpaceColorShader::Attributes>(scene.layers[layer]),
                                   std::span<const std::uint32_t>(scene.indices), fb, context);
}

bool sameBytes(const std::vector<vec4>& a, const std::vector<vec4>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(vec4)) == 0;
}

// Same bytes for 1, 2 and 7 threads and for any tile size: each tile's pool is filled by one thread in
// submission order, and the resolve of a pixel depends only on its list.
TEST(FragmentLists, SameBytesForAnyThreadCountAndTileSize) {
    const RandomScene scene = makeRandomScene(4);
    std::vector<vec4> reference;
    FragmentListStats referenceStats;
    for (int threads : {1, 2, 7})
        for (int tileSize : {64, 16, 128}) {
            Framebuffer fb(123, 97);
            DrawContext context(threads, tileSize);
            fb.clear(vec4(0.1f, 0.2f, 0.3f, 1.0f), 1.0f, context.pool);
            drawRandomScene(scene, fb, context);
            const FragmentListStats stats = resolveFragmentLists(fb, context.pool);
            if (reference.empty()) {
                reference = fb.colorPixels();
                referenceStats = stats;
                EXPECT_GT(stats.fragments, 20000u);
                EXPECT_GT(stats.longestList, 8u);
                continue;
            }
            EXPECT_TRUE(sameBytes(fb.colorPixels(), reference))
                << threads << " threads, tiles of " << tileSize;
            EXPECT_EQ(stats.fragments, referenceStats.fragments);
            EXPECT_EQ(stats.pixels, referenceStats.pixels);
            EXPECT_EQ(stats.longestList, referenceStats.longestList);
        }
}

// A tile's fragment list has one writer: a draw that appends to lists draws its tiles whole however many
// threads it is cut for, while the same draw blending is cut in parts. Breaks caught: drawBatchTiles
// cutting the tiles of a list-appending draw (two threads would write one tile's pool at once).
TEST(FragmentLists, ADrawAppendingToListsDrawsItsTilesWhole) {
    const RandomScene scene = makeRandomScene(4);
    for (FragmentOutput output : {FragmentOutput::AppendToLists, FragmentOutput::Blend}) {
        Framebuffer fb(123, 97);
        DrawContext context(1);
        context.cutForThreads = 16;
        fb.clear(vec4(0.1f, 0.2f, 0.3f, 1.0f), 1.0f, context.pool);
        draw<ClipSpaceColorShader>(transparentState(fb, BlendMode::Over, output), {},
                                   std::span<const ClipSpaceColorShader::Attributes>(scene.layers[0]),
                                   std::span<const std::uint32_t>(scene.indices), fb, context);
        int widest = 1;
        for (const TilePart& part : context.tileParts)
            widest = std::max<int>(widest, part.side);
        EXPECT_EQ(widest > 1, output == FragmentOutput::Blend) << static_cast<int>(output);
    }
}

// Clearing empties every list and keeps the memory: the next frame reuses it, allocating nothing per
// fragment (a pool that lost its capacity would grow again, allocation by allocation).
TEST(FragmentLists, ClearingEmptiesTheListsAndKeepsTheirMemory) {
    Framebuffer fb(200, 150);
    DrawContext context(2, 16);  // many small tiles: many pools
    const RandomScene scene = makeRandomScene(8);
    auto frame = [&] {
        fb.clear(vec4(0, 0, 0, 1), 1.0f, context.pool);
        drawRandomScene(scene, fb, context);
        return resolveFragmentLists(fb, context.pool);
    };
    const FragmentListStats first = frame();
    const std::vector<vec4> image = fb.colorPixels();
    EXPECT_GT(first.fragments, 50000u);
    EXPECT_LT(first.longestList, 256u);  // resolve scratch of that size is held from the start
    FragmentLists& lists = fb.fragmentLists();
    EXPECT_EQ(lists.size(), first.fragments);

    fb.clear(vec4(0), 1.0f, context.pool);
    EXPECT_EQ(lists.size(), 0u);
    EXPECT_TRUE(lists.empty());
    for (int y = 0; y < fb.height(); ++y)
        for (int x = 0; x < fb.width(); ++x)
            ASSERT_TRUE(lists.fragmentsAt(x, y).empty()) << x << ", " << y;
    EXPECT_EQ(lists.bytesHeld(), first.bytesHeld);
    // Resolving empty lists leaves the colour alone.
    const FragmentListStats empty = resolveFragmentLists(fb, context.pool);
    EXPECT_EQ(empty.fragments, 0u);
    EXPECT_EQ(fb.color(100, 75), vec4(0));

    const long before = gAllocations.load();
    const FragmentListStats second = frame();
    const long allocations = gAllocations.load() - before;
    EXPECT_TRUE(sameBytes(fb.colorPixels(), image));
    EXPECT_EQ(second.fragments, first.fragments);
    EXPECT_EQ(second.bytesHeld, first.bytesHeld);
    // A handful per draw and per parallel loop (std::function), none per fragment.
    if (kCountingAllocations) {
        EXPECT_LT(allocations, 64) << second.fragments << " fragments";
    }
}

// Each fragment composites with its own draw's mode, farthest first, as blend() says.
TEST(FragmentLists, EachFragmentBlendsWithItsOwnMode) {
    Framebuffer fb(32, 32);
    DrawContext context(2);
    struct Layer {
        BlendMode mode;
        float z;
        vec4 color;
    };
    // Far to near.
    const std::array<Layer, 4> layers = {
        Layer{BlendMode::Additive, 0.6f, vec4(0.1f, 0.2f, 0.3f, 0.5f)},
        Layer{BlendMode::Multiply, 0.2f, vec4(0.5f, 0.5f, 0.25f, 0.7f)},
        Layer{BlendMode::PremultipliedOver, -0.2f, vec4(0.2f, 0.1f, 0.05f, 0.25f)},
        Layer{BlendMode::Over, -0.6f, vec4(1, 0, 0, 0.25f)}};
    const vec4 background(0.4f, 0.4f, 0.4f, 1.0f);
    vec4 expected = background;
    for (const Layer& l : layers)
        expected = blend(l.mode, l.color, expected);
    // By hand: additive (0.5, 0.6, 0.7, 1.5); multiply (0.25, 0.3, 0.175, 1.5); premultiplied over
    // (0.3875, 0.325, 0.18125, 1.375); over (0.540625, 0.24375, 0.1359375, 1.28125).
    EXPECT_NEAR(expected.r, 0.540625f, 1e-6f);
    EXPECT_NEAR(expected.g, 0.24375f, 1e-6f);
    EXPECT_NEAR(expected.b, 0.1359375f, 1e-6f);
    EXPECT_NEAR(expected.a, 1.28125f, 1e-6f);

    std::array<int, 4> order = {0, 1, 2, 3};
    do {
        fb.clear(background, 1.0f, context.pool);
        for (int k : order) {
            const Layer& l = layers[static_cast<std::size_t>(k)];
            drawQuads(transparentState(fb, l.mode), {Quad{0, 0, 32, 32, l.z, l.color}}, fb, context);
        }
        resolveFragmentLists(fb, context.pool);
        ASSERT_EQ(fb.color(7, 9), expected) << order[0] << order[1] << order[2] << order[3];
        ASSERT_EQ(fb.color(31, 31), expected);
    } while (std::next_permutation(order.begin(), order.end()));
}

// Lists longer than the insertion sort's limit, with repeated depths, sort the same way.
TEST(FragmentLists, LongListsSortByDepthThenSubmission) {
    Framebuffer fb(8, 8);
    DrawContext context(1);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::uniform_int_distribution<int> depthStep(0, 39);
    std::vector<Quad> quads;
    for (int i = 0; i < 150; ++i)
        quads.push_back(Quad{0, 0, 8, 8, -0.9f + 0.045f * static_cast<float>(depthStep(rng)),
                             vec4(unit(rng), unit(rng), unit(rng), unit(rng))});
    fb.clear(vec4(0, 0, 0, 1), 1.0f, context.pool);
    drawQuads(transparentState(fb), quads, fb, context);
    const FragmentListStats stats = resolveFragmentLists(fb, context.pool);
    EXPECT_EQ(stats.longestList, 150u);
    EXPECT_EQ(stats.fragments, 150u * 64);

    std::vector<Quad> sorted = quads;
    std::stable_sort(sorted.begin(), sorted.end(), [](const Quad& a, const Quad& b) { return a.z > b.z; });
    vec4 expected(0, 0, 0, 1);
    for (const Quad& q : sorted)
        expected = blend(BlendMode::Over, q.color, expected);
    EXPECT_EQ(fb.color(3, 4), expected);

    // The lists themselves: submission order, each fragment's depth and mode.
    const std::vector<FragmentLists::Node> list = fb.fragmentLists().fragmentsAt(3, 4);
    ASSERT_EQ(list.size(), quads.size());
    for (std::size_t i = 0; i < list.size(); ++i) {
        EXPECT_EQ(list[i].color, quads[i].color);
        EXPECT_EQ(list[i].blend(), BlendMode::Over);
    }
}

struct FateObserver : NullObserver {
    static constexpr bool enabled = true;
    std::vector<FragmentEvent> fragments;
    void onFragment(const FragmentEvent& e) { fragments.push_back(e); }
};

// Discards every fragment whose colour has negative alpha.
struct DiscardingShader {
    struct Attributes {
        vec4 position;
        vec4 color;
    };
    struct Varyings {
        vec4 color;
    };
    static constexpr int kFlatVaryingFloats = 4;
    struct Uniforms {};
    static VertexOut<Varyings> vertex(const Attributes& in, const Uniforms&) {
        return {in.position, {in.color}};
    }
    static std::optional<vec4> fragment(const Varyings& in, const Uniforms&) {
        if (in.color.a < 0.0f) return std::nullopt;
        return in.color;
    }
};

// The observer sees stored fragments with their own fate, the colour buffer untouched; hidden and
// discarded ones keep theirs.
TEST(FragmentLists, ObserverSeesStoredFragments) {
    Framebuffer fb(8, 8);
    fb.clearColor(vec4(0));
    fb.clearDepth(1.0f);
    DrawContext context(1);
    drawQuads(testing::stateFor(fb), {Quad{0, 0, 4, 8, 0.0f, vec4(1)}}, fb, context);  // opaque left half
    const vec4 glass(0, 0, 1, 0.5f);
    std::vector<DiscardingShader::Attributes> v;
    for (const auto& a : [&] {
             std::vector<FlatColorShader::Attributes> quad;
             appendQuad(fb, Quad{0, 0, 8, 4, 0.5f, glass}, quad);               // top: behind on the left
             appendQuad(fb, Quad{0, 4, 8, 8, -0.5f, vec4(0, 0, 1, -1)}, quad);  // bottom: discarded
             return quad;
         }())
        v.push_back({a.position, a.color});
    std::vector<std::uint32_t> indices(v.size());
    for (std::size_t i = 0; i < indices.size(); ++i)
        indices[i] = static_cast<std::uint32_t>(i);
    FateObserver observer;
    const DrawStats stats =
        draw<DiscardingShader>(transparentState(fb), {}, std::span<const DiscardingShader::Attributes>(v),
                               std::span<const std::uint32_t>(indices), fb, context, observer);
    EXPECT_EQ(stats.fragmentsStored, 16u);
    EXPECT_EQ(stats.fragmentsDepthFailed, 16u);
    EXPECT_EQ(stats.fragmentsDiscarded, 32u);
    EXPECT_EQ(stats.fragmentsWritten, 0u);
    ASSERT_EQ(observer.fragments.size(), 64u);
    int stored = 0;
    for (const FragmentEvent& e : observer.fragments) {
        if (e.y >= 4) {
            EXPECT_EQ(e.fate, FragmentFate::Discarded);
            continue;
        }
        EXPECT_EQ(e.fate, e.x < 4 ? FragmentFate::DepthFailed : FragmentFate::Stored);
        if (e.fate != FragmentFate::Stored) continue;
        ++stored;
        EXPECT_EQ(e.shaded, glass);
        EXPECT_EQ(e.colorBefore, vec4(0));
        EXPECT_EQ(e.colorAfter, vec4(0));  // the colour buffer waits for the resolve
        EXPECT_NE((std::ostringstream() << e).str().find("stored"), std::string::npos);
    }
    EXPECT_EQ(stored, 16);
    EXPECT_EQ(fb.fragmentLists().size(), 16u);
}

TEST(FragmentLists, AppendingWithAnotherTileSizeNeedsAClear) {
    Framebuffer fb(40, 40);
    DrawContext tiles64(1, 64), tiles16(1, 16);
    drawQuads(transparentState(fb), {Quad{0, 0, 40, 40, 0.0f, vec4(1, 0, 0, 0.5f)}}, fb, tiles64);
    EXPECT_THROW(drawQuads(transparentState(fb), {Quad{0, 0, 40, 40, 0.0f, vec4(1)}}, fb, tiles16),
                 std::invalid_argument);
    fb.clear(vec4(0), 1.0f, tiles16.pool);
    const DrawStats stats = drawQuads(transparentState(fb), {Quad{0, 0, 40, 40, 0.0f, vec4(1)}}, fb, tiles16);
    EXPECT_EQ(stats.fragmentsStored, 1600u);
    EXPECT_EQ(fb.fragmentLists().tileSize(), 16);
}

TEST(FragmentLists, BlendingDrawsAllocateNoLists) {
    Framebuffer fb(40, 40);
    DrawContext context(1);
    drawQuads(transparentState(fb, BlendMode::Over, FragmentOutput::Blend),
              {Quad{0, 0, 40, 40, 0.0f, vec4(1)}}, fb, context);
    EXPECT_FALSE(fb.fragmentLists().allocated());
    EXPECT_EQ(fb.fragmentLists().bytesHeld(), 0u);
}

TEST(FragmentLists, Printing) {
    Framebuffer fb(4, 4);
    std::ostringstream state, fate, stats;
    state << transparentState(fb);
    EXPECT_NE(state.str().find("output append to fragment lists"), std::string::npos) << state.str();
    fate << FragmentFate::Stored << "; " << FragmentFate::Dropped;
    EXPECT_EQ(fate.str(), "stored in the pixel's fragment list; dropped: its tile's fragment pool is full");
    stats << FragmentListStats{12, 5, 3, 0, 1000};
    EXPECT_EQ(stats.str(), "12 fragments in 5 pixel lists (longest 3), 1000 bytes held");
}

}  // namespace
}  // namespace facet
