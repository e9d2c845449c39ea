// The step mode traces a shader of one's own (--shader): the trace equals the rendered bytes, the
// shader's recorded values, uniforms and output are on its screens and in the JSON, NaN is flagged and
// counted (--stats), and --versus puts it beside the built-in shader. One shader
// (tests/step/shaders/toon_step.cpp) and one that discards (cutout_step.cpp) are compiled once, into a
// cache folder of the tests' own.
// Each test names the one-line break it catches.
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli/run_facet.h"
#include "render/user_shaders.h"
#include "shading/gamma.h"
#include "step/screens.h"
#include "step/versus.h"
#include "step/views.h"
#include "step/walk.h"
#include "support/user_shader_files.h"

namespace facet::step {
namespace {

namespace fs = std::filesystem;

const fs::path kShader = fs::path(FACET_SOURCE_DIR) / "tests/step/shaders/toon_step.cpp";
const fs::path kCutout = fs::path(FACET_SOURCE_DIR) / "tests/step/shaders/cutout_step.cpp";
const fs::path kSpot = fs::path(FACET_SOURCE_DIR) / "models/spot/spot_triangulated.obj";

class UserShaderStep : public ::testing::Test {
  protected:
    // The walk's draws are watched: compiled with them at once, as facet step does.
    static void SetUpTestSuite() {
        testing_support::useSharedShaderCache();
        compileForWatchedDraws();
    }

    // spot at 96×72 drawn with the test shader and `uniforms` (as --uniform gives them).
    static PreparedScene prepared(const std::vector<std::pair<std::string, std::vector<double>>>& uniforms,
                                  const fs::path& shader = kShader) {
        Scene scene = loadSceneOrModel(kSpot);
        scene.width = 96;
        scene.height = 72;
        scene.shader = ShaderSpec{shader, {}};
        for (const auto& [name, numbers] : uniforms) {
            std::ostringstream origin;  // a stream: GCC 12 warns falsely on sums of strings (-Wrestrict)
            origin << "--uniform " << name << "=";
            for (std::size_t k = 0; k < numbers.size(); ++k)
                origin << (k ? "," : "") << numbers[k];
            scene.uniforms.push_back(UniformValue{name, numbers, false, origin.str()});
        }
        return prepareScene(scene);
    }

