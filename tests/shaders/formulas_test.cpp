// The built-in formulas as a user shader calls them (shaders/formulas.h): a shader of one's own that adds
// up the standard equation's terms from them, in the built-in order, gives SurfaceShader<Phong>'s colour
// bit for bit, in one lane and in eight, for Phong and Blinn-Phong, both precisions and normalisations,
// fog and blends; D, F, G, the fog factor and the sRGB lanes are the renderer's own numbers.
#include "float_bits.h"
#include "shaders/user_shader.h"
#include "three_lights.h"

#include <bit>
#include <cstdint>
#include <random>

#include <gtest/gtest.h>

namespace facet {
namespace {

using namespace glsl;  // the one-lane functions

SurfaceUniforms shinyThreeLights() {
    SurfaceUniforms u = testing_shaders::threeLights();
    u.material.shininess = 24.0f;
    return u;
}

using Varyings = PerPixelSurface::VaryingsT<float>;

// A user's Phong or Blinn-Phong fragment part written from the formula functions alone, the sums in the
// built-in order (formulas.h's header comment).
template <class F>
LaneVec4<F> userStandard(const PerPixelSurface::VaryingsT<F>& in, const SurfaceUniforms& u) {
    using V3 = LaneVec3<F>;
    const V3 P = in.position;
    const V3 N = unitVector<F>(facingNormal<F>(in.normal, P, u), u);
    const V3 V = viewVector<F>(P, u);
    V3 ambient = globalAmbientTerm<F>(u);
    V3 diffuse(vec3(0.0f)), specular(vec3(0.0f));
    for (const LightParams& light : u.activeLights()) {
        const LightVector<F, V3> toLight = lightVectorAt<F>(light, P, u);
        const F reach = lightReach<F>(light, toLight, u);
        if (light.ambient != vec3(0.0f)) ambient += ambientTerm(light.ambient, u.material.ambient, reach);
        diffuse += lambertTerm(V3(u.material.diffuse), light.diffuse, reach, dot(N, toLight.L));
        const F spec = u.reflection == ReflectionModel::Phong ? phongSpecular<F>(N, toLight.L, V, u)
                                                              : blinnPhongSpecular<F>(N, toLight.L, V, u);
        specular += specularTerm(light.specular, u.material.specular, reach, spec);
    }
    const V3 c = V3(u.material.emission) + ambient + diffuse + specular;
    return builtinOutput<F>(c, lanes<F>(u.opacity), P, u);
}

using testing_shaders::bits;
void expectSameBits(const vec4& got, const vec4& want, const char* what) {
    for (int k = 0; k < 4; ++k)
        EXPECT_EQ(bits(got[k]), bits(want[k]))
            << what << " component " << k << ": " << got[k] << " vs " << want[k];
}

// A user's Phong and Blinn-Phong from the term functions equal the built-in shader's output bit for bit,
// one lane and eight. Breaks caught: a term function that normalises, raises to a power or attenuates
// with another precision than the scene's; a wrapper with its own copy of a formula that rounds
// differently (R computed as 2(N·L)N − L with the product ordered otherwise, H not safe-normalised);
// Blinn's matched exponent (4n) not applied; the flip or V computed from −P instead of 0 − P.
TEST(Formulas, UserStandardEquationEqualsTheBuiltInShader) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> r(-1.0f, 1.0f);
    using S = SurfaceShader<ShadingFrequency::Phong>;
    SurfaceUniforms u = shinyThreeLights();
    for (int variant = 0; variant < 3; ++variant) {
        if (variant == 1) {
            u.fog.mode = FogMode::Exponential;
            u.fog.density = 0.3f;
            u.blend = BlendMode::PremultipliedOver;
            u.opacity = 0.7f;
        }
        if (variant == 2) {
            u.fog.mode = FogMode::Linear;
            u.fog.start = 1.0f;
            u.fog.end = 5.0f;
            u.fog.distance = FogDistance::Radial;
            u.twoSidedFlip = false;
            u.brdf.blinnExponent = BlinnExponent::Matched;
        }
        for (ReflectionModel model : {ReflectionModel::Phong, ReflectionModel::BlinnPhong})
            for (MathPrecision precision : {MathPrecision::Exact, MathPrecision::Fast})
                for (Normalization normalization : {Normalization::Exact, Normalization::Fast}) {
                    u.reflection = model;
                    u.precision = precision;
                    u.normalization = normalization;
                    for (int trial = 0; trial < 20; ++trial) {
                        FragmentBatch batch{};
                        batch.mask = 0xff;
                        Varyings one[8];
                        for (int lane = 0; lane < 8; ++lane) {
                            float* f = reinterpret_cast<float*>(&one[lane]);
                            for (int k = 0; k < 8; ++k) {
                                f[k] = r(rng) - (k == 2 ? 3.0f : 0.0f);  // in front of the eye
                                batch.varyings[k][lane] = f[k];
                            }
                        }
                        const Vec4x8 wide =
                            userStandard<Float8>(loadLanes<PerPixelSurface::VaryingsT>(batch), u);
                        const Vec4x8 builtinWide = S::fragmentBatch(batch, u);
                        for (int lane = 0; lane < 8; ++lane) {
                            const vec4 builtin = S::fragment(one[lane], u);
                            expectSameBits(userStandard<float>(one[lane], u), builtin, "one lane");
                            expectSameBits(vec4(wide.x[lane], wide.y[lane], wide.z[lane], wide.w[lane]),
                                           vec4(builtinWide.x[lane], builtinWide.y[lane], builtinWide.z[lane],
                                                builtinWide.w[lane]),
                                           "eight lanes");
                        }
                    }
                }
    }
}

// D, F, G and the lobes through the wrappers are the numbers brdfLobes computes (its record). Breaks
// caught: a wrapper that ignores the scene's choice of distribution, Fresnel or geometry term, or uses
// another precision for Beckmann's exp.
TEST(Formulas, CookTorranceTermsAreTheBuiltInOnes) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> r(-1.0f, 1.0f);
    SurfaceUniforms u = shinyThreeLights();
    for (NormalDistribution d : {NormalDistribution::GGX, NormalDistribution::Beckmann})
        for (FresnelModel fm : {FresnelModel::Schlick, FresnelModel::Exact})
            for (GeometryTerm g : {GeometryTerm::SmithGGX, GeometryTerm::CookTorrance})
                for (MathPrecision precision : {MathPrecision::Exact, MathPrecision::Fast}) {
                    u.brdf = {d, fm, g, BlinnExponent::Given};
                    u.precision = precision;
                    for (int trial = 0; trial < 30; ++trial) {
                        const vec3 n(r(rng), r(rng), 1.0f), l(r(rng), r(rng), 0.7f), v(r(rng), 0.2f, 0.9f);
                        BrdfRecord record;
                        const BrdfLobes<vec3> lobes =
                            precision == MathPrecision::Exact
                                ? brdfLobes<float, vec3, MathPrecision::Exact>(
                                      n, l, v, u.pbr, u.pbr.baseColor, u.brdf, nullptr, &record)
                                : brdfLobes<float, vec3, MathPrecision::Fast>(n, l, v, u.pbr, u.pbr.baseColor,
                                                                              u.brdf, nullptr, &record);
                        EXPECT_EQ(microfacetDistribution(record.NdotH, record.alpha, u), record.D);
                        EXPECT_EQ(fresnelTerm<float>(record.f0, record.VdotH, u), record.F);
                        EXPECT_EQ(geometryTerm(record.NdotH, record.NdotV, record.NdotL, record.VdotH,
                                               record.alpha, u),
                                  record.G);
                        const BrdfLobes<vec3> mine =
                            cookTorranceLobes<float>(n, l, v, vec3(u.pbr.baseColor), u);
                        EXPECT_EQ(mine.diffuse, lobes.diffuse);
                        EXPECT_EQ(mine.specular, lobes.specular);
                    }
                }
}

