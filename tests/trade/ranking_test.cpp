// facet trade ranks honestly: an image that draws nothing of the scene is flagged and kept off the
// Pareto front, a reference that shows nothing is refused, knobs that change what the scene shows are
// flagged and kept off the front and out of the presets, and the linear metrics stay meaningful when
// the reference is brighter than 1.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "cli/render_command.h"
#include "cli/trade_command.h"
#include "quick_trade.h"
#include "scene/knobs.h"
#include "support/bundled_models.h"
#include "support/temp_folder.h"
#include "trade/blank.h"
#include "trade/knobs.h"
#include "trade/metrics.h"
#include "trade/trade.h"

namespace facet {
namespace {

using testing_support::kModels;
using testing_support::quickTrade;

// A scene file of `text` in `folder`; "MODELS" in it is replaced by the bundled models' folder.
std::filesystem::path writeScene(const std::filesystem::path& folder, const std::string& name,
                                 std::string text) {
    for (std::size_t at = text.find("MODELS"); at != std::string::npos; at = text.find("MODELS"))
        text.replace(at, 6, kModels.string());
    const std::filesystem::path path = folder / name;
    std::ofstream(path) << text;
    return path;
}

const TradeRow* rowLabelled(const TradeResult& result, const std::string& label) {
    for (const TradeRow& row : result.rows)
        if (row.setting.label() == label) return &row;
    return nullptr;
}

bool anyLineHas(const std::vector<std::string>& lines, const std::string& text) {
    return std::any_of(lines.begin(), lines.end(),
                       [&](const std::string& line) { return line.find(text) != std::string::npos; });
}

// The camera at the centre of a closed sphere drawn without culling: it sees the sphere's inside, all
// back faces, so `--cull back` draws nothing at all, and does it faster than anything that draws.
// Catches: a blank image not flagged, or flagged but left on the front as the fastest setting (the
// issue's "blank image won"); a drawn image flagged blank; no warning naming the setting.
TEST(TradeBlank, ASettingThatDrawsNothingIsFlaggedWarnedAndOffTheFront) {
    const testing_support::TempFolder folder;
    const std::filesystem::path scene =
        writeScene(folder.path(), "inside.json",
                   R"({"width": 48, "height": 36, "camera": {"eye": [0, 0, 0], "target": [0, 0, -1]},
                       "objects": [{"model": "MODELS/sphere/sphere.obj"}], "pipeline": {"cull": "none"}})");
    const TradeResult result = quickTrade(scene, "cull,shading", folder.path() / "trade");
    const TradeRow* culled = rowLabelled(result, "--cull back");
    ASSERT_NE(culled, nullptr);
    EXPECT_TRUE(culled->blank);
    EXPECT_FALSE(culled->pareto);
    EXPECT_TRUE(anyLineHas(result.warnings, "--cull back draws nothing"));
    for (const TradeRow& row : result.rows)
        if (row.setting.knob == "baseline" || row.setting.knob == "shading") {
            SCOPED_TRACE(row.setting.label());
            EXPECT_FALSE(row.blank);  // they draw the sphere's inside, as the reference does
        }
    EXPECT_FALSE(rowLabelled(result, "baseline")->blank);
    EXPECT_TRUE(
        std::any_of(result.rows.begin(), result.rows.end(), [](const TradeRow& row) { return row.pareto; }));
}

// The issue's case: the camera inside the model's bounds and a near plane of 1e-6, so that in a 16-bit
// unorm depth buffer every depth, 1 − near/z within half a step of 1, rounds to the far plane and fails
// the depth test; float depth keeps them. Catches: `--depth unorm16` "5.7× faster" on the front again.
TEST(TradeBlank, ATinyNearPlaneWithSixteenBitDepthIsBlank) {
    const testing_support::TempFolder folder;
    const std::filesystem::path scene = writeScene(
        folder.path(), "near.json",
        R"({"width": 48, "height": 36, "camera": {"eye": [0.1, 0.3, 0.5], "target": [0, 0.2, 0], "near": 1e-6},
            "objects": [{"model": "MODELS/spot/spot_triangulated.obj"}]})");
    const TradeResult result = quickTrade(scene, "depth", folder.path() / "trade");
    const TradeRow* unorm16 = rowLabelled(result, "--depth unorm16");
    ASSERT_NE(unorm16, nullptr);
    EXPECT_TRUE(unorm16->blank);
    EXPECT_FALSE(unorm16->pareto);
    EXPECT_FALSE(rowLabelled(result, "baseline")->blank);
    EXPECT_FALSE(rowLabelled(result, "--depth reversed-float")->blank);
}

