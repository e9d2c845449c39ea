// The shading formulas on double lanes (F = double, V3 = dvec3), as the exact reference renderer runs
// them: the same templates as the rasterizer's float ones, computed in double throughout.
#include <cmath>

#include <gtest/gtest.h>

#include "shading/fog.h"
#include "shading/lighting.h"

namespace facet {
namespace {

// A point light at distance d above a surface, off-axis: the Lambert term and Blinn-Phong's power
// evaluated by hand in double. A float anywhere on the way (a double narrowed into a float overload)
// leaves an error near 1e-8; double throughout keeps it near 1e-15.
TEST(DoubleLanes, StandardLightingIsComputedInDouble) {
    LightParams light;
    light.kind = LightKind::Point;
    light.position = vec3(0.3f, 2.0f, 0.1f);
    light.c0 = 0.5f;
    light.c1 = 0.25f;
    light.diffuse = vec3(0.7f);
    light.specular = vec3(0.9f);
    PhongMaterial m;
    m.diffuse = vec3(0.6f);
    m.specular = vec3(0.5f);
    m.shininess = 37.0f;
    const glm::dvec3 P(0.1, 0.0, -0.2), N(0.0, 1.0, 0.0);
    const vec3 eye(0.0f, 1.0f, 3.0f);
    const std::span<const LightParams> lights(&light, 1);
    const LightingTerms<glm::dvec3> t = standardLighting<double, glm::dvec3, MathPrecision::Exact>(
        P, N, eye, m, vec3(0.0f), lights, SpecularModel::BlinnPhong);

    const glm::dvec3 toLight = glm::dvec3(light.position) - P;
    const double d = glm::length(toLight);
    const glm::dvec3 L = toLight / d;
    const double att = 1.0 / (double(light.c0) + double(light.c1) * d);
    const double diffuse = att * L.y * double(m.diffuse.x) * double(light.diffuse.x);
    const glm::dvec3 H = glm::normalize(L + glm::normalize(glm::dvec3(eye) - P));
    const double specular =
        att * std::pow(H.y, double(m.shininess)) * double(m.specular.x) * double(light.specular.x);
    EXPECT_NEAR(t.diffuse.x, diffuse, 1e-14);
    EXPECT_NEAR(t.specular.x, specular, 1e-14);

    // The float instantiation of the same formula agrees to float precision, and no better.
    const LightingTerms<vec3> f = standardLighting<float, vec3, MathPrecision::Exact>(
        vec3(P), vec3(N), eye, m, vec3(0.0f), lights, SpecularModel::BlinnPhong);
    EXPECT_NEAR(f.diffuse.x, diffuse, 1e-6);
    EXPECT_NEAR(f.specular.x, specular, 1e-6);
}

// Cook-Torrance with exact Fresnel and exp² fog run on double lanes too, and agree with float.
TEST(DoubleLanes, PhysicallyBasedTermsAndFogAgreeWithFloat) {
    LightParams light;
    light.kind = LightKind::Directional;
    light.direction = vec3(-0.3f, -1.0f, -0.2f);
    PbrMaterial m;
    m.baseColor = vec3(0.8f, 0.5f, 0.2f);
    m.roughness = 0.35f;
    const BrdfModel model{NormalDistribution::Beckmann, FresnelModel::Exact, GeometryTerm::CookTorrance};
    const std::span<const LightParams> lights(&light, 1);
    const glm::dvec3 P(0.2, 0.1, -3.0), N = glm::normalize(glm::dvec3(0.1, 1.0, 0.3));
    const auto d = physicallyBasedTerms<double, glm::dvec3, MathPrecision::Exact>(
        P, N, vec3(0.0f), m, glm::dvec3(m.baseColor), vec3(0.0f), vec3(0.1f), lights, model);
    const auto f = physicallyBasedTerms<float, vec3, MathPrecision::Exact>(
        vec3(P), vec3(N), vec3(0.0f), m, m.baseColor, vec3(0.0f), vec3(0.1f), lights, model);
    for (int c = 0; c < 3; ++c) {
        EXPECT_GT(d.specular[c], 0.0);
        EXPECT_NEAR(d.specular[c], f.specular[c], 1e-5 * (1.0 + std::abs(d.specular[c])));
        EXPECT_NEAR(d.diffuse[c], f.diffuse[c], 1e-5);
    }
    FogParams fog;
    fog.mode = FogMode::ExponentialSquared;
    fog.density = 0.3f;
    const glm::dvec3 fogged = applyFog<double, glm::dvec3, MathPrecision::Exact>(fog, glm::dvec3(1.0), P);
    const double factor = std::exp(-std::pow(double(fog.density) * 3.0, 2.0));
    EXPECT_NEAR(fogged.x, factor + (1.0 - factor) * double(fog.color.x), 1e-15);
}

}  // namespace
}  // namespace facet