// The fog factor and fogged colour are fog.h's (its record's f), with the scene's precision; the sRGB
// lanes are color.h's curve in every lane. Breaks caught: fogFactorAt using the eye depth where the
// scene asked for the radial distance (or the reverse), an exp of another precision, an sRGB lane that
// skipped the linear toe below 0.0031308.
TEST(Formulas, FogAndSrgbAreTheBuiltInOnes) {
    SurfaceUniforms u;
    for (FogMode mode : {FogMode::Linear, FogMode::Exponential, FogMode::ExponentialSquared})
        for (FogDistance distance : {FogDistance::EyeDepth, FogDistance::Radial})
            for (MathPrecision precision : {MathPrecision::Exact, MathPrecision::Fast}) {
                u.fog = {mode, vec3(0.5f, 0.6f, 0.7f), 1.0f, 6.0f, 0.35f, distance};
                u.precision = precision;
                for (float z : {-0.5f, -1.0f, -2.5f, -4.0f, -7.0f}) {
                    const vec3 P(0.8f, -0.3f, z), c(0.9f, 0.2f, 0.1f);
                    FogRecord record;
                    const vec3 fogged =
                        precision == MathPrecision::Exact
                            ? applyFog<float, vec3, MathPrecision::Exact>(u.fog, c, P, &record)
                            : applyFog<float, vec3, MathPrecision::Fast>(u.fog, c, P, &record);
                    EXPECT_EQ(fogFactorAt<float>(P, u), record.f);
                    EXPECT_EQ(withFog<float>(c, P, u), fogged);
                    const Vec3x8 wide = withFog<Float8>(Vec3x8(c), Vec3x8(P), u);
                    EXPECT_EQ(laneOf(wide, 5), fogged);
                }
            }
    const Float8 c = {-0.1f, 0.0f, 0.001f, 0.0031308f, 0.2f, 0.5f, 1.0f, 2.0f};
    const Float8 encoded = linearToSrgb(c), decoded = srgbToLinear(c);
    for (int lane = 0; lane < 8; ++lane) {
        EXPECT_EQ(bits(encoded[lane]), bits(linearToSrgb(c[lane]))) << lane;
        EXPECT_EQ(bits(decoded[lane]), bits(srgbToLinear(c[lane]))) << lane;
    }
    EXPECT_EQ(linearToSrgb(vec3(0.001f, 0.5f, 1.0f)),
              vec3(linearToSrgb(0.001f), linearToSrgb(0.5f), linearToSrgb(1.0f)));
}

