#include "step/notation.h"

#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/run_facet.h"
#include "step/screens.h"

namespace facet::step {
namespace {

namespace fs = std::filesystem;

// The code points a symbol is made of: ASCII letters, digits and '_', Greek letters, the prime ′ and
// the combining hat of n̂. Everything else (spaces, ·, ², brackets, the ASCII apostrophe) ends a token.
bool symbolCodePoint(char32_t c) {
    return (c < 0x80 && (std::isalnum(static_cast<int>(c)) || c == '_')) || (c >= 0x370 && c <= 0x3FF) ||
           c == 0x2032 || c == 0x302;
}

// The text cut into tokens of symbol code points (each token as written, in order).
std::vector<std::string> tokensOf(const std::string& text) {
    std::vector<std::string> tokens(1);
    for (std::size_t i = 0; i < text.size();) {
        // One UTF-8 code point.
        const unsigned char lead = static_cast<unsigned char>(text[i]);
        const std::size_t length = lead < 0x80 ? 1 : lead < 0xE0 ? 2 : lead < 0xF0 ? 3 : 4;
        char32_t c = length == 1 ? lead : lead & (0x7F >> length);
        for (std::size_t k = 1; k < length && i + k < text.size(); ++k)
            c = (c << 6) | (static_cast<unsigned char>(text[i + k]) & 0x3F);
        if (symbolCodePoint(c)) {
            tokens.back().append(text, i, length);
        } else if (!tokens.back().empty()) {
            tokens.emplace_back();
        }
        i += length;
    }
    if (tokens.back().empty()) tokens.pop_back();
    return tokens;
}

// The text's tokens that are symbols the notation must explain: those with a Greek letter, and those
// written with one subscript, a base of at most two characters (x_w, F0_dielectric, n̂_own), which
// leaves out file names (spot_triangulated) and OpenGL's constants (GL_SRC_ALPHA).
std::set<std::string> symbolsIn(const std::string& text) {
    std::set<std::string> symbols;
    for (const std::string& token : tokensOf(text)) {
        bool hasGreek = false;  // Greek letters are U+0370 to U+03FF: lead bytes 0xCD to 0xCF
        for (unsigned char c : token)
            hasGreek = hasGreek || (c >= 0xCD && c <= 0xCF);
        const std::size_t underscore = token.find('_');
        const bool subscripted = underscore != std::string::npos && underscore > 0 &&
                                 underscore + 1 < token.size() &&
                                 token.find('_', underscore + 1) == std::string::npos;
        std::size_t base = 0;  // characters before the '_', not counting the hat and the prime
        for (std::size_t i = 0; subscripted && i < underscore; ++i) {
            const unsigned char c = static_cast<unsigned char>(token[i]);
            base += (c & 0xC0) != 0x80 && token.compare(i, 2, "\xCC\x82") != 0 &&
                    token.compare(i, 3, "\xE2\x80\xB2") != 0;
        }
        if (!std::isdigit(static_cast<unsigned char>(token[0])) && (hasGreek || (subscripted && base <= 2)))
            symbols.insert(token);
    }
    return symbols;
}

std::set<std::string> tableForms() {
    std::set<std::string> forms;
    for (const Symbol& s : notation())
        for (std::string_view form : formsOf(s))
            forms.insert(std::string(form));
    return forms;
}

// The tokenizer the walk check relies on: a check that found no symbol would pass on any screen.
// Catches: a tokenizer that misses primes, hats or subscripts, or takes file names for symbols.
TEST(Notation, SymbolsInFindsGreekAndSubscriptedSymbolsOnly) {
    const std::set<std::string> expected = {"λ′0", "n̂_own", "x_w", "F0_dielectric", "α", "ρ", "λ_i"};
    EXPECT_EQ(symbolsIn("a = λ′0·a0 + n̂_own, x_w = 3; F0_dielectric α² and ρ, λ_i/w spot_triangulated.obj "
                        "GL_SRC_ALPHA x"),
              expected);
}

// Catches: one form listed under two meanings (the clash the table exists to prevent), or an empty form.
TEST(Notation, EachFormMeansOneThing) {
    std::set<std::string> seen;
    for (const Symbol& s : notation()) {
        EXPECT_FALSE(s.meaning.empty()) << s.symbol;
        EXPECT_FALSE(s.where.empty()) << s.symbol;
        for (std::string_view form : formsOf(s)) {
            EXPECT_FALSE(form.empty()) << "\"" << s.symbol << "\" has an empty form (two spaces?)";
            EXPECT_TRUE(seen.insert(std::string(form)).second) << form << " is listed twice";
        }
    }
}

// Catches: a meaning or symbol that makes the notation screen wider than the 80 columns of a terminal.
TEST(Notation, TextFitsEightyColumns) {
    std::istringstream lines(notationText());
    std::string line;
    int count = 0;
    while (std::getline(lines, line)) {
        ++count;
        EXPECT_LE(columnsOf(line), 80u) << line;
    }
    EXPECT_GT(count, static_cast<int>(notation().size()));
}

// The table in docs/teaching.md's "Notation" section, row for row: symbol (in backticks), meaning,
// screens.
// Catches: a symbol added, renamed or explained anew in the code and not in the docs, or the reverse.
TEST(Notation, DocsTableListsExactlyTheCodesTable) {
    std::ifstream in(fs::path(FACET_SOURCE_DIR) / "docs/teaching.md");
    ASSERT_TRUE(in) << "docs/teaching.md";
    std::string line;
    while (std::getline(in, line) && line != "## Notation") {
    }
    ASSERT_EQ(line, "## Notation") << "docs/teaching.md has no \"## Notation\" section";
    while (std::getline(in, line) && line != "| Symbol | Meaning | Screens |") {
    }
    ASSERT_TRUE(std::getline(in, line) && line == "|---|---|---|") << line;
    std::vector<std::string> rows;
    while (std::getline(in, line) && line.starts_with("| "))
        rows.push_back(line);
    std::vector<std::string> expected;
    for (const Symbol& s : notation())
        expected.push_back("| `" + std::string(s.symbol) + "` | " + std::string(s.meaning) + " | " +
                           std::string(s.where) + " |");
    EXPECT_EQ(rows, expected);
}

// What the students see in one walk over several models and options: every screen of --print, and
// the web page's stage titles and descriptions (its trace data without the legend itself).
class NotationWalk : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        const std::vector<std::string> runs = {
            "models/red-sphere.json",
            "models/red-sphere.json --pixel 380,180 --shininess 32 --reflection blinn-phong "
            "--blinn-exponent matched --gamma 2.2",
            "models/lighting-scene.json --shading flat",
            "models/lighting-scene.json --shading gouraud",
            "models/near-plane.json --pixel 320,420",
            "models/near-plane.json --pixel 320,420 --depth reversed-float",
            "models/fog-and-glass.json --fog linear",
            "models/intersecting-quads.json --transparency sorted --pixel 390,264",
            "models/fog-and-glass.json --fog height",
            "models/glass-fresnel.json",
            "models/glass-fresnel.json --distribution gaussian",
            "models/area-light.json",
            "models/lighting-scene.json --normals angle",
            "models/anisotropic.json",
            "models/example-scene.json --texture-filter trilinear",
            "models/shadows.json",
            "models/environment.json",
            "models/shared-edge.json",
            "models/gouraud-vertex.json",
        };
        testing_support::TempFolder dir;
        text_ = new std::string;
        for (const std::string& run : runs) {
            const auto result = testing_support::runFacet("step " + run + " --print", dir, FACET_SOURCE_DIR);
            ASSERT_EQ(result.status, 0) << run << ": " << result.err;
            *text_ += result.out;
        }
        const auto page = testing_support::runFacet(
            "step models/lighting-scene.json --width 160 --height 120 --html-step 64 --html '" +
                (dir.path() / "page").string() + "'",
            dir, FACET_SOURCE_DIR);
        ASSERT_EQ(page.status, 0) << page.err;
        // trace-data.js: "window.facetStepTrace = {...};" after a comment line.
        const std::string script = testing_support::readText(dir.path() / "page/trace-data.js");
        const std::size_t begin = script.find('{'), end = script.rfind(';');
        ASSERT_TRUE(begin != std::string::npos && end != std::string::npos && begin < end);
        nlohmann::json data = nlohmann::json::parse(script.substr(begin, end - begin));
        ASSERT_TRUE(data.contains("notation"));
        data.erase("notation");
        for (const auto& stage : data["stages"])
            *text_ +=
                stage["title"].get<std::string>() + "\n" + stage["description"].get<std::string>() + "\n";
    }
    static void TearDownTestSuite() {
        delete text_;
        text_ = nullptr;
    }
    static const std::string& text() { return *text_; }

