// The record the lighting and fog formulas fill (shading/record.h): every number in it equals the value
// computed by hand for a hand-built light, and recording changes nothing of the result.
#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "expect_near.h"
#include "shading/fog.h"
#include "shading/lighting.h"

namespace facet {
namespace {

using testing_shading::expectVec3Near;

bool sameBits(const vec3& a, const vec3& b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

// The scene of every test here: the surface point at the origin facing +z, the eye on the normal at
// (0, 0, 2), and a point light at distance 2 in the xz plane, 0.6 of the way along x: L = (0.6, 0, 0.8).
constexpr vec3 kPosition(0.0f);
constexpr vec3 kNormal(0.0f, 0.0f, 1.0f);
constexpr vec3 kEye(0.0f, 0.0f, 2.0f);

LightParams pointLight() {
    LightParams light;
    light.kind = LightKind::Point;
    light.position = vec3(1.2f, 0.0f, 1.6f);
    light.c0 = 1.0f;
    light.c1 = 0.5f;
    light.c2 = 0.25f;
    light.ambient = vec3(0.3f);
    light.diffuse = vec3(1.0f, 0.5f, 0.25f);
    light.specular = vec3(1.0f);
    return light;
}

PhongMaterial material() {
    PhongMaterial m;
    m.emission = vec3(0.01f, 0.02f, 0.03f);
    m.ambient = vec3(0.1f, 0.2f, 0.3f);
    m.diffuse = vec3(0.5f, 0.25f, 1.0f);
    m.specular = vec3(0.5f);
    m.shininess = 8.0f;
    return m;
}

constexpr vec3 kGlobalAmbient(0.2f);

LightingRecord lightOnce(const LightParams& light, SpecularModel model,
                         LightingTerms<vec3>* terms = nullptr) {
    LightingRecord record;
    const LightParams lights[] = {light};
    const LightingTerms<vec3> t = standardLighting<float>(kPosition, kNormal, kEye, material(),
                                                          kGlobalAmbient, lights, model, nullptr, &record);
    if (terms) *terms = t;
    return record;
}

TEST(LightingRecord, PointLightBlinnPhongNumbersEqualTheHandComputedOnes) {
    const LightingRecord record = lightOnce(pointLight(), SpecularModel::BlinnPhong);
    ASSERT_EQ(record.lightCount, 1);
    EXPECT_FALSE(record.physicallyBased);
    expectVec3Near(record.N, kNormal);
    expectVec3Near(record.V, vec3(0.0f, 0.0f, 1.0f));
    expectVec3Near(record.globalAmbientTerm, vec3(0.02f, 0.04f, 0.06f));  // a_global ⊗ m_a

    const LightRecord& light = record.lights[0];
    expectVec3Near(light.L, vec3(0.6f, 0.0f, 0.8f));
    EXPECT_NEAR(light.distance, 2.0f, 1e-6f);
    EXPECT_NEAR(light.attenuation, 1.0f / 3.0f, 1e-6f);  // 1/(1 + 0.5·2 + 0.25·2²)
    EXPECT_FALSE(light.spot.cone);
    EXPECT_EQ(light.spot.factor, 1.0f);
    EXPECT_NEAR(light.reach, 1.0f / 3.0f, 1e-6f);
    EXPECT_NEAR(light.NdotL, 0.8f, 1e-6f);
    // H = normalize(L + V) = (0.6, 0, 1.8)/√3.6, N·H = 1.8/√3.6 = √0.9.
    expectVec3Near(light.reflected, vec3(0.6f, 0.0f, 1.8f) / std::sqrt(3.6f));
    EXPECT_NEAR(light.cosine, std::sqrt(0.9f), 1e-6f);
    EXPECT_FALSE(light.grazing);
    EXPECT_NEAR(light.spec, 0.6561f, 1e-5f);                                 // (√0.9)^8 = 0.9⁴
    expectVec3Near(light.ambient, vec3(0.03f, 0.06f, 0.09f) / 3.0f);         // l_a⊗m_a·att
    expectVec3Near(light.diffuse, 0.8f * vec3(0.5f, 0.125f, 0.25f) / 3.0f);  // N·L·l_d⊗m_d·att
    expectVec3Near(light.specular, 0.6561f * vec3(0.5f) / 3.0f, 1e-5f);      // spec·l_s⊗m_s·att
    expectVec3Near(record.terms.emission, vec3(0.01f, 0.02f, 0.03f));
    expectVec3Near(record.terms.ambient, vec3(0.02f, 0.04f, 0.06f) + vec3(0.01f, 0.02f, 0.03f));
}

TEST(LightingRecord, PhongReflectsLAboutN) {
    const LightRecord light = lightOnce(pointLight(), SpecularModel::Phong).lights[0];
    // R = 2(N·L)N − L = 1.6·(0, 0, 1) − (0.6, 0, 0.8) = (−0.6, 0, 0.8); R·V = 0.8.
    expectVec3Near(light.reflected, vec3(-0.6f, 0.0f, 0.8f));
    EXPECT_NEAR(light.cosine, 0.8f, 1e-6f);
    EXPECT_NEAR(light.spec, 0.16777216f, 1e-6f);  // 0.8^8
    expectVec3Near(light.specular, 0.16777216f * vec3(0.5f) / 3.0f);
}

TEST(LightingRecord, LightBehindTheSurfaceIsGrazingWithNoSpecular) {
    LightParams light = pointLight();
    light.position = vec3(1.2f, 0.0f, -1.6f);
    const LightRecord r = lightOnce(light, SpecularModel::BlinnPhong).lights[0];
    EXPECT_NEAR(r.NdotL, -0.8f, 1e-6f);
    EXPECT_TRUE(r.grazing);
    EXPECT_EQ(r.spec, 0.0f);
    EXPECT_EQ(r.diffuse, vec3(0.0f));  // max(N·L, 0) = 0
}

// The spot's axis straight down −z: the point is at cos θ = −L·s = 0.8 from it (θ = 36.87°).
TEST(LightingRecord, SpotInsideAndOutsideItsCone) {
    LightParams light = pointLight();
    light.kind = LightKind::Spot;
    light.spotDirection = vec3(0.0f, 0.0f, -1.0f);
    light.spotCutoffDegrees = 45.0f;
    light.spotExponent = 2.0f;
    const LightRecord inside = lightOnce(light, SpecularModel::BlinnPhong).lights[0];
    EXPECT_TRUE(inside.spot.cone);
    EXPECT_NEAR(inside.spot.cosAngle, 0.8f, 1e-6f);
    EXPECT_NEAR(inside.spot.cosCutoff, std::sqrt(0.5f), 1e-6f);  // cos 45°
    EXPECT_NEAR(inside.spot.factor, 0.64f, 1e-6f);               // 0.8²
    EXPECT_NEAR(inside.attenuation, 1.0f / 3.0f, 1e-6f);
    EXPECT_NEAR(inside.reach, 0.64f / 3.0f, 1e-6f);  // att·spot
    expectVec3Near(inside.diffuse, 0.64f * 0.8f * vec3(0.5f, 0.125f, 0.25f) / 3.0f);

    light.spotCutoffDegrees = 30.0f;
    const LightRecord outside = lightOnce(light, SpecularModel::BlinnPhong).lights[0];
    EXPECT_NEAR(outside.spot.cosAngle, 0.8f, 1e-6f);
    EXPECT_NEAR(outside.spot.cosCutoff, std::cos(glm::radians(30.0f)), 1e-6f);
    EXPECT_EQ(outside.spot.factor, 0.0f);
    EXPECT_EQ(outside.diffuse, vec3(0.0f));

    // The smooth profile between cones of 30° and 40°: smoothstep(cos 40°, cos 30°, 0.8).
    light.spotProfile = SpotProfile::Smooth;
    light.spotInnerDegrees = 30.0f;
    light.spotOuterDegrees = 40.0f;
    const LightRecord smooth = lightOnce(light, SpecularModel::BlinnPhong).lights[0];
    const double t = (0.8 - std::cos(40.0 * std::numbers::pi / 180)) /
                     (std::cos(30.0 * std::numbers::pi / 180) - std::cos(40.0 * std::numbers::pi / 180));
    EXPECT_NEAR(smooth.spot.cosOuter, std::cos(40.0 * std::numbers::pi / 180), 1e-6);
    EXPECT_NEAR(smooth.spot.cosInner, std::cos(30.0 * std::numbers::pi / 180), 1e-6);
    EXPECT_NEAR(smooth.spot.factor, t * t * (3 - 2 * t), 1e-5);
}

TEST(LightingRecord, CookTorranceDFGEqualTheHandComputedOnes) {
    PbrMaterial m;
    m.baseColor = vec3(0.5f, 0.4f, 0.3f);
    m.roughness = 0.5f;
    m.metalness = 0.0f;
    m.f0 = vec3(0.04f);
    LightParams light = pointLight();
    const LightParams lights[] = {light};
    LightingRecord record;
    physicallyBasedTerms<float>(kPosition, kNormal, kEye, m, m.baseColor, vec3(0.0f), kGlobalAmbient, lights,
                                BrdfModel{}, nullptr, nullptr, &record);
    ASSERT_TRUE(record.physicallyBased);
    const LightRecord& r = record.lights[0];
    const BrdfRecord& b = r.brdf;
    // α = 0.5² = 0.25; N·H = V·H = √0.9, N·V = 1, N·L = 0.8.
    const double a2 = 0.0625, nh = std::sqrt(0.9), nl = 0.8, nv = 1.0;
    EXPECT_NEAR(b.alpha, 0.25f, 1e-7f);
    EXPECT_NEAR(b.NdotH, nh, 1e-6);
    EXPECT_NEAR(b.VdotH, nh, 1e-6);
    EXPECT_NEAR(b.NdotL, nl, 1e-6);
    EXPECT_NEAR(b.NdotV, nv, 1e-6);
    // GGX: D = α²/(π((N·H)²(α² − 1) + 1)²) = 0.0625/(π·0.15625²) = 2.56/π.
    EXPECT_NEAR(b.D, 2.56 / std::numbers::pi, 1e-5);
    // Schlick: F = F0 + (1 − F0)(1 − V·H)^5.
    const double fresnel = 0.04 + 0.96 * std::pow(1 - nh, 5);
    EXPECT_NEAR(b.F.x, fresnel, 1e-7);
    // Smith GGX: G1(x) = 2x/(x + √(α² + (1 − α²)x²)); G1(1) = 1.
    const double g1 = 2 * nl / (nl + std::sqrt(a2 + (1 - a2) * nl * nl));
    EXPECT_NEAR(b.G, g1, 1e-6);
    const double specular = 2.56 / std::numbers::pi * fresnel * g1 / (4 * nl * nv);
    EXPECT_NEAR(b.lobes.specular.x, specular, 1e-6);
    EXPECT_NEAR(b.lobes.diffuse.x, (1 - fresnel) * 0.5 / std::numbers::pi, 1e-6);
    // Falloff 1/d² = 1/4; irradiance factor falloff·spot·N·L = 0.2; incoming π·c_light·0.2.
    EXPECT_NEAR(r.attenuation, 0.25f, 1e-7f);
    EXPECT_NEAR(r.reach, 0.2f, 1e-6f);
    EXPECT_NEAR(r.incoming.x, std::numbers::pi * 0.2, 1e-6);
    EXPECT_NEAR(r.specular.x, specular * std::numbers::pi * 0.2, 1e-6);

    // Beckmann and Cook-Torrance's G on the same setting.
    BrdfRecord other;
    brdfLobes<float>(
        kNormal, r.L, vec3(0.0f, 0.0f, 1.0f), m, m.baseColor,
        BrdfModel{NormalDistribution::Beckmann, FresnelModel::Schlick, GeometryTerm::CookTorrance}, nullptr,
        &other);
    // D = exp((c² − 1)/(α² c²))/(π α² c⁴), c² = 0.9.
    EXPECT_NEAR(other.D, std::exp((0.9 - 1) / (a2 * 0.9)) / (std::numbers::pi * a2 * 0.81), 1e-5);
    // G = min(1, 2(N·H)(N·V)/(V·H), 2(N·H)(N·L)/(V·H)) = min(1, 2, 1.6) = 1.
    EXPECT_NEAR(other.G, 1.0f, 1e-6f);
}

TEST(FogRecord, LinearExpAndExp2FactorsEqualTheHandComputedOnes) {
    FogParams fog;
    fog.color = vec3(0.5f, 0.6f, 0.7f);
    fog.start = 1.0f;
    fog.end = 5.0f;
    fog.density = 0.25f;
    const vec3 color(1.0f, 0.0f, 0.2f);
    const vec3 eyePosition(0.0f, 3.0f, -2.0f);  // |z_eye| = 2, |P_eye| = √13
    FogRecord record;

    fog.mode = FogMode::Linear;
    applyFog<float>(fog, color, eyePosition, &record);
    EXPECT_EQ(record.z, 2.0f);
    EXPECT_NEAR(record.f, 0.75f, 1e-7f);  // (5 − 2)/(5 − 1)
    expectVec3Near(record.fogged, 0.75f * color + 0.25f * fog.color);

    fog.mode = FogMode::Exponential;
    applyFog<float>(fog, color, eyePosition, &record);
    EXPECT_NEAR(record.f, std::exp(-0.5), 1e-7);  // e^(−0.25·2)

    fog.mode = FogMode::ExponentialSquared;
    fog.distance = FogDistance::Radial;
    applyFog<float>(fog, color, eyePosition, &record);
    EXPECT_NEAR(record.z, std::sqrt(13.0), 1e-6);
    EXPECT_NEAR(record.f, std::exp(-0.0625 * 13), 1e-6);  // e^(−(0.25·√13)²)
    expectVec3Near(record.color, color);

    fog.mode = FogMode::None;
    applyFog<float>(fog, color, eyePosition, &record);
    EXPECT_EQ(record.f, 1.0f);
    EXPECT_EQ(record.fogged, color);
}

// Recording is watching: with the record the results are the very bits they are without it, for
// every model, both precisions and lights of every kind.
TEST(LightingRecord, RecordingChangesNoBitOfTheResult) {
    std::vector<LightParams> lights{pointLight(), pointLight(), pointLight()};
    lights[1].kind = LightKind::Spot;
    lights[1].position = vec3(-1.0f, 2.0f, 3.0f);
    lights[1].spotDirection = normalize(vec3(0.3f, -0.6f, -1.0f));
    lights[1].spotCutoffDegrees = 40.0f;
    lights[1].spotExponent = 3.0f;
    lights[2].kind = LightKind::Directional;
    lights[2].direction = vec3(0.2f, -1.0f, -0.4f);
    const vec3 position(0.1f, -0.2f, 0.05f), normal(0.1f, 0.3f, 0.9f);
    PbrMaterial pbr;
    pbr.metalness = 0.3f;
    for (const SpecularModel model : {SpecularModel::Phong, SpecularModel::BlinnPhong}) {
        LightingRecord record;
        const LightingTerms<vec3> plain = standardLighting<float, vec3, MathPrecision::Fast>(
            position, normal, kEye, material(), kGlobalAmbient, lights, model);
        const LightingTerms<vec3> recorded = standardLighting<float, vec3, MathPrecision::Fast>(
            position, normal, kEye, material(), kGlobalAmbient, lights, model, nullptr, &record);
        EXPECT_TRUE(sameBits(plain.sum(), recorded.sum()));
        EXPECT_TRUE(sameBits(plain.specular, recorded.specular));
        EXPECT_TRUE(sameBits(recorded.specular, record.terms.specular));
    }
    for (const BrdfModel model : {BrdfModel{}, BrdfModel{NormalDistribution::Beckmann, FresnelModel::Exact,
                                                         GeometryTerm::CookTorrance}}) {
        LightingRecord record;
        const LightingTerms<vec3> plain = physicallyBasedTerms<float, vec3, MathPrecision::Exact>(
            position, normal, kEye, pbr, pbr.baseColor, vec3(0.0f), kGlobalAmbient, lights, model);
        const LightingTerms<vec3> recorded = physicallyBasedTerms<float, vec3, MathPrecision::Exact>(
            position, normal, kEye, pbr, pbr.baseColor, vec3(0.0f), kGlobalAmbient, lights, model, nullptr,
            nullptr, &record);
        EXPECT_TRUE(sameBits(plain.sum(), recorded.sum()));
        EXPECT_TRUE(
            sameBits(record.lights[0].specular + record.lights[1].specular + record.lights[2].specular,
                     recorded.specular));
    }
}

}  // namespace
}  // namespace facet
