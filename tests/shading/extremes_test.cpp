// The lighting and fog formulas at their numerical extremes — shininess 0 and 10⁴, roughness 0,
// grazing light and view, zero and NaN normals, fog density 0 and 10⁶ — each against the same formula
// in double, with the tolerance stated and derived. None may give NaN or Inf.
#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "shading/fog.h"
#include "shading/lighting.h"

namespace facet {
namespace {

bool finite(const vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

LightParams directionalLight(vec3 direction) {
    LightParams light;
    light.kind = LightKind::Directional;
    light.direction = direction;
    light.diffuse = vec3(1.0f);
    light.specular = vec3(1.0f);
    return light;
}

// Blinn-Phong and Phong with n = 0 and n = 10⁴ over a sweep of light directions near the mirror one.
// n = 0: max(cos, 0)^0 = 1 wherever the light reaches (N·L > 0), as OpenGL's pow(0, 0) = 1.
// n = 10⁴: x^n amplifies the relative error of x n times, so a float cosine off by its half ulp
// (2^-24) moves the result by n·2^-24 ≈ 6e-4 relative: the tolerance is 4·n·2^-24 relative on top
// of 1e-6 absolute. Exact pow is checked against that; the 8-lane approximation (exp2 ∘ n·log2,
// about 1e-7 absolute error in log2) with the same allowance doubled.
TEST(LightingExtremes, ShininessZeroAndTenThousandAgreeWithDouble) {
    const vec3 eye(0.0f, 0.0f, 0.0f);
    const glm::dvec3 P(0.0, 0.0, -3.0), N(0.0, 0.0, 1.0);
    for (float n : {0.0f, 1e4f})
        for (SpecularModel model : {SpecularModel::BlinnPhong, SpecularModel::Phong})
            for (int step = 0; step <= 40; ++step) {
                const double angle = 0.002 * step;  // radians off the mirror direction
                const LightParams light =
                    directionalLight(vec3(glm::dvec3(std::sin(angle), 0.0, -std::cos(angle))));
                PhongMaterial m;
                m.specular = vec3(1.0f);
                m.shininess = n;
                const std::span<const LightParams> lights(&light, 1);
                const auto d = standardLighting<double, glm::dvec3, MathPrecision::Exact>(
                    P, N, eye, m, vec3(0.0f), lights, model);
                const auto exact = standardLighting<float, vec3, MathPrecision::Exact>(
                    vec3(P), vec3(N), eye, m, vec3(0.0f), lights, model);
                const auto fast = standardLighting<float, vec3, MathPrecision::Fast>(
                    vec3(P), vec3(N), eye, m, vec3(0.0f), lights, model);
                SCOPED_TRACE(::testing::Message() << "n " << n << " angle " << angle);
                ASSERT_TRUE(finite(exact.specular) && finite(fast.specular));
                if (n == 0.0f) {
                    EXPECT_EQ(exact.specular.x, 1.0f);
                    EXPECT_EQ(fast.specular.x, 1.0f);
                }
                const double allowance = 4.0 * n * 0x1p-24 * d.specular.x + 1e-6;
                EXPECT_NEAR(exact.specular.x, d.specular.x, allowance);
                EXPECT_NEAR(fast.specular.x, d.specular.x, 2.0 * allowance);
            }
}

// Roughness 0 (a mirror): α is clamped to 1e-3 (alphaFromRoughness), so D's peak is 1/(π α²) ≈ 3.2e5,
// finite. Both distributions are evaluated from the same cosines in float and in double; the
// tolerance is 1e-5 relative. This needs the well-conditioned form of the denominators:
// GGX's c²(α² − 1) + 1 written as c²α² + (1 − c)(1 + c), Beckmann's c² − 1 as −(1 − c)(1 + c). Near the
// peak c² − 1 cancels to the size of α² = 1e-6, where float's rounding of c² (6e-8) is already a 6%
// error of D; 1 − c is exact in float (Sterbenz), so the rewritten forms keep full precision.
TEST(LightingExtremes, RoughnessZeroGivesAFiniteMirrorPeakInBothDistributions) {
    const float alpha = alphaFromRoughness(0.0f);
    EXPECT_GT(alpha, 0.0f);
    for (int step = 0; step <= 60; ++step) {
        // Cosines from 1 down to about 0.9999 (the peak, where α² = 1e-6 matters), then coarser.
        const float c = step <= 40 ? 1.0f - 0x1p-24f * static_cast<float>(step * step * step)
                                   : std::cos(0.01f * static_cast<float>(step - 40));
        const double cd = c;
        const double a2 = double(alpha) * double(alpha);
        const double ggx = a2 / (std::numbers::pi * std::pow(cd * cd * a2 + (1.0 - cd) * (1.0 + cd), 2.0));
        const double beckmann =
            std::exp(-(1.0 - cd) * (1.0 + cd) / (a2 * cd * cd)) / (std::numbers::pi * a2 * cd * cd * cd * cd);
        const float ggxFloat = distributionGGX<float>(c, alpha);
        const float beckmannFloat = distributionBeckmann<float, MathPrecision::Exact>(c, alpha);
        SCOPED_TRACE(::testing::Message() << "cos " << c);
        ASSERT_TRUE(std::isfinite(ggxFloat) && std::isfinite(beckmannFloat));
        EXPECT_NEAR(ggxFloat, ggx, 1e-5 * ggx + 1e-30);
        EXPECT_NEAR(beckmannFloat, beckmann, 1e-5 * beckmann + 1e-30);
    }
    // The whole Cook-Torrance term at the mirror direction, roughness 0: finite, and the float and
    // double evaluations agree (1e-4 relative: D ≈ 3e5 times Fresnel and G, each a few ulps).
    PbrMaterial m;
    m.roughness = 0.0f;
    const LightParams light = directionalLight(vec3(0.0f, 0.0f, -1.0f));
    const std::span<const LightParams> lights(&light, 1);
    for (NormalDistribution distribution : {NormalDistribution::GGX, NormalDistribution::Beckmann}) {
        const BrdfModel model{distribution, FresnelModel::Exact, GeometryTerm::SmithGGX};
        const auto d = physicallyBasedTerms<double, glm::dvec3, MathPrecision::Exact>(
            glm::dvec3(0, 0, -2), glm::dvec3(0, 0, 1), vec3(0.0f), m, glm::dvec3(m.baseColor), vec3(0.0f),
            vec3(0.0f), lights, model);
        const auto f = physicallyBasedTerms<float, vec3, MathPrecision::Exact>(
            vec3(0, 0, -2), vec3(0, 0, 1), vec3(0.0f), m, m.baseColor, vec3(0.0f), vec3(0.0f), lights, model);
        ASSERT_TRUE(finite(f.specular));
        EXPECT_GT(f.specular.x, 1e3f);
        EXPECT_NEAR(f.specular.x, d.specular.x, 1e-4 * d.specular.x);
    }
}

// Light and view at grazing angles — N·L and N·V of 1e-7 and exactly 0, from both sides — give finite,
// non-negative terms that agree with double to 1e-6 absolute (every term is at most about 1 here).
TEST(LightingExtremes, GrazingLightAndViewStayFiniteAndNonNegative) {
    for (double grazing : {0.0, 1e-7, -1e-7, 1e-4}) {
        for (bool grazingView : {false, true}) {
            const glm::dvec3 N(0.0, 1.0, 0.0), P(0.0, 0.0, 0.0);
            const glm::dvec3 lightDir = grazingView ? glm::normalize(glm::dvec3(0.3, -1.0, 0.2))
                                                    : glm::normalize(glm::dvec3(1.0, -grazing, 0.0));
            const vec3 eye =
                grazingView ? vec3(glm::dvec3(-5.0, 5.0 * grazing, 0.0)) : vec3(0.0f, 3.0f, 1.0f);
            const LightParams light = directionalLight(vec3(lightDir));
            const std::span<const LightParams> lights(&light, 1);
            PhongMaterial m;
            m.specular = vec3(0.5f);
            m.shininess = 20.0f;
            const auto d =
                standardLighting<double, glm::dvec3, MathPrecision::Exact>(P, N, eye, m, vec3(0.1f), lights);
            const auto f = standardLighting<float, vec3, MathPrecision::Fast>(vec3(P), vec3(N), eye, m,
                                                                              vec3(0.1f), lights);
            PbrMaterial pbr;
            pbr.roughness = 0.2f;
            const auto cook = physicallyBasedTerms<float, vec3, MathPrecision::Fast>(
                vec3(P), vec3(N), eye, pbr, pbr.baseColor, vec3(0.0f), vec3(0.0f), lights);
            SCOPED_TRACE(::testing::Message() << "grazing " << grazing << (grazingView ? " view" : " light"));
            for (const vec3& term : {f.diffuse, f.specular, cook.diffuse, cook.specular}) {
                ASSERT_TRUE(finite(term));
                EXPECT_GE(glm::min(term.x, glm::min(term.y, term.z)), 0.0f);
            }
            EXPECT_NEAR(f.diffuse.x, d.diffuse.x, 1e-6);
            EXPECT_NEAR(f.specular.x, d.specular.x, 1e-6);
        }
    }
}

// A zero-length normal and a NaN normal (a degenerate triangle's, a broken file's) light the point
// with finite colours, never NaN: the image shows a wrong shade, not a hole that blending spreads.
TEST(LightingExtremes, ZeroAndNaNNormalsGiveFiniteColours) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const LightParams light = directionalLight(vec3(-0.3f, -1.0f, -0.2f));
    const std::span<const LightParams> lights(&light, 1);
    PhongMaterial m;
    m.specular = vec3(0.5f);
    PbrMaterial pbr;
    for (const vec3& normal : {vec3(0.0f), vec3(nan), vec3(0.0f, nan, 1.0f), vec3(1e-30f, 0.0f, 0.0f)}) {
        SCOPED_TRACE(::testing::Message() << normal.x << "," << normal.y << "," << normal.z);
        const auto phong = standardLighting<float, vec3, MathPrecision::Fast>(
            vec3(0.0f, 0.0f, -2.0f), normal, vec3(0.0f), m, vec3(0.1f), lights);
        const auto cook = physicallyBasedTerms<float, vec3, MathPrecision::Fast>(
            vec3(0.0f, 0.0f, -2.0f), normal, vec3(0.0f), pbr, pbr.baseColor, vec3(0.0f), vec3(0.1f), lights);
        for (const vec3& term : {phong.ambient, phong.diffuse, phong.specular, cook.diffuse, cook.specular})
            EXPECT_TRUE(finite(term));
    }
}

// Fog of density 0 leaves the colour exactly as it was (f = e^0 = 1); density 10⁶ gives exactly the
// fog colour at any distance beyond 1e-3 (f = e^-1000 underflows to 0), in float and in double, under
// both exponential modes, with either precision of exp; in between, float agrees with double to 1e-6.
TEST(FogExtremes, DensityZeroAndAMillion) {
    const vec3 color(0.9f, 0.2f, 0.4f);
    for (FogMode mode : {FogMode::Exponential, FogMode::ExponentialSquared}) {
        FogParams fog;
        fog.mode = mode;
        fog.color = vec3(0.5f, 0.6f, 0.7f);
        for (float distance : {1e-3f, 1.0f, 1e3f, 1e30f}) {
            const vec3 P(0.0f, 0.0f, -distance);
            SCOPED_TRACE(::testing::Message() << "distance " << distance);
            fog.density = 0.0f;
            EXPECT_EQ((applyFog<float, vec3, MathPrecision::Fast>(fog, color, P)), color);
            EXPECT_EQ((applyFog<float, vec3, MathPrecision::Exact>(fog, color, P)), color);
            fog.density = 1e6f;
            EXPECT_EQ((applyFog<float, vec3, MathPrecision::Fast>(fog, color, P)), fog.color);
            EXPECT_EQ((applyFog<float, vec3, MathPrecision::Exact>(fog, color, P)), fog.color);
            fog.density = 0.7f;
            const glm::dvec3 d =
                applyFog<double, glm::dvec3, MathPrecision::Exact>(fog, glm::dvec3(color), glm::dvec3(P));
            const vec3 f = applyFog<float, vec3, MathPrecision::Fast>(fog, color, P);
            ASSERT_TRUE(finite(f));
            EXPECT_NEAR(f.x, d.x, 1e-6);
        }
    }
}

}  // namespace
}  // namespace facet
