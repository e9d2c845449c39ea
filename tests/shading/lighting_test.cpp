// The lighting formulas: hand-computed light sources and lighting-equation terms, Fresnel against its
// closed forms, the microfacet distributions' normalisation and the Lambert white furnace by numerical
// integration, the eight-lane templates against the one-lane ones, and the material presets.
#include "shading/lighting.h"
#include "expect_near.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace facet {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

using testing_shading::expectVec3Near;

// ---- Light sources ----------------------------------------------------------------------------------

TEST(LightAttenuation, KnownDistances) {
    LightParams light;
    light.kind = LightKind::Point;
    light.c0 = 1.0f;
    light.c1 = 0.5f;
    light.c2 = 0.25f;
    EXPECT_FLOAT_EQ(attenuation(light, 0.0f), 1.0f);          // 1/1
    EXPECT_FLOAT_EQ(attenuation(light, 1.0f), 1.0f / 1.75f);  // 1/(1 + 0.5 + 0.25)
    EXPECT_FLOAT_EQ(attenuation(light, 2.0f), 1.0f / 3.0f);   // 1/(1 + 1 + 1)
    light.kind = LightKind::Directional;
    EXPECT_FLOAT_EQ(attenuation(light, 2.0f), 1.0f);
}

// A spot at the origin shining down −y, and a surface point 5 units away at `degrees` from its axis:
// the spot factor there.
float spotAt(const LightParams& light, float degrees) {
    const float theta = glm::radians(degrees);
    const vec3 position = 5.0f * vec3(std::sin(theta), -std::cos(theta), 0.0f);
    return spotFactor<float>(light, lightVector<float>(light, position).L);
}

LightParams downwardSpot() {
    LightParams light;
    light.kind = LightKind::Spot;
    light.position = vec3(0.0f);
    light.spotDirection = vec3(0.0f, -1.0f, 0.0f);
    light.spotCutoffDegrees = 30.0f;
    return light;
}

TEST(LightSpot, OpenGLConeEdgeWithExponentZero) {
    const LightParams light = downwardSpot();
    EXPECT_FLOAT_EQ(spotAt(light, 0.0f), 1.0f);
    EXPECT_FLOAT_EQ(spotAt(light, 29.9f), 1.0f);  // just inside: cos^0 = 1
    EXPECT_EQ(spotAt(light, 30.1f), 0.0f);        // just outside
    EXPECT_EQ(spotAt(light, 120.0f), 0.0f);
}

TEST(LightSpot, OpenGLConeEdgeWithExponentTwo) {
    LightParams light = downwardSpot();
    light.spotExponent = 2.0f;
    const float c = std::cos(glm::radians(29.9f));        // 0.866897
    EXPECT_NEAR(spotAt(light, 29.9f), c * c, 1e-5f);      // 0.751511
    EXPECT_NEAR(spotAt(light, 10.0f), 0.969846f, 1e-5f);  // cos²10°
    EXPECT_EQ(spotAt(light, 30.1f), 0.0f);
}

TEST(LightSpot, CutoffOf180MeansNoCone) {
    LightParams light = downwardSpot();
    light.spotCutoffDegrees = 180.0f;
    light.spotExponent = 2.0f;
    EXPECT_EQ(spotAt(light, 45.0f), 1.0f);
    EXPECT_EQ(spotAt(light, 170.0f), 1.0f);  // even behind the spot
}

TEST(LightSpot, SmoothVariantAtInnerOuterAndHalfway) {
    LightParams light = downwardSpot();
    light.spotProfile = SpotProfile::Smooth;
    light.spotInnerDegrees = 20.0f;
    light.spotOuterDegrees = 30.0f;
    EXPECT_NEAR(spotAt(light, 20.0f), 1.0f, 1e-4f);
    EXPECT_EQ(spotAt(light, 10.0f), 1.0f);
    EXPECT_NEAR(spotAt(light, 30.0f), 0.0f, 1e-4f);
    EXPECT_EQ(spotAt(light, 35.0f), 0.0f);
    // Halfway in cosine: t = ½, smoothstep = ½²(3 − 1) = ½.
    const float halfwayCos = 0.5f * (std::cos(glm::radians(20.0f)) + std::cos(glm::radians(30.0f)));
    EXPECT_NEAR(spotAt(light, glm::degrees(std::acos(halfwayCos))), 0.5f, 1e-4f);
    // A quarter of the way in from the outer edge: t = ¼, ¼²(3 − ½) = 0.15625.
    const float quarterCos = 0.75f * std::cos(glm::radians(30.0f)) + 0.25f * std::cos(glm::radians(20.0f));
    EXPECT_NEAR(spotAt(light, glm::degrees(std::acos(quarterCos))), 0.15625f, 1e-4f);
}

// ---- The standard lighting equation -----------------------------------------------------------------