  private:
    static inline std::string* text_ = nullptr;
};

// Catches: a screen printing a Greek or subscripted symbol the notation does not explain (a new
// symbol, or a second spelling of a quantity that has one already, like μ beside λ′).
TEST_F(NotationWalk, EveryPrintedSymbolIsInTheTable) {
    const std::set<std::string> forms = tableForms();
    for (const std::string& symbol : symbolsIn(text()))
        EXPECT_TRUE(forms.contains(symbol)) << symbol << " is printed but not in the notation";
}

// Catches: a symbol the table explains that no screen prints any more (renamed on the screens only).
TEST_F(NotationWalk, EverySymbolOfTheTableIsPrinted) {
    const std::vector<std::string> tokens = tokensOf(text());
    const std::set<std::string> printed(tokens.begin(), tokens.end());
    for (const Symbol& s : notation()) {
        bool any = false;
        for (std::string_view form : formsOf(s))
            any = any || printed.contains(std::string(form));
        EXPECT_TRUE(any) << "no screen of the walk prints " << s.symbol;
    }
}

// The spellings the notation retired; none may come back.
// Catches: a screen that writes μ for the perspective-correct weights, λ for the texture level, n and
// f for the depth range, n for the specular exponent, or a material's colour by its long name.
TEST_F(NotationWalk, NoRetiredSpellingIsPrinted) {
    const std::vector<std::string> retired = {
        "μ",         "λ'",        "λ = log2",      "z_w = n",     "(f − n)",       "^n",         "4n",
        "m_ambient", "m_diffuse", "m_specular",    "l_ambient",   "l_diffuse",     "l_specular", "N·n_obj",
        "c'",        "α·c_s",     "f = metalness", "f = (1 − F)", "α = roughness", "(R·V)^s",
    };
    for (const std::string& spelling : retired)
        EXPECT_EQ(text().find(spelling), std::string::npos) << "\"" << spelling << "\" is printed";
}

}  // namespace
}  // namespace facet::step