// A camera that looks away from the scene: the reference itself is only background, every setting would
// score perfectly against it. Catches: such a trade exiting with perfect scores instead of a one-line error.
TEST(TradeBlank, AReferenceThatShowsNothingIsRefused) {
    const testing_support::TempFolder folder;
    const std::filesystem::path scene =
        writeScene(folder.path(), "away.json",
                   R"({"width": 32, "height": 24, "camera": {"eye": [0, 0, 5], "target": [0, 0, 10]},
                       "objects": [{"model": "MODELS/sphere/sphere.obj"}]})");
    try {
        quickTrade(scene, "shading", folder.path() / "trade");
        FAIL() << "the trade ran";
    } catch (const InputError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("away.json"), std::string::npos) << message;
        EXPECT_NE(message.find("shows only the background"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

// Coverage counts, of the pixels where the reference shows a surface, those where the image shows one
// too; blank is below a tenth of them. 100 reference pixels: 9 shown is blank, 10 is not; surface
// pixels outside the reference's (stray fragments) do not count. Catches: coverage counted over the
// whole image (a scattered mess passing for the scene), the share's comparison off by one.
TEST(TradeBlank, CoverageCountsOnlyWhereTheReferenceShowsTheScene) {
    std::vector<bool> reference(400, false), image(400, false);
    for (int i = 0; i < 100; ++i)
        reference[i] = true;
    for (int i = 100; i < 400; ++i)  // everywhere else: not where the reference shows the scene
        image[i] = true;
    for (int i = 0; i < 9; ++i)
        image[i] = true;
    EXPECT_EQ(coverageOf(image, reference).reference, 100u);
    EXPECT_EQ(coverageOf(image, reference).shown, 9u);
    EXPECT_TRUE(coverageOf(image, reference).blank());
    image[9] = true;
    EXPECT_FALSE(coverageOf(image, reference).blank());

    // A surface pixel is one whose 8-bit colour differs from the empty image's; the same colour is not.
    LinearImage background{
        2, 1, {glm::vec4(0.05f, 0.05f, 0.07f, 1.0f), glm::vec4(0.05f, 0.05f, 0.07f, 1.0f)}};
    LinearImage drawn = background;
    drawn.pixels[1] = glm::vec4(0.05f, 0.5f, 0.07f, 1.0f);
    EXPECT_EQ(surfacePixels(drawn, background, kSrgbEncoding), (std::vector<bool>{false, true}));
}

// The knobs that change what the scene shows rather than how exactly it is drawn: every value of the
// textures, the reflection model, the Blinn exponent and the vertex normals' weighting other than the
// scene's own; shadows (and the shadow map's knobs, which carry --shadows map) only where the scene has
// a light without them. Catches:
// a knob added to or dropped from the list; shadows flagged on a scene that already casts them (there
// --shadows map against ray is an accuracy trade) or not flagged on one without.
TEST(TradeContent, ExactlyTheDeclaredKnobsChangeContent) {
    const std::set<std::string> alwaysContent = {"textures", "reflection", "blinn-exponent", "normals"};
    const std::set<std::string> shadowKnobs = {"shadows", "shadow-map-size", "shadow-filter", "shadow-bias",
                                               "shadow-slope-bias"};
    const Scene unshadowed = defaultKnobScene();  // the default light casts no shadows
    Scene shadowed = defaultKnobScene();
    shadowed.lights.emplace_back();
    shadowed.lights.back().shadows = ShadowMethod::Ray;
    Scene mixed = shadowed;  // a second light without shadows: map or ray adds its shadows
    mixed.lights.emplace_back();
    for (const Knob& knob : knobTable())
        for (const std::string& value : knob.values) {
            const TradeSetting setting = knobSetting(knob, value);
            SCOPED_TRACE(setting.label());
            // Not where the value is the scene's own: that setting changes nothing.
            auto always = [&](const Scene& scene) {
                return alwaysContent.count(knob.name) > 0 && knob.valueIn(scene) != value;
            };
            const bool addsShadows = shadowKnobs.count(knob.name) > 0 && setting.words[1] != "none";
            EXPECT_EQ(settingChangesContent(unshadowed, setting), always(unshadowed) || addsShadows);
            EXPECT_EQ(settingChangesContent(mixed, setting), always(mixed) || addsShadows);
            EXPECT_EQ(settingChangesContent(shadowed, setting), always(shadowed));
        }
}

// No preset sets a knob that changes the content, whatever the scene's shadows: a preset is the scene
// drawn faster or more exactly. Catches: `--textures off` (or shadows) put into the fast or best preset,
// the default preset switching a scene's own textures or reflection model back to the defaults.
TEST(TradeContent, NoPresetChangesTheContent) {
    Scene shadowed = defaultKnobScene();
    shadowed.lights.emplace_back();
    shadowed.lights.back().shadows = ShadowMethod::Map;
    // A scene whose textures are off and whose reflection model is Phong: the default preset must not
    // turn them back to the defaults.
    Scene ownLook = defaultKnobScene();
    for (const char* name : {"textures", "reflection"}) {
        const Knob& knob = knobNamed(name);
        for (const std::string& value : knob.values)
            if (value != knob.defaultValue) sceneKnobNamed(name)->set(ownLook, value);
    }
    ASSERT_NE(knobNamed("textures").valueIn(ownLook), knobNamed("textures").defaultValue);
    for (const Scene& scene : {defaultKnobScene(), shadowed, ownLook})
        for (const std::string& preset : kPresetNames) {
            SCOPED_TRACE(preset);
            EXPECT_FALSE(settingChangesContent(scene, presetSetting(preset)));
        }
}

// The trade flags the rows: on spot (textured, no shadows) `--textures off` and `--shadows ray` change
// what is shown; shading does not. Catches: the flag computed but not set on the rows, or such a row on
// the front.
TEST(TradeContent, ContentRowsAreFlaggedAndOffTheFront) {
    const testing_support::TempFolder folder;
    const std::filesystem::path scene = writeScene(
        folder.path(), "spot.json",
        R"({"width": 40, "height": 30, "objects": [{"model": "MODELS/spot/spot_triangulated.obj"}]})");
    const TradeResult result = quickTrade(scene, "shading,shadows,textures", folder.path() / "trade");
    for (const char* label : {"--textures off", "--shadows ray", "--shadows map"}) {
        SCOPED_TRACE(label);
        const TradeRow* row = rowLabelled(result, label);
        ASSERT_NE(row, nullptr);
        EXPECT_TRUE(row->changesContent);
        EXPECT_FALSE(row->pareto);
    }
    for (const TradeRow& row : result.rows)
        if (row.setting.knob == "shading" || row.setting.knob == "preset" || row.setting.knob == "baseline") {
            SCOPED_TRACE(row.setting.label());
            EXPECT_FALSE(row.changesContent);
        }
    EXPECT_FALSE(result.linearToneMapped);  // spot's highlights overshoot 1 by a few percent only
}

// A reference far brighter than 1 (3 where the image has 0): PSNR with a peak of 1 reads 10·log10(1/9)
// = −9.5 dB; after the tone map x/(1+x) the difference is 0.75 and the PSNR 10·log10(1/0.5625) = +2.5
// dB. A reference within 0..2 keeps the plain metrics. Catches: HDR detected from the wrong image or never;
// the tone map not applied to both images; LDR scenes' linear columns changed.
TEST(TradeMetrics, ABrightReferenceIsComparedAfterAToneMap) {
    LinearImage reference{4, 4, std::vector<glm::vec4>(16, glm::vec4(3.0f, 3.0f, 3.0f, 1.0f))};
    LinearImage image{4, 4, std::vector<glm::vec4>(16, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f))};
    EXPECT_LT(measureError(image, reference, kSrgbEncoding, LinearLight::AsIs).linear.psnr, 0.0);
    ASSERT_EQ(linearLightFor(reference), LinearLight::ToneMapped);
    const ImageError mapped = measureError(image, reference, kSrgbEncoding, LinearLight::ToneMapped);
    EXPECT_TRUE(mapped.linearToneMapped);
    EXPECT_NEAR(mapped.linear.psnr, 10.0 * std::log10(1.0 / 0.5625), 1e-4);
    EXPECT_NEAR(mapped.linear.maxAbs, 0.75, 1e-6);
    EXPECT_EQ(linearLightFor(image), LinearLight::AsIs);
    // A highlight's overshoot, up to 2, keeps the plain metrics; above 2 they are tone mapped.
    for (glm::vec4& p : reference.pixels)
        p = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
    reference.pixels[7] = glm::vec4(kPlainLinearPeak, 1.0f, 1.0f, 1.0f);
    EXPECT_EQ(linearLightFor(reference), LinearLight::AsIs);
    reference.pixels[7].b = 2.5f;
    EXPECT_EQ(linearLightFor(reference), LinearLight::ToneMapped);
}

// A sphere glowing with emission 50: the silhouette's pixels differ from the reference by tens, so with a
// peak of 1 the linear PSNR would go negative (the issue's case). Catches: the trade not choosing the
// tone map from its reference, or not saying so in its notes.
TEST(TradeMetrics, AnEmissionAboveOneIsToneMappedAndNoted) {
    const testing_support::TempFolder folder;
    const std::filesystem::path scene = writeScene(folder.path(), "glow.json",
                                                   R"({"width": 40, "height": 30,
                       "objects": [{"model": "MODELS/sphere/sphere-coarse.obj", "material": {"emission": [50, 50, 50]}}]})");
    const TradeResult result = quickTrade(scene, "shading", folder.path() / "trade");
    EXPECT_TRUE(result.linearToneMapped);
    EXPECT_TRUE(anyLineHas(result.notes, "x / (1 + x)"));
    for (const TradeRow& row : result.rows) {
        SCOPED_TRACE(row.setting.label());
        EXPECT_TRUE(row.error.linearToneMapped);
        EXPECT_GE(row.error.linear.psnr, 0.0);
    }
}

}  // namespace
}  // namespace facet
