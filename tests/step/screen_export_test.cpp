// The screens for slides (step/screen_export.h): the LaTeX translation table against every character the
// screens print over walks of the bundled models under many options, the LaTeX's well-formedness, the
// notation's typesetting, and the text and Markdown forms.
#include "step/screen_export.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "render/renderer.h"
#include "step/walk.h"

namespace facet::step {
namespace {

// The code points of `text` outside ASCII.
std::set<char32_t> nonAscii(const std::string& text) {
    std::set<char32_t> found;
    for (std::size_t i = 0; i < text.size();) {
        const auto b = static_cast<unsigned char>(text[i]);
        const int extra = b < 0x80 ? 0 : b < 0xE0 ? 1 : b < 0xF0 ? 2 : 3;
        char32_t c = extra == 0 ? b : extra == 1 ? b & 0x1F : extra == 2 ? b & 0x0F : b & 0x07;
        for (int k = 1; k <= extra && i + k < text.size(); ++k)
            c = (c << 6) | (static_cast<unsigned char>(text[i + k]) & 0x3F);
        if (extra) found.insert(c);
        i += 1 + extra;
    }
    return found;
}

// A walk for every kind of screen the step mode prints: each bundled scene under each shading frequency
// and reflection model with a fog mode, and the cases with screens of their own (a clipped triangle, a
// tie lost to the top-left rule, culling, transparency, reversed depth, trilinear filtering, a power
// curve, a scene given as an OBJ). Small images: the screens' kinds do not depend on the size.
const std::vector<Walk>& walks() {
    static const std::vector<Walk> all = [] {
        const std::filesystem::path models = std::filesystem::path(FACET_SOURCE_DIR) / "models";
        struct Case {
            std::string file;
            std::function<void(Scene&)> change;
            std::optional<std::pair<int, int>> pixel;
            std::optional<std::uint32_t> triangle;
        };
        std::vector<Case> cases;
        auto add = [&](std::string file, std::function<void(Scene&)> change,
                       std::optional<std::pair<int, int>> pixel = std::nullopt,
                       std::optional<std::uint32_t> triangle = std::nullopt) {
            cases.push_back({std::move(file), std::move(change), pixel, triangle});
        };
        // Each scene under the three shading frequencies, each with another reflection model and fog
        // mode, so that every pairing turns up over the scenes.
        int variant = 0;
        for (const char* file :
             {"lighting-scene.json", "fog-and-glass.json", "shadows.json", "glass-fresnel.json",
              "red-sphere.json", "area-light.json", "anisotropic.json", "environment.json",
              "example-scene.json", "gouraud-vertex.json"}) {
            if (!std::filesystem::exists(models / file)) continue;
            for (const ShadingFrequency frequency :
                 {ShadingFrequency::Phong, ShadingFrequency::Gouraud, ShadingFrequency::Flat}) {
                const int v = variant++;
                const ReflectionModel model = std::array{ReflectionModel::Phong, ReflectionModel::BlinnPhong,
                                                         ReflectionModel::CookTorrance}[(v + v / 3) % 3];
                add(file, [=](Scene& scene) {
                    for (ObjectSpec& object : scene.objects) {
                        object.shading = frequency;
                        object.reflection = model;
                    }
                    if (scene.fog.mode == FogMode::None) scene.fog.mode = static_cast<FogMode>(v % 5);
                });
            }
        }
        add("near-plane.json", {}, std::pair(320, 420));
        add("shared-edge.json", {}, std::pair(10, 7), 0u);
        add(
            "intersecting-quads.json", [](Scene& s) { s.transparency.mode = TransparencyMode::Unsorted; },
            std::pair(390, 264));
        add(
            "intersecting-quads.json", [](Scene& s) { s.transparency.mode = TransparencyMode::Exact; },
            std::pair(390, 264));
        add("lighting-scene.json", [](Scene& s) {
            s.pipeline.depth = DepthBufferFormat::ReversedFloat;
            s.textures.filter = TextureFilter::Trilinear;
            s.gamma.encode = TransferCurve::Power;
        });
        add("cube/cube.obj", [](Scene& s) {
            s.camera.eye = vec3(0.0f, 0.0f, 0.2f);
            s.camera.target = vec3(0.0f, 0.0f, -1.0f);
        });
        std::vector<Walk> result;
        DrawContext context(1);
        for (const Case& c : cases) {
            Scene scene = loadSceneOrModel(models / c.file);
            if (!c.pixel) {
                scene.width = 96;
                scene.height = 72;
            }
            if (c.change) c.change(scene);
            const PreparedScene prepared = prepareScene(scene);
            StepRequest request;
            request.pixel = c.pixel;
            request.triangle = c.triangle;
            result.push_back(traceStep(prepared, context, request).walk);
        }
        return result;
    }();
    return all;
}

// Catches: a screen starting to print a symbol (a new Greek letter, an arrow) that the LaTeX export has
// no translation for, which would reach the slide as raw Unicode or stop the export.
TEST(ScreenExport, EverySymbolTheScreensPrintHasALatexTranslation) {
    std::set<char32_t> known;
    for (const LatexSymbol& symbol : latexSymbols())
        known.insert(symbol.character);
    std::map<char32_t, std::string> missing;  // each with a screen that prints it
    std::size_t screens = 0;
    for (const Walk& walk : walks()) {
        for (const Screen& screen : walk.screens) {
            ++screens;
            for (const char32_t c : nonAscii(screen.title + screen.text + walk.verdict))
                if (!known.count(c)) missing.emplace(c, screen.id);
        }
    }
    EXPECT_GT(screens, 400u);  // the walks above did run
    for (const auto& [c, id] : missing)
        ADD_FAILURE() << "U+" << std::hex << std::uppercase << static_cast<unsigned>(c) << " (on the " << id
                      << " screen) has no entry in latexSymbols()";
}

// Catches: LaTeX output that would not compile or not show the screen: a raw Unicode character left, a
// brace group or a math shift ($) left open on a line.
TEST(ScreenExport, LatexOfEveryScreenIsAsciiWithBalancedBracesAndMath) {
    for (const Walk& walk : walks()) {
        for (std::size_t k = 0; k < walk.screens.size(); ++k) {
            const std::string latex = formatScreen(walk, k, ScreenFormat::Latex);
            const std::string& id = walk.screens[k].id;
            ASSERT_TRUE(std::all_of(latex.begin(), latex.end(),
                                    [](char c) { return static_cast<unsigned char>(c) < 0x80; }))
                << id << ":\n"
                << latex;
            std::istringstream lines(latex);
            for (std::string line; std::getline(lines, line);) {
                int depth = 0, shifts = 0;
                for (std::size_t i = 0; i < line.size(); ++i) {
                    if (line[i] == '\\') {  // an escaped character (\{ \$ \\) is not a delimiter
                        ++i;
                        continue;
                    }
                    if (line[i] == '{') ++depth;
                    if (line[i] == '}' && --depth < 0) break;
                    if (line[i] == '$') ++shifts;
                }
                EXPECT_EQ(depth, 0) << id << ": " << line;
                EXPECT_EQ(shifts % 2, 0) << id << ": " << line;
            }
        }
    }
}

// Catches: the screens' notation typeset wrongly: an index not subscripted (λ0), a word in italics, a
// parenthesised exponent left as ^(…), stacked superscripts that LaTeX refuses (x^a^b), a number in e
// notation set as the letter e.
TEST(ScreenExport, LatexMathTypesetsTheScreensNotation) {
    EXPECT_EQ(latexMath("λ0 = 926023680 / 2261523456 = 0.409469"),
              "\\lambda_{0} = 926023680 / 2261523456 = 0.409469");
    EXPECT_EQ(latexMath("att = 1/(c0 + c1·d + c2·d²)"),
              "\\text{att} = 1/(c_{0} + c_{1}\\cdot d + c_{2}\\cdot d^{2})");
    EXPECT_EQ(latexMath("f = e^(−density·z)"), "f = e^{-\\text{density}\\cdot z}");
    EXPECT_EQ(latexMath("N = ((V·M)⁻¹)ᵀ"), "N = ((V\\cdot M)^{-1})^{T}");
    EXPECT_EQ(latexMath("spec = max(R·V, 0)^n = 5.73e-06"),
              "\\text{spec} = \\max(R\\cdot V, 0)^{n} = 5.73\\times 10^{-6}");
    EXPECT_EQ(latexMath("η = (1 + √F0)/(1 − √F0)"), "\\eta = (1 + \\sqrt{F_{0}})/(1 - \\sqrt{F_{0}})");
    EXPECT_EQ(latexMath("F0_dielectric"), "F_{0}{}_{\\text{dielectric}}");
    EXPECT_EQ(latexMath("n̂_f·n̂_own ≥ 0.5"), "\\hat{n}_{f}\\cdot\\hat{n}_{\\text{own}} \\geq 0.5");
    EXPECT_EQ(latexMath("‖Σ w‖ → P_eye.x"), "\\lVert\\sum w\\rVert \\to P_{\\text{eye}}.x");
    EXPECT_EQ(latexMath("λ'_i = ⌊x⌋ × ½"), "\\lambda'_{i} = \\lfloor x\\rfloor \\times \\tfrac{1}{2}");
}

// Catches: one of LaTeX's special characters in a prose line reaching the slide unescaped (a % that
// comments out the rest of the line, a lone & or #), or a symbol in prose left outside math mode.
TEST(ScreenExport, LatexTextEscapesTheSpecialsAndSetsSymbolsAsMath) {
    EXPECT_EQ(
        latexText("50% of #1 & $2 {a} ~b \\ <c>"),
        "50\\% of \\#1 \\& \\$2 \\{a\\} \\textasciitilde{}b \\textbackslash{} \\textless{}c\\textgreater{}");
    EXPECT_EQ(latexText("weights (λ_i, at 80°), then P_eye."),
              "weights ($\\lambda_{i}$, at $80^{\\circ}$), then $P_{\\text{eye}}$.");
}

// Catches: --format text differing from what --print shows for the same screen.
TEST(ScreenExport, TextIsTheScreensBlockOfPrint) {
    const Walk& walk = walks().front();
    const std::string all = printWalk(walk);
    for (std::size_t k = 0; k < walk.screens.size(); ++k) {
        const std::string one = formatScreen(walk, k, ScreenFormat::Text);
        EXPECT_NE(all.find("\n" + one), std::string::npos) << walk.screens[k].id;
        // Appended piece by piece: GCC 12 at -O1 warns falsely (-Warray-bounds) on a chain of + on a
        // temporary string.
        std::string heading(80, '=');
        heading.append("\n").append(std::to_string(k + 1)).append(". ").append(walk.screens[k].title);
        EXPECT_EQ(one.rfind(heading, 0), 0u);
    }
    EXPECT_EQ(formatWalk(walk, ScreenFormat::Text), all);
}

// Catches: Markdown that a slide tool would reflow into one paragraph, collapsing the aligned formula
// lines, or a prose line starting with * turned into a list.
TEST(ScreenExport, MarkdownJoinsProseAndFencesTheIndentedLines) {
    Walk walk;
    walk.screens = {
        {"depth", "Depth test: passed",
         "* marks the one that\nwon, by z_fragment < z_buffer:\n  z_fragment = 0.4\n  z_buffer   = 1\n"
         "\nDone.\n"}};
    EXPECT_EQ(formatScreen(walk, 0, ScreenFormat::Markdown),
              "## Depth test: passed\n\n"
              "\\* marks the one that won, by z\\_fragment \\< z\\_buffer:\n\n"
              "```text\n  z_fragment = 0.4\n  z_buffer   = 1\n```\n\n"
              "Done.\n");
}

// Catches: a --screen name the walk lacks answered with nothing, or with a message that does not say
// which names there are.
TEST(ScreenExport, AnUnknownScreenNamesTheWalksScreens) {
    const Walk& walk = walks().front();
    EXPECT_EQ(screenIndex(walk, walk.screens[1].id), 1u);
    try {
        screenIndex(walk, "clipping");
        FAIL() << "no error";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("--screen clipping"), std::string::npos) << message;
        for (const Screen& screen : walk.screens)
            EXPECT_NE(message.find(screen.id), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos);
    }
}

}  // namespace
}  // namespace facet::step