// A light's L, distance, attenuation and spot factor through the wrappers are lighting.h's, with the
// scene's choices (the spot's pow). Breaks caught: lightReach multiplying att and spot in the other
// order (the float product is commutative, but a wrapper that added an extra factor would show), a
// spot wrapper that ignores the smooth profile.
TEST(Formulas, LightVectorReachAndSpotAreTheBuiltInOnes) {
    SurfaceUniforms u = shinyThreeLights();
    u.lights[2].spotProfile = SpotProfile::Smooth;
    for (const LightParams& light : u.activeLights())
        for (const vec3 P : {vec3(0.1f, 0.2f, -3.0f), vec3(-1.0f, 0.5f, -2.0f), vec3(0.0f, 0.0f, -1.0f)}) {
            const LightVector<float, vec3> builtin = lightVector<float>(light, P);
            const LightVector<float, vec3> mine = lightVectorAt<float>(light, P, u);
            EXPECT_EQ(mine.L, builtin.L);
            EXPECT_EQ(mine.distance, builtin.distance);
            EXPECT_EQ(spotFactorAt<float>(light, mine.L, u),
                      (spotFactor<float, vec3, MathPrecision::Fast>(light, builtin.L)));
            const float spot = spotFactor<float, vec3, MathPrecision::Fast>(light, builtin.L);
            EXPECT_EQ(lightReach<float>(light, mine, u), attenuation(light, builtin.distance) * spot);
        }
}

}  // namespace
}  // namespace facet