PhongMaterial testMaterial() {
    PhongMaterial m;
    m.emission = vec3(0.01f, 0.02f, 0.03f);
    m.ambient = vec3(0.2f, 0.3f, 0.4f);
    m.diffuse = vec3(0.5f, 0.5f, 1.0f);
    m.specular = vec3(1.0f);
    m.shininess = 2.0f;
    return m;
}

TEST(LightingEquation, LightStraightAboveGivesDiffuseProduct) {
    LightParams light;
    light.kind = LightKind::Point;
    light.position = vec3(0.0f, 5.0f, 0.0f);
    light.ambient = vec3(0.1f);
    light.diffuse = vec3(0.8f, 0.6f, 0.4f);
    const PhongMaterial m = testMaterial();
    const vec3 globalAmbient(0.5f);
    const std::vector<LightParams> lights{light};
    const LightingTerms<vec3> t = standardLighting<float>(vec3(0.0f), vec3(0.0f, 1.0f, 0.0f),
                                                          vec3(3.0f, 4.0f, 0.0f), m, globalAmbient, lights);
    EXPECT_FLOAT_EQ(t.diffuse.x, 0.4f);  // 0.8·0.5, N·L = 1
    EXPECT_FLOAT_EQ(t.diffuse.y, 0.3f);  // 0.6·0.5
    EXPECT_FLOAT_EQ(t.diffuse.z, 0.4f);  // 0.4·1
    expectVec3Near(t.emission, m.emission, 0.0f);
    expectVec3Near(t.ambient,
                   vec3(0.5f * 0.2f + 0.1f * 0.2f, 0.5f * 0.3f + 0.1f * 0.3f, 0.5f * 0.4f + 0.1f * 0.4f),
                   1e-6f);
    expectVec3Near(t.sum(), t.emission + t.ambient + t.diffuse + t.specular, 1e-6f);

    // The same from a directional light travelling straight down.
    LightParams sun = light;
    sun.kind = LightKind::Directional;
    sun.direction = vec3(0.0f, -1.0f, 0.0f);
    const std::vector<LightParams> suns{sun};
    const LightingTerms<vec3> s = standardLighting<float>(vec3(0.0f), vec3(0.0f, 1.0f, 0.0f),
                                                          vec3(3.0f, 4.0f, 0.0f), m, globalAmbient, suns);
    EXPECT_FLOAT_EQ(s.diffuse.x, 0.4f);
    EXPECT_FLOAT_EQ(s.diffuse.y, 0.3f);
    EXPECT_FLOAT_EQ(s.diffuse.z, 0.4f);
}

TEST(LightingEquation, LightBehindSurfaceGivesNoDiffuseNorSpecular) {
    LightParams light;
    light.kind = LightKind::Point;
    light.position = vec3(1.0f, -5.0f, 0.5f);  // below the face: N·L < 0
    light.ambient = vec3(0.1f);
    const std::vector<LightParams> lights{light};
    for (SpecularModel model : {SpecularModel::Phong, SpecularModel::BlinnPhong}) {
        const LightingTerms<vec3> t =
            standardLighting<float>(vec3(0.0f), vec3(0.0f, 1.0f, 0.0f), vec3(0.0f, -3.0f, 1.0f),
                                    testMaterial(), vec3(0.0f), lights, model);
        EXPECT_EQ(t.diffuse, vec3(0.0f));
        EXPECT_EQ(t.specular, vec3(0.0f));
        expectVec3Near(t.ambient, vec3(0.02f, 0.03f, 0.04f), 1e-7f);  // ambient does not care
    }
}

// N = +y, light travelling along −(1, 1, 0) so L = (√½, √½, 0), eye straight above so V = +y, n = 2:
//   Phong:       R = 2(N·L)N − L = (−√½, √½, 0), R·V = √½, spec = ½;
//   Blinn-Phong: H = normalize(L + V), N·H = cos 22.5°, spec = cos² 22.5° = (2 + √2)/4 = 0.853553.
TEST(LightingEquation, PhongAndBlinnPhongSpecularDiffer) {
    LightParams light;
    light.kind = LightKind::Directional;
    light.direction = vec3(-1.0f, -1.0f, 0.0f);
    const std::vector<LightParams> lights{light};
    const auto specular = [&](SpecularModel model) {
        return standardLighting<float>(vec3(0.0f), vec3(0.0f, 1.0f, 0.0f), vec3(0.0f, 10.0f, 0.0f),
                                       testMaterial(), vec3(0.0f), lights, model)
            .specular;
    };
    expectVec3Near(specular(SpecularModel::Phong), vec3(0.5f), 1e-6f);
    expectVec3Near(specular(SpecularModel::BlinnPhong), vec3((2.0f + std::sqrt(2.0f)) / 4.0f), 1e-6f);
}

// ---- Fresnel ----------------------------------------------------------------------------------------

