// The framebuffer's clear (framebuffer.h): a clear to the values of the last one writes only the cells
// (kClearCell pixels square) written since, and whatever wrote them (a draw, a resolve, a caller
// through color() or depth()), the pixels after a clear are the clear values, exactly as if every
// pixel had been written. The writes wait until a draw asks for a cell's pixels (or finishClear(), or
// any accessor), and nothing can see a cell before its clear values are in it.
#include "framebuffer.h"

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "pipeline.h"
#include "support/test_shaders.h"
#include "thread_pool.h"

namespace facet {
namespace {

// 4 × 3 cells of 64, the last column and row partial; the last column is 11 pixels wide, not a multiple of
// the clear's stores of four pixels.
constexpr int kWidth = 203, kHeight = 130;
constexpr std::size_t kCells = 12;
const vec4 kBackground(0.25f, 0.5f, 0.75f, 1.0f);

// Every pixel holds exactly `color` and `depth`, in every plane.
::testing::AssertionResult holdsEverywhere(const Framebuffer& fb, vec4 color, float depth) {
    const std::span<const vec4> colors = fb.colorSpan();
    const std::span<const DepthFormat::Stored> depths = fb.depthSpan();
    for (std::size_t i = 0; i < colors.size(); ++i)
        if (colors[i] != color || depths[i] != depth)
            return ::testing::AssertionFailure()
                   << "pixel " << i % kWidth << ", " << i / kWidth << " holds (" << colors[i].r << ", "
                   << colors[i].g << ", " << colors[i].b << ", " << colors[i].a << ") at depth " << depths[i];
    return ::testing::AssertionSuccess();
}

// One triangle of one colour, at NDC depth 0, over window pixels around (x, y).
void drawTriangleAt(Framebuffer& fb, DrawContext& context, float x, float y, vec4 color,
                    FragmentOutput output = FragmentOutput::Blend, int samples = 1) {
    const std::vector<testing::ClipSpaceColorShader::Attributes> vertices = {
        {testing::clipFromWindow({x - 10, y - 8}, fb), color},
        {testing::clipFromWindow({x + 12, y - 6}, fb), color},
        {testing::clipFromWindow({x, y + 11}, fb), color}};
    const std::vector<std::uint32_t> indices = {0, 1, 2};
    DrawState state = testing::stateFor(fb);
    state.output = output;
    state.samples = samples;
    if (output == FragmentOutput::AppendToLists) state.depth.writeEnabled = false;
    draw<testing::ClipSpaceColorShader>(state, {}, std::span(vertices), std::span(indices), fb, context);
}

// Breaks caught: clear() ignoring the cells (12 written every time), or never marking them (a second
// clear to new values writing 0), or a clear counting a cell twice.
TEST(Framebuffer, AClearToTheSameValuesWritesNothingAndToOthersEverything) {
    ThreadPool pool(2);
    Framebuffer fb(kWidth, kHeight);
    EXPECT_EQ(fb.clear(kBackground, 1.0f, pool), kCells);  // a new framebuffer holds 0 and kClear
    EXPECT_EQ(fb.clear(kBackground, 1.0f, pool), 0u);
    EXPECT_TRUE(holdsEverywhere(fb, kBackground, 1.0f));
    EXPECT_EQ(fb.clear(vec4(0.0f), 1.0f, pool), kCells);
    EXPECT_TRUE(holdsEverywhere(fb, vec4(0.0f), 1.0f));
    EXPECT_EQ(fb.clear(vec4(0.0f), 0.5f, pool), kCells) << "another depth is other values";
    EXPECT_TRUE(holdsEverywhere(fb, vec4(0.0f), 0.5f));
    EXPECT_EQ(fb.clear(vec4(-0.0f), 0.5f, pool), kCells) << "−0 is not the bits of +0";
}

// Breaks caught: planesToDraw not marking the cells its area overlaps (the triangle survives the
// clear), marking one cell too few at a cell's edge, or the back end asking for the wrong area.
TEST(Framebuffer, AClearAfterADrawWritesTheCellsTheDrawTouchedAndRestoresThem) {
    for (const int threads : {1, 2}) {
        DrawContext context(threads);
        Framebuffer fb(kWidth, kHeight);
        fb.clear(kBackground, 1.0f, context.pool);
        // Across the corner of four cells (64, 64): each of the four gets some of it.
        drawTriangleAt(fb, context, 64.0f, 64.0f, vec4(1, 0, 0, 1));
        const std::size_t written = fb.clear(kBackground, 1.0f, context.pool);
        EXPECT_GE(written, 4u) << threads << " threads";
        EXPECT_LT(written, kCells) << "cells the draw's tiles never reached need no writing";
        EXPECT_TRUE(holdsEverywhere(fb, kBackground, 1.0f)) << threads << " threads";
        EXPECT_EQ(fb.clear(kBackground, 1.0f, context.pool), 0u);
    }
}

// Frames of different content into one framebuffer give the bytes of a fresh framebuffer, through
// each path that writes pixels: blending, the fragment lists' resolve, multisampling and its resolve.
// Break caught: any of those writing pixels without marking their cells (the previous frame's
// triangle shows through).
TEST(Framebuffer, FramesOfMovingContentMatchAFreshFramebuffer) {
    struct Path {
        const char* name;
        FragmentOutput output;
        int samples;
    };
    for (const Path path :
         {Path{"blend", FragmentOutput::Blend, 1}, Path{"fragment lists", FragmentOutput::AppendToLists, 1},
          Path{"multisample", FragmentOutput::Blend, 4}}) {
        // Tiles of 24 pixels share cells of 64 between the pool's two threads: a cell's clear values
        // must be in before either draws into it, and written once.
        for (const int tileSize : {kDefaultTileSize, 24}) {
            SCOPED_TRACE(tileSize);
            DrawContext context(2, tileSize);
            Framebuffer reused(kWidth, kHeight);
            auto frame = [&](Framebuffer& fb, float x, float y, vec4 color) {
                if (fb.samples() != path.samples) fb.useSamples(path.samples);
                fb.clear(kBackground, 1.0f, context.pool);
                drawTriangleAt(fb, context, x, y, color, path.output, path.samples);
                if (path.output == FragmentOutput::AppendToLists) resolveFragmentLists(fb, context.pool);
                fb.resolveSamples(ColorBufferFormat::Float, context.pool);
            };
            frame(reused, 30.0f, 30.0f, vec4(1, 0, 0, 1));
            frame(reused, 150.0f, 100.0f, vec4(0, 1, 0, 1));
            Framebuffer fresh(kWidth, kHeight);
            frame(fresh, 150.0f, 100.0f, vec4(0, 1, 0, 1));
            EXPECT_TRUE(reused.colorPixels() == fresh.colorPixels()) << path.name;
            EXPECT_TRUE(reused.depthPixels() == fresh.depthPixels()) << path.name;
            EXPECT_EQ(fresh.colorPixels()[100 * kWidth + 150], vec4(0, 1, 0, 1)) << path.name << ": drawn";
        }
    }
}

// Breaks caught: an area beside the framebuffer marking a cell (a truncating division takes −1/64 to
// cell 0), or a 0×0 framebuffer's cells written past their end.
TEST(Framebuffer, AnAreaOutsideTheFramebufferMarksNoCell) {
    ThreadPool pool(1);
    Framebuffer fb(kWidth, kHeight);
    fb.clear(kBackground, 1.0f, pool);
    fb.planesToDraw({-40, -30, -1, -1});
    fb.planesToDraw({kWidth, 0, kWidth + 50, 20});
    EXPECT_EQ(fb.clear(kBackground, 1.0f, pool), 0u);
    Framebuffer empty(0, 0);
    empty.planesToDraw({0, 0, 63, 63});
    EXPECT_EQ(empty.clear(kBackground, 1.0f, pool), 0u);
}

// Breaks caught: color(), depth(), colorSpanToWrite() or the sample planes' accessors handing out a pixel
// to write without the framebuffer forgetting which cells hold the clear values (the pixel survives the
// next clear), or useSamples keeping the cells' memory for planes it has just made.
TEST(Framebuffer, APixelWrittenDirectlyIsClearedByTheNextClear) {
    ThreadPool pool(1);
    Framebuffer fb(kWidth, kHeight);
    fb.clear(kBackground, 1.0f, pool);
    fb.color(3, 4) = vec4(1.0f);
    EXPECT_EQ(fb.clear(kBackground, 1.0f, pool), kCells);
    EXPECT_TRUE(holdsEverywhere(fb, kBackground, 1.0f));
    fb.depth(199, 129) = 0.25f;
    EXPECT_EQ(fb.clear(kBackground, 1.0f, pool), kCells);
    EXPECT_TRUE(holdsEverywhere(fb, kBackground, 1.0f));
    fb.colorSpanToWrite()[5 * kWidth + 6] = vec4(1.0f);  // as a resolve writes
    EXPECT_EQ(fb.clear(kBackground, 1.0f, pool), kCells);
    EXPECT_TRUE(holdsEverywhere(fb, kBackground, 1.0f));

    fb.useSamples(4);
    EXPECT_EQ(fb.clear(kBackground, 1.0f, pool), kCells) << "new sample planes hold no clear yet";
    EXPECT_EQ(fb.sampleColors(0, 0)[2], kBackground);
    fb.sampleColors(5, 6)[3] = vec4(1.0f);
    fb.sampleDepths(7, 8)[1] = 0.125f;
    EXPECT_EQ(fb.clear(kBackground, 1.0f, pool), kCells);
    EXPECT_EQ(fb.sampleColors(5, 6)[3], kBackground);
    EXPECT_EQ(fb.sampleDepths(7, 8)[1], 1.0f);
}

// The planes of a framebuffer without asking for any cell (an area beside it): what its memory holds.
FramebufferPlanes rawPlanes(Framebuffer& fb) {
    return fb.planesToDraw({-40, -30, -1, -1});
}

// Breaks caught: clear() writing every cell at once (the cells a draw will reach are then written to
// memory and read back by the draw), a draw's area not getting its cells' clear values before it
// draws, or finishClear() leaving a cell pending.
TEST(Framebuffer, AClearWritesACellWhenADrawAsksForItOrAtTheEnd) {
    ThreadPool pool(2);
    Framebuffer fb(kWidth, kHeight);
    EXPECT_EQ(fb.clear(kBackground, 0.5f, pool), kCells);
    EXPECT_EQ(fb.pendingCells(), kCells);
    EXPECT_EQ(rawPlanes(fb).color(70, 10), vec4(0.0f)) << "the constructor's values, until asked for";
    // A tile over pixels (64..127, 0..63): cell (1, 0) only.
    const FramebufferPlanes tile = fb.planesToDraw({64, 0, 127, 63});
    EXPECT_EQ(fb.pendingCells(), kCells - 1);
    EXPECT_EQ(tile.color(70, 10), kBackground);
    EXPECT_EQ(tile.depth(127, 63), 0.5f);
    EXPECT_EQ(tile.color(63, 10), vec4(0.0f)) << "cell (0, 0) is not the tile's";
    fb.finishClear(pool);
    EXPECT_EQ(fb.pendingCells(), 0u);
    EXPECT_EQ(rawPlanes(fb).color(63, 10), kBackground);
    EXPECT_EQ(rawPlanes(fb).depth(199, 129), 0.5f) << "the last, partial cell";
}

// Breaks caught: any accessor of pixels handing out or reading one before the pending cells are
// written (it would see the previous frame's pixels).
TEST(Framebuffer, EveryAccessorSeesAPendingClear) {
    ThreadPool pool(1);
    const auto cleared = [&] {
        auto fb = std::make_unique<Framebuffer>(kWidth, kHeight);
        fb->clear(kBackground, 0.5f, pool);
        return fb;
    };
    EXPECT_EQ(cleared()->color(150, 100), kBackground);
    EXPECT_EQ(std::as_const(*cleared()).color(150, 100), kBackground);
    EXPECT_EQ(cleared()->depth(150, 100), 0.5f);
    EXPECT_EQ(std::as_const(*cleared()).depth(150, 100), 0.5f);
    EXPECT_EQ(cleared()->colorSpan()[5], kBackground);
    EXPECT_EQ(cleared()->depthSpan()[5], 0.5f);
    EXPECT_EQ(cleared()->colorPixels()[5], kBackground);
    EXPECT_EQ(cleared()->depthPixels()[5], 0.5f);
    auto fb = cleared();
    fb->clearColor(vec4(1.0f));
    EXPECT_EQ(fb->depthSpan()[5], 0.5f) << "clearColor keeps the pending depth";
    fb = cleared();
    fb->clearDepth(0.25f);
    EXPECT_EQ(fb->colorSpan()[5], kBackground) << "clearDepth keeps the pending colour";

    Framebuffer samples(kWidth, kHeight);
    samples.useSamples(4);
    samples.clear(kBackground, 0.5f, pool);
    EXPECT_EQ(samples.sampleColors(150, 100)[3], kBackground);
    samples.clear(vec4(0.0f), 0.5f, pool);
    EXPECT_EQ(samples.sampleDepths(150, 100)[3], 0.5f);
    EXPECT_EQ(samples.sampleColors(150, 100)[3], vec4(0.0f));
    samples.clear(kBackground, 0.5f, pool);
    samples.useSamples(1);
    EXPECT_EQ(samples.colorSpan()[5], kBackground) << "useSamples writes the pending cells first";
}

}  // namespace
}  // namespace facet
