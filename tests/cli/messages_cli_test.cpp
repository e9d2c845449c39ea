// The command line's messages: an option given twice named in Facet's words, the rasterizer's
// approximations refused with the exact reference renderer, facet compare keeping the scene's loading
// warnings, and every scene file key of a number knob held to its flag's bounds.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "cli/options.h"
#include "cli/run_facet.h"
#include "scene/knobs.h"
#include "support/bundled_models.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

using testing_support::runFacet;
using testing_support::TempFolder;

using testing_support::kCube;

// Catches: CLI11's "--width: At Most 1 required but received 2" back, a second line, or another exit
// status than a bad command line's (2), for any command.
TEST(MessagesCli, AnOptionGivenTwiceIsNamedOnce) {
    const TempFolder dir;
    const struct {
        std::string args, option;
    } cases[] = {
        {"render '" + kCube + "' --width 5 --width 6 -o x.png", "--width"},
        {"step '" + kCube + "' --eye 1,2,3 --eye 1,2,4 --print", "--eye"},
        {"trade '" + kCube + "' --frames 1 --frames 2", "--frames"},
        {"compare '" + kCube + "' --height 5 --height 6", "--height"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.args);
        const testing_support::RunResult run = runFacet(c.args, dir);
        EXPECT_EQ(run.status, 2);
        EXPECT_EQ(run.err,
                  "facet: error: " + c.option +
                      " was given twice; give it once (facet --help lists the commands and options)\n");
    }
    const testing_support::RunResult thrice =
        runFacet("render '" + kCube + "' -o a.png -o b.png -o c.png", dir);
    EXPECT_EQ(thrice.status, 2);
    EXPECT_NE(thrice.err.find("--output was given 3 times; give it once"), std::string::npos) << thrice.err;
}

// Every knob the table declares the reference replaces, given with --renderer reference, is refused
// naming the flag and what the reference does instead; a knob the reference follows is accepted.
// Catches: `--aa msaa4 --renderer reference` accepted and silently ignored again (the battery's case),
// a rasterizer-only knob the table marks but the check misses, or the check refusing every knob.
TEST(MessagesCli, RasterizerOnlyKnobsAreRefusedWithTheReferenceRenderer) {
    const TempFolder dir;
    int marked = 0;
    for (const SceneKnob& knob : sceneKnobs()) {
        if (knob.referenceInstead.empty() || knob.flag.empty()) continue;
        ++marked;
        const std::string value =
            knob.kind == KnobKind::Names ? knob.names.back() : knobNumberText(knob.highest);
        SCOPED_TRACE(knob.flag + " " + value);
        const testing_support::RunResult run =
            runFacet("render '" + kCube + "' --renderer reference --width 8 --height 8 -o x.png " +
                         knob.flag + " " + value,
                     dir);
        EXPECT_EQ(run.status, 1);
        EXPECT_EQ(run.err, "facet: error: " + knob.flag + " " + value +
                               " does not go with --renderer reference, which " + knob.referenceInstead +
                               ": leave " + knob.flag + " out, or render without --renderer reference\n");
        EXPECT_FALSE(std::filesystem::exists(dir.path() / "x.png"));
    }
    EXPECT_GE(marked, 1);
    ASSERT_FALSE(sceneKnobNamed("aa")->referenceInstead.empty());  // the battery's case is among them
    // The reference lights the scene by its lighting convention: --lighting is followed, not refused.
    ASSERT_TRUE(sceneKnobNamed("lighting")->referenceInstead.empty());
    const testing_support::RunResult followed =
        runFacet("render '" + kCube +
                     "' --renderer reference --samples 1 --width 8 --height 8 -q -o y.png --lighting gl",
                 dir, dir.path());
    EXPECT_EQ(followed.status, 0) << followed.err;
}

// A model whose MTL has a statement Facet leaves out with a warning: facet compare --reference prints
// the same warning facet render prints. Catches: compare dropping every loading warning (the battery's
// case: render warns, compare is silent about the same file).
TEST(MessagesCli, CompareKeepsTheLoadingWarnings) {
    const TempFolder dir;
    std::ofstream(dir.path() / "w.obj") << "mtllib w.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n";
    std::ofstream(dir.path() / "w.mtl") << "newmtl a\nKd nan 1 1\n";
    const std::string warning = "w.mtl:2: Kd expects three finite numbers";
    const testing_support::RunResult render =
        runFacet("render w.obj --width 16 --height 16 -q -o w.png", dir, dir.path());
    ASSERT_EQ(render.status, 0) << render.err;
    ASSERT_NE(render.err.find(warning), std::string::npos) << render.err;
    const testing_support::RunResult compare =
        runFacet("compare w.obj --reference --shadow-map-sizes 0 --width 16 --height 16", dir, dir.path());
    EXPECT_NE(compare.status, 1) << compare.err;
    EXPECT_NE(compare.err.find("facet: warning: " + warning), std::string::npos) << compare.err;
}

// Every number knob with both a flag and a scene file key: a value beyond either bound is refused in
// the scene file as on the command line, both messages naming the same allowed range (one declaration).
// Catches: `"shadow_map": {"bias": 1e30}` accepted where `--shadow-bias 1e30` is refused, or any other
// key read with bounds of its own (or none).
TEST(MessagesCli, SceneKeysKeepTheirFlagsBounds) {
    const TempFolder dir;
    int checked = 0;
    for (const SceneKnob& knob : sceneKnobs()) {
        if (knob.kind == KnobKind::Names || knob.flag.empty() || knob.section.empty()) continue;
        for (const double value : {knob.highest * 10 + 10, knob.lowest - 1, 1e30}) {
            if (knob.allows(value) || std::abs(value) > 3e38) continue;
            const std::string text = knobNumberText(value);
            SCOPED_TRACE(knob.scenePath() + " " + text);
            ++checked;
            // The fog's keys are read with their mode (start and end for linear fog only).
            std::string section = "\"" + knob.key + "\": " + text;
            if (knob.section == "fog")
                section += knob.key == "density" ? ", \"mode\": \"exp\"" : ", \"mode\": \"linear\"";
            const std::filesystem::path scene = dir.path() / "s.json";
            std::ofstream(scene) << "{\"objects\": [{\"model\": \"" << kCube << "\"}], \"" << knob.section
                                 << "\": {" << section << "}}";
            cli::SceneArgs fromFile;
            fromFile.input = scene.string();
            try {
                cli::sceneFromArgs(fromFile);
                ADD_FAILURE() << "the scene file's key was accepted";
            } catch (const InputError& e) {
                EXPECT_NE(std::string(e.what()).find(knob.allowed()), std::string::npos) << e.what();
            }
            cli::SceneArgs fromFlag;
            fromFlag.input = kCube;
            fromFlag.knobs[knob.name] = text;
            try {
                cli::sceneFromArgs(fromFlag);
                ADD_FAILURE() << "the flag was accepted";
            } catch (const InputError& e) {
                EXPECT_NE(std::string(e.what()).find(knob.allowed()), std::string::npos) << e.what();
            }
        }
    }
    EXPECT_GE(checked, 10);
}

}  // namespace
}  // namespace facet
