// The knobs' table (scene/knobs.h) is what every reader of a knob reads: each entry's flag reaches the
// scene from every command that takes it (render, step, step's --versus, trade's settings; compare and
// bench their share), its scene file key reaches the scene through the scene reader, its default is the
// Scene's own, and a value out of its range is refused by the command line and the scene file alike.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "bench/bench.h"
#include "cli/bench_command.h"
#include "cli/compare_command.h"
#include "cli/render_command.h"
#include "cli/step_command.h"
#include "cli/trade_command.h"
#include "run_facet.h"
#include "scene/knobs.h"
#include "support/temp_folder.h"
#include "trade/knobs.h"

namespace facet::cli {
namespace {

// A value of `knob` other than its default (any, for a knob without one), as its flag takes it.
std::string otherValue(const SceneKnob& knob) {
    const std::string byDefault = knob.defaultValue();
    std::vector<std::string> candidates = knob.kind == KnobKind::Names ? knob.names : knob.tradeValues;
    if (knob.kind != KnobKind::Names) {
        candidates.push_back(knobNumberText(knob.lowest));
        candidates.push_back(knobNumberText(knob.highest));
    }
    for (const std::string& value : candidates)
        if (value != byDefault) return value;
    ADD_FAILURE() << knob.name << " has no value other than " << byDefault;
    return byDefault;
}

// `words` (after the command's name and the input) parsed by `command` as CLI11 parses a command line.
template <class Args, class Add>
void parse(Add add, Args& args, const std::string& command, std::vector<std::string> words) {
    CLI::App app;
    add(app, args);
    words.insert(words.begin(), {command, "model.obj"});
    std::reverse(words.begin(), words.end());  // CLI11 takes them last first
    app.parse(words);
}

// The one-model scene with the command line's choices applied.
Scene sceneWith(const SceneArgs& args) {
    Scene scene = sceneForModel("model.obj");
    applyLightingOptions(args, scene);
    return scene;
}

// Every flag, at a value other than its default, reaches the scene from render, step, step's --versus
// and the trade's settings, and the knob's own entry reads that value back. Catches a command that
// registers some knobs only, an entry whose set writes another field than its get reads, and --versus
// or the trade parsing the words with a parser of their own.
TEST(Knobs, EveryFlagReachesTheSceneFromEveryCommand) {
    for (const SceneKnob& knob : sceneKnobs()) {
        if (knob.flag.empty()) continue;
        const std::string value = otherValue(knob);
        SCOPED_TRACE(knob.flag + " " + value);
        RenderArgs render;
        parse(addRenderCommand, render, "render", {"-o", "out.png", knob.flag, value});
        EXPECT_EQ(knob.get(sceneWith(render)), value) << "render";
        StepArgs step;
        parse(addStepCommand, step, "step", {knob.flag, value});
        EXPECT_EQ(knob.get(sceneWith(step)), value) << "step";
        StepArgs plain;
        parse(addStepCommand, plain, "step", {});
        EXPECT_EQ(knob.get(sceneWith(versusArgs(plain, knob.flag + " " + value))), value) << "--versus";
        TradeArgs trade;
        parse(addTradeCommand, trade, "trade", {knob.flag, value});
        EXPECT_EQ(knob.get(sceneWith(trade.scene)), value) << "trade";
        EXPECT_EQ(knob.get(sceneWithWords(plain, {knob.flag, value})), value) << "the trade's setting";
    }
}

// compare and bench take their share of the knobs through the same entries.
TEST(Knobs, CompareAndBenchTakeTheirKnobsFromTheTable) {
    for (const char* name : {"lighting", "reflection", "shading", "crease-angle", "depth", "color-buffer",
                             "texture-filter", "normals", "powers", "normalize", "fresnel", "aa"}) {
        const SceneKnob& knob = *sceneKnobNamed(name);
        const std::string value = otherValue(knob);
        SCOPED_TRACE(knob.flag + " " + value);
        CompareArgs compare;
        parse(addCompareCommand, compare, "compare", {knob.flag, value});
        EXPECT_EQ(knob.get(sceneWith(compare.scene)), value);
    }
    BenchOptions bench;
    parse(addBenchCommand, bench, "bench", {"--aa", "msaa4"});
    EXPECT_EQ(bench.antialiasing, Antialiasing::Msaa4);
}

class KnobKeysTest : public testing_support::TempFolderTest {
  protected:
    // A scene of one model with `section`: {`key`: `value`} (JSON text). The fog's numbers come with
    // the mode that uses them (the file refuses a fog without a mode, or a key its mode ignores).
    Scene sceneWith(const SceneKnob& knob, const std::string& value) const {
        touch("m.obj");
        std::string context;
        if (knob.section == "fog" && knob.key != "mode")
            context = knob.key == "density" ? R"("mode": "exp", )" : R"("mode": "linear", )";
        return loadScene(write("scene.json", R"({"model": "m.obj", ")" + knob.section + R"(": {)" + context +
                                                 '"' + knob.key + R"(": )" + value + "}}"));
    }
    static std::string json(const SceneKnob& knob, const std::string& value) {
        return knob.kind == KnobKind::Names ? '"' + value + '"' : value;
    }
};

// Every scene file key, at a value other than its default, reaches the scene through the scene reader;
// a scene file without it has the knob's default. Catches a section that reads some of its knobs only
// or a key spelled otherwise than its entry says.
TEST_F(KnobKeysTest, EverySceneKeyReachesTheScene) {
    for (const SceneKnob& knob : sceneKnobs()) {
        if (knob.section.empty()) continue;
        const std::string value = otherValue(knob);
        SCOPED_TRACE(knob.scenePath() + " " + value);
        EXPECT_EQ(knob.get(sceneWith(knob, json(knob, value))), value);
    }
}

// A knob's default is the Scene's own: what a scene file and a command line that leave the knob alone
// render with; the trade's default preset uses the same. Catches a default written down again (in the
// help or the trade) that drifts from the Scene's.
TEST(Knobs, EachDefaultIsTheScenes) {
    for (const SceneKnob& knob : sceneKnobs()) {
        SCOPED_TRACE(knob.name);
        if (!knob.defaultNote.empty()) {
            EXPECT_EQ(knob.defaultValue(), "");
            continue;
        }
        EXPECT_EQ(knob.defaultValue(), knob.get(sceneForModel("model.obj")));
        if (knob.kind == KnobKind::Names)
            EXPECT_NE(std::find(knob.names.begin(), knob.names.end(), knob.defaultValue()), knob.names.end());
        else
            EXPECT_TRUE(knob.allows(std::stod(knob.defaultValue())));
    }
    for (const Knob& traded : knobTable())
        EXPECT_EQ(traded.defaultValue, sceneKnobNamed(traded.name)->defaultValue()) << traded.name;
}

// A number out of a knob's range is refused by the command line and by the scene file with the same
// words: the flag or the key, then what the value must be. Catches a range checked in one place only.
TEST_F(KnobKeysTest, OutOfRangeIsRefusedByBothWithTheSameWords) {
    for (const SceneKnob& knob : sceneKnobs()) {
        if (knob.kind == KnobKind::Names) continue;
        const std::string value = knobNumberText(knob.lowest - 1);
        SCOPED_TRACE(knob.name + " " + value);
        RenderArgs render;
        parse(addRenderCommand, render, "render", {"-o", "out.png", knob.flag, value});
        try {
            cli::sceneWith(render);
            ADD_FAILURE() << "the command line took it";
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()),
                      knob.flag + " must be " + knob.allowed() + " (got " + value + ")");
        }
        if (knob.section.empty()) continue;  // the command line only (--shininess)
        try {
            sceneWith(knob, value);
            ADD_FAILURE() << "the scene file took it";
        } catch (const InputError& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find('"' + knob.scenePath() + "\" must be"), std::string::npos) << message;
            EXPECT_NE(message.find(knob.allowed()), std::string::npos) << message;
        }
    }
}

