// The built-in formulas, as a shader of one's own calls them (user_shader.h includes this): each term of
// the lighting equation, a light's vector, attenuation and spot factor, Cook-Torrance's D, F and G, fog
// and the sRGB curve, over the lane type F (float or Float8), so that an assignment can replace one term
// and keep the others. Each function here only calls the formula the renderer itself runs
// (shading/lighting.h, fog.h, pipeline/color.h), with the precision and normalisation the scene chose
// (SceneUniforms::precision, ::normalization), so a shader that adds the terms up in the built-in order
// reproduces the built-in image bit for bit (tests/shaders/formulas_test.cpp).
//
// The standard equation, in the lecture notes' notation, per light j with unit N, L_j, V:
//   L_total = L_emission + k_amb ⊗ I_amb + Σ_j att_j · spot_j · ( k_amb ⊗ I_amb,j
//             + k_diff ⊗ I_j · max(N·L_j, 0) + k_spec ⊗ I_j · (R_j·V)^n_s ),  R_j = 2(N·L_j)N − L_j.
// Built in, the sums run in this order: terms start as emission, a_global ⊗ m_ambient and zeros, and
// each light adds its ambient (only where its l_a is not zero), diffuse and specular, lights in order.
#pragma once

#include <cstdint>

#include "pipeline/color.h"
#include "pipeline/wide.h"
#include "shaders/shaders.h"
#include "shading/fog.h"
#include "shading/lighting.h"

