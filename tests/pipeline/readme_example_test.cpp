// Compiles and runs the shader example of README.md, cut out of the README by tests/CMakeLists.txt.
#include <gtest/gtest.h>

#include "readme_example.h"

namespace {

TEST(ReadmeExample, DrawsTheInterpolatedTriangle) {
    const facet::Framebuffer image = drawGradientTriangle();
    ASSERT_EQ(image.width(), 64);
    // Corners outside the triangle keep the clear colour.
    EXPECT_EQ(image.color(0, 0), facet::vec4(0, 0, 0, 1));
    EXPECT_EQ(image.color(63, 0), facet::vec4(0, 0, 0, 1));
    // Near each corner the colour is that corner's; in the middle the three mix, summing to 1.
    // Window positions: red (−0.8,−0.8) → (6.4, 57.6); green → (57.6, 57.6); blue (0, 0.8) → (32, 6.4).
    EXPECT_GT(image.color(8, 56).r, 0.9f);
    EXPECT_GT(image.color(55, 56).g, 0.9f);
    EXPECT_GT(image.color(32, 8).b, 0.9f);
    const facet::vec4 middle = image.color(32, 40);
    EXPECT_NEAR(middle.r + middle.g + middle.b, 1.0f, 1e-5f);
    EXPECT_GT(middle.r, 0.2f);
    EXPECT_GT(middle.g, 0.2f);
    EXPECT_GT(middle.b, 0.2f);
}

}  // namespace