// Blinn-Phong's exponent reaches the shaders, the reference and the step mode: with --blinn-exponent
// matched, or "lighting": {"blinn_exponent": "matched"}, a Blinn-Phong model of shininess n renders as the
// same model of shininess 4n, and not as it does with the exponent given; the option wins over the
// scene's key. Catches the knob set in the scene but not used by the shader (matched = given), a factor
// other than 4, the reference shading with the material's n, and the step screen printing n where e′
// was used.
TEST(BlinnExponent, MatchedRendersAsFourTimesTheShininess) {
    const testing_support::TempFolder dir;
    const std::string spot = std::string(FACET_SOURCE_DIR) + "/models/spot/spot_triangulated.obj";
    const auto scene = [&](const std::string& name, int shininess, const std::string& exponent) {
        return dir
            .write(name, R"({"width": 64, "height": 48, "objects": [{"model": ")" + spot +
                             R"(", "material": {"shininess": )" + std::to_string(shininess) +
                             R"(, "specular": [1, 1, 1]}}], "lighting": {"model": "blinn-phong")" + exponent +
                             "}}")
            .string();
    };
    const std::string n = scene("n.json", 10, "");
    const std::string fourN = scene("4n.json", 40, "");
    const std::string matched = scene("matched.json", 10, R"(, "blinn_exponent": "matched")");
    int images = 0;
    const auto render = [&](const std::string& input, const std::string& options) {
        const std::string image = (dir.path() / ("image" + std::to_string(++images) + ".png")).string();
        const testing_support::RunResult run =
            testing_support::runFacet("render -q '" + input + "' -o '" + image + "' " + options, dir);
        EXPECT_EQ(run.status, 0) << run.err;
        return testing_support::readText(image);
    };
    for (const std::string renderer : {"", "--renderer reference --samples 1"}) {
        SCOPED_TRACE(renderer);
        const std::string given = render(n, renderer);
        const std::string four = render(fourN, renderer);
        EXPECT_NE(given, four);
        EXPECT_EQ(render(n, renderer + " --blinn-exponent matched"), four) << "the option";
        EXPECT_EQ(render(matched, renderer), four) << "the scene key";
        EXPECT_EQ(render(matched, renderer + " --blinn-exponent given"), given) << "the option over the key";
    }
    const testing_support::RunResult step =
        testing_support::runFacet("step --print '" + n + "' --versus '--blinn-exponent matched'", dir);
    ASSERT_EQ(step.status, 0) << step.err;
    EXPECT_NE(step.out.find("e′ = 4e = 40"), std::string::npos) << step.out;
}

}  // namespace
}  // namespace facet::cli

