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

}  // namespace
}  // namespace facet
