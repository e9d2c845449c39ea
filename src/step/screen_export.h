// One screen of the step mode, or the whole walk, for a slide or a handout (facet step --screen NAME
// --format text|markdown|latex): the screen as --print shows it, as Markdown, or as a LaTeX fragment
// for a Beamer frame with its formulas typeset in math mode.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "step/screens.h"

namespace facet::step {

enum class ScreenFormat { Text, Markdown, Latex };

// The format's names as --format takes them, in the order of the enum.
inline constexpr std::array<const char*, 3> kScreenFormatNames = {"text", "markdown", "latex"};

// The format named `name` (one of kScreenFormatNames), or none.
std::optional<ScreenFormat> screenFormatNamed(std::string_view name);

// Screen `index` of `walk` in `format`:
//   text: the screen's block of printWalk (its number, title and rules), byte for byte;
//   markdown: the title as a "##" heading; prose lines (those that start at the left margin) joined
//     into paragraphs that a slide tool reflows, and each run of indented lines (the formulas, tables
//     and pictures, which are laid out in columns) in a fenced block, where monospace keeps them aligned;
//   latex: \frametitle{title}, then the prose as text and each formula line in math mode (see
//     latexMath), a matrix as a bmatrix, a table or picture line in monospace.
std::string formatScreen(const Walk& walk, std::size_t index, ScreenFormat format);

// The whole walk in `format`: text is printWalk; markdown the pixel and verdict, then every screen;
// latex one Beamer frame per screen.
std::string formatWalk(const Walk& walk, ScreenFormat format);

// The index of the screen with `id` in `walk`; throws InputError naming the walk's screen ids when
// there is none.
std::size_t screenIndex(const Walk& walk, const std::string& id);

// How LaTeX writes a character the screens print outside ASCII: `math` in math mode, `text` in a
// prose line ("" for $math$). `letter`: a symbol that takes digits after it as a subscript, as the
// screens write λ0 for λ₀.
struct LatexSymbol {
    char32_t character;
    const char* math;
    const char* text = "";
    bool letter = false;
};

// The one table of them.
std::span<const LatexSymbol> latexSymbols();

// A formula line in LaTeX math mode (without the $ signs): symbols by latexSymbols, words of two or
// more letters upright (\text{spec}, \max), a letter followed by digits subscripted (v0 → v_{0}),
// x_word → x_{\text{word}}, a^(b) and a^b → a^{b}, superscript characters → ^{…}, √(x) → \sqrt{x},
// 1e-06 → 1\times 10^{-6}, ‖x‖ → \lVert x\rVert, and LaTeX's special characters escaped. Throws
// InputError for a character outside ASCII that the table lacks.
std::string latexMath(std::string_view formula);

// A prose line as LaTeX text: specials escaped, each word holding a symbol, _ or ^ typeset as $math$.
std::string latexText(std::string_view prose);

}  // namespace facet::step