namespace facet::cli {
namespace {

// The image `facet render` writes for `input` (a path under models/) with `options`, 64 × 48, as bytes.
std::string renderedBytes(const testing_support::TempFolder& dir, const std::string& input,
                          const std::string& options) {
    static int images = 0;
    const std::string image = (dir.path() / ("lecture" + std::to_string(++images) + ".png")).string();
    const testing_support::RunResult run =
        testing_support::runFacet("render -q '" + std::string(FACET_SOURCE_DIR) + "/models/" + input +
                                      "' -o '" + image + "' --width 64 --height 48 " + options,
                                  dir);
    EXPECT_EQ(run.status, 0) << options << ": " << run.err;
    return testing_support::readText(image);
}

// --shininess reaches the image: the red sphere's highlight narrows from the file's hardness 1 to 128,
// and the flag at the file's own value 1 gives the file's image. Catches a flag that does not reach
// the objects' materials, or reaches one object's only.
TEST(LectureFlags, ShininessChangesTheHighlight) {
    const testing_support::TempFolder dir;
    const std::string given = renderedBytes(dir, "red-sphere.json", "");
    const std::string sharp = renderedBytes(dir, "red-sphere.json", "--shininess 128");
    EXPECT_NE(given, sharp);
    EXPECT_EQ(renderedBytes(dir, "red-sphere.json", "--shininess 1"), given);
    // Every object takes it, whatever its own was.
    Scene scene = sceneForModel("model.obj");
    scene.objects.resize(2);
    scene.objects[1].material.shininess = 7.0f;
    const SceneKnob& knob = *sceneKnobNamed("shininess");
    EXPECT_EQ(knob.get(scene), "");  // the objects disagree
    knob.set(scene, "64");
    EXPECT_EQ(knob.get(scene), "64");
    EXPECT_EQ(*scene.objects[0].material.shininess, 64.0f);
    EXPECT_EQ(*scene.objects[1].material.shininess, 64.0f);
}

// The fog flags reach the image, over the scene's own "fog": each mode gives another image, the file's
// own mode and density give the file's image, density moves exp fog and start/end move linear fog.
// Catches a flag that the scene's "fog" section overrides, or one that sets another field.
TEST(LectureFlags, FogFlagsChangeTheImage) {
    const testing_support::TempFolder dir;
    const std::string scene = "fog-and-glass.json";  // its own fog: exp2, density 0.1
    const std::string own = renderedBytes(dir, scene, "");
    EXPECT_EQ(renderedBytes(dir, scene, "--fog exp2 --fog-density 0.1"), own);
    const std::string none = renderedBytes(dir, scene, "--fog none");
    const std::string exp = renderedBytes(dir, scene, "--fog exp");
    const std::string linear = renderedBytes(dir, scene, "--fog linear --fog-start 4 --fog-end 14");
    EXPECT_NE(none, own);
    EXPECT_NE(exp, own);
    EXPECT_NE(exp, none);
    EXPECT_NE(linear, own);
    EXPECT_NE(renderedBytes(dir, scene, "--fog exp2 --fog-density 0.2"), own);
    EXPECT_NE(renderedBytes(dir, scene, "--fog linear --fog-start 4 --fog-end 20"), linear);
    EXPECT_NE(renderedBytes(dir, scene, "--fog linear --fog-start 8 --fog-end 14"), linear);
}

// Bad values of the new flags: one line, naming the flag and what it must be.
TEST(LectureFlags, BadValuesGiveOneLine) {
    const testing_support::TempFolder dir;
    const std::string input = "render -q '" + std::string(FACET_SOURCE_DIR) +
                              "/models/red-sphere.json' -o '" + (dir.path() / "x.png").string() + "' ";
    for (const auto& [options, message] : std::vector<std::pair<std::string, std::string>>{
             {"--shininess -1", "--shininess must be from 0 to 10000 (got -1)"},
             {"--shininess many", "--shininess: expects a finite number (got \"many\")"},
             {"--fog fog", "--fog: fog not in {none,linear,exp,exp2,height}"},
             {"--fog-density -2", "--fog-density must be from 0 to 1e30 (got -2)"},
             {"--fog-start -1", "--fog-start must be from 0 to 1e30 (got -1)"},
             {"--fog linear --fog-start 10 --fog-end 2",
              "the fog's end (2) must be greater than its start (10)"}}) {
        SCOPED_TRACE(options);
        const testing_support::RunResult run = testing_support::runFacet(input + options, dir);
        EXPECT_NE(run.status, 0);
        EXPECT_NE(run.err.find(message), std::string::npos) << run.err;
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    }
}

}  // namespace
}  // namespace facet::cli
