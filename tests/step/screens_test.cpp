#include "step/screens.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace facet::step {
namespace {

TEST(Screens, PrintWalkNumbersEveryScreenUnderItsTitle) {
    Walk walk;
    walk.x = 3;
    walk.y = 4;
    walk.verdict = "the shader computed this colour";
    walk.screens = {{"clip", "Clipping", "no plane cuts it\n"},
                    {"history", "Pixel history", "one triangle\n"}};
    const std::string text = printWalk(walk);
    EXPECT_EQ(text.find("Pixel (3, 4)\nVerdict: the shader computed this colour\n"), 0u);
    EXPECT_NE(text.find("1. Clipping\n"), std::string::npos);
    EXPECT_NE(text.find("2. Pixel history\n" + std::string(80, '=') + "\none triangle\n"), std::string::npos);
    EXPECT_LT(text.find("no plane cuts it"), text.find("one triangle"));
}

TEST(Screens, WrapTextKeepsWordsWholeWithinTheWidth) {
    EXPECT_EQ(wrapText("  one two three four", 12, 4), "  one two\n    three\n    four\n");
    EXPECT_EQ(wrapText("λ₀ λ₁ λ₂", 8, 0), "λ₀ λ₁ λ₂\n");  // columns, not bytes
}

// The safety net: a line over 80 columns is wrapped, its words kept and in order, the rest indented two
// more than it; a line within 80 is left as it is (its spacing too); the wrapped line is recorded, and
// linesTooWide finds it before and nothing after. Catches: the net cutting a line, rewrapping lines
// that fit, or wrapping silently (so that the walking test could not see a screen's long line).
TEST(Screens, FitToColumnsWrapsOnlyTheLinesTooWideAndRecordsThem) {
    std::string longLine = "  c =";
    for (int k = 0; k < 20; ++k)
        longLine += " word" + std::to_string(k);  // 2 + 3 + 20 words of 5 or 6 columns and a space: > 80
    ASSERT_GT(columnsOf(longLine), kScreenColumns);
    const std::string aligned = "  λ0    0.5         λ1    0.25\n";  // fits; its spacing means something
    Walk walk;
    walk.screens = {{"encode", "Encoding", aligned + longLine + "\n" + aligned}};
    EXPECT_EQ(linesTooWide(walk), std::vector<std::string>{"encode: " + longLine});
    fitToColumns(walk);
    EXPECT_EQ(walk.linesWrappedToFit, std::vector<std::string>{"encode: " + longLine});
    EXPECT_TRUE(linesTooWide(walk).empty());
    const std::string& text = walk.screens[0].text;
    EXPECT_EQ(text.substr(0, aligned.size()), aligned);
    EXPECT_EQ(text.substr(text.size() - aligned.size()), aligned);
    const std::string middle = text.substr(aligned.size(), text.size() - 2 * aligned.size());
    EXPECT_EQ(middle, wrapText(longLine, kScreenColumns, 4));
    EXPECT_NE(middle.find('\n'), middle.size() - 1);  // more than one line
}

// A title too wide for --print's numbered heading keeps the words that fit, marked with "…", and the
// whole title opens the screen's text. Catches: a title cut without a mark, or its end lost.
TEST(Screens, FitToColumnsShortensATitleTooWideAndKeepsItWhole) {
    const std::string title =
        "Clipping: left+right+bottom+top+near+far+w cut the triangle, which is then drawn as a fan";
    ASSERT_GT(columnsOf(title), kTitleColumns);
    Walk walk;
    walk.screens = {{"clip", title, "text\n"}};
    fitToColumns(walk);
    const Screen& screen = walk.screens[0];
    EXPECT_LE(columnsOf(screen.title), kTitleColumns);
    EXPECT_TRUE(screen.title.ends_with(" …")) << screen.title;
    EXPECT_EQ(title.find(screen.title.substr(0, screen.title.size() - std::string(" …").size())), 0u);
    EXPECT_EQ(screen.text, wrapText(title, kScreenColumns, 2) + "\ntext\n");
    EXPECT_EQ(walk.linesWrappedToFit.size(), 1u);
}

}  // namespace
}  // namespace facet::step