TEST(BrdfFresnel, SchlickVersusExactForEta1_5) {
    const float eta = 1.5f;
    const float f0 = 0.04f;  // ((η − 1)/(η + 1))² = (0.5/2.5)²
    EXPECT_NEAR(etaFromF0(f0), eta, 1e-6f);
    for (float degrees : {0.0f, 60.0f, 89.0f}) {
        const float c = std::cos(glm::radians(degrees));
        std::printf("Fresnel, eta 1.5, %2.0f deg: Schlick %.6f, exact %.6f\n", degrees, fresnelSchlick(f0, c),
                    fresnelExact(c, eta));
    }
    EXPECT_NEAR(fresnelExact(1.0f, eta), 0.04f, 1e-6f);
    EXPECT_NEAR(fresnelSchlick(f0, 1.0f), f0, 1e-7f);
    // 60°: Schlick 0.04 + 0.96·0.5⁵ = 0.07; exact ½(R_s + R_p) = ½(0.176571 + 0.001802) = 0.089187.
    EXPECT_NEAR(fresnelSchlick(f0, 0.5f), 0.07f, 1e-6f);
    EXPECT_NEAR(fresnelExact(0.5f, eta), 0.089187f, 1e-5f);
    // 89°: both close to 1. Schlick 0.04 + 0.96·(1 − 0.017452)⁵ = 0.919102; exact, g = 1.118171:
    // ½ (1.100719/1.135623)² (1 + (−0.980181/1.019210)²) = 0.904186.
    const float c89 = std::cos(glm::radians(89.0f));
    EXPECT_NEAR(fresnelSchlick(f0, c89), 0.919102f, 1e-5f);
    EXPECT_NEAR(fresnelExact(c89, eta), 0.904186f, 2e-5f);
    EXPECT_NEAR(fresnelExact(0.0f, eta), 1.0f, 1e-6f);  // grazing
}

TEST(BrdfFresnel, TotalInternalReflectionReflectsEverything) {
    // From glass into air (η = 1/1.5): the critical angle is asin(1/1.5) = 41.8°.
    EXPECT_EQ(fresnelExact(std::cos(glm::radians(60.0f)), 1.0f / 1.5f), 1.0f);
    EXPECT_LT(fresnelExact(std::cos(glm::radians(20.0f)), 1.0f / 1.5f), 0.1f);
}

// ---- Microfacet distributions and the Lambert term: numerical integration over the hemisphere -------

// ∫_Ω f(cos θ) dω = 2π ∫_0^{π/2} f(cos θ) sin θ dθ, by the midpoint rule.
template <class Integrand>
double integrateHemisphere(Integrand f) {
    constexpr int kSteps = 200000;
    const double step = (std::numbers::pi / 2) / kSteps;
    double sum = 0;
    for (int i = 0; i < kSteps; ++i) {
        const double theta = (i + 0.5) * step;
        sum += f(static_cast<float>(std::cos(theta))) * std::sin(theta);
    }
    return 2 * std::numbers::pi * sum * step;
}

TEST(BrdfDistribution, GgxAndBeckmannNormalise) {
    for (float alpha : {0.1f, 0.3f, 0.7f}) {
        const double ggx = integrateHemisphere([&](float c) { return distributionGGX(c, alpha) * c; });
        const double beckmann =
            integrateHemisphere([&](float c) { return distributionBeckmann(c, alpha) * c; });
        EXPECT_NEAR(ggx, 1.0, 0.01) << "GGX, alpha " << alpha;
        EXPECT_NEAR(beckmann, 1.0, 0.01) << "Beckmann, alpha " << alpha;
    }
}

TEST(BrdfDistribution, ZeroBelowTheHorizon) {
    EXPECT_EQ(distributionGGX(-0.5f, 0.3f), 0.0f);
    EXPECT_EQ(distributionBeckmann(-0.5f, 0.3f), 0.0f);
    EXPECT_EQ(distributionBeckmann(0.0f, 0.3f), 0.0f);
}

// A white Lambertian surface (F = 0: the exact Fresnel of η = 1) reflects all it receives:
// ∫_Ω (1/π) cos θ dω = 1, integrating the BRDF itself over the light directions.
TEST(BrdfLambert, WhiteFurnace) {
    PbrMaterial white;
    white.baseColor = vec3(1.0f);
    white.metalness = 0.0f;
    white.f0 = vec3(0.0f);
    const BrdfModel model{NormalDistribution::GGX, FresnelModel::Exact, GeometryTerm::SmithGGX};
    const vec3 n(0.0f, 0.0f, 1.0f), v = normalize(vec3(0.3f, 0.1f, 1.0f));
    const double reflected = integrateHemisphere([&](float c) {
        const vec3 l(std::sqrt(std::max(1.0f - c * c, 0.0f)), 0.0f, c);
        return brdf<float>(n, l, v, white, model).x * c;
    });
    EXPECT_NEAR(reflected, 1.0, 1e-4);
    EXPECT_NEAR(integrateHemisphere([](float c) { return c / kPi; }), 1.0, 1e-6);
}

