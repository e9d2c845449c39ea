// What the step-through teaching mode (facet step) shows: a Walk, one Screen per stage, in pipeline
// order. The terminal walk pages through the screens, --print writes them all, the web page shows them
// beside the stage images; all three show the same text.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace facet::step {

// One stage's view of the traced triangle or pixel: text of at most 80 columns a line, no colour codes
// (a terminal adds them), readable on a projector and in a handout.
struct Screen {
    std::string id;  // short and stable, like "clip" or "history": `facet step` jumps and the page link by it
    std::string title;  // one line, like "Clipping: the near plane cuts the triangle"
    std::string text;   // the lines, each ending in '\n'
};

// A triangle of the scene as the step mode numbers it: its place among all triangles of the frame's
// draws (PreparedScene::draws in order), and where that is in its draw.
struct TriangleRef {
    std::uint32_t number = 0;    // --triangle N
    std::uint32_t draw = 0;      // index into PreparedScene::draws
    std::uint32_t triangle = 0;  // index of the triangle in its draw (indices / 3)
    friend bool operator==(const TriangleRef&, const TriangleRef&) = default;
};

// Everything one trace shows.
struct Walk {
    int x = 0, y = 0;                     // the traced pixel (window coordinates, y down)
    std::optional<TriangleRef> triangle;  // the traced triangle; none when nothing covers the pixel
    std::string verdict;                  // one line: what happened at the pixel
    std::vector<Screen> screens;          // in pipeline order
    // The traced triangle where the rasterizer met it: after clipping, each piece's three corners in
    // window coordinates (pixels, y down, pixel (x, y) covering x..x+1, y..y+1), snapped as its edge
    // functions used them. Empty when the triangle never reached the rasterizer. The web page outlines
    // the triangle with these edges.
    std::vector<std::array<std::array<double, 2>, 3>> windowPieces;
    // The lines fitToColumns had to wrap, as the screens made them: each a screen's fault (tests
    // expect none), wrapped only so that a user never sees a line over 80 columns.
    std::vector<std::string> linesWrappedToFit;
};

// An image of the whole frame after one stage (facet step --stages DIR), as the web page lists it.
struct StageImage {
    std::string id;           // short and stable, like "depth" or "build-003"
    std::string title;        // one line, like "Depth, linearised from near 0.1 to far 10"
    std::string file;         // the image's file name, relative to the folder it was written to
    std::string description;  // a sentence or two: what the image shows and how to read its colours
};

// `text` as lines of at most `width` columns (words kept whole), each ending in '\n'; the first line
// keeps `text`'s leading spaces, the others start with `indent` spaces.
std::string wrapText(const std::string& text, std::size_t width, std::size_t indent);

// Screen `index` of `walk` under its number, its title and a rule: its block of printWalk.
std::string printScreen(const Walk& walk, std::size_t index);
// The columns a screen's line may take: the README promises 80 (a terminal, a handout, a slide).
inline constexpr std::size_t kScreenColumns = 80;
// A title's: --print writes it after its number ("12. ").
inline constexpr std::size_t kTitleColumns = kScreenColumns - 4;

// The columns a UTF-8 text takes on a terminal: one per code point (the screens' symbols, like · and
// ≤, are one column wide), i.e. every byte that is not a continuation byte 10xxxxxx.
std::size_t columnsOf(std::string_view text);

// The lines of a text, without their '\n' (a last line without one counts; none after a final '\n').
std::vector<std::string_view> linesOf(std::string_view text);
// The same lines as strings of their own, for when the text does not outlive them.
std::vector<std::string> ownedLinesOf(std::string_view text);

// The lines of the walk's screens wider than their columns (texts kScreenColumns, titles
// kTitleColumns), each as "id: line": what the screens made, before any fitting.
std::vector<std::string> linesTooWide(const Walk& walk);

// The walk's safety net: every text line wider than kScreenColumns wrapped (words kept whole, the
// rest indented two more than the line), every title wider than kTitleColumns cut at a word with
// "…"; each such line kept in linesWrappedToFit. A screen should need none of it.
void fitToColumns(Walk& walk);

// The screens one after another, each under a numbered title and a rule: what --print writes.
std::string printWalk(const Walk& walk);

}  // namespace facet::step
