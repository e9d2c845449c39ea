// The command line's shadow options: --shadows reaches the scene (every light's method), the shadow
// map options reach Scene::shadowMap, and values outside what is allowed are refused with a one-line
// message naming the option, the range and the value given.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "cli/render_command.h"
#include "cli/step_command.h"

namespace facet::cli {
namespace {

// `facet render model.obj -o out.png ARGS...`, parsed, applied to the one-model scene.
Scene sceneFromCommandLine(std::vector<std::string> args) {
    CLI::App app;
    RenderArgs parsed;
    addRenderCommand(app, parsed);
    args.insert(args.begin(), {"render", "model.obj", "-o", "out.png"});
    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
    app.parse(reversed);
    Scene scene = sceneForModel("model.obj");
    applyLightingOptions(parsed, scene);
    return scene;
}

// The InputError message for ARGS.
std::string refusal(const std::vector<std::string>& args) {
    try {
        sceneFromCommandLine(args);
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        return message;
    }
    ADD_FAILURE() << "not refused: " << args.front() << " " << args.back();
    return {};
}

// Every method's name reaches Scene::shadows; without the option it stays unset (each light's own).
// Breaks if --shadows is parsed but not applied.
TEST(ShadowOptions, ShadowsReachTheScene) {
    EXPECT_FALSE(sceneFromCommandLine({}).shadows.has_value());
    EXPECT_EQ(sceneFromCommandLine({"--shadows", "ray"}).shadows, ShadowMethod::Ray);
    EXPECT_EQ(sceneFromCommandLine({"--shadows", "map"}).shadows, ShadowMethod::Map);
    EXPECT_EQ(sceneFromCommandLine({"--shadows", "none"}).shadows, ShadowMethod::None);
    EXPECT_THROW(sceneFromCommandLine({"--shadows", "yes"}), CLI::ParseError);
}

// The shadow map's options reach Scene::shadowMap, each its own field; the bounds themselves are
// allowed. Breaks if an option is applied to the wrong field or a bound is off by one.
TEST(ShadowOptions, ShadowMapOptionsReachTheScene) {
    const Scene scene = sceneFromCommandLine({"--shadow-map-size", "512", "--shadow-bias", "2",
                                              "--shadow-slope-bias", "0.5", "--shadow-filter", "16"});
    EXPECT_EQ(scene.shadowMap.size, 512);
    EXPECT_EQ(scene.shadowMap.constantBias, 2.0f);
    EXPECT_EQ(scene.shadowMap.slopeBias, 0.5f);
    EXPECT_EQ(scene.shadowMap.filterTaps, 16);
    EXPECT_EQ(sceneFromCommandLine({"--shadow-map-size", "16"}).shadowMap.size, 16);
    EXPECT_EQ(sceneFromCommandLine({"--shadow-map-size", "8192"}).shadowMap.size, 8192);
    EXPECT_EQ(sceneFromCommandLine({"--shadow-bias", "0"}).shadowMap.constantBias, 0.0f);
    EXPECT_EQ(sceneFromCommandLine({"--shadow-filter", "1"}).shadowMap.filterTaps, 1);
}

// Out of range: refused, naming the option, what is allowed and the value as typed. Breaks if a
// check is dropped (the value would reach the scene) or the filter is only range-checked (3 let
// through).
TEST(ShadowOptions, ValuesOutOfRangeAreRefusedWithAClearMessage) {
    EXPECT_EQ(refusal({"--shadow-filter", "3"}),
              "--shadow-filter must be 1, 4 or 16 depth comparisons per point (got 3)");
    EXPECT_EQ(refusal({"--shadow-filter", "0"}),
              "--shadow-filter must be 1, 4 or 16 depth comparisons per point (got 0)");
    EXPECT_EQ(refusal({"--shadow-map-size", "10"}),
              "--shadow-map-size must be from 16 to 8192 texels (got 10)");
    EXPECT_EQ(refusal({"--shadow-map-size", "8193"}),
              "--shadow-map-size must be from 16 to 8192 texels (got 8193)");
    EXPECT_EQ(refusal({"--shadow-bias", "-1"}), "--shadow-bias must be from 0 to 1e6 (got -1)");
    EXPECT_EQ(refusal({"--shadow-slope-bias", "-0.5"}),
              "--shadow-slope-bias must be from 0 to 1e6 (got -0.5)");
    EXPECT_EQ(refusal({"--shadow-bias", "2e6"}), "--shadow-bias must be from 0 to 1e6 (got 2e6)");
    // Not numbers of the right kind: CLI11's validators refuse them while parsing.
    EXPECT_THROW(sceneFromCommandLine({"--shadow-map-size", "1.5"}), CLI::ParseError);
    EXPECT_THROW(sceneFromCommandLine({"--shadow-bias", "nan"}), CLI::ParseError);
}

// facet step takes the same options (they decide the frame it traces).
TEST(ShadowOptions, StepTakesTheShadowOptions) {
    CLI::App app;
    StepArgs args;
    CLI::App* step = addStepCommand(app, args);
    for (const char* name :
         {"--shadows", "--shadow-map-size", "--shadow-bias", "--shadow-slope-bias", "--shadow-filter"})
        EXPECT_NE(step->get_option_no_throw(name), nullptr) << name;
}

}  // namespace
}  // namespace facet::cli