TEST(BrdfMicrofacet, MetalsReflectTheirBaseColour) {
    PbrMaterial gold;
    gold.baseColor = findMaterialPreset("gold")->f0;
    gold.metalness = 1.0f;
    gold.roughness = 0.5f;
    const vec3 n(0.0f, 0.0f, 1.0f);
    // Head-on: F = F0 = base colour, no diffuse, so f ∝ base colour.
    const vec3 f = brdf<float>(n, n, n, gold);
    const float alpha = 0.25f;
    const float expected = distributionGGX(1.0f, alpha) * geometrySmithGGX(1.0f, 1.0f, alpha) / 4.0f;
    expectVec3Near(f, gold.baseColor * expected, 1e-5f * expected);
}

// ---- The lecture notes' Cook-Torrance form (the lecture preset's BrdfModel fields) ------------------

// One point computed in double from the formulas as the decks write them, not by the code under test:
// GGX D, Smith-GGX G and Schlick's F (at V·H or N·L, from F0 mixed or not), and both forms of the BRDF.
struct HandBrdf {
    glm::dvec3 c{0.8, 0.5, 0.2};                      // c_base
    double metalness = 0.3, f0 = 0.04, alpha = 0.25;  // roughness 0.5
    glm::dvec3 N{0.0, 0.0, 1.0};
    glm::dvec3 L = glm::normalize(glm::dvec3(0.9, 0.2, 0.6));
    glm::dvec3 V = glm::normalize(glm::dvec3(-0.3, 0.1, 1.0));
    glm::dvec3 H = glm::normalize(L + V);
    double nl = glm::dot(N, L), nv = glm::dot(N, V), nh = glm::dot(N, H), vh = glm::dot(V, H);
    double D() const {
        const double a2 = alpha * alpha, b = nh * nh * (a2 - 1.0) + 1.0;
        return a2 / (std::numbers::pi * b * b);
    }
    double G1(double x) const {
        return 2.0 * x / (x + std::sqrt(alpha * alpha + (1.0 - alpha * alpha) * x * x));
    }
    double G() const { return G1(nl) * G1(nv); }
    static double schlick(double r0, double cosine) { return r0 + (1.0 - r0) * std::pow(1.0 - cosine, 5.0); }
    // Facet's: F0 = mix(f0, c, metalness), F at V·H, D·F·G/(4 (N·L)(N·V)).
    glm::dvec3 facetSpecular() const {
        glm::dvec3 out;
        for (int i = 0; i < 3; ++i)
            out[i] = D() * schlick(f0 + (c[i] - f0) * metalness, vh) * G() / (4.0 * nl * nv);
        return out;
    }
    // lighting-deck-C.txt's "putting it together", with lighting-deck-A.txt's π(n·v)(n·l) and F at n·l:
    // metal = D·F·G/(π(n·v)(n·l))·c, dielectric = D·F·G/(π(n·v)(n·l)) + (1 − F)·c/π,
    // brdf = metalness·metal + (1 − metalness)·dielectric.
    glm::dvec3 deckBrdf() const {
        const double F = schlick(f0, nl), spec = D() * F * G() / (std::numbers::pi * nv * nl);
        const glm::dvec3 metal = spec * c, dielectric = glm::dvec3(spec) + (1.0 - F) * c / std::numbers::pi;
        return metalness * metal + (1.0 - metalness) * dielectric;
    }
};

PbrMaterial handMaterial(const HandBrdf& h) {
    PbrMaterial m;
    m.baseColor = vec3(h.c);
    m.metalness = float(h.metalness);
    m.roughness = 0.5f;
    m.f0 = vec3(float(h.f0));
    return m;
}

BrdfRecord recordAt(const HandBrdf& h, const BrdfModel& model) {
    BrdfRecord record;
    const PbrMaterial m = handMaterial(h);
    brdfLobes<float>(vec3(h.N), vec3(h.L), vec3(h.V), m, m.baseColor, model, nullptr, &record);
    return record;
}

void expectNearDouble(const vec3& actual, const glm::dvec3& expected, double relative) {
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(actual[i], expected[i], relative * std::abs(expected[i])) << "channel " << i;
}

// The denominator alone: π(N·V)(N·L) instead of 4(N·L)(N·V) scales the specular lobe by 4/π and
// nothing else. Catches: the field ignored (ratio 1), or the constant applied to the diffuse lobe.
TEST(BrdfLectureForm, PiDenominatorScalesTheSpecularLobeByFourOverPi) {
    const HandBrdf h;
    BrdfModel pi;
    pi.denominator = MicrofacetDenominator::Pi;
    const BrdfRecord four = recordAt(h, {}), lecture = recordAt(h, pi);
    expectNearDouble(four.lobes.specular, h.facetSpecular(), 1e-5);
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(lecture.lobes.specular[i] / four.lobes.specular[i], 4.0 / std::numbers::pi, 1e-5);
    expectVec3Near(lecture.lobes.diffuse, four.lobes.diffuse, 0.0f);
}