namespace facet {

// ---- Vectors: N, V, L -------------------------------------------------------------------------------

// v/|v| as the lighting makes N, L, V unit length, under the scene's normalisation (0 stays 0).
template <class F, class V3 = LaneVec3<F>>
V3 unitVector(const V3& v, const SurfaceUniforms& u) {
    return u.normalization == Normalization::Fast ? safeNormalize<F, V3, Normalization::Fast>(v)
                                                  : safeNormalize<F, V3, Normalization::Exact>(v);
}

// The normal turned towards the viewer when the scene lights both sides (u.twoSidedFlip): −N where
// N·(−P) < 0 (the eye is at the origin of eye space). Not normalised: unitVector does that.
template <class F, class V3 = LaneVec3<F>>
V3 facingNormal(const V3& normal, const V3& P, const SurfaceUniforms& u) {
    if (!u.twoSidedFlip) return normal;
    return select(seesUnderside(normal, P), -normal, normal);
}

// V, the unit vector from the eye-space point P towards the eye (at the origin).
template <class F, class V3 = LaneVec3<F>>
V3 viewVector(const V3& P, const SurfaceUniforms& u) {
    return unitVector<F, V3>(vec3(0.0f) - P, u);
}

// L and the distance d from P to the light (d = 0 for a directional light; L = 0 at the light itself).
template <class F, class V3 = LaneVec3<F>>
LightVector<F, V3> lightVectorAt(const LightParams& light, const V3& P, const SurfaceUniforms& u) {
    return u.normalization == Normalization::Fast ? lightVector<F, V3, Normalization::Fast>(light, P)
                                                  : lightVector<F, V3, Normalization::Exact>(light, P);
}

// ---- How much of a light arrives: attenuation and spot ------------------------------------------

// att = 1/(c0 + c1·d + c2·d²) is attenuation(light, d) (lighting.h), usable as it is.

// The spot factor under the light's own profile (1 for point and directional lights).
template <class F, class V3 = LaneVec3<F>>
F spotFactorAt(const LightParams& light, const V3& L, const SurfaceUniforms& u) {
    return u.precision == MathPrecision::Exact ? spotFactor<F, V3, MathPrecision::Exact>(light, L)
                                               : spotFactor<F, V3, MathPrecision::Fast>(light, L);
}

// att · f_win · spot: what the standard equation scales a light's three terms by (f_win, the range's
// window, only for a light with a range: standardFalloff, lighting.h).
template <class F, class V3 = LaneVec3<F>>
F lightReach(const LightParams& light, const LightVector<F, V3>& toLight, const SurfaceUniforms& u) {
    return standardFalloff(light, toLight.distance) * spotFactorAt<F, V3>(light, toLight.L, u);
}

// ---- The standard equation's terms -----------------------------------------------------------------

// The scene-wide ambient term a_global ⊗ m_ambient (the lecture's k_amb · I_amb).
template <class F, class V3 = LaneVec3<F>>
V3 globalAmbientTerm(const SurfaceUniforms& u) {
    return V3(u.globalAmbient * u.material.ambient);
}

// One light's ambient term (l_a ⊗ m_ambient)·reach: ambientTerm(light.ambient, m_ambient, reach),
// lighting.h. Lambert's diffuse term m_diffuse ⊗ l_d · lit · max(N·L, 0): lambertTerm(m_diffuse,
// light.diffuse, lit, N·L). The specular term (l_s ⊗ m_specular)·lit·spec: specularTerm(light.specular,
// m_specular, lit, spec). Phong's R: phongReflected(N, L, N·L). These four are lighting.h's own.

// Blinn's halfway vector H = normalize(L + V), under the scene's normalisation.
template <class F, class V3 = LaneVec3<F>>
V3 halfwayVector(const V3& L, const V3& V, const SurfaceUniforms& u) {
    return u.normalization == Normalization::Fast ? blinnHalfway<F, V3, Normalization::Fast>(L, V)
                                                  : blinnHalfway<F, V3, Normalization::Exact>(L, V);
}

// spec = max(cosine, 0)^exponent, 0 where the light grazes or is behind (N·L ≤ kGrazingCosine), with the
// scene's pow.
template <class F>
F specularPowerOf(F NdotL, F cosine, float exponent, const SurfaceUniforms& u) {
    return u.precision == MathPrecision::Exact
               ? specularPower<F, MathPrecision::Exact>(NdotL, cosine, exponent)
               : specularPower<F, MathPrecision::Fast>(NdotL, cosine, exponent);
}

// Phong's specular power (R·V)^n_s, R = 2(N·L)N − L, n_s = the material's shininess.
template <class F, class V3 = LaneVec3<F>>
F phongSpecular(const V3& N, const V3& L, const V3& V, const SurfaceUniforms& u) {
    const F NdotL = dot(N, L);
    return specularPowerOf<F>(NdotL, dot(phongReflected(N, L, NdotL), V), u.material.shininess, u);
}

// Blinn-Phong's specular power (N·H)^e, H = normalize(L + V), e = the shininess or 4× it as the scene's
// blinn_exponent says.
template <class F, class V3 = LaneVec3<F>>
F blinnPhongSpecular(const V3& N, const V3& L, const V3& V, const SurfaceUniforms& u) {
    const SpecularFormula formula(SpecularModel::BlinnPhong, u.brdf.blinnExponent);
    return specularPowerOf<F>(dot(N, L), dot(N, halfwayVector<F, V3>(L, V, u)),
                              formula.exponent(u.material.shininess), u);
}

// The whole equation as the built-in shaders run it (shaders.h's surfaceTerms): the model the scene
// chose, the two-sided flip, shadows and the selected terms, as LightingTerms (emission, ambient,
// diffuse, specular; sum() adds them).
template <class F, class V3 = LaneVec3<F>>
LightingTerms<V3> builtinTerms(const V3& P, const V3& normal, const V3& albedo, const SurfaceUniforms& u) {
    return surfaceTerms<F, V3>(P, normal, albedo, u, static_cast<const V3*>(nullptr));
}

// ---- Cook-Torrance's D, F and G ----------------------------------------------------------------------

// α = roughness² (kept ≥ 1e−3) is alphaFromRoughness(roughness), lighting.h.

// D(h): GGX or Beckmann, as the scene's brdf chooses, with its exp.
template <class F>
F microfacetDistribution(F NdotH, float alpha, const SurfaceUniforms& u) {
    if (u.brdf.distribution == NormalDistribution::GGX) return distributionGGX(NdotH, alpha);
    return u.precision == MathPrecision::Exact ? distributionBeckmann<F, MathPrecision::Exact>(NdotH, alpha)
                                               : distributionBeckmann<F, MathPrecision::Fast>(NdotH, alpha);
}

// F(v, h): Schlick's F0 + (1 − F0)(1 − v·h)^5 or the exact Fresnel equations, as the scene chooses.
template <class F, class V3 = LaneVec3<F>>
V3 fresnelTerm(const vec3& f0, F VdotH, const SurfaceUniforms& u) {
    return u.brdf.fresnel == FresnelModel::Schlick ? fresnelSchlick<F, V3>(f0, VdotH)
                                                   : fresnelExact<F, V3>(f0, VdotH);
}

// G(l, v, h): Smith's GGX or Cook-Torrance's, as the scene chooses.
template <class F>
F geometryTerm(F NdotH, F NdotV, F NdotL, F VdotH, float alpha, const SurfaceUniforms& u) {
    return u.brdf.geometry == GeometryTerm::SmithGGX ? geometrySmithGGX(NdotV, NdotL, alpha)
                                                     : geometryCookTorrance(NdotH, NdotV, NdotL, VdotH);
}

// The BRDF's two lobes for one light (diffuse (1 − F)(1 − metalness)·albedo/π, specular
// D·F·G/(4 (N·L)(N·V))), with the scene's model and precision.
template <class F, class V3 = LaneVec3<F>>
BrdfLobes<V3> cookTorranceLobes(const V3& N, const V3& L, const V3& V, const V3& albedo,
                                const SurfaceUniforms& u) {
    if (u.normalization == Normalization::Fast)
        return u.precision == MathPrecision::Exact
                   ? brdfLobes<F, V3, MathPrecision::Exact, Normalization::Fast>(N, L, V, u.pbr, albedo,
                                                                                 u.brdf)
                   : brdfLobes<F, V3, MathPrecision::Fast, Normalization::Fast>(N, L, V, u.pbr, albedo,
                                                                                u.brdf);
    return u.precision == MathPrecision::Exact
               ? brdfLobes<F, V3, MathPrecision::Exact, Normalization::Exact>(N, L, V, u.pbr, albedo, u.brdf)
               : brdfLobes<F, V3, MathPrecision::Fast, Normalization::Exact>(N, L, V, u.pbr, albedo, u.brdf);
}

// ---- Fog ---------------------------------------------------------------------------------------------

// The fog factor f at the eye-space point P (1 = no fog, 0 = only fog), with the scene's fog and exp.
template <class F, class V3 = LaneVec3<F>>
F fogFactorAt(const V3& P, const SurfaceUniforms& u) {
    const F z = fogDistance<F, V3>(u.fog, P);
    return u.precision == MathPrecision::Exact ? fogFactor<F, MathPrecision::Exact>(u.fog, z)
                                               : fogFactor<F, MathPrecision::Fast>(u.fog, z);
}

// c = f·c_s + (1 − f)·c_fog: the scene's fog applied to the colour c at P.
template <class F, class V3 = LaneVec3<F>>
V3 withFog(const V3& color, const V3& P, const SurfaceUniforms& u) {
    return u.precision == MathPrecision::Exact ? applyFog<F, V3, MathPrecision::Exact>(u.fog, color, P)
                                               : applyFog<F, V3, MathPrecision::Fast>(u.fog, color, P);
}

// What the built-in shaders write for a lit colour c of opacity α at P: fog, then the form the draw's
// blend expects (surfaceOutput, shaders.h), with α.
template <class F, class V3 = LaneVec3<F>>
LaneVec4<F> builtinOutput(const V3& c, F alpha, const V3& P, const SurfaceUniforms& u) {
    return withAlpha(surfaceOutput<F, V3>(c, alpha, P, u), alpha);
}

// ---- The sRGB curve ------------------------------------------------------------------------------------

// pipeline/color.h's linearToSrgb and srgbToLinear (one float) for every lane and component. The
// framebuffer holds linear light and the image writer encodes it: a shader needs these only to compute
// in display values on purpose (a colour picked in an image editor is sRGB: srgbToLinear it).
template <WideLanes F>
F linearToSrgb(F c) {
    for (int i = 0; i < LaneTraits<F>::kCount; ++i)
        c[i] = linearToSrgb(c[i]);
    return c;
}
template <WideLanes F>
F srgbToLinear(F c) {
    for (int i = 0; i < LaneTraits<F>::kCount; ++i)
        c[i] = srgbToLinear(c[i]);
    return c;
}
inline vec3 linearToSrgb(const vec3& c) {
    return {linearToSrgb(c.x), linearToSrgb(c.y), linearToSrgb(c.z)};
}
template <class F>
WideVec3<F> linearToSrgb(const WideVec3<F>& c) {
    return {linearToSrgb(c.x), linearToSrgb(c.y), linearToSrgb(c.z)};
}
inline vec3 srgbToLinear(const vec3& c) {
    return {srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z)};
}
template <class F>
WideVec3<F> srgbToLinear(const WideVec3<F>& c) {
    return {srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z)};
}

}  // namespace facet
