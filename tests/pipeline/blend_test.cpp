#include "blend.h"

#include <cmath>

#include <gtest/gtest.h>

namespace facet {
namespace {

TEST(Blend, ReplaceTakesTheSource) {
    EXPECT_EQ(blend(BlendMode::Replace, vec4(0.1f, 0.2f, 0.3f, 0.4f), vec4(1)), vec4(0.1f, 0.2f, 0.3f, 0.4f));
}

TEST(Blend, AdditiveSums) {
    EXPECT_EQ(blend(BlendMode::Additive, vec4(0.25f, 0.5f, 1.0f, 0.5f), vec4(0.5f, 0.25f, 1.0f, 0.5f)),
              vec4(0.75f, 0.75f, 2.0f, 1.0f));
}

TEST(Blend, OverOnHandComputedValues) {
    // c = 0.25·(1, 0, 0) + 0.75·(0, 0, 1) = (0.25, 0, 0.75); α = 0.25 + 0.75·1 = 1.
    const vec4 c = blend(BlendMode::Over, vec4(1, 0, 0, 0.25f), vec4(0, 0, 1, 1));
    EXPECT_FLOAT_EQ(c.r, 0.25f);
    EXPECT_FLOAT_EQ(c.g, 0.0f);
    EXPECT_FLOAT_EQ(c.b, 0.75f);
    EXPECT_FLOAT_EQ(c.a, 1.0f);
    // An opaque source hides the destination; a transparent one leaves it.
    EXPECT_EQ(blend(BlendMode::Over, vec4(0.3f, 0.6f, 0.9f, 1), vec4(1)), vec4(0.3f, 0.6f, 0.9f, 1));
    EXPECT_EQ(blend(BlendMode::Over, vec4(0.3f, 0.6f, 0.9f, 0), vec4(0.5f)), vec4(0.5f));
}

// The gl preset's over is glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA) on all four channels: the
// colour as Porter–Duff's over, α = α_s² + (1 − α_s)·α_d. α_s = 0.5 over α_d = 0.5: 0.25 + 0.25 = 0.5
// (Porter–Duff: 0.5 + 0.25 = 0.75).
TEST(Blend, OverGLSquaresTheSourceAlpha) {
    const vec4 source(1, 0, 0, 0.5f), destination(0, 0, 1, 0.5f);
    const vec4 gl = blend(BlendMode::OverGL, source, destination);
    EXPECT_EQ(vec3(gl), vec3(blend(BlendMode::Over, source, destination)));
    EXPECT_EQ(vec3(gl), vec3(0.5f, 0.0f, 0.5f));
    EXPECT_EQ(gl.a, 0.5f);
    EXPECT_EQ(blend(BlendMode::Over, source, destination).a, 0.75f);
    // An opaque source over anything: α = 1 either way.
    EXPECT_EQ(blend(BlendMode::OverGL, vec4(0.3f, 0.6f, 0.9f, 1), vec4(0.5f, 0.5f, 0.5f, 0)).a, 1.0f);
}

// Premultiplied over gives what straight over gives when the source is premultiplied: c_s·α_s.
TEST(Blend, PremultipliedOverEqualsOverOnPremultipliedColour) {
    const vec4 straight(0.8f, 0.4f, 0.2f, 0.25f), destination(0.1f, 0.5f, 0.9f, 1.0f);
    const vec4 premultiplied(vec3(straight) * straight.a, straight.a);
    const vec4 a = blend(BlendMode::Over, straight, destination);
    const vec4 b = blend(BlendMode::PremultipliedOver, premultiplied, destination);
    EXPECT_FLOAT_EQ(a.r, b.r);
    EXPECT_FLOAT_EQ(a.g, b.g);
    EXPECT_FLOAT_EQ(a.b, b.b);
    EXPECT_FLOAT_EQ(a.a, b.a);
    // c = (0.2, 0.1, 0.05) + 0.75·(0.1, 0.5, 0.9) = (0.275, 0.475, 0.725).
    EXPECT_FLOAT_EQ(b.r, 0.275f);
    EXPECT_FLOAT_EQ(b.g, 0.475f);
    EXPECT_FLOAT_EQ(b.b, 0.725f);
    // Premultiplied colour can add light without covering: α = 0 and c > 0 is a pure glow.
    EXPECT_EQ(blend(BlendMode::PremultipliedOver, vec4(0.2f, 0.2f, 0.2f, 0.0f), vec4(0.5f, 0.5f, 0.5f, 1.0f)),
              vec4(0.7f, 0.7f, 0.7f, 1.0f));
}

// A filter multiplies: c = c_s ⊗ c_d, the destination's coverage unchanged; two filters commute.
TEST(Blend, MultiplyFiltersAndCommutes) {
    const vec4 red(1.0f, 0.25f, 0.5f, 0.3f), blue(0.5f, 0.5f, 1.0f, 0.7f), white(0.8f, 0.8f, 0.8f, 1.0f);
    EXPECT_EQ(blend(BlendMode::Multiply, red, white), vec4(0.8f, 0.2f, 0.4f, 1.0f));
    EXPECT_EQ(blend(BlendMode::Multiply, blue, blend(BlendMode::Multiply, red, white)),
              blend(BlendMode::Multiply, red, blend(BlendMode::Multiply, blue, white)));
    // Over does not commute: the nearer surface (drawn last) dominates.
    const vec4 redOverBlue = blend(BlendMode::Over, red, blend(BlendMode::Over, blue, white));
    const vec4 blueOverRed = blend(BlendMode::Over, blue, blend(BlendMode::Over, red, white));
    EXPECT_GT(std::abs(redOverBlue.b - blueOverRed.b), 0.1f);
}

}  // namespace
}  // namespace facet