// F at N·L (the decks' F(l∘n), F(n, l)) instead of at V·H: F = F0 + (1 − F0)(1 − N·L)^5.
// Catches: the cosine field ignored (F still at V·H), or N·V taken for N·L.
TEST(BrdfLectureForm, FresnelAtNdotLDiffersFromFresnelAtVdotH) {
    const HandBrdf h;
    BrdfModel atNdotL;
    atNdotL.fresnelCosine = FresnelCosine::NdotL;
    const BrdfRecord facet = recordAt(h, {}), lecture = recordAt(h, atNdotL);
    for (int i = 0; i < 3; ++i) {
        const double f0 = h.f0 + (h.c[i] - h.f0) * h.metalness;
        EXPECT_NEAR(facet.F[i], HandBrdf::schlick(f0, h.vh), 1e-6);
        EXPECT_NEAR(lecture.F[i], HandBrdf::schlick(f0, h.nl), 1e-6);
        EXPECT_GT(std::abs(lecture.F[i] - facet.F[i]), 1e-4);
    }
    EXPECT_FLOAT_EQ(lecture.fresnelCosine, float(h.nl));
}

// lighting-deck-C.txt's metalness blend: F from F0_dielectric, the specular lobe tinted by
// mix(1, c_base, metalness); a pure metal reflects f0 ⊗ c_base head-on, not c_base. Catches: F0 still
// mixed towards c_base, the tint missing, or the tint applied to the diffuse lobe.
TEST(BrdfLectureForm, TintedMetalLobeAsDeckCWritesIt) {
    const HandBrdf h;
    BrdfModel tinted;
    tinted.metal = MetalBlend::TintedLobe;
    const BrdfRecord lecture = recordAt(h, tinted);
    expectVec3Near(lecture.f0, vec3(float(h.f0)), 0.0f);
    const double F = HandBrdf::schlick(h.f0, h.vh), spec = h.D() * F * h.G() / (4.0 * h.nl * h.nv);
    expectNearDouble(lecture.lobes.specular, spec * (glm::dvec3(1.0) + (h.c - 1.0) * h.metalness), 1e-5);
    expectNearDouble(lecture.lobes.diffuse, (1.0 - F) * (1.0 - h.metalness) * h.c / std::numbers::pi, 1e-5);
    const BrdfRecord facet = recordAt(h, {});
    EXPECT_GT(std::abs(lecture.lobes.specular.r - facet.lobes.specular.r), 1e-3f * facet.lobes.specular.r);
}

// All three together are deck C's "putting it together" with deck A's denominator, term by term, in one
// lane and in eight. Catches: any of the three not applied, or applied differently in the wide code.
TEST(BrdfLectureForm, TheWholeFormEqualsTheDecksBrdfInOneLaneAndEight) {
    const HandBrdf h;
    BrdfModel lecture;
    lecture.fresnelCosine = FresnelCosine::NdotL;
    lecture.denominator = MicrofacetDenominator::Pi;
    lecture.metal = MetalBlend::TintedLobe;
    const PbrMaterial m = handMaterial(h);
    const vec3 one = brdf<float>(vec3(h.N), vec3(h.L), vec3(h.V), m, lecture);
    expectNearDouble(one, h.deckBrdf(), 1e-5);
    const Vec3x8 eight =
        brdf<Float8, Vec3x8>(Vec3x8(vec3(h.N)), Vec3x8(vec3(h.L)), Vec3x8(vec3(h.V)), m, lecture);
    for (int lane = 0; lane < 8; ++lane) {
        EXPECT_EQ(eight.x[lane], one.x);
        EXPECT_EQ(eight.y[lane], one.y);
        EXPECT_EQ(eight.z[lane], one.z);
    }
    // And Facet's form is not the decks' at this point.
    const vec3 facet = brdf<float>(vec3(h.N), vec3(h.L), vec3(h.V), m);
    EXPECT_GT(std::abs(facet.r - one.r), 1e-3f * one.r);
}

TEST(BrdfMicrofacet, ZeroVectorsGiveNoNaN) {
    const PbrMaterial m;
    const vec3 zero(0.0f), up(0.0f, 0.0f, 1.0f), side = normalize(vec3(1.0f, 0.0f, 0.2f));
    for (NormalDistribution d : {NormalDistribution::Beckmann, NormalDistribution::GGX})
        for (FresnelModel fr : {FresnelModel::Schlick, FresnelModel::Exact})
            for (GeometryTerm g : {GeometryTerm::CookTorrance, GeometryTerm::SmithGGX}) {
                const BrdfModel model{d, fr, g};
                for (const auto& [n, l, v] : {std::array{zero, up, up}, std::array{up, zero, up},
                                              std::array{up, up, zero}, std::array{up, side, -side}}) {
                    const vec3 f = brdf<float>(n, l, v, m, model);
                    EXPECT_TRUE(std::isfinite(f.x) && std::isfinite(f.y) && std::isfinite(f.z));
                }
            }
}

// ---- Eight lanes = one lane ---------------------------------------------------------------------------

