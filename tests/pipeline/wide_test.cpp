#include "wide.h"

#include <algorithm>
#include <cmath>
#include <iostream>
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

// Lane i of the four Float8 ends as out[i] = (x_i, y_i, z_i, w_i) (breaks caught: a shuffle index off
// by one, halves swapped between the 128-bit lanes of the transpose).
TEST(Wide, StoreTransposedPutsEachLaneInItsVec4) {
    Vec4x8 v;
    for (int lane = 0; lane < 8; ++lane) {
        v.x[lane] = 10.0f * lane + 1.0f;
        v.y[lane] = 10.0f * lane + 2.0f;
        v.z[lane] = 10.0f * lane + 3.0f;
        v.w[lane] = 10.0f * lane + 4.0f;
    }
    vec4 out[8];
    storeTransposed(v, out);
    for (int lane = 0; lane < 8; ++lane)
        EXPECT_EQ(out[lane],
                  vec4(10.0f * lane + 1.0f, 10.0f * lane + 2.0f, 10.0f * lane + 3.0f, 10.0f * lane + 4.0f))
            << "lane " << lane;
}

// loadTransposed reads eight vec4 back into the lanes storeTransposed wrote them from (breaks caught: a
// shuffle index off by one, the vertices of the two 128-bit halves swapped).
TEST(Wide, LoadTransposedPutsEachVec4InItsLane) {
    vec4 in[8];
    for (int lane = 0; lane < 8; ++lane)
        in[lane] = vec4(10.0f * lane + 1.0f, 10.0f * lane + 2.0f, 10.0f * lane + 3.0f, 10.0f * lane + 4.0f);
    const Vec4x8 v = loadTransposed(in);
    for (int lane = 0; lane < 8; ++lane) {
        EXPECT_EQ(v.x[lane], in[lane].x) << "lane " << lane;
        EXPECT_EQ(v.y[lane], in[lane].y) << "lane " << lane;
        EXPECT_EQ(v.z[lane], in[lane].z) << "lane " << lane;
        EXPECT_EQ(v.w[lane], in[lane].w) << "lane " << lane;
    }
}

// Element (k, j) of the eight rows ends at (j, k), for float and int lanes (breaks caught: any of the
// three rounds' shuffle indices or pairings off).
TEST(Wide, Transpose8x8SwapsRowsAndColumns) {
    Float8 floats[8];
    Int8 ints[8];
    for (int k = 0; k < 8; ++k)
        for (int j = 0; j < 8; ++j) {
            floats[k][j] = static_cast<float>(8 * k + j);
            ints[k][j] = -(8 * k + j);
        }
    transpose8x8(floats);
    transpose8x8(ints);
    for (int k = 0; k < 8; ++k)
        for (int j = 0; j < 8; ++j) {
            EXPECT_EQ(floats[j][k], static_cast<float>(8 * k + j)) << k << ", " << j;
            EXPECT_EQ(ints[j][k], -(8 * k + j)) << k << ", " << j;
        }
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

// Normalization::Fast's 1/√x against the double 1/√x, over every binade of the normal floats (and 64
// mantissas in each): within kFastInverseSqrtError relative, and the eight-lane and one-lane versions
// give the same bits.
constexpr double kFastInverseSqrtError = 1.0 / (1 << 21);

TEST(Wide, FastInverseSqrtIsWithinItsBoundOfTheDoubleOne) {
    double worst = 0.0;
    for (int exponent = -126; exponent <= 127; ++exponent) {
        for (int step = 0; step < 64; step += 8) {
            Float8 x;
            for (int i = 0; i < 8; ++i)
                x[i] = std::ldexp(1.0f + float(step + i) / 64.0f, exponent);
            const Float8 y = fastInverseSqrt(x);
            for (int i = 0; i < 8; ++i) {
                if (!std::isfinite(x[i])) continue;
                const double exact = 1.0 / std::sqrt(double(x[i]));
                const double error = std::abs(double(y[i]) / exact - 1.0);
                worst = std::max(worst, error);
                EXPECT_LE(error, kFastInverseSqrtError) << x[i];
                EXPECT_EQ(fastInverseSqrt(x[i]), y[i]) << x[i];  // one lane, the same bits
            }
        }
    }
    std::cout << "fastInverseSqrt: worst relative error " << worst << " (2^" << std::log2(worst) << ")\n";
}

// safeNormalize under either choice: unit length within the choice's bound for tiny and huge vectors,
// and the zero vector stays zero (no NaN).
TEST(Wide, SafeNormalizeKeepsTinyHugeAndZeroVectorsFinite) {
    const vec3 cases[] = {vec3(1e-15f, 2e-15f, -2e-15f), vec3(3e18f, -4e18f, 0.0f), vec3(0.0f),
                          vec3(1e-20f, 0.0f, 0.0f), vec3(0.3f, -0.2f, 0.9f)};
    for (const vec3& v : cases) {
        for (const vec3 n : {safeNormalize<float, vec3, Normalization::Exact>(v),
                             safeNormalize<float, vec3, Normalization::Fast>(v)}) {
            EXPECT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z)) << v.x;
            if (v == vec3(0.0f)) {
                EXPECT_EQ(n, vec3(0.0f));
                continue;
            }
            if (glm::dot(glm::dvec3(v), glm::dvec3(v)) < 1e-30) continue;  // clamped: shorter than unit
            EXPECT_NEAR(glm::length(glm::dvec3(n)), 1.0, kFastInverseSqrtError + 3e-7) << v.x;
        }
    }
}

}  // namespace
}  // namespace facet
