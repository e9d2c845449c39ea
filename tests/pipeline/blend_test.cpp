#include "blend.h"

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

}  // namespace
}  // namespace facet