vec3 lane(const Vec3x8& v, int i) {
    return vec3(v.x[i], v.y[i], v.z[i]);
}

void expectLaneNear(const vec3& wide, const vec3& scalar, const char* what) {
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(wide[k], scalar[k], 1e-4f * std::max(std::abs(scalar[k]), 1e-3f)) << what;
}

struct RandomLanes {
    std::mt19937 rng{7};
    std::uniform_real_distribution<float> u{-1.0f, 1.0f};
    vec3 next() { return vec3(u(rng), u(rng), u(rng)); }
    void fill(vec3 (&scalar)[8], Vec3x8& wide, float scale = 1.0f) {
        for (int i = 0; i < 8; ++i) {
            scalar[i] = next() * scale;
            wide.x[i] = scalar[i].x;
            wide.y[i] = scalar[i].y;
            wide.z[i] = scalar[i].z;
        }
    }
};

std::vector<LightParams> testLights() {
    LightParams sun;
    sun.kind = LightKind::Directional;
    sun.direction = vec3(-0.3f, -1.0f, -0.5f);
    sun.ambient = vec3(0.05f);
    sun.diffuse = vec3(1.0f, 0.9f, 0.8f);
    LightParams point;
    point.position = vec3(2.0f, 1.0f, 1.5f);
    point.c1 = 0.3f;
    point.c2 = 0.1f;
    point.diffuse = vec3(0.4f, 0.5f, 1.2f);
    LightParams spot;
    spot.kind = LightKind::Spot;
    spot.position = vec3(0.0f, 3.0f, 0.0f);
    spot.spotCutoffDegrees = 50.0f;
    spot.spotExponent = 3.0f;
    LightParams soft = spot;
    soft.spotProfile = SpotProfile::Smooth;
    soft.position = vec3(1.0f, 2.5f, -1.0f);
    soft.spotInnerDegrees = 25.0f;
    soft.spotOuterDegrees = 45.0f;
    return {sun, point, spot, soft};
}

// One lane and eight run one formula: under each precision lane i of the eight-lane result is the
// one-lane result, bit for bit; and the fast maths stay within 1e−4 of the exact.
void expectTermsEqual(const LightingTerms<Vec3x8>& wide, int i, const LightingTerms<vec3>& one,
                      const char* what) {
    EXPECT_EQ(lane(wide.emission, i), one.emission) << what;
    EXPECT_EQ(lane(wide.ambient, i), one.ambient) << what;
    EXPECT_EQ(lane(wide.diffuse, i), one.diffuse) << what;
    EXPECT_EQ(lane(wide.specular, i), one.specular) << what;
}

TEST(LightingWide, StandardLightingEightLanesEqualOneAndFastIsNearExact) {
    RandomLanes random;
    const std::vector<LightParams> lights = testLights();
    PhongMaterial m = testMaterial();
    for (float shininess : {1.0f, 12.0f, 128.0f})
        for (SpecularModel model : {SpecularModel::Phong, SpecularModel::BlinnPhong})
            for (int trial = 0; trial < 100; ++trial) {
                m.shininess = shininess;
                vec3 position[8], normal[8];
                Vec3x8 positionWide, normalWide;
                random.fill(position, positionWide);
                random.fill(normal, normalWide);
                const vec3 eye(0.3f, 0.5f, 4.0f);
                const LightingTerms<Vec3x8> wide = standardLighting<Float8, Vec3x8, MathPrecision::Fast>(
                    positionWide, normalWide, eye, m, vec3(0.1f), lights, model);
                const LightingTerms<Vec3x8> wideExact =
                    standardLighting<Float8>(positionWide, normalWide, eye, m, vec3(0.1f), lights, model);
                for (int i = 0; i < 8; ++i) {
                    const LightingTerms<vec3> one =
                        standardLighting<float>(position[i], normal[i], eye, m, vec3(0.1f), lights, model);
                    expectTermsEqual(wideExact, i, one, "exact");
                    expectTermsEqual(wide, i,
                                     standardLighting<float, vec3, MathPrecision::Fast>(
                                         position[i], normal[i], eye, m, vec3(0.1f), lights, model),
                                     "fast");
                    expectLaneNear(lane(wide.emission, i), one.emission, "emission");
                    expectLaneNear(lane(wide.ambient, i), one.ambient, "ambient");
                    expectLaneNear(lane(wide.diffuse, i), one.diffuse, "diffuse");
                    expectLaneNear(lane(wide.specular, i), one.specular, "specular");
                }
            }
}