    static const Screen* screen(const Walk& walk, const std::string& id) {
        for (const Screen& s : walk.screens)
            if (s.id == id) return &s;
        return nullptr;
    }
};

void expectWithin80Columns(const Walk& walk) {
    for (const Screen& s : walk.screens) {
        std::istringstream lines(s.text);
        for (std::string line; std::getline(lines, line);)
            EXPECT_LE(columnsOf(line), 80u) << s.id << ": " << line;
    }
}

std::array<std::uint8_t, 4> bytesOf(const vec4& c, const ColorEncoding& e) {
    return {encodeChannel(c.r, e), encodeChannel(c.g, e), encodeChannel(c.b, e), toByte(c.a, e.rounding)};
}

// The fragment part run on one lane at the traced pixel, blended as the trace says (opaque: replaced),
// gives the rendered image's bytes, at pixels across the model; and the trace's final bytes are the
// render's. Catches: the step mode tracing a user-shader draw with other uniforms or varyings than the
// frame's (settings or the scene's part not passed, varyings of another fragment or in another order).
TEST_F(UserShaderStep, OneLaneOutputOfTheTracedPixelIsTheRenderedPixel) {
    const PreparedScene scene = prepared({{"bands", {3}}});
    Framebuffer rendered(scene.scene.width, scene.scene.height);
    DrawContext threads(2);
    FrameMemory memory;
    renderFrame(scene, rendered, threads, memory);
    DrawContext calling(1);
    int checked = 0;
    for (int y = 20; y < 56; y += 7)
        for (int x = 20; x < 80; x += 9) {
            StepRequest request;
            request.pixel = std::pair(x, y);
            const StepTrace trace = traceStep(scene, calling, request);
            const auto expected = bytesOf(rendered.color(x, y), scene.encoding);
            EXPECT_EQ(trace.pixel.finalBytes, expected) << x << "," << y;
            if (!trace.userShader || !trace.pixel.producer) continue;
            const TriangleAtPixel& producer = trace.pixel.triangles[*trace.pixel.producer];
            if (!(producer.ref == trace.triangle->ref) || producer.blend != BlendMode::Replace) continue;
            ASSERT_TRUE(trace.userShader->shaderRan);
            ASSERT_FALSE(trace.userShader->discarded);
            EXPECT_EQ(bytesOf(trace.userShader->output, scene.encoding), expected) << x << "," << y;
            EXPECT_FALSE(trace.shading) << "the built-in shading must not be recomputed for a user shader";
            ++checked;
        }
    EXPECT_GT(checked, 10) << "the pixels should mostly lie on the model";
}

// The walk of a user-shader pixel: the vertex screen shows the vertex part's varyings by the shader's
// names, the interpolation screen names them the same way, the shader screens show its name, file,
// every recorded value and the output, and no built-in lighting screen; all within 80 columns.
// Catches: the built-in shader's names or formulas shown for a user shader, gl.record values lost on the
// way to the screen, a long line.
TEST_F(UserShaderStep, ScreensShowTheShadersNamesRecordedValuesAndOutput) {
    const PreparedScene scene = prepared({});
    DrawContext context(1);
    const StepTrace trace = traceStep(scene, context, StepRequest{});
    ASSERT_TRUE(trace.userShader);
    const UserShaderTrace& u = *trace.userShader;
    ASSERT_EQ(u.recorded.size(), 3u);
    EXPECT_EQ(u.recorded[1].name, "N.V");
    const Walk& walk = trace.walk;
    EXPECT_FALSE(screen(walk, "lighting"));
    const Screen* transform = screen(walk, "transform");
    ASSERT_TRUE(transform);
    EXPECT_NE(transform->text.find("N_eye.z = "), std::string::npos) << transform->text;
    EXPECT_NE(transform->text.find("toon_step.cpp"), std::string::npos);
    const Screen* interpolate = screen(walk, "interpolate");
    ASSERT_TRUE(interpolate);
    EXPECT_NE(interpolate->text.find("P_eye.x"), std::string::npos) << interpolate->text;
    const Screen* shader = screen(walk, "shader");
    ASSERT_TRUE(shader);
    EXPECT_NE(shader->text.find("N.V = " + number(u.recorded[1].values[0])), std::string::npos)
        << shader->text;
    EXPECT_NE(shader->text.find("c = (" + number(u.recorded[2].values[0])), std::string::npos)
        << shader->text;
    EXPECT_NE(shader->text.find("Its output: colour " + vectorText(u.output)), std::string::npos);
    EXPECT_EQ(shader->text.find("NaN"), std::string::npos) << "no NaN here: nothing to flag";
    const Screen* uniforms = screen(walk, "uniforms");
    ASSERT_TRUE(uniforms);
    EXPECT_NE(uniforms->title.find("ToonStep (toon_step.cpp)"), std::string::npos) << uniforms->title;
    EXPECT_NE(stepStats(trace).find("non-finite shader values (NaN or infinite): 0\n"), std::string::npos);
    expectWithin80Columns(walk);
    // The JSON: the recorded values, the uniforms and the output.
    const nlohmann::json j = toJson(trace);
    ASSERT_TRUE(j.contains("userShader"));
    EXPECT_EQ(j["userShader"]["recorded"][1]["name"], "N.V");
    EXPECT_EQ(j["userShader"]["recorded"][1]["value"].get<float>(), u.recorded[1].values[0]);
    EXPECT_EQ(j["userShader"]["uniforms"].size(), 4u);
    EXPECT_EQ(j["userShader"]["output"][0].get<float>(), u.output.r);
}

// Every declared uniform is shown with its value for the draw: those given by --uniform marked as set
// (with where and the default), the others as defaults. Catches: the shown value taken from the
// defaults (or from another uniform's setting), the set/default marking lost.
TEST_F(UserShaderStep, UniformsShownAreThoseOfUniformOptions) {
    const PreparedScene scene = prepared({{"bands", {3}}, {"ink", {0.25, 0.5, 1}}});
    DrawContext context(1);
    const StepTrace trace = traceStep(scene, context, StepRequest{});
    ASSERT_TRUE(trace.userShader);
    const Screen* uniforms = screen(trace.walk, "uniforms");
    ASSERT_TRUE(uniforms);
    const std::string& text = uniforms->text;
    EXPECT_NE(text.find("* bands (int) = 3, set by --uniform bands=3 (default 4)"), std::string::npos)
        << text;
    EXPECT_NE(text.find("* ink (vec3) = (0.25, 0.5, 1), set by --uniform ink=0.25,0.5,1"), std::string::npos)
        << text;
    EXPECT_NE(text.find("  outline (float) = 0.3, the default"), std::string::npos) << text;
    EXPECT_NE(text.find("  normal_scale (float) = 1, the default"), std::string::npos) << text;
}

// A shader that normalizes a zero vector: the NaN is flagged on the shader screen with what may cause
// it, counted by --stats and named in the JSON. Catches: non-finite values printed as plain numbers
// (or "-nan"), the count missing, NaN turned into null in the JSON.
TEST_F(UserShaderStep, NaNIsFlaggedOnTheScreenAndCounted) {
    const PreparedScene scene = prepared({{"normal_scale", {0}}});
    DrawContext context(1);
    StepRequest request;
    request.pixel = std::pair(48, 36);
    const StepTrace trace = traceStep(scene, context, request);
    ASSERT_TRUE(trace.userShader);
    ASSERT_TRUE(trace.userShader->shaderRan);
    const Screen* shader = screen(trace.walk, "shader");
    ASSERT_TRUE(shader);
    EXPECT_NE(shader->text.find("<- NaN!"), std::string::npos) << shader->text;
    EXPECT_NE(shader->text.find("normalize of a zero vector?"), std::string::npos) << shader->text;
    EXPECT_NE(shader->text.find("N.V = NaN"), std::string::npos) << shader->text;
    // The JSON says so too (a NaN would otherwise be written as null).
    const nlohmann::json j = toJson(trace)["userShader"];
    EXPECT_EQ(j["recorded"][1]["value"], "NaN");
    EXPECT_EQ(j["recorded"][1]["finite"], false);
    EXPECT_EQ(j["nonFinite"], nonFiniteCount(*trace.userShader));
    EXPECT_GE(nonFiniteCount(*trace.userShader), 2);  // N, N.V, (c, output)
    const std::string stats = stepStats(trace);
    EXPECT_NE(stats.find("non-finite shader values (NaN or infinite): " +
                         std::to_string(nonFiniteCount(*trace.userShader))),
              std::string::npos)
        << stats;
    expectWithin80Columns(trace.walk);
}

// A discarding shader: where it discards, the shader screen says so (and no colour), the history's fate
// is "discarded" and the JSON has it; where it keeps the fragment, its one-lane output is the rendered
// pixel. Catches: a discarded fragment shown with a colour (FragmentOut's colour), the discard lost in
// the trace, the discarding draw traced with other inputs than the frame's.
TEST_F(UserShaderStep, DiscardIsShownAndKeptFragmentsMatchTheRender) {
    const PreparedScene scene = prepared({}, kCutout);
    Framebuffer rendered(scene.scene.width, scene.scene.height);
    DrawContext threads(2);
    FrameMemory memory;
    renderFrame(scene, rendered, threads, memory);
    DrawContext calling(1);
    int discarded = 0, kept = 0;
    for (int x = 30; x < 70; x += 4) {
        StepRequest request;
        request.pixel = std::pair(x, 36);
        const StepTrace trace = traceStep(scene, calling, request);
        EXPECT_EQ(trace.pixel.finalBytes, bytesOf(rendered.color(x, 36), scene.encoding)) << x;
        if (!trace.userShader || !trace.userShader->shaderRan) continue;
        const UserShaderTrace& u = *trace.userShader;
        ASSERT_EQ(u.recorded.size(), 1u);
        const Screen* shader = screen(trace.walk, "shader");
        ASSERT_TRUE(shader);
        const nlohmann::json j = toJson(trace)["userShader"];
        if (u.discarded) {
            ++discarded;
            EXPECT_LT(u.recorded[0].values[0], 0.0f) << "it discards eye-space x < 0";
            EXPECT_NE(shader->title.find("discarded the fragment"), std::string::npos) << shader->title;
            EXPECT_NE(shader->text.find("Its output: discarded"), std::string::npos) << shader->text;
            EXPECT_EQ(shader->text.find("Its output: colour"), std::string::npos);
            EXPECT_EQ(j["discarded"], true);
            EXPECT_FALSE(j.contains("output"));
            EXPECT_NE(screen(trace.walk, "history")->text.find("discarded"), std::string::npos);
        } else if (trace.pixel.producer &&
                   trace.pixel.triangles[*trace.pixel.producer].ref == trace.triangle->ref) {
            ++kept;
            EXPECT_EQ(bytesOf(u.output, scene.encoding), bytesOf(rendered.color(x, 36), scene.encoding)) << x;
            EXPECT_EQ(j["discarded"], false);
        }
    }
    EXPECT_GT(discarded, 0);
    EXPECT_GT(kept, 0);
}

// The facet program: --shader with --versus "" puts the user's shader beside the built-in one (both
// columns, its screen facing the built-in lighting), --versus "--shader FILE" the other way round, and
// --stats prints the count. Catches: --versus "" comparing the shader with itself, "--shader" in
// --versus ignored, the "shader" screen not paired with "lighting", --stats not wired to the command.
TEST_F(UserShaderStep, VersusPrintsTheUserShaderBesideTheBuiltInOne) {
    testing_support::TempFolder dir;
    std::ostringstream model, shader;  // streams: GCC 12 warns falsely on sums of strings (-Wrestrict)
    model << "'" << kSpot.string() << "' --width 96 --height 72 --pixel 48,36";
    shader << "'" << kShader.string() << "'";
    {
        const testing_support::RunResult run = testing_support::runFacet(
            "step " + model.str() + " --shader " + shader.str() + " --versus '' --stats", dir);
        ASSERT_EQ(run.status, 0) << run.err;
        EXPECT_NE(run.out.find("right (>): with the built-in shaders"), std::string::npos) << run.out;
        // The user's shader screen on the left faces the built-in lighting on the right: the two titles
        // one under the other.
        EXPECT_NE(run.out.find(" < Your shader: ToonStep's fragment part and its output\n > Lighting"),
                  std::string::npos)
            << run.out.substr(0, 4000);
        EXPECT_NE(run.out.find("N.V = "), std::string::npos);
        EXPECT_NE(run.err.find("non-finite shader values (NaN or infinite): 0"), std::string::npos)
            << run.err;
    }
    {
        const testing_support::RunResult run = testing_support::runFacet(
            "step " + model.str() + " --versus \"--shader " + shader.str() + "\"", dir);
        ASSERT_EQ(run.status, 0) << run.err;
        EXPECT_NE(run.out.find(" < Lighting"), std::string::npos) << run.out.substr(0, 4000);
        EXPECT_NE(run.out.find("\n > Your shader: ToonStep's fragment part"), std::string::npos)
            << run.out.substr(0, 4000);
    }
}

// A module loaded for some kinds of draw (walks, pipeline/back_end.h) meets a draw of another: the shader
// is compiled again, once, with every walk; the module loaded first stays as it was (draws prepared with
// it keep using it), and the loader serves the larger one from then on.
// Breaks caught: userShaderFor returning a module that lacks the walk (the pipeline refuses the draw);
// compiling again at every such draw; the loader going back to the smaller module (compiling again at
// the next scene of another walk).
TEST(UserShaderWalks, ADrawOfAnotherKindCompilesTheShaderOnceMoreWithEveryWalk) {
    testing_support::useSharedShaderCache();
    const UserShader first = loadUserShader(kCutout, walk::kFloatDepth);
    ASSERT_NE(first.module->walks & walk::kFloatDepth, 0u);
    ASSERT_EQ(first.module->walks & walk::kUnormDepth, 0u) << "compiled for one depth coding only";
    EXPECT_EQ(&userShaderFor(first, walk::kFloatDepth), first.module);
    const ShaderModule& every = userShaderFor(first, walk::kUnormDepth);
    EXPECT_EQ(every.walks, walk::kAll);
    EXPECT_NE(every.drawWatched, nullptr);
    EXPECT_EQ(&userShaderFor(first, walk::kMultisampleUnormDepth), &every) << "compiled yet again";
    EXPECT_EQ(loadUserShader(kCutout, walk::kListsFloatDepth).module, &every);
    EXPECT_EQ(first.module->walks & walk::kUnormDepth, 0u) << "the first module changed";
}

}  // namespace
}  // namespace facet::step
