#include "wide.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace facet {
namespace {

TEST(Wide, Log2AndExp2MatchTheLibrary) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> exponent(-30.0f, 30.0f);
    for (int trial = 0; trial < 2000; ++trial) {
        Float8 x;
        for (int i = 0; i < 8; ++i)
            x[i] = std::exp2(exponent(rng));
        const Float8 l = log2(x);
        const Float8 e = exp2(l);
        for (int i = 0; i < 8; ++i) {
            EXPECT_NEAR(l[i], std::log2(x[i]), 2e-6f) << x[i];
            EXPECT_NEAR(e[i] / x[i], 1.0f, 4e-6f) << x[i];
        }
    }
}

TEST(Wide, PowFollowsGlslAtTheEdges) {
    const Float8 x = {0.0f, 1.0f, 0.5f, 0.25f, 0.999f, 1e-20f, 0.0f, 0.75f};
    const Float8 p = pow(x, 32.0f);
    for (int i = 0; i < 8; ++i)
        EXPECT_NEAR(p[i], std::pow(x[i], 32.0f), 2e-5f * std::pow(x[i], 32.0f) + 1e-30f) << x[i];
    EXPECT_EQ(p[0], 0.0f);  // 0^n = 0 for n > 0
    const Float8 one = pow(x, 0.0f);
    for (int i = 0; i < 8; ++i)
        EXPECT_EQ(one[i], 1.0f);  // x^0 = 1, also for x = 0 (GLSL leaves it undefined)
}

TEST(Wide, VectorHelpersAreLaneWise) {
    const Vec3x8 v(vec3(3, 4, 0));
    const Vec3x8 n = normalize(v);
    for (int i = 0; i < 8; ++i) {
        EXPECT_FLOAT_EQ(n.x[i], 0.6f);
        EXPECT_FLOAT_EQ(n.y[i], 0.8f);
    }
    const Float8 a = {1, -2, 3, -4, 5, -6, 7, -8};
    const Float8 m = max(a, 0.0f);
    const Float8 s = select(a > 0.0f, 1.0f, -1.0f);
    for (int i = 0; i < 8; ++i) {
        EXPECT_EQ(m[i], std::max(a[i], 0.0f));
        EXPECT_EQ(s[i], a[i] > 0 ? 1.0f : -1.0f);
    }
}

}  // namespace
}  // namespace facet