// Where a point light is seen from: at the light itself L = 0 with distance 0 (no NaN), and where the
// squared distance underflows float L is still 0 or a unit vector, in one lane and in eight.
TEST(LightingWide, LightVectorAtTheLightIsZeroElseUnit) {
    LightParams light;
    light.kind = LightKind::Point;
    light.position = vec3(0.0f);  // at the origin, so that the tiny offsets are not rounded away
    const vec3 offsets[8] = {vec3(0.0f),         vec3(1e-25f, 0, 0), vec3(0, 3e-21f, 0),
                             vec3(0, 0, 1e-19f), vec3(1.0f, 0, 0),   vec3(0.3f, -0.4f, 0.1f),
                             vec3(0, 0, -1e-3f), vec3(1e-10f)};
    Vec3x8 positions;
    for (int i = 0; i < 8; ++i) {
        const vec3 p = light.position + offsets[i];
        positions.x[i] = p.x;
        positions.y[i] = p.y;
        positions.z[i] = p.z;
    }
    const LightVector<Float8> wide = lightVector<Float8>(light, positions);
    for (int i = 0; i < 8; ++i) {
        const LightVector<float> one = lightVector<float>(light, lane(positions, i));
        for (const vec3 L : {one.L, lane(wide.L, i)}) {
            ASSERT_TRUE(std::isfinite(L.x) && std::isfinite(L.y) && std::isfinite(L.z)) << i;
            const float length = glm::length(L);
            EXPECT_TRUE(length == 0.0f || std::abs(length - 1.0f) < 1e-5f)
                << "lane " << i << ": |L| = " << length;
        }
        EXPECT_EQ(one.L, lane(wide.L, i)) << i;
    }
    EXPECT_EQ(lightVector<float>(light, light.position).L, vec3(0.0f));
    EXPECT_EQ(lightVector<float>(light, light.position).distance, 0.0f);
}

// A point light a hair above a surface's plane (N·L = 1e-5, as rounding leaves a light placed in the
// plane) gives no highlight, as exactly in the plane: otherwise rounding speckles the face.
TEST(LightingEquation, GrazingLightGivesNoSpecular) {
    PhongMaterial m;
    m.diffuse = vec3(0.5f);
    m.specular = vec3(1.0f);
    m.shininess = 10.0f;
    LightParams light;
    light.kind = LightKind::Point;
    light.position = vec3(1.0f, 0.0f, 1e-5f);
    const vec3 position(0.0f), normal(0.0f, 0.0f, 1.0f), eye(-1.0f, 0.0f, 1.0f);
    const std::vector<LightParams> lights{light};
    for (SpecularModel model : {SpecularModel::Phong, SpecularModel::BlinnPhong}) {
        const LightingTerms<vec3> one =
            standardLighting<float>(position, normal, eye, m, vec3(0.0f), lights, model);
        EXPECT_EQ(one.specular, vec3(0.0f)) << int(model);
        EXPECT_LT(one.diffuse.x, 1e-4f);
        const LightingTerms<Vec3x8> wide =
            standardLighting<Float8>(Vec3x8(position), Vec3x8(normal), eye, m, vec3(0.0f), lights, model);
        EXPECT_EQ(lane(wide.specular, 3), vec3(0.0f)) << int(model);
    }
    PbrMaterial pbr;
    pbr.roughness = 0.3f;
    const LightingTerms<vec3> cookTorrance = physicallyBasedTerms<float>(
        position, normal, eye, pbr, pbr.baseColor, vec3(0.0f), vec3(0.0f), lights);
    EXPECT_EQ(cookTorrance.specular, vec3(0.0f));
    EXPECT_EQ(cookTorrance.diffuse, vec3(0.0f));
}

TEST(BrdfWide, BrdfAndPhysicallyBasedLightingEightLanesEqualOneAndFastIsNearExact) {
    RandomLanes random;
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const std::vector<LightParams> lights = testLights();
    for (NormalDistribution d : {NormalDistribution::Beckmann, NormalDistribution::GGX})
        for (FresnelModel fr : {FresnelModel::Schlick, FresnelModel::Exact})
            for (GeometryTerm g : {GeometryTerm::CookTorrance, GeometryTerm::SmithGGX})
                for (int trial = 0; trial < 50; ++trial) {
                    const BrdfModel model{d, fr, g};
                    PbrMaterial m;
                    m.baseColor = vec3(unit(random.rng), unit(random.rng), unit(random.rng));
                    m.metalness = unit(random.rng);
                    m.roughness = 0.05f + 0.95f * unit(random.rng);
                    m.f0 = vec3(0.02f + 0.06f * unit(random.rng));
                    vec3 n[8], l[8], v[8];
                    Vec3x8 nWide, lWide, vWide;
                    random.fill(n, nWide);
                    random.fill(l, lWide);
                    random.fill(v, vWide);
                    constexpr MathPrecision kFast = MathPrecision::Fast;
                    const Vec3x8 f = brdf<Float8, Vec3x8, kFast>(nWide, lWide, vWide, m, model);
                    const Vec3x8 lit = physicallyBasedLighting<Float8, Vec3x8, kFast>(
                        lWide, nWide, vec3(0.3f, 0.5f, 4.0f), m, lights, model);
                    const Vec3x8 litExact = physicallyBasedLighting<Float8>(
                        lWide, nWide, vec3(0.3f, 0.5f, 4.0f), m, lights, model);
                    for (int i = 0; i < 8; ++i) {
                        EXPECT_EQ(lane(f, i), (brdf<float, vec3, kFast>(n[i], l[i], v[i], m, model)));
                        EXPECT_EQ(lane(lit, i), (physicallyBasedLighting<float, vec3, kFast>(
                                                    l[i], n[i], vec3(0.3f, 0.5f, 4.0f), m, lights, model)));
                        EXPECT_EQ(lane(litExact, i),
                                  physicallyBasedLighting<float>(l[i], n[i], vec3(0.3f, 0.5f, 4.0f), m,
                                                                 lights, model));
                        expectLaneNear(lane(f, i), brdf<float>(n[i], l[i], v[i], m, model), "brdf");
                        expectLaneNear(lane(lit, i),
                                       physicallyBasedLighting<float>(l[i], n[i], vec3(0.3f, 0.5f, 4.0f), m,
                                                                      lights, model),
                                       "physically based lighting");
                    }
                }
}

