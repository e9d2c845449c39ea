// The equirectangular environment map (shading/environment.h) against formulas written here: the six
// axis directions at the texels they must land on, the round trip direction → uv → direction, the
// lookup's bilinear read, and the mirror reflection's vector and Fresnel weight.
#include "shading/environment.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace facet {
namespace {

using std::numbers::pi;

// A map of 8×4 texels, each its own colour: red = column/8, green = row/4 (row 0 at the top), as codes
// read linearly (code/255).
Texture indexMap() {
    Texture t;
    t.width = 8;
    t.height = 4;
    for (int row = 0; row < 4; ++row)
        for (int column = 0; column < 8; ++column)
            t.texels.push_back(vec4(float(column) / 8.0f, float(row) / 4.0f, 0.5f, 1.0f));
    return t;
}

TEST(Environment, AxisDirectionsLandWhereTheMappingPutsThem) {
    // Independent statement: longitude 0 (the map's centre column) is −z, +x a quarter turn to the
    // right (u = 3/4), −x to the left (u = 1/4), +z the seam (u = 0 or 1); up the top row (v = 1),
    // down the bottom (v = 0), the horizon the middle (v = ½).
    const auto uv = [](double x, double y, double z) { return equirectUv<double>(glm::dvec3(x, y, z)); };
    EXPECT_NEAR(uv(0, 0, -1).x, 0.5, 1e-12);
    EXPECT_NEAR(uv(0, 0, -1).y, 0.5, 1e-12);
    EXPECT_NEAR(uv(1, 0, 0).x, 0.75, 1e-12);
    EXPECT_NEAR(uv(-1, 0, 0).x, 0.25, 1e-12);
    const double seam = uv(0, 0, 1).x;
    EXPECT_TRUE(std::abs(seam) < 1e-12 || std::abs(seam - 1.0) < 1e-12) << seam;
    EXPECT_NEAR(uv(0, 1, 0).y, 1.0, 1e-12);
    EXPECT_NEAR(uv(0, -1, 0).y, 0.0, 1e-12);
    EXPECT_NEAR(uv(1, 0, 0).y, 0.5, 1e-12);
    // Length does not matter.
    EXPECT_NEAR(uv(0, 0, -7).x, 0.5, 1e-12);
    EXPECT_NEAR(uv(3, 3, 0).y, 0.75, 1e-12);  // 45° up: v = ½ + (π/4)/π
}

TEST(Environment, AxisDirectionsReadTheirTexels) {
    const Texture map = indexMap();
    EnvironmentParams env;
    env.map = &map;
    // −z at u = ½, v = ½: between columns 3 and 4 and rows 1 and 2, the four texels' mean.
    const vec3 ahead = environmentColor(env, vec3(0, 0, -1));
    EXPECT_NEAR(ahead.r, 3.5f / 8.0f, 1e-6f);
    EXPECT_NEAR(ahead.g, 1.5f / 4.0f, 1e-6f);
    // +x at u = ¾: between columns 5 and 6.
    EXPECT_NEAR(environmentColor(env, vec3(1, 0, 0)).r, 5.5f / 8.0f, 1e-6f);
    // −x at u = ¼: between columns 1 and 2.
    EXPECT_NEAR(environmentColor(env, vec3(-1, 0, 0)).r, 1.5f / 8.0f, 1e-6f);
    // +z at the seam: columns 7 and 0 wrap, their mean.
    EXPECT_NEAR(environmentColor(env, vec3(0, 0, 1)).r, 3.5f / 8.0f, 1e-6f);
    // Straight up: the top row alone (v is held at the row's centre, never wrapped to the bottom row).
    EXPECT_NEAR(environmentColor(env, vec3(0, 1, 0)).g, 0.0f, 1e-6f);
    // Straight down: the bottom row alone.
    EXPECT_NEAR(environmentColor(env, vec3(0, -1, 0)).g, 3.0f / 4.0f, 1e-6f);
    // The intensity scales the texel.
    env.intensity = 2.0f;
    EXPECT_NEAR(environmentColor(env, vec3(1, 0, 0)).r, 2.0f * 5.5f / 8.0f, 1e-6f);
}

TEST(Environment, RotationAboutUpTurnsTheMap) {
    const Texture map = indexMap();
    EnvironmentParams env;
    env.map = &map;
    // A quarter turn that sends eye direction −z to map direction +x: −z reads what +x read.
    env.mapFromEye = mat3(vec3(0, 0, -1), vec3(0, 1, 0), vec3(1, 0, 0));  // columns: x → −z, z → +x
    ASSERT_NEAR((env.mapFromEye * vec3(0, 0, -1)).x, -1.0f, 1e-6f);
    env.mapFromEye = mat3(vec3(0, 0, 1), vec3(0, 1, 0), vec3(-1, 0, 0));
    ASSERT_NEAR((env.mapFromEye * vec3(0, 0, -1)).x, 1.0f, 1e-6f);
    EXPECT_NEAR(environmentColor(env, vec3(0, 0, -1)).r, 5.5f / 8.0f, 1e-6f);
}

TEST(Environment, RoundTripDirectionUvDirection) {
    for (int i = 0; i < 200; ++i) {
        // Directions spread over the sphere (a spiral), poles excluded (longitude is undefined there).
        const double y = -0.99 + 1.98 * (i + 0.5) / 200.0;
        const double phi = 2.399963 * i;
        const glm::dvec3 d(std::sqrt(1 - y * y) * std::cos(phi), y, std::sqrt(1 - y * y) * std::sin(phi));
        const glm::dvec3 back = equirectDirection<double>(equirectUv<double>(d));
        EXPECT_NEAR(glm::length(back - d), 0.0, 1e-12) << i;
        // And the other way: (u, v) → d → (u, v), from the textbook's spherical coordinates.
        const glm::dvec2 uv((i % 17 + 0.5) / 17.0, (i % 13 + 0.5) / 13.0);
        const double p = 2 * pi * (uv.x - 0.5), t = pi * (uv.y - 0.5);
        const glm::dvec3 expected(std::cos(t) * std::sin(p), std::sin(t), -std::cos(t) * std::cos(p));
        EXPECT_NEAR(glm::length(equirectDirection<double>(uv) - expected), 0.0, 1e-12);
        EXPECT_NEAR(glm::length(equirectUv<double>(expected) - uv), 0.0, 1e-12);
    }
}

// A constant white map: the reflection term is then the weight itself.
Texture whiteMap() {
    Texture t;
    t.width = 4;
    t.height = 2;
    t.texels.assign(8, vec4(1.0f));
    return t;
}

TEST(Environment, MirrorVectorAndSchlickWeight) {
    const Texture map = whiteMap();
    EnvironmentParams env;
    env.map = &map;
    // A surface at P = (0, 0, −5) tilted 60° from the view: N·V = cos 60° = ½.
    const glm::dvec3 P(0, 0, -5);
    const glm::dvec3 N(std::sin(pi / 3), 0, std::cos(pi / 3));
    const vec3 f0(0.04f);
    EnvironmentRecord record;
    const glm::dvec3 term = environmentReflection<double>(env, P, N, true, &f0, vec3(0.0f), 1u, &record);
    // Schlick by hand: F = F0 + (1 − F0)(1 − ½)^5.
    const double F = 0.04 + 0.96 * std::pow(0.5, 5);
    EXPECT_NEAR(term.x, F, 1e-6);
    EXPECT_NEAR(record.NdotV, 0.5, 1e-6);
    // R = 2(N·V)N − V with V = (0, 0, 1): (2·½·sin 60°, 0, 2·½·cos 60° − 1).
    EXPECT_NEAR(record.R.x, std::sin(pi / 3), 1e-6);
    EXPECT_NEAR(record.R.z, std::cos(pi / 3) - 1.0, 1e-6);
    // The standard equation's weight is m_specular as given.
    const glm::dvec3 standard =
        environmentReflection<double>(env, P, N, true, nullptr, vec3(0.3f, 0.2f, 0.1f), 1u);
    EXPECT_NEAR(standard.x, 0.3, 1e-6);
    EXPECT_NEAR(standard.z, 0.1, 1e-6);
}

TEST(Environment, FresnelWeightGrowsTowardTheSilhouette) {
    const Texture map = whiteMap();
    EnvironmentParams env;
    env.map = &map;
    const vec3 f0(0.04f);
    double previous = 0.0;
    for (int k = 0; k <= 8; ++k) {
        const double angle = (pi / 2) * k / 9.0;  // from head-on towards grazing
        const glm::dvec3 N(std::sin(angle), 0, std::cos(angle));
        const double w =
            environmentReflection<double>(env, glm::dvec3(0, 0, -5), N, true, &f0, vec3(0.0f), 1u).x;
        EXPECT_GT(w, previous) << angle;
        previous = w;
    }
    EXPECT_NEAR(environmentReflection<double>(env, glm::dvec3(0, 0, -5), glm::dvec3(0, 0, 1), true, &f0,
                                              vec3(0.0f), 1u)
                    .x,
                0.04, 1e-6);  // head-on: F0
    // At 80°, Schlick by hand: 0.04 + 0.96·(1 − cos 80°)^5.
    EXPECT_NEAR(previous, 0.04 + 0.96 * std::pow(1.0 - std::cos(pi * 4.0 / 9.0), 5), 1e-6);
}

TEST(Environment, EightLanesMatchOneLane) {
    const Texture map = indexMap();
    EnvironmentParams env;
    env.map = &map;
    const vec3 f0(0.5f, 0.3f, 0.1f);
    Vec3x8 P, N;
    vec3 p[8], n[8];
    for (int i = 0; i < 8; ++i) {
        p[i] = vec3(0.3f * i - 1.0f, 0.2f * i - 0.5f, -4.0f - i);
        n[i] = glm::normalize(vec3(std::sin(0.7f * i), std::cos(1.3f * i), 0.5f + 0.1f * i));
        P.x[i] = p[i].x, P.y[i] = p[i].y, P.z[i] = p[i].z;
        N.x[i] = n[i].x, N.y[i] = n[i].y, N.z[i] = n[i].z;
    }
    const Vec3x8 wide = environmentReflection<Float8>(env, P, N, true, &f0, vec3(0.0f), 0xffu);
    for (int i = 0; i < 8; ++i) {
        const vec3 one = environmentReflection<float>(env, p[i], n[i], true, &f0, vec3(0.0f), 1u);
        EXPECT_EQ(one.x, wide.x[i]) << i;
        EXPECT_EQ(one.y, wide.y[i]) << i;
        EXPECT_EQ(one.z, wide.z[i]) << i;
    }
}

}  // namespace
}  // namespace facet
