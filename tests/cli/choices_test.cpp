// The command line's choices: each option's every name (from its enum's table) reaches the scene the
// command renders, and a wrong name is refused with the table's names.
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "bench/bench.h"
#include "cli/bench_command.h"
#include "cli/compare_command.h"
#include "cli/render_command.h"
#include "cli/step_command.h"
#include "pipeline/names.h"

namespace facet::cli {
namespace {

// `facet render model.obj -o out.png OPTION NAME`, parsed; the arguments it fills.
RenderArgs parseOption(const std::string& option, const std::string& name) {
    CLI::App app;
    RenderArgs args;
    addRenderCommand(app, args);
    app.parse(std::vector<std::string>{name, option, "out.png", "-o", "model.obj", "render"});  // reversed
    return args;
}

// The scene a parsed command line makes of a one-object scene.
Scene sceneWith(const RenderArgs& args) {
    Scene scene = sceneForModel("model.obj");
    applyLightingOptions(args, scene);
    return scene;
}

// For each name E's table offers, `option NAME` gives a scene in which `reached` reads that value.
template <class E, class Reached>
void expectEveryNameReaches(const std::string& option, Reached reached) {
    for (const std::string& name : namesOf<E>()) {
        SCOPED_TRACE(option + " " + name);
        EXPECT_EQ(reached(sceneWith(parseOption(option, name))), *parseName<E>(name));
    }
}

// --subpixel-bits reaches the scene's pipeline options at both ends of its range, and a value beyond
// them is refused naming the option and its range, as every knob's range is (scene/knobs.h); a value
// that is not a whole number is refused by the parser.
TEST(CommandLineChoices, SubpixelBitsReachTheScene) {
    EXPECT_EQ(sceneWith(parseOption("--subpixel-bits", "0")).pipeline.subpixelBits, 0);
    EXPECT_EQ(sceneWith(parseOption("--subpixel-bits", "3")).pipeline.subpixelBits, 3);
    EXPECT_EQ(sceneWith(parseOption("--subpixel-bits", "8")).pipeline.subpixelBits, 8);
    try {
        sceneWith(parseOption("--subpixel-bits", "9"));
        ADD_FAILURE() << "--subpixel-bits 9 accepted";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "--subpixel-bits must be from 0 to 8 (got 9)");
    }
    EXPECT_THROW(parseOption("--subpixel-bits", "2.5"), CLI::ParseError);
}

TEST(CommandLineChoices, EveryNameReachesTheScene) {
    expectEveryNameReaches<LightingPreset>("--lighting", [](const Scene& s) { return s.lighting.preset; });
    expectEveryNameReaches<ReflectionModel>("--reflection", [](const Scene& s) {
        EXPECT_EQ(s.objects[0].reflection, s.lighting.model);  // every object, too
        return s.lighting.model;
    });
    expectEveryNameReaches<ShadingFrequency>("--shading", [](const Scene& s) {
        EXPECT_EQ(s.objects[0].shading, s.lighting.shading);
        return *s.lighting.shading;
    });
    expectEveryNameReaches<TransparencyMode>("--transparency",
                                             [](const Scene& s) { return s.transparency.mode; });
    expectEveryNameReaches<SortKey>("--sort-key", [](const Scene& s) { return s.transparency.key; });
    expectEveryNameReaches<TransferCurve>("--encode", [](const Scene& s) { return s.gamma.encode; });
    expectEveryNameReaches<Interpolation>("--interpolation",
                                          [](const Scene& s) { return s.pipeline.interpolation; });
    expectEveryNameReaches<CullMode>("--cull", [](const Scene& s) { return s.pipeline.cull; });
    expectEveryNameReaches<Antialiasing>("--aa", [](const Scene& s) { return s.pipeline.antialiasing; });
    expectEveryNameReaches<VertexNormals>("--normals", [](const Scene& s) { return s.lighting.normals; });
    expectEveryNameReaches<MathPrecision>("--powers", [](const Scene& s) { return s.lighting.powers; });
    expectEveryNameReaches<Normalization>("--normalize", [](const Scene& s) { return s.lighting.normalize; });
    expectEveryNameReaches<FresnelModel>("--fresnel", [](const Scene& s) { return s.lighting.brdf.fresnel; });
}

// facet step traces exactly the render `facet render` would make with the same options: it takes every
// option of render's that decides the frame (all but the output's).
TEST(CommandLineChoices, StepTakesEveryOptionOfRenderThatDecidesTheFrame) {
    CLI::App app;
    RenderArgs renderArgs;
    StepArgs stepArgs;
    CLI::App* render = addRenderCommand(app, renderArgs);
    CLI::App* step = addStepCommand(app, stepArgs);
    // And the reference renderer's: step follows the rasterizer's pipeline, which the reference does not use.
    const std::set<std::string> outputOnly = {"--output",  "--quiet",          "--frames", "--turntable",
                                              "--stats",   "--components",     "--help",   "--renderer",
                                              "--samples", "--png-compression"};
    std::size_t checked = 0;
    for (const CLI::Option* option : render->get_options()) {
        const std::string name = option->get_name();
        if (outputOnly.count(name)) continue;
        EXPECT_NE(step->get_option_no_throw(name), nullptr) << name;
        ++checked;
    }
    EXPECT_GE(checked, 18u);  // input, size, camera, threads and the choices
}

TEST(CommandLineChoices, OnlyTakesEachTermByItsName) {
    for (const EnumName<LightingTerm>& term : kLightingTermNames) {
        const RenderArgs args = parseOption("--only", std::string(term.name));
        ASSERT_TRUE(args.only.has_value()) << term.name;
        EXPECT_EQ(*args.only, term.value) << term.name;
    }
}

// A wrong name is refused, the message listing every name of the table.
TEST(CommandLineChoices, WrongNameListsTheTablesNames) {
    try {
        parseOption("--reflection", "lambert");
        ADD_FAILURE() << "lambert accepted";
    } catch (const CLI::ParseError& e) {
        const std::string message = e.what();
        for (const std::string& name : namesOf<ReflectionModel>())
            EXPECT_NE(message.find(name), std::string::npos) << message;
    }
}

// compare takes the same choices as render.
TEST(CommandLineChoices, CompareTakesTheSameNames) {
    for (const std::string& name : namesOf<ShadingFrequency>()) {
        CLI::App app;
        CompareArgs args;
        addCompareCommand(app, args);
        app.parse(std::vector<std::string>{name, "--shading", "model.obj", "compare"});
        EXPECT_EQ(args.scene.knobs.at("shading"), name);
    }
    // The formulas' choices reach the scene compare renders.
    const auto compareScene = [](const std::string& option, const std::string& name) {
        CLI::App app;
        CompareArgs args;
        addCompareCommand(app, args);
        app.parse(std::vector<std::string>{name, option, "model.obj", "compare"});
        Scene scene = sceneForModel("model.obj");
        applyLightingOptions(args.scene, scene);
        return scene;
    };
    for (const std::string& name : namesOf<VertexNormals>())
        EXPECT_EQ(compareScene("--normals", name).lighting.normals, parseName<VertexNormals>(name)) << name;
    for (const std::string& name : namesOf<MathPrecision>())
        EXPECT_EQ(compareScene("--powers", name).lighting.powers, parseName<MathPrecision>(name)) << name;
    for (const std::string& name : namesOf<Normalization>())
        EXPECT_EQ(compareScene("--normalize", name).lighting.normalize, parseName<Normalization>(name))
            << name;
    for (const std::string& name : namesOf<FresnelModel>())
        EXPECT_EQ(compareScene("--fresnel", name).lighting.brdf.fresnel, parseName<FresnelModel>(name))
            << name;
    // The buffer formats and the texture filter, which OpenGL's side takes too (gl_scene.h).
    for (const std::string& name : namesOf<DepthBufferFormat>())
        EXPECT_EQ(compareScene("--depth", name).pipeline.depth, parseName<DepthBufferFormat>(name)) << name;
    for (const std::string& name : namesOf<ColorBufferFormat>())
        EXPECT_EQ(compareScene("--color-buffer", name).pipeline.colorBuffer,
                  parseName<ColorBufferFormat>(name))
            << name;
    for (const std::string& name : namesOf<TextureFilter>())
        EXPECT_EQ(compareScene("--texture-filter", name).textures.filter, parseName<TextureFilter>(name))
            << name;
    // --driver: each of Mesa's rasterizers by its table's name; absent, the default (softpipe).
    for (const std::string& name : namesOf<MesaDriver>()) {
        CLI::App app;
        CompareArgs args;
        addCompareCommand(app, args);
        app.parse(std::vector<std::string>{name, "--driver", "model.obj", "compare"});
        EXPECT_EQ(args.driver, parseName<MesaDriver>(name)) << name;
        EXPECT_EQ(driverName(*args.driver), name);
    }
    EXPECT_EQ(namesOf<MesaDriver>().size(), 2u);
}

// `facet bench --aa NAME` reaches the scene the benchmark times, for every name; without --aa the
// scene file's choice stands.
TEST(CommandLineChoices, BenchTakesEveryAntialiasingName) {
    for (const std::string& name : namesOf<Antialiasing>()) {
        SCOPED_TRACE(name);
        CLI::App app;
        BenchOptions options;
        addBenchCommand(app, options);
        app.parse(std::vector<std::string>{name, "--aa", "bench"});  // reversed: bench --aa NAME
        ASSERT_TRUE(options.antialiasing.has_value());
        EXPECT_EQ(*options.antialiasing, *parseName<Antialiasing>(name));
    }
}

}  // namespace
}  // namespace facet::cli
