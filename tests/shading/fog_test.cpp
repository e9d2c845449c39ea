// Fog factors as OpenGL defines them (glFog): hand-computed values at the start, the end and beyond
// for each mode, the two fog distances, and the eight-lane path against the one-lane path.
#include "shading/fog.h"

#include <cmath>

#include <gtest/gtest.h>

namespace facet {
namespace {

FogParams fog(FogMode mode) {
    FogParams f;
    f.mode = mode;
    f.start = 2.0f;
    f.end = 10.0f;
    f.density = 0.25f;
    f.color = vec3(0.5f, 0.6f, 0.7f);
    return f;
}

TEST(Fog, LinearIsOneBeforeStartZeroBeyondEndAndLinearBetween) {
    const FogParams f = fog(FogMode::Linear);
    EXPECT_FLOAT_EQ(fogFactor(f, 0.0f), 1.0f);   // nearer than start: clamped to 1
    EXPECT_FLOAT_EQ(fogFactor(f, 2.0f), 1.0f);   // at start: (10 − 2)/(10 − 2)
    EXPECT_FLOAT_EQ(fogFactor(f, 6.0f), 0.5f);   // halfway
    EXPECT_FLOAT_EQ(fogFactor(f, 8.0f), 0.25f);  // (10 − 8)/8
    EXPECT_FLOAT_EQ(fogFactor(f, 10.0f), 0.0f);  // at end
    EXPECT_FLOAT_EQ(fogFactor(f, 50.0f), 0.0f);  // beyond: clamped to 0
}

TEST(Fog, ExponentialModes) {
    const FogParams e = fog(FogMode::Exponential), e2 = fog(FogMode::ExponentialSquared);
    EXPECT_FLOAT_EQ(fogFactor(e, 0.0f), 1.0f);
    EXPECT_FLOAT_EQ(fogFactor(e2, 0.0f), 1.0f);
    EXPECT_NEAR(fogFactor(e, 4.0f), std::exp(-1.0f), 1e-6f);    // e^(−0.25·4)
    EXPECT_NEAR(fogFactor(e2, 4.0f), std::exp(-1.0f), 1e-6f);   // e^(−(0.25·4)²)
    EXPECT_NEAR(fogFactor(e, 8.0f), std::exp(-2.0f), 1e-6f);    // e^(−2)
    EXPECT_NEAR(fogFactor(e2, 8.0f), std::exp(-4.0f), 1e-6f);   // e^(−(2)²): exp² thickens faster
    EXPECT_NEAR(fogFactor(e2, 2.0f), std::exp(-0.25f), 1e-6f);  // and stays clearer near the eye
    EXPECT_GT(fogFactor(e2, 2.0f), fogFactor(e, 2.0f));
    EXPECT_LT(fogFactor(e, 1e6f), 1e-6f);  // far away: all fog, never negative
    EXPECT_GE(fogFactor(e, 1e6f), 0.0f);
}

TEST(Fog, NoneLeavesTheColourAndTheBlendIsFTimesColourPlusOneMinusFTimesFog) {
    const vec3 c(1.0f, 0.0f, 0.2f);
    EXPECT_EQ((applyFog<float, vec3>(FogParams{}, c, vec3(0.0f, 0.0f, -100.0f))), c);
    // Linear at z = 6: f = 0.5, c = 0.5·(1, 0, 0.2) + 0.5·(0.5, 0.6, 0.7).
    const vec3 fogged = applyFog<float, vec3>(fog(FogMode::Linear), c, vec3(0.0f, 0.0f, -6.0f));
    EXPECT_FLOAT_EQ(fogged.r, 0.75f);
    EXPECT_FLOAT_EQ(fogged.g, 0.3f);
    EXPECT_FLOAT_EQ(fogged.b, 0.45f);
}

// Eye depth is |z_eye|; radial is the distance |P|: at P = (6, 0, −8), 8 and 10.
TEST(Fog, EyeDepthAndRadialDistance) {
    FogParams f = fog(FogMode::Linear);
    const vec3 P(6.0f, 0.0f, -8.0f);
    EXPECT_FLOAT_EQ(fogDistance<float>(f, P), 8.0f);
    f.distance = FogDistance::Radial;
    EXPECT_FLOAT_EQ(fogDistance<float>(f, P), 10.0f);
    EXPECT_FLOAT_EQ(fogFactor(f, fogDistance<float>(f, P)), 0.0f);
}

TEST(Fog, DegenerateLinearRangeIsAWall) {
    FogParams f = fog(FogMode::Linear);
    f.start = f.end = 5.0f;
    EXPECT_EQ(fogFactor(f, 4.9f), 1.0f);
    EXPECT_EQ(fogFactor(f, 5.0f), 0.0f);
}

TEST(Fog, EightLanesMatchOne) {
    for (FogMode mode : {FogMode::Linear, FogMode::Exponential, FogMode::ExponentialSquared}) {
        for (FogDistance distance : {FogDistance::EyeDepth, FogDistance::Radial}) {
            FogParams f = fog(mode);
            f.distance = distance;
            Vec3x8 P;
            for (int lane = 0; lane < 8; ++lane) {
                P.x[lane] = 0.7f * lane - 2.0f;
                P.y[lane] = 0.3f * lane;
                P.z[lane] = -1.5f * lane - 0.5f;
            }
            constexpr MathPrecision kFast = MathPrecision::Fast;
            const Vec3x8 color(vec3(0.9f, 0.1f, 0.4f));
            const Vec3x8 wide = applyFog<Float8, Vec3x8, kFast>(f, color, P);
            const Vec3x8 wideExact = applyFog<Float8, Vec3x8>(f, color, P);
            for (int lane = 0; lane < 8; ++lane) {
                const vec3 Pi(P.x[lane], P.y[lane], P.z[lane]);
                const vec3 one = applyFog<float, vec3>(f, vec3(0.9f, 0.1f, 0.4f), Pi);
                const vec3 oneFast = applyFog<float, vec3, kFast>(f, vec3(0.9f, 0.1f, 0.4f), Pi);
                // Each precision gives the same bits in one lane and in eight.
                EXPECT_EQ(vec3(wideExact.x[lane], wideExact.y[lane], wideExact.z[lane]), one);
                EXPECT_EQ(vec3(wide.x[lane], wide.y[lane], wide.z[lane]), oneFast);
                // The fast exponential is near the exact one.
                EXPECT_NEAR(wide.x[lane], one.r, 2e-6f);
                EXPECT_NEAR(wide.y[lane], one.g, 2e-6f);
                EXPECT_NEAR(wide.z[lane], one.b, 2e-6f);
            }
        }
    }
}

// ---- Height fog --------------------------------------------------------------------------------------

// τ by the midpoint rule in double with many steps, straight from the definition ρ(h) = a·e^(−b(h − h0))
// along the segment from the eye (height yEye) to the point P (eye space, up = +y).
double numericalDepth(double a, double b, double h0, double yEye, glm::dvec3 P, int steps = 200000) {
    const double length = glm::length(P);
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double s = (i + 0.5) / steps;
        const double h = yEye + s * P.y;
        sum += a * std::exp(-b * (h - h0));
    }
    return sum * length / steps;
}

FogParams heightFog(float a, float b, float h0, float yEye) {
    FogParams f;
    f.mode = FogMode::Height;
    f.density = a;
    f.falloff = b;
    f.baseHeight = h0;
    f.eyeHeight = yEye;
    f.up = vec3(0, 1, 0);
    return f;
}

TEST(HeightFog, ClosedFormMatchesNumericalIntegration) {
    struct Case {
        float a, b, h0, yEye;
        glm::dvec3 P;
    };
    const Case cases[] = {
        {0.3f, 0.5f, 0.0f, 2.0f, {3, -1, -10}},      // gently down
        {0.3f, 0.5f, 0.0f, 2.0f, {0, -1.9, -0.5}},   // steep down, nearly to the base
        {0.3f, 0.5f, 0.0f, 2.0f, {1, 12, -3}},       // steep up, into thin fog
        {0.1f, 2.0f, 1.0f, 0.5f, {-4, 0.3, -8}},     // from below the base, slightly up
        {0.2f, 0.05f, 0.0f, 0.0f, {0, -20, -40}},    // weak falloff, long ray
        {0.2f, 0.8f, -1.0f, 3.0f, {5, 0.001, -30}},  // all but horizontal
    };
    for (const Case& c : cases) {
        const FogParams f = heightFog(c.a, c.b, c.h0, c.yEye);
        const double expected = numericalDepth(c.a, c.b, c.h0, c.yEye, c.P);
        const double closed = heightFogDepth<double>(f, c.P);
        EXPECT_NEAR(closed, expected, 1e-6 * std::max(1.0, expected))
            << c.P.x << " " << c.P.y << " " << c.P.z;
        // Float lanes: within float's rounding.
        const float inFloat = heightFogDepth<float>(f, vec3(c.P));
        EXPECT_NEAR(inFloat, expected, 2e-5 * std::max(1.0, expected));
        // The fog factor is e^(−τ).
        EXPECT_NEAR(fogFactorAt<double>(f, c.P), std::exp(-expected), 1e-6);
    }
}

TEST(HeightFog, HorizontalRayIsTheLimitWithoutCancellation) {
    // Δy = 0: τ = a·e^(−b(y_e − h0))·d exactly.
    const FogParams f = heightFog(0.25f, 0.7f, 0.5f, 1.5f);
    const double b = double(0.7f);
    const double limit = 0.25 * std::exp(-b * (1.5 - 0.5)) * 10.0;
    // (the factor a·e^(−b(y_e − h0)) is a per-draw constant computed in float)
    EXPECT_NEAR(heightFogDepth<double>(f, glm::dvec3(0, 0, -10)), limit, 2e-7 * limit);
    EXPECT_NEAR(heightFogDepth<float>(f, vec3(6, 0, -8)), limit, 1e-6 * limit);
    // Nearly horizontal, both sides of zero: continuous and close to the limit in float, where
    // (1 − e^(−x))/x computed directly would lose most of its digits.
    for (const float dy : {1e-7f, -1e-7f, 1e-5f, -1e-5f, 1e-3f, -1e-3f}) {
        const glm::dvec3 P(0, dy, -10);
        const double expected = numericalDepth(0.25, b, 0.5, 1.5, P, 1000);
        EXPECT_NEAR(heightFogDepth<float>(f, vec3(P)), expected, 2e-6 * expected) << dy;
    }
    // Either side of the series' edge (|b·Δy| = 0.1) the two forms agree.
    const float below = heightFogDepth<float>(f, vec3(0, 0.0999f / 0.7f, -10));
    const float above = heightFogDepth<float>(f, vec3(0, 0.1001f / 0.7f, -10));
    EXPECT_NEAR(below, above, 1e-4f * below);
}

TEST(HeightFog, ExtremeRaysStayFinite) {
    const FogParams f = heightFog(1.0f, 5.0f, 0.0f, 0.0f);
    // Far down into dense fog: τ huge, f = 0, never NaN.
    const float down = fogFactorAt<float>(f, vec3(0, -1000, -1));
    EXPECT_EQ(down, 0.0f);
    // Far up: almost nothing.
    EXPECT_GT(fogFactorAt<float>(f, vec3(0, 1000, -1)), 0.8f);
    // The eye: no fog.
    EXPECT_EQ(fogFactorAt<float>(f, vec3(0.0f)), 1.0f);
}

TEST(HeightFog, EightLanesMatchOneLane) {
    const FogParams f = heightFog(0.3f, 0.6f, 0.2f, 1.0f);
    Vec3x8 P;
    vec3 p[8];
    for (int i = 0; i < 8; ++i) {
        p[i] = vec3(0.5f * i - 2.0f, 0.4f * i - 1.5f, -3.0f - 2.0f * i);
        P.x[i] = p[i].x, P.y[i] = p[i].y, P.z[i] = p[i].z;
    }
    const Float8 wide = fogFactorAt<Float8>(f, P);
    for (int i = 0; i < 8; ++i)
        EXPECT_EQ(fogFactorAt<float>(f, p[i]), wide[i]) << i;
}

TEST(HeightFog, UpDirectionOtherThanY) {
    // The same fog about +z: a point displaced along z sees what a point along y does about +y.
    FogParams f = heightFog(0.3f, 0.5f, 0.0f, 2.0f);
    const double alongY = heightFogDepth<double>(f, glm::dvec3(1, -1, -4));
    f.up = vec3(0, 0, 1);
    EXPECT_NEAR(heightFogDepth<double>(f, glm::dvec3(1, -4, -1)), alongY, 1e-6);
}

}  // namespace
}  // namespace facet
