#include "step/screens.h"

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

}  // namespace
}  // namespace facet::step
