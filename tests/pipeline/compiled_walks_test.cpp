// A shader compiled with only some of the back end's walks (kCompiledWalks, back_end.h), as a shader
// module compiled for one scene's draws is: the walk a draw takes is the one backEndWalkOf names, a
// shader holding only that walk draws it with the bytes of one holding every walk, and a draw whose walk
// its shader lacks is refused before anything is drawn.
#include <array>
#include <stdexcept>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "../support/test_shaders.h"
#include "draw_run.h"
#include "pipeline.h"

namespace facet {
namespace {

using testing::ClipSpaceColorShader;

template <unsigned kWalks>
struct ShaderWithWalks : ClipSpaceColorShader {
    static constexpr unsigned kCompiledWalks = kWalks;
};

// One kind of draw and the walk it takes.
struct Setting {
    const char* name;
    DepthBufferFormat depth;
    int samples;
    FragmentOutput output;
    unsigned walk;
};

constexpr std::array kSettings = {
    Setting{"float depth", DepthBufferFormat::Float, 1, FragmentOutput::Blend, walk::kFloatDepth},
    Setting{"reversed float depth", DepthBufferFormat::ReversedFloat, 1, FragmentOutput::Blend,
            walk::kFloatDepth},
    Setting{"unorm16 depth", DepthBufferFormat::Unorm16, 1, FragmentOutput::Blend, walk::kUnormDepth},
    Setting{"unorm24 depth", DepthBufferFormat::Unorm24, 1, FragmentOutput::Blend, walk::kUnormDepth},
    Setting{"4 samples, float depth", DepthBufferFormat::Float, 4, FragmentOutput::Blend,
            walk::kMultisampleFloatDepth},
    Setting{"4 samples, unorm24 depth", DepthBufferFormat::Unorm24, 4, FragmentOutput::Blend,
            walk::kMultisampleUnormDepth},
    Setting{"fragment lists, float depth", DepthBufferFormat::Float, 1, FragmentOutput::AppendToLists,
            walk::kListsFloatDepth},
    Setting{"fragment lists, unorm16 depth", DepthBufferFormat::Unorm16, 1, FragmentOutput::AppendToLists,
            walk::kListsUnormDepth}};

DrawState stateOf(const Setting& setting, const Framebuffer& fb) {
    DrawState state = testing::stateFor(fb);
    state.depth.format = setting.depth;
    state.depth.compare = nearerPasses(setting.depth, CompareOp::Less);
    state.samples = setting.samples;
    state.output = setting.output;
    if (setting.output == FragmentOutput::AppendToLists) {
        state.depth.writeEnabled = false;
        state.blend = BlendMode::Over;
    }
    return state;
}

// Two overlapping half-transparent triangles at different depths, drawn with S in `setting`, resolved:
// the final colours.
template <class S>
std::vector<vec4> drawScene(const Setting& setting) {
    Framebuffer fb(48, 40);
    DrawContext context(2);
    fb.useSamples(setting.samples);
    fb.clear(vec4(0), depthClearValue(setting.depth), context.pool);
    const std::vector<ClipSpaceColorShader::Attributes> vertices = {
        {testing::clipFromWindow({2, 3}, fb, 0.5f), vec4(1, 0, 0, 0.5f)},
        {testing::clipFromWindow({45, 9}, fb, 0.5f), vec4(1, 0, 0, 0.5f)},
        {testing::clipFromWindow({9, 37}, fb, 0.5f), vec4(1, 0, 0, 0.5f)},
        {testing::clipFromWindow({40, 2}, fb, -0.25f), vec4(0, 0, 1, 0.5f)},
        {testing::clipFromWindow({30, 38}, fb, 0.25f), vec4(0, 0, 1, 0.5f)},
        {testing::clipFromWindow({4, 20}, fb, -0.5f), vec4(0, 0, 1, 0.5f)}};
    const std::vector<std::uint32_t> indices = {0, 1, 2, 3, 4, 5};
    draw<S>(stateOf(setting, fb), {}, std::span(vertices), std::span(indices), fb, context);
    if (setting.output == FragmentOutput::AppendToLists) resolveFragmentLists(fb, context.pool);
    fb.resolveSamples(ColorBufferFormat::Float, context.pool);
    return fb.colorPixels();
}

// Break caught: backEndWalkOf naming another walk than the one a setting's draw takes (a mistake in
// backEndWalk's order of questions: multisampled before lists, the depth coding of a format).
TEST(CompiledWalks, EachSettingTakesItsOwnWalk) {
    Framebuffer fb(8, 8);
    for (const Setting& setting : kSettings) {
        const DrawPlan plan = planDraw(stateOf(setting, fb));
        EXPECT_EQ(backEndWalkOf(plan, false), setting.walk) << setting.name;
        EXPECT_EQ(backEndWalkOf(plan, true),
                  setting.output == FragmentOutput::AppendToLists ? walk::kWatchedLists : walk::kWatched)
            << setting.name;
    }
    // Samples decide before the output: a multisampled draw never appends to lists (draw() refuses
    // neither; the frame refuses exact transparency with multisampling).
    DrawPlan both = planDraw(stateOf(kSettings[4], fb));
    both.output = FragmentOutput::AppendToLists;
    EXPECT_EQ(backEndWalkOf(both, false), walk::kMultisampleFloatDepth);
}

// A shader holding only the walk of a setting draws it as the shader holding every walk does, and is
// refused, with nothing drawn, every setting of another walk.
// Breaks caught: drawTileOfChunks keeping a walk other than the one backEndWalk names for its template
// parameters (the draw runs and draws nothing); draw() or drawRun() not checking the shader's walks (a
// lacking walk draws nothing, silently).
template <std::size_t kSetting>
void checkShaderOfOneWalk() {
    constexpr Setting kOwn = kSettings[kSetting];
    using Own = ShaderWithWalks<kOwn.walk>;
    const std::vector<vec4> expected = drawScene<ClipSpaceColorShader>(kOwn);
    EXPECT_EQ(drawScene<Own>(kOwn), expected) << kOwn.name;
    EXPECT_NE(expected, std::vector<vec4>(expected.size(), vec4(0))) << kOwn.name << ": something is drawn";
    for (const Setting& other : kSettings) {
        if (other.walk == kOwn.walk) continue;
        EXPECT_THROW(drawScene<Own>(other), std::logic_error) << kOwn.name << " drawn as " << other.name;
    }
    // A run of draws is checked as draw() checks one.
    Framebuffer fb(16, 16);
    DrawContext context(1);
    const std::vector<ClipSpaceColorShader::Attributes> vertices = {
        {{-1, -1, 0, 1}, vec4(1)}, {{1, -1, 0, 1}, vec4(1)}, {{-1, 1, 0, 1}, vec4(1)}};
    const std::vector<std::uint32_t> indices = {0, 1, 2};
    for (const Setting& other : kSettings) {
        if (other.samples > 1 || other.output != FragmentOutput::Blend) continue;  // never in a run
        fb.clear(vec4(0), depthClearValue(other.depth), context.pool);
        const DrawState state = stateOf(other, fb);
        const typename Own::Uniforms uniforms;
        const RunDraw<Own> one{&state, &uniforms, vertices, indices};
        const auto run = [&] { drawRun<Own>(std::span(&one, 1), fb, context); };
        if (other.walk == kOwn.walk) {
            EXPECT_NO_THROW(run()) << kOwn.name;
        } else {
            EXPECT_THROW(run(), std::logic_error) << kOwn.name << " run as " << other.name;
            EXPECT_EQ(fb.color(3, 3), vec4(0)) << "refused, yet drawn";
        }
    }
}

TEST(CompiledWalks, AShaderHoldingOnlyADrawsWalkDrawsItAndNoOther) {
    [&]<std::size_t... k>(std::index_sequence<k...>) {
        (checkShaderOfOneWalk<k>(), ...);
    }
    (std::make_index_sequence<kSettings.size()>());
}

// An observer that counts the fragments it is shown.
struct CountingWatcher : NullObserver {
    static constexpr bool enabled = true;
    int fragments = 0;
    void onFragment(const FragmentEvent&) { ++fragments; }
};

// Watching a draw (the step mode) takes a walk of its own.
// Breaks caught: a watched draw of a shader without the watched walk drawing nothing, silently (the
// observer sees the draw begin and end and nothing between); the watched walk left out of a shader that
// declares it.
TEST(CompiledWalks, AWatchedDrawTakesTheWatchedWalk) {
    Framebuffer fb(16, 16);
    DrawContext context(1);
    const DrawState state = testing::stateFor(fb);
    const std::vector<ClipSpaceColorShader::Attributes> vertices = {
        {{-1, -1, 0, 1}, vec4(1)}, {{1, -1, 0, 1}, vec4(1)}, {{-1, 1, 0, 1}, vec4(1)}};
    const std::vector<std::uint32_t> indices = {0, 1, 2};
    CountingWatcher watcher;
    using Unwatched = ShaderWithWalks<walk::kAll & ~walk::kWatched>;
    EXPECT_THROW(draw<Unwatched>(state, {}, std::span(vertices), std::span(indices), fb, context, watcher),
                 std::logic_error);
    EXPECT_EQ(watcher.fragments, 0);
    using Watched = ShaderWithWalks<walk::kWatched>;
    draw<Watched>(state, {}, std::span(vertices), std::span(indices), fb, context, watcher);
    EXPECT_GE(watcher.fragments, 16 * 15 / 2) << "half the pixels, the diagonal's aside";
    EXPECT_THROW(draw<Watched>(state, {}, std::span(vertices), std::span(indices), fb, context),
                 std::logic_error);
}

}  // namespace
}  // namespace facet