// ---- Math precision (wide.h): the lighting's pow and exp ----------------------------------------------

// The fast pow and exp are one body for one lane and eight (the same bits in every lane); the exact
// ones are the C library's in every lane; the two differ by less than 2e−5 (relative).
TEST(MathPrecision, EachChoiceIsTheSameInOneLaneAndEight) {
    std::mt19937 rng(13);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f), exponent(-20.0f, 5.0f);
    using Fast = Maths<MathPrecision::Fast>;
    using Exact = Maths<MathPrecision::Exact>;
    for (int trial = 0; trial < 500; ++trial) {
        Float8 x, y;
        for (int i = 0; i < 8; ++i) {
            x[i] = i == 0 ? 0.0f : unit(rng);
            y[i] = exponent(rng);
        }
        const float n = trial % 50 == 0 ? 0.0f : 200.0f * unit(rng);
        const Float8 fastPow = Fast::pow(x, n), exactPow = Exact::pow(x, n);
        const Float8 fastExp = Fast::exp(y), exactExp = Exact::exp(y);
        for (int i = 0; i < 8; ++i) {
            EXPECT_EQ(fastPow[i], Fast::pow(x[i], n)) << x[i] << "^" << n;
            EXPECT_EQ(exactPow[i], std::pow(x[i], n)) << x[i] << "^" << n;
            EXPECT_EQ(Exact::pow(x[i], n), std::pow(x[i], n));
            EXPECT_NEAR(fastPow[i], exactPow[i], 2e-5f * exactPow[i] + 1e-30f) << x[i] << "^" << n;
            EXPECT_EQ(fastExp[i], Fast::exp(y[i])) << y[i];
            EXPECT_EQ(exactExp[i], std::exp(y[i])) << y[i];
            EXPECT_EQ(Exact::exp(y[i]), std::exp(y[i]));
            EXPECT_NEAR(fastExp[i], exactExp[i], 2e-5f * exactExp[i]) << y[i];
        }
    }
    // pow's edges, as GLSL's: 0^n = 0 for n > 0, x^0 = 1 (also 0^0), in both precisions.
    EXPECT_EQ(Fast::pow(0.0f, 3.0f), 0.0f);
    EXPECT_EQ(Exact::pow(0.0f, 3.0f), 0.0f);
    EXPECT_EQ(Fast::pow(0.0f, 0.0f), 1.0f);
    EXPECT_EQ(Exact::pow(0.0f, 0.0f), 1.0f);
}

// ---- Presets -----------------------------------------------------------------------------------------

TEST(BrdfPresets, LookupIgnoresCaseAndRejectsUnknownNames) {
    const std::optional<MaterialPreset> gold = findMaterialPreset("GoLd");
    ASSERT_TRUE(gold.has_value());
    EXPECT_TRUE(gold->metal);
    expectVec3Near(gold->f0, vec3(1.000f, 0.782f, 0.344f), 0.02f);  // RTR4 table 9.2
    EXPECT_EQ(findMaterialPreset("aluminum")->f0, findMaterialPreset("Aluminium")->f0);
    EXPECT_FLOAT_EQ(findMaterialPreset("water")->f0.x, 0.02f);
    EXPECT_FLOAT_EQ(findMaterialPreset("skin")->f0.x, 0.028f);
    EXPECT_FLOAT_EQ(findMaterialPreset("hair")->f0.x, 0.046f);
    EXPECT_FALSE(findMaterialPreset("hair")->metal);
    for (std::string_view name : {"gold", "silver", "copper", "iron", "aluminium", "titanium", "chromium",
                                  "nickel", "platinum", "brass", "zinc", "mercury", "palladium"})
        EXPECT_TRUE(findMaterialPreset(name).has_value()) << name;
    EXPECT_FALSE(findMaterialPreset("unobtainium").has_value());
    EXPECT_FALSE(findMaterialPreset("").has_value());
    EXPECT_FALSE(findMaterialPreset("gol").has_value());
}

}  // namespace
}  // namespace facet
