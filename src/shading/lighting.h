// Lighting formulas as the lectures write them: light sources (attenuation, spot cones), the standard
// (OpenGL fixed-function) lighting equation with Phong or Blinn-Phong specular, and a physically based
// Cook-Torrance microfacet BRDF. Header only; every formula is one template over the lane type, for
// F, V3 = float, vec3 (one fragment) and Float8, Vec3x8 (eight). Those with a power or an exponential
// take a MathPrecision P (wide.h): Exact (the C library's, the default) or Fast (the polynomials), the
// same choice giving the same bits in one lane and in eight.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>
#include <span>
#include <string_view>
#include <type_traits>

#include "pipeline/glsl.h"
#include "pipeline/names.h"
#include "pipeline/wide.h"
#include "shading/record.h"
#include "shading/tangent.h"

namespace facet {

// =====================================================================================================
// 1. Light sources and the standard lighting equation
// =====================================================================================================

// Which reflection model lights a surface.
enum class ReflectionModel {
    Phong,         // standard equation, specular max(R·V, 0)^n
    BlinnPhong,    // standard equation, specular max(N·H, 0)^n
    CookTorrance,  // physically based: Lambert c_base/π + D·F·G / (4 (N·L)(N·V))
};
inline constexpr EnumName<ReflectionModel> kReflectionModelNames[] = {
    {ReflectionModel::Phong, "phong"},
    {ReflectionModel::BlinnPhong, "blinn-phong"},
    {ReflectionModel::CookTorrance, "cook-torrance"}};
constexpr std::span<const EnumName<ReflectionModel>> enumNames(ReflectionModel) {
    return kReflectionModelNames;
}

// How often the lighting equation is evaluated (the lecture's "shading frequency").
enum class ShadingFrequency {
    Flat,     // once per face: every pixel of a triangle gets its provoking vertex's colour
    Gouraud,  // once per vertex, the colours interpolated across the triangle
    Phong,    // once per pixel, with the interpolated normal renormalised
    // never: one unlit colour, the material's diffuse colour (its texture's texel) plus its emission
    // (lighting-deck-A.txt's "constant shading"); drawn by the flat shader, SurfaceUniforms::unlit
    Constant,
};
inline constexpr EnumName<ShadingFrequency> kShadingFrequencyNames[] = {
    {ShadingFrequency::Constant, "constant"},
    {ShadingFrequency::Flat, "flat"},
    {ShadingFrequency::Gouraud, "gouraud"},
    {ShadingFrequency::Phong, "phong"}};
constexpr std::span<const EnumName<ShadingFrequency>> enumNames(ShadingFrequency) {
    return kShadingFrequencyNames;
}

// Rect and Disk are area lights: a one-sided emitting rectangle or disk. They light a point as a point
// light at their centre whose intensity falls off with the emitter's cosine (a Lambertian emitter), and
// their shadows are the fraction of their samples a point sees (shaders/shadowing.h): soft shadows.
enum class LightKind { Directional, Point, Spot, Rect, Disk };
inline constexpr EnumName<LightKind> kLightKindNames[] = {{LightKind::Directional, "directional"},
                                                          {LightKind::Point, "point"},
                                                          {LightKind::Spot, "spot"},
                                                          {LightKind::Rect, "rect"},
                                                          {LightKind::Disk, "disk"}};
constexpr std::span<const EnumName<LightKind>> enumNames(LightKind) {
    return kLightKindNames;
}

// How a spot light falls off towards the edge of its cone.
enum class SpotProfile {
    OpenGL,  // hard edge at the cutoff, cos^exponent inside (glLight GL_SPOT_CUTOFF, GL_SPOT_EXPONENT)
    Smooth,  // smoothstep(cos outer, cos inner, cos angle): a soft rim between the two cones
};
inline constexpr EnumName<SpotProfile> kSpotProfileNames[] = {{SpotProfile::OpenGL, "opengl"},
                                                              {SpotProfile::Smooth, "smooth"}};
constexpr std::span<const EnumName<SpotProfile>> enumNames(SpotProfile) {
    return kSpotProfileNames;
}

constexpr bool isAreaLight(LightKind kind) {
    return kind == LightKind::Rect || kind == LightKind::Disk;
}

// Which windowing function brings a light with a range to zero there (Real-Time Rendering, 4th ed.,
// §5.2.2), x = d/r_max:
enum class RangeWindow {
    Ue4,  // f_win = (1 − x⁴)²₊, Karis 2013 (Unreal Engine 4): nearly 1 up close, the falloff kept
    Jc2,  // f_win = (1 − x²)²₊, Just Cause 2 (there the whole distance falloff): a softer, earlier fade
};
inline constexpr EnumName<RangeWindow> kRangeWindowNames[] = {{RangeWindow::Ue4, "ue4"},
                                                              {RangeWindow::Jc2, "jc2"}};
constexpr std::span<const EnumName<RangeWindow>> enumNames(RangeWindow) {
    return kRangeWindowNames;
}

inline constexpr int kDefaultAreaSamples = 16;     // an area light's shadow samples, 4×4
inline constexpr int kReferenceAreaSamples = 256;  // the exact reference's, 16×16

struct LightParams {
    LightKind kind = LightKind::Point;
    vec3 position{0.0f};                    // world space; point and spot lights
    vec3 direction{0.0f, -1.0f, 0.0f};      // world space, the way the light travels; directional
    vec3 spotDirection{0.0f, -1.0f, 0.0f};  // world space, unit: the spot's axis, pointing away from it
    SpotProfile spotProfile = SpotProfile::OpenGL;
    float spotCutoffDegrees = 180.0f;       // half-angle of the cone; 180 = no cone (OpenGL's default)
    float spotExponent = 0.0f;              // concentration inside the cone
    float spotInnerDegrees = 20.0f;         // Smooth profile: full intensity inside this half-angle
    float spotOuterDegrees = 30.0f;         // Smooth profile: none outside this half-angle
    float c0 = 1.0f, c1 = 0.0f, c2 = 0.0f;  // attenuation 1/(c0 + c1·d + c2·d²); point and spot
    // The scene gave c0 c1 c2: Cook-Torrance then uses 1/(c0 + c1·d + c2·d²) in place of 1/d².
    bool attenuationGiven = false;
    float range = 0.0f;                     // r_max of the windowed falloff; 0: no window
    RangeWindow window = RangeWindow::Ue4;  // the window's formula, when range > 0
    // Area lights (Rect, Disk): `position` is the centre, `areaNormal` the unit normal of the emitting
    // side; the emitter spans centre + a·areaU + b·areaV, (a, b) in [−1, 1]² for a rectangle (areaU and
    // areaV are its half width and half height) and in the unit disk for a disk (both of length radius).
    vec3 areaNormal{0.0f, -1.0f, 0.0f};
    vec3 areaU{0.5f, 0.0f, 0.0f};
    vec3 areaV{0.0f, 0.0f, 0.5f};
    int areaSamples = kDefaultAreaSamples;  // shadow rays per point, a square m×m
    vec3 ambient{0.0f};                     // l_a, linear RGB
    vec3 diffuse{1.0f};                     // l_d, linear RGB (c_light in the physically based model)
    vec3 specular{1.0f};                    // l_s, linear RGB
};

inline constexpr int kMaxLights = 8;  // lights in one scene, as OpenGL 1.x guarantees (GL_MAX_LIGHTS)

// Where a light is seen from a surface point: L, the unit vector towards the light, and the distance d
// (0 for a directional light, which has none).
template <class F, class V3 = LaneVec3<F>>
struct LightVector {
    V3 L;
    F distance;
};

// At the light's own position there is no direction to it: L = 0 there (no diffuse, no specular
// light from it), never 0/0. "At the light" means within the rounding of the positions: a vertex placed
// exactly at the light arrives in eye space a few float steps away from the light's own eye-space
// position (d = 1.5e-8 for a unit cube's corner), and normalising that rounding error would give a
// unit L pointing anywhere (N·L = 0.9 lit its faces under flat and Gouraud shading). So L = 0 wherever
// d ≤ 2^-20·|P| (P in eye space, 16 float steps of its size), or the squared distance is below normal
// floats: L is a unit vector or 0, nothing between.
// Under Normalization::Fast, 1/d is fastInverseSqrt(d²) and d = d²·(1/d).
inline constexpr float kSmallestSquare = 1e-30f;     // normal floats: sqrt and the division stay exact enough
inline constexpr float kAtLightRelative = 0x1p-20f;  // d/|P| below this: the point is at the light
template <class F, class V3 = LaneVec3<F>, Normalization kNormalization = Normalization::Exact>
[[gnu::always_inline]] inline LightVector<F, V3> lightVector(const LightParams& light, const V3& position) {
    if (light.kind == LightKind::Directional) return {V3(-normalize(light.direction)), lanes<F>(0.0f)};
    const V3 toLight = light.position - position;
    const F squared = dot(toLight, toLight);
    const auto awayFromLight = squared >= max(dot(position, position) * (kAtLightRelative * kAtLightRelative),
                                              lanes<F>(kSmallestSquare));
    if constexpr (kNormalization == Normalization::Fast) {
        const F inverse =
            select(awayFromLight, inverseSqrt<kNormalization>(max(squared, kSmallestSquare)), lanes<F>(0.0f));
        return {toLight * inverse, squared * inverse};
    }
    const F distance = sqrt(squared);
    const F inverse = select(awayFromLight, 1.0f / max(distance, 1e-15f), 0.0f);
    return {toLight * inverse, distance};
}

// N·L at or below this counts as grazing: the light lies in the surface's plane (or behind it). The
// rounding of eye-space positions puts N·L for a light in the plane a hair either side of 0, and a gate
// at exactly 0 would switch highlights on and off from pixel to pixel; within 0.006° of grazing the
// highlight is gone anyway.
inline constexpr float kGrazingCosine = 1e-4f;

// att(d) = 1/(c0 + c1·d + c2·d²) for point and spot lights, 1 for directional ones.
template <class F>
F attenuation(const LightParams& light, F distance) {
    if (light.kind == LightKind::Directional) return lanes<F>(1.0f);
    // Constant attenuation alone (the default) needs no per-pixel division.
    if (light.c1 == 0.0f && light.c2 == 0.0f) return lanes<F>(1.0f / light.c0);
    return 1.0f / (light.c0 + distance * (light.c1 + distance * light.c2));
}

// The windowed falloff's window (Real-Time Rendering, 4th ed., §5.2.2), x = d/r_max:
//   f_win(d) = (1 − x⁴)²₊  (Karis 2013, Unreal Engine 4)   or   (1 − x²)²₊  (Just Cause 2),
// (·)₊ = max(·, 0): 1 at the light, 0 at and beyond r_max. It multiplies the distance falloff (the
// attenuation, or 1/d²). 1 for a light without a range and for a directional light.
template <class F>
F rangeWindow(const LightParams& light, F distance) {
    if (light.kind == LightKind::Directional || !(light.range > 0.0f)) return lanes<F>(1.0f);
    const F x = distance / light.range;
    const F x2 = x * x;
    const F t = max(1.0f - (light.window == RangeWindow::Ue4 ? x2 * x2 : x2), 0.0f);
    return t * t;
}

// The standard equation's distance falloff: att(d)·f_win(d) (the window only for a light with a range).
template <class F>
F standardFalloff(const LightParams& light, F distance) {
    const F att = attenuation(light, distance);
    if (!(light.range > 0.0f)) return att;
    return att * rangeWindow(light, distance);
}

// The physically based model's distance falloff: 1/d² (the physical default), or 1/(c0 + c1·d + c2·d²)
// where the scene gave the light an attenuation; times f_win(d) for a light with a range. 1 for a
// directional light.
template <class F>
F physicalFalloff(const LightParams& light, F distance) {
    if (light.kind == LightKind::Directional) return lanes<F>(1.0f);
    const F falloff =
        light.attenuationGiven ? attenuation(light, distance) : 1.0f / max(distance * distance, 1e-8f);
    if (!(light.range > 0.0f)) return falloff;
    return falloff * rangeWindow(light, distance);
}

// Sample k (0 ≤ k < n) of an area light's n = m×m shadow samples, eye space: stratified, one per cell of
// an m×m grid over the emitter's square [−1, 1]², at a position within its cell from a hash of (i, j, m)
// (the same for every point and every thread: the shadows are deterministic, and the rasterizer and the
// reference share them at the same n). A disk maps the square onto itself by Shirley and Chiu's
// concentric map (1997), which keeps the strata's areas equal. One sample (n = 1) is the centre.
inline vec3 areaLightSample(const LightParams& light, int k, int n) {
    if (n <= 1) return light.position;
    const int m = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(n)))));
    const int i = k % m, j = k / m;
    const auto mix = [](std::uint64_t z) {  // splitmix64's finaliser
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    };
    const std::uint64_t h = (std::uint64_t(i) << 40) ^ (std::uint64_t(j) << 20) ^ std::uint64_t(m);
    const float jitterX = float(mix(h) >> 40) * 0x1.0p-24f;
    const float jitterY = float(mix(h + 0x632be59bd9b4e019ull) >> 40) * 0x1.0p-24f;
    float a = 2.0f * (float(i) + jitterX) / float(m) - 1.0f;
    float b = 2.0f * (float(j) + jitterY) / float(m) - 1.0f;
    if (light.kind == LightKind::Disk && (a != 0.0f || b != 0.0f)) {
        constexpr float kQuarterPi = std::numbers::pi_v<float> / 4.0f;
        float r, phi;
        if (std::abs(a) > std::abs(b)) {
            r = a;
            phi = kQuarterPi * (b / a);
        } else {
            r = b;
            phi = 2.0f * kQuarterPi - kQuarterPi * (a / b);
        }
        a = r * std::cos(phi);
        b = r * std::sin(phi);
    }
    return light.position + light.areaU * a + light.areaV * b;
}

// The record of a spot factor (record.h): its inputs and result at one point.
struct SpotRecord {
    static constexpr bool enabled = true;
    bool emitter = false;  // an area light: the factor is the emitter's cosine max(−L·n_light, 0)
    bool cone = false;     // the light is a spot with a cone; else the factor is 1
    float cosAngle = 0;    // −L·s, the cosine of the angle between the spot's axis and the point
    float cosCutoff = 0;   // OpenGL profile: cos(cutoff)
    float cosInner = 0;    // smooth profile: cos(inner), cos(outer)
    float cosOuter = 0;
    float factor = 1;
};

// OpenGL's spot factor (glLight, OpenGL 2.1 §2.14.1), with L the unit vector from the surface to the
// light and s the spot direction: 0 where the angle between −L and s exceeds the cutoff,
// max(−L·s, 0)^exponent inside, and 1 when the cutoff is 180° (no cone). 1 for non-spot lights.
template <class F, class V3 = LaneVec3<F>, MathPrecision P = MathPrecision::Exact, class... Recording>
F spotFactorOpenGL(const LightParams& light, const V3& L, Recording*... recording) {
    using Record = RecordOf<Recording...>;
    if (light.kind != LightKind::Spot || light.spotCutoffDegrees >= 180.0f) return lanes<F>(1.0f);
    const F cosAngle = dot(-L, normalize(light.spotDirection));
    const float cosCutoff = std::cos(glm::radians(light.spotCutoffDegrees));
    if constexpr (Record::enabled)
        *recordOf(recording...) = {.cone = true,
                                   .cosAngle = cosAngle,
                                   .cosCutoff = cosCutoff,
                                   .factor = spotFactorOpenGL<F, V3, P>(light, L)};
    return select(cosAngle >= cosCutoff, Maths<P>::pow(max(cosAngle, 0.0f), light.spotExponent),
                  lanes<F>(0.0f));
}

// The smooth variant: smoothstep(cos θ_outer, cos θ_inner, −L·s), 1 inside the inner cone, 0 outside
// the outer one and a C¹ ramp between them. 1 for non-spot lights.
template <class F, class V3 = LaneVec3<F>, class... Recording>
F spotFactorSmooth(const LightParams& light, const V3& L, Recording*... recording) {
    using Record = RecordOf<Recording...>;
    if (light.kind != LightKind::Spot) return lanes<F>(1.0f);
    const F cosAngle = dot(-L, normalize(light.spotDirection));
    const float cosInner = std::cos(glm::radians(light.spotInnerDegrees));
    const float cosOuter = std::cos(glm::radians(light.spotOuterDegrees));
    if constexpr (Record::enabled)
        *recordOf(recording...) = {.cone = true,
                                   .cosAngle = cosAngle,
                                   .cosInner = cosInner,
                                   .cosOuter = cosOuter,
                                   .factor = spotFactorSmooth<F, V3>(light, L)};
    return smoothstep(cosOuter, cosInner, cosAngle);
}

// An area light's emitter cosine max(−L·n_light, 0): a one-sided Lambertian emitter's intensity
// towards the point, 0 behind it. 1 for other lights.
template <class F, class V3 = LaneVec3<F>, class... Recording>
F emitterCosine(const LightParams& light, const V3& L, Recording*... recording) {
    using Record = RecordOf<Recording...>;
    if (!isAreaLight(light.kind)) return lanes<F>(1.0f);
    const F cosAngle = dot(-L, light.areaNormal);
    const F factor = max(cosAngle, 0.0f);
    if constexpr (Record::enabled)
        *recordOf(recording...) = {.emitter = true, .cosAngle = cosAngle, .factor = factor};
    return factor;
}

// The light's spot factor under its own profile, and an area light's emitter cosine. Inlined so that
// a point or directional light (1, no record) costs a compare per batch, not a call that spills every
// live vector register.
template <class F, class V3 = LaneVec3<F>, MathPrecision P = MathPrecision::Exact, class... Recording>
[[gnu::always_inline]] inline F spotFactor(const LightParams& light, const V3& L, Recording*... recording) {
    if (light.kind != LightKind::Spot) {
        if (isAreaLight(light.kind)) return emitterCosine<F, V3>(light, L, recording...);
        return lanes<F>(1.0f);
    }
    return light.spotProfile == SpotProfile::Smooth ? spotFactorSmooth<F, V3>(light, L, recording...)
                                                    : spotFactorOpenGL<F, V3, P>(light, L, recording...);
}

// Material of the standard lighting equation; linear RGB.
struct PhongMaterial {
    vec3 emission{0.0f};   // m_emission
    vec3 ambient{0.0f};    // m_ambient
    vec3 diffuse{0.8f};    // m_diffuse
    vec3 specular{0.0f};   // m_specular
    float shininess = 32;  // n
};

enum class SpecularModel {
    Phong,       // max(R·V, 0)^n, R = 2(N·L)N − L (Phong 1975)
    BlinnPhong,  // max(N·H, 0)^e, H = normalize(L + V) (Blinn 1977), e by BlinnExponent
};

// The exponent Blinn-Phong raises N·H to ("lighting": {"blinn_exponent"}, --blinn-exponent). H is halfway
// between L and V, so where N, L and V are coplanar the angle between N and H is half the angle between
// R and V, and (N·H)^e′ ≈ (R·V)^n takes e′ ≈ 4n: with the material's n, Blinn's highlight is wider than
// Phong's; with 4n it matches it.
enum class BlinnExponent : std::uint8_t {
    Given,    // e = n, the material's shininess (as OpenGL 1.x does)
    Matched,  // e′ = 4n: the highlight of Phong's model with the same n
};
inline constexpr EnumName<BlinnExponent> kBlinnExponentNames[] = {{BlinnExponent::Given, "given"},
                                                                  {BlinnExponent::Matched, "matched"}};
constexpr std::span<const EnumName<BlinnExponent>> enumNames(BlinnExponent) {
    return kBlinnExponentNames;
}

// The standard equation's specular formula: the model and, for Blinn-Phong, its exponent. Made from a
// SpecularModel alone, Blinn-Phong takes the material's shininess as it is.
struct SpecularFormula {
    SpecularModel model = SpecularModel::BlinnPhong;
    BlinnExponent blinnExponent = BlinnExponent::Given;
    constexpr SpecularFormula(SpecularModel m = SpecularModel::BlinnPhong,
                              BlinnExponent exponent = BlinnExponent::Given)
        : model(m), blinnExponent(exponent) {}
    // The exponent the cosine (R·V or N·H) is raised to, for a material of shininess n.
    constexpr float exponent(float shininess) const {
        return model == SpecularModel::BlinnPhong && blinnExponent == BlinnExponent::Matched
                   ? 4.0f * shininess
                   : shininess;
    }
};

// The standard equation's terms for one light, each the one place its formula is written
// (standardLighting below adds them up; shaders of one's own call them through shaders/formulas.h).
// `reach` is att·spot, `lit` the reach times the share of the light that reaches the point (shadows).

// The light's ambient term: (l_a ⊗ m_ambient)·reach.
template <class F>
[[gnu::always_inline]] inline auto ambientTerm(const vec3& lightAmbient, const vec3& materialAmbient,
                                               F reach) {
    return (lightAmbient * materialAmbient) * reach;
}

// Lambert's cosine law: m_diffuse ⊗ l_d · lit · max(N·L, 0), nothing from a light behind the surface.
template <class F, class V3>
[[gnu::always_inline]] inline V3 lambertTerm(const V3& diffuseColor, const vec3& lightDiffuse, F lit,
                                             F NdotL) {
    return diffuseColor * lightDiffuse * (lit * max(NdotL, 0.0f));
}

// Phong's reflected light vector R = 2(N·L)N − L (N, L unit).
template <class F, class V3>
[[gnu::always_inline]] inline V3 phongReflected(const V3& N, const V3& L, F NdotL) {
    return N * (2.0f * NdotL) - L;
}

// Blinn's halfway vector H = normalize(L + V).
template <class F, class V3, Normalization kNormalization = Normalization::Exact>
[[gnu::always_inline]] inline V3 blinnHalfway(const V3& L, const V3& V) {
    return safeNormalize<F, V3, kNormalization>(L + V);
}

// The specular power spec = max(cosine, 0)^exponent (cosine = R·V or N·H), 0 where N·L ≤ kGrazingCosine.
template <class F, MathPrecision P = MathPrecision::Exact>
[[gnu::always_inline]] inline F specularPower(F NdotL, F cosine, float exponent) {
    return select(NdotL > kGrazingCosine, Maths<P>::pow(max(cosine, 0.0f), exponent), lanes<F>(0.0f));
}

// The light's specular term: (l_s ⊗ m_specular)·(lit·spec).
template <class F>
[[gnu::always_inline]] inline auto specularTerm(const vec3& lightSpecular, const vec3& materialSpecular,
                                                F lit, F spec) {
    return (lightSpecular * materialSpecular) * (lit * spec);
}

// The equation's four terms apart, so each can be drawn as its own image; sum() is the colour.
template <class V3>
struct LightingTerms {
    V3 emission;
    V3 ambient;  // the global ambient term included
    V3 diffuse;
    V3 specular;
    V3 sum() const { return emission + ambient + diffuse + specular; }
};

// The standard lighting equation (OpenGL 2.1 §2.14.1; Akenine-Möller et al., RTR 2nd ed. §5.5):
//   c = m_emission + a_global ⊗ m_ambient
//     + Σ_lights att · spot · (l_a ⊗ m_ambient + max(N·L, 0) · l_d ⊗ m_diffuse + spec · l_s ⊗ m_specular),
// spec = max(R·V, 0)^n (Phong) or max(N·H, 0)^n (Blinn-Phong), and 0 where N·L ≤ 0 (the light is
// behind the surface; in practice N·L ≤ kGrazingCosine, see there). N is used as given (normalised, not
// flipped towards the viewer). `diffuseColor` is m_diffuse per lane (a texture may vary it); the overload
// below uses the material's. `visibility`, when given, holds per light the share of it that reaches the
// point (1 lit, 0 in shadow; a shadow map's filter gives shares between): the lecture's shadow test, "if
// the light is blocked by another renderable, don't add diffuse or specular illumination", so
//   c = … + Σ_lights att · spot · (l_a ⊗ m_ambient + v · (max(N·L, 0) · l_d ⊗ m_diffuse + spec · l_s ⊗
//   m_specular)).
// Null: every light reaches every point (no shadows, no cost). A LightingRecord (below), when given,
// receives every number of it.
template <class F, class V3 = LaneVec3<F>, MathPrecision P = MathPrecision::Exact,
          Normalization kNormalization = Normalization::Exact, class... Recording>
[[gnu::always_inline]] inline LightingTerms<V3> standardLighting(
    const V3& position, const V3& normal, const vec3& eye, const PhongMaterial& m, const V3& diffuseColor,
    const vec3& globalAmbient, std::span<const LightParams> lights, SpecularFormula specular = {},
    const F* visibility = nullptr, Recording*... recording) {
    using Record = RecordOf<Recording...>;
    static_assert(!Record::enabled || std::is_same_v<F, float>, "records hold one lane");
    const V3 N = safeNormalize<F, V3, kNormalization>(normal);
    const V3 V = safeNormalize<F, V3, kNormalization>(eye - position);
    LightingTerms<V3> terms{V3(m.emission), V3(globalAmbient * m.ambient), V3(vec3(0.0f)), V3(vec3(0.0f))};
    if constexpr (Record::enabled)
        *recordOf(recording...) = {.physicallyBased = false,
                                   .specularModel = specular.model,
                                   .position = position,
                                   .normal = normal,
                                   .N = N,
                                   .V = V,
                                   .materialAmbient = m.ambient,
                                   .materialDiffuse = diffuseColor,
                                   .materialSpecular = m.specular,
                                   .shininess = m.shininess,
                                   .blinnExponent = specular.blinnExponent,
                                   .specularExponent = specular.exponent(m.shininess),
                                   .globalAmbient = globalAmbient,
                                   .globalAmbientTerm = terms.ambient,
                                   .lightCount = static_cast<int>(lights.size())};
    for (const LightParams& light : lights) {
        // Where the light is and how much of it arrives.
        const LightVector<F, V3> toLight = lightVector<F, V3, kNormalization>(light, position);
        const V3& L = toLight.L;
        const F reach = standardFalloff(light, toLight.distance) *
                        spotFactor<F, V3, P>(light, L, &recording->lights[&light - lights.data()].spot...);

        // Ambient and Lambert diffuse.
        const F NdotL = dot(N, L);
        if (light.ambient != vec3(0.0f)) {
            const V3 ambient = ambientTerm(light.ambient, m.ambient, reach);
            terms.ambient += ambient;
            if constexpr (Record::enabled)
                recordOf(recording...)->lights[&light - lights.data()].ambient = ambient;
        }
        const F lit = visibility ? reach * visibility[&light - lights.data()] : reach;
        const V3 diffuse = lambertTerm(diffuseColor, light.diffuse, lit, NdotL);
        terms.diffuse += diffuse;

        // Specular, only where the light is in front of the surface.
        F cosine;
        if (specular.model == SpecularModel::Phong) {
            const V3 R = phongReflected(N, L, NdotL);
            cosine = dot(R, V);
            if constexpr (Record::enabled)
                recordOf(recording...)->lights[&light - lights.data()].reflected = R;
        } else {
            const V3 H = blinnHalfway<F, V3, kNormalization>(L, V);
            cosine = dot(N, H);
            if constexpr (Record::enabled)
                recordOf(recording...)->lights[&light - lights.data()].reflected = H;
        }
        const F spec = specularPower<F, P>(NdotL, cosine, specular.exponent(m.shininess));
        const V3 specularLight = specularTerm(light.specular, m.specular, lit, spec);
        terms.specular += specularLight;

        if constexpr (Record::enabled) {
            auto& r = recordOf(recording...)->lights[&light - lights.data()];
            r.light = light;
            r.L = L;
            r.distance = toLight.distance;
            r.attenuation = attenuation(light, toLight.distance);
            r.window = rangeWindow(light, toLight.distance);
            r.reach = reach;
            r.visibility = visibility ? visibility[&light - lights.data()] : 1.0f;
            r.shadowTested = visibility != nullptr;
            r.NdotL = NdotL;
            r.cosine = cosine;
            r.grazing = !(NdotL > kGrazingCosine);
            r.spec = spec;
            r.diffuse = diffuse;
            r.specular = specularLight;
        }
    }
    if constexpr (Record::enabled) recordOf(recording...)->terms = terms;
    return terms;
}

template <class F, class V3 = LaneVec3<F>, MathPrecision P = MathPrecision::Exact,
          Normalization kNormalization = Normalization::Exact, class... Recording>
LightingTerms<V3> standardLighting(const V3& position, const V3& normal, const vec3& eye,
                                   const PhongMaterial& m, const vec3& globalAmbient,
                                   std::span<const LightParams> lights, SpecularFormula specular = {},
                                   const F* visibility = nullptr, Recording*... recording) {
    return standardLighting<F, V3, P, kNormalization>(position, normal, eye, m, V3(m.diffuse), globalAmbient,
                                                      lights, specular, visibility, recording...);
}

// =====================================================================================================
// 2. Physically based shading: Lambert diffuse + Cook-Torrance microfacet specular
// =====================================================================================================

struct PbrMaterial {
    vec3 baseColor{0.8f};    // linear RGB: albedo for dielectrics, F0 for metals
    float metalness = 0;     // 0 dielectric, 1 metal; blends F0 and removes the diffuse term
    float roughness = 0.5f;  // perceptual, α = roughness²
    vec3 f0{0.04f};          // dielectric reflectance at normal incidence (linear)
    // The index of refraction η = n2/n1 (n1 = 1, air) of a dielectric; 0: none given, F0 alone. When
    // given, f0 is ((1 − η)/(1 + η))² and the exact Fresnel term of a dielectric (metalness 0) uses η
    // itself rather than the η recovered from F0.
    float ior = 0;
    // Anisotropy a in [−1, 1] (0: isotropic) of the GGX lobe along the surface's tangent frame:
    // α_x = α(1 + a), α_y = α(1 − a) (Kulla & Conty 2017), each at least 1e−3.
    float anisotropy = 0;
};

enum class NormalDistribution { Beckmann, GGX, Gaussian };
enum class FresnelModel { Schlick, Exact };
enum class GeometryTerm { CookTorrance, SmithGGX };
inline constexpr EnumName<NormalDistribution> kNormalDistributionNames[] = {
    {NormalDistribution::GGX, "ggx"},
    {NormalDistribution::Beckmann, "beckmann"},
    {NormalDistribution::Gaussian, "gaussian"}};
constexpr std::span<const EnumName<NormalDistribution>> enumNames(NormalDistribution) {
    return kNormalDistributionNames;
}
inline constexpr EnumName<FresnelModel> kFresnelModelNames[] = {{FresnelModel::Schlick, "schlick"},
                                                                {FresnelModel::Exact, "exact"}};
constexpr std::span<const EnumName<FresnelModel>> enumNames(FresnelModel) {
    return kFresnelModelNames;
}
inline constexpr EnumName<GeometryTerm> kGeometryTermNames[] = {
    {GeometryTerm::SmithGGX, "smith-ggx"}, {GeometryTerm::CookTorrance, "cook-torrance"}};
constexpr std::span<const EnumName<GeometryTerm>> enumNames(GeometryTerm) {
    return kGeometryTermNames;
}

// The cosine the Fresnel term is evaluated at.
enum class FresnelCosine : std::uint8_t {
    VdotH,  // cos θ = V·H, the angle at the microfacet that reflects L into V (Walter et al. 2007)
    NdotL,  // cos θ = N·L, at the macroscopic normal (lighting-deck-A.txt, lighting-deck-C.txt)
};
// The constant of the microfacet specular lobe's denominator: D·F·G / (k (N·L)(N·V)).
enum class MicrofacetDenominator : std::uint8_t {
    Four,  // k = 4, from the Jacobian of the half vector (Walter et al. 2007; Karis 2013; RTR4 eq. 9.34)
    Pi,    // k = π, as Cook & Torrance 1982 and lighting-deck-A.txt write it
};
// How metalness enters the BRDF.
enum class MetalBlend : std::uint8_t {
    // F0 = mix(F0_dielectric, c_base, metalness): a metal's Fresnel reflectance is its colour (Karis 2013).
    F0,
    // lighting-deck-C.txt's "putting it together": F from F0_dielectric for both, the metal's specular
    // lobe tinted by c_base: brdf = metalness·spec·c_base + (1 − metalness)·(spec + (1 − F)·c_base/π).
    TintedLobe,
};
inline constexpr float microfacetConstant(MicrofacetDenominator d) {
    return d == MicrofacetDenominator::Four ? 4.0f : std::numbers::pi_v<float>;
}

// The reflection models' formulas: Cook-Torrance's D, F and G, and Blinn-Phong's exponent. The last
// three are the conventions the lecture preset changes (docs/lighting.md, "Facet's form and the notes'").
struct BrdfModel {
    NormalDistribution distribution = NormalDistribution::GGX;
    FresnelModel fresnel = FresnelModel::Schlick;
    GeometryTerm geometry = GeometryTerm::SmithGGX;
    BlinnExponent blinnExponent = BlinnExponent::Given;
    FresnelCosine fresnelCosine = FresnelCosine::VdotH;
    MicrofacetDenominator denominator = MicrofacetDenominator::Four;
    MetalBlend metal = MetalBlend::F0;
};

// α = roughness² (Burley 2012), kept ≥ 1e−3 so D stays finite for a mirror.
inline float alphaFromRoughness(float roughness) {
    return std::max(roughness * roughness, 1e-3f);
}

// Beckmann: D(h) = exp((n·h² − 1)/(α² n·h²)) / (π α² n·h⁴) for n·h > 0, else 0.
// n·h² − 1 is computed as −(1 − n·h)(1 + n·h): near the peak of a smooth surface it cancels to the size
// of α² (1e-6 at roughness 0), where float's rounding of n·h² alone would be a 6% error of D; 1 − n·h
// is exact in float (Sterbenz's lemma), so the product keeps full precision.
template <class F, MathPrecision P = MathPrecision::Exact>
F distributionBeckmann(F NdotH, float alpha) {
    const F c = max(NdotH, 1e-4f);
    const F c2 = c * c;
    const float a2 = alpha * alpha;
    const F d =
        Maths<P>::exp(-((1.0f - c) * (1.0f + c)) / (a2 * c2)) / (std::numbers::pi_v<float> * a2 * c2 * c2);
    return select(NdotH > 0.0f, d, lanes<F>(0.0f));
}

// The angle θ = acos(c) of a cosine c in [−1, 1], as atan2(√((1 − c)(1 + c)), c): exact near c = 1,
// where acos of a rounded c loses the small angles a smooth surface's highlight lives on.
template <class F>
F angleFromCosine(F c) {
    if constexpr (std::is_floating_point_v<F>) {
        return std::atan2(std::sqrt(std::max((1 - c) * (1 + c), F(0))), c);
    } else {
        F theta = c;
        for (int i = 0; i < 8; ++i)
            theta[i] = angleFromCosine(c[i]);
        return theta;
    }
}

// The Gaussian's normalisation constant c(m): 1/(2π ∫₀^{π/2} exp(−(θ/m)²) cos θ sin θ dθ), so that
// ∫ D(h) (n·h) dω_h = 1 over the hemisphere. With θ = m·t the integral is
// (m/2) ∫₀^{π/(2m)} exp(−t²) sin(2mt) dt, a smooth integrand, summed here by Simpson's rule in double
// (t beyond 6.5 adds less than e^−42); for small m, c → 1/(π m²). A teaching model, so one m is
// remembered: a draw computes it once.
inline double gaussianNormalizationExact(double m) {
    const double upper = std::min(std::numbers::pi / (2.0 * m), 6.5);
    constexpr int kIntervals = 512;  // even
    const double h = upper / kIntervals;
    double sum = 0.0;
    for (int i = 0; i <= kIntervals; ++i) {
        const double t = i * h;
        const double f = std::exp(-t * t) * std::sin(2.0 * m * t);
        sum += f * (i == 0 || i == kIntervals ? 1.0 : (i % 2 ? 4.0 : 2.0));
    }
    const double integral = 0.5 * m * sum * h / 3.0;
    return 1.0 / (2.0 * std::numbers::pi * integral);
}
// The last m and its c travel together in one 64-bit atomic word, shared by the threads (a plain
// static, not thread_local: a shader module loaded with dlopen must hold no thread-local storage,
// which the leak checker's thread scan trips over once the module is unloaded).
inline float gaussianNormalization(float m) {
    static std::atomic<std::uint64_t> last{0};
    const std::uint64_t word = last.load(std::memory_order_relaxed);
    if (word != 0 && std::bit_cast<float>(static_cast<std::uint32_t>(word >> 32)) == m)
        return std::bit_cast<float>(static_cast<std::uint32_t>(word));
    const float c = static_cast<float>(gaussianNormalizationExact(m));
    last.store((std::uint64_t{std::bit_cast<std::uint32_t>(m)} << 32) | std::bit_cast<std::uint32_t>(c),
               std::memory_order_relaxed);
    return c;
}

// The Gaussian distribution of Torrance & Sparrow 1967 (lighting-deck-A.txt, "possible terms D"):
// D(h) = c·exp(−(θ_h/m)²), θ_h the angle between n and h, for n·h > 0, else 0; c = c(m) above, and
// m = α (= roughness²): for small angles tan θ_h ≈ θ_h, so the lobe is Beckmann's of the same α near
// its peak, and c → 1/(π α²) as Beckmann's constant.
template <class F, MathPrecision P = MathPrecision::Exact>
F distributionGaussian(F NdotH, float alpha) {
    const F theta = angleFromCosine(saturate(NdotH)) * (1.0f / alpha);
    const F d = gaussianNormalization(alpha) * Maths<P>::exp(-(theta * theta));
    return select(NdotH > 0.0f, d, lanes<F>(0.0f));
}

// GGX / Trowbridge-Reitz (Walter et al. 2007): D(h) = α² / (π ((n·h)²(α² − 1) + 1)²) for n·h > 0, else 0.
// The bracket is computed as (n·h)²α² + (1 − n·h)(1 + n·h), the same value without the cancellation of
// 1 − (n·h)² that costs a smooth surface's peak several percent in float (see distributionBeckmann).
template <class F>
F distributionGGX(F NdotH, float alpha) {
    const float a2 = alpha * alpha;
    const F c = max(NdotH, 0.0f);
    const F denominator = c * c * a2 + (1.0f - c) * (1.0f + c);
    const F d = a2 / (std::numbers::pi_v<float> * denominator * denominator);
    return select(NdotH > 0.0f, d, lanes<F>(0.0f));
}

// Schlick 1994: F = F0 + (1 − F0)(1 − cos θ)^5, cos θ = v·h clamped to [0, 1].
template <class F>
F fresnelSchlick(float f0, F cosTheta) {
    const F m = 1.0f - saturate(cosTheta);
    const F m2 = m * m;
    return f0 + (1.0f - f0) * (m2 * m2 * m);
}
template <class F, class V3 = LaneVec3<F>>
V3 fresnelSchlick(const vec3& f0, F cosTheta) {
    const F m = 1.0f - saturate(cosTheta);
    const F m2 = m * m;
    return (vec3(1.0f) - f0) * (m2 * m2 * m) + f0;
}

// The index of refraction whose normal-incidence reflectance is F0: F0 = ((η − 1)/(η + 1))², so
// η = (1 + √F0)/(1 − √F0). F0 is kept below 1 (η finite).
inline float etaFromF0(float f0) {
    const float s = std::sqrt(std::clamp(f0, 0.0f, 0.9999f));
    return (1.0f + s) / (1.0f - s);
}

// The reflectance at normal incidence of an interface from n1 = 1 (air) into n2 = η:
// F0 = ((n1 − n2)/(n1 + n2))² (Schlick 1994; lighting-deck-A.txt), in double, rounded once.
inline float f0FromEta(float eta) {
    const double r = (1.0 - double(eta)) / (1.0 + double(eta));
    return static_cast<float>(r * r);
}

// Fresnel's equations for the two polarisations (Hecht, Optics, 5th ed., §4.6.2; lighting-deck-A.txt),
// light arriving from n1 = 1 at cos θ_i onto n2 = η, Snell's law sin θ_t = sin θ_i/η:
//   R_s = ((n1 cos θ_i − n2 cos θ_t)/(n1 cos θ_i + n2 cos θ_t))²   (perpendicular)
//   R_p = ((n1 cos θ_t − n2 cos θ_i)/(n1 cos θ_t + n2 cos θ_i))²   (parallel)
// and unpolarised light reflects F = (R_s + R_p)/2 (fresnelExact below, in Cook & Torrance's form). Total
// internal reflection (sin θ_t > 1, η < 1) reflects all of both.
template <class F>
struct FresnelPolarized {
    F s, p;
};
template <class F>
FresnelPolarized<F> fresnelPolarized(F cosTheta, float eta) {
    const F ci = saturate(cosTheta);
    const F sinT2 = (1.0f - ci * ci) * (1.0f / (eta * eta));
    const F ct = sqrt(max(1.0f - sinT2, 0.0f));
    const F rs = (ci - eta * ct) / max(ci + eta * ct, 1e-7f);
    const F rp = (ct - eta * ci) / max(ct + eta * ci, 1e-7f);
    const F one = lanes<F>(1.0f);
    return {select(sinT2 > 1.0f, one, rs * rs), select(sinT2 > 1.0f, one, rp * rp)};
}

// Exact Fresnel reflectance of unpolarised light at a dielectric interface (Cook & Torrance 1982):
//   g = √(η² − 1 + c²), F = ½ ((g − c)/(g + c))² (1 + ((c(g + c) − 1)/(c(g − c) + 1))²), c = cos θ,
// and total internal reflection (η² − 1 + c² < 0) reflects everything: F = 1.
template <class F>
F fresnelExact(F cosTheta, float eta) {
    const F c = saturate(cosTheta);
    const F g2 = eta * eta - 1.0f + c * c;
    const F g = sqrt(max(g2, 0.0f));
    const F a = (g - c) / max(g + c, 1e-7f);
    const F b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
    return select(g2 < 0.0f, lanes<F>(1.0f), 0.5f * a * a * (1.0f + b * b));
}
template <class F, class V3 = LaneVec3<F>>
V3 fresnelExact(const vec3& f0, F cosTheta) {
    return V3(fresnelExact(cosTheta, etaFromF0(f0.x)), fresnelExact(cosTheta, etaFromF0(f0.y)),
              fresnelExact(cosTheta, etaFromF0(f0.z)));
}

// Anisotropic GGX (Walter et al. 2007 §5.2 as Burley 2012 app. B.2 writes it; RTR4 eq. 9.47), with t, b
// the unit tangent and bitangent of the surface's frame and α_x, α_y the roughnesses along them:
//   D(h) = 1/(π α_x α_y ((h·t/α_x)² + (h·b/α_y)² + (h·n)²)²) for n·h > 0, else 0.
// With α_x = α_y = α it is distributionGGX above.
template <class F>
F distributionGGXAnisotropic(F HdotT, F HdotB, F NdotH, float alphaX, float alphaY) {
    const F x = HdotT * (1.0f / alphaX);
    const F y = HdotB * (1.0f / alphaY);
    const F c = max(NdotH, 0.0f);
    const F denominator = x * x + y * y + c * c;
    const F d = 1.0f / (std::numbers::pi_v<float> * alphaX * alphaY * denominator * denominator);
    return select(NdotH > 0.0f, d, lanes<F>(0.0f));
}

// The roughnesses along the tangent and bitangent for anisotropy a (PbrMaterial::anisotropy):
// α_x = α(1 + a), α_y = α(1 − a) (Kulla & Conty 2017), each at least 1e−3 as alphaFromRoughness.
struct AnisotropicAlpha {
    float x, y;
};
inline AnisotropicAlpha anisotropicAlpha(float alpha, float anisotropy) {
    return {std::max(alpha * (1.0f + anisotropy), 1e-3f), std::max(alpha * (1.0f - anisotropy), 1e-3f)};
}

// Smith's masking for anisotropic GGX (Heitz 2014, eqs. 72 and 86): G1(ω) = 1/(1 + Λ(ω)),
//   Λ(ω) = (−1 + √(1 + (α_x² (ω·t)² + α_y² (ω·b)²)/(ω·n)²))/2,
// the separable G = G1(l)·G1(v). With α_x = α_y it is smithG1GGX below.
template <class F>
F smithG1GGXAnisotropic(F XdotT, F XdotB, F NdotX, float alphaX, float alphaY) {
    const F c = max(NdotX, 1e-7f);
    const F a2tan2 = (alphaX * alphaX * XdotT * XdotT + alphaY * alphaY * XdotB * XdotB) / (c * c);
    return 2.0f / (1.0f + sqrt(1.0f + a2tan2));
}

// The same for all three channels: a dielectric of index η.
template <class F, class V3 = LaneVec3<F>>
V3 fresnelExactOneEta(F cosTheta, float eta) {
    const F f = fresnelExact(cosTheta, eta);
    return V3(f, f, f);
}

// Cook-Torrance 1982: G = min(1, 2(n·h)(n·v)/(v·h), 2(n·h)(n·l)/(v·h)).
template <class F>
F geometryCookTorrance(F NdotH, F NdotV, F NdotL, F VdotH) {
    const F k = 2.0f * max(NdotH, 0.0f) / max(VdotH, 1e-4f);
    return min(min(k * NdotV, k * NdotL), lanes<F>(1.0f));
}

// Smith's separable masking-shadowing for GGX: G = G1(n·l) G1(n·v),
// G1(x) = 2(n·x) / ((n·x) + √(α² + (1 − α²)(n·x)²)).
template <class F>
F smithG1GGX(F NdotX, float alpha) {
    const float a2 = alpha * alpha;
    const F c = max(NdotX, 0.0f);
    return 2.0f * c / max(c + sqrt(a2 + (1.0f - a2) * c * c), 1e-7f);
}
template <class F>
F geometrySmithGGX(F NdotV, F NdotL, float alpha) {
    return smithG1GGX(NdotV, alpha) * smithG1GGX(NdotL, alpha);
}

// The BRDF (Cook & Torrance 1982; Karis 2013):
//   f(l, v) = (1 − F)(1 − metalness) · c_base/π + D·F·G / (4 (n·l)(n·v)),
// F0 = mix(F0_dielectric, c_base, metalness) (metals reflect their colour), and f = 0 where n·l ≤ 0.
// The model's fresnelCosine, denominator and metal choose the lecture notes' variants instead: F at n·l,
// π (n·l)(n·v), and F0 = F0_dielectric with the specular lobe times mix(1, c_base, metalness).
// n, l, v need not be unit; zero vectors give 0, never NaN.
// The two lobes of the BRDF apart: diffuse (1 − F)(1 − metalness)·albedo/π and specular D·F·G/(4 (n·l)(n·v)).
template <class V3>
struct BrdfLobes {
    V3 diffuse;
    V3 specular;
};

// The record of the BRDF at one point (record.h): the vectors, the cosines, D, F, G and the lobes.
struct BrdfRecord {
    static constexpr bool enabled = true;
    vec3 N{0.0f}, L{0.0f}, V{0.0f}, H{0.0f};  // unit; H = normalize(L + V)
    float NdotLRaw = 0;                       // N·L as it is
    float NdotL = 0, NdotV = 0;               // clamped to ≥ 1e−4 for the division
    float NdotH = 0, VdotH = 0;               // V·H clamped to [0, 1]
    float alpha = 0;                          // roughness²
    vec3 f0{0.0f};                            // mix(F0_dielectric, c_base, metalness)
    BrdfModel model{};
    float D = 0;
    float gaussianC = 0;  // the Gaussian distribution's normalisation c(m), m = α
    float thetaH = 0;     // the Gaussian distribution's θ_h = acos(N·H), radians
    vec3 F{0.0f};
    // Exact Fresnel: η per channel (the material's IOR, or recovered from F0) and the reflectances of
    // the two polarisations, F = (R_s + R_p)/2.
    vec3 eta{0.0f}, Rs{0.0f}, Rp{0.0f};
    float G = 0;
    // Anisotropic GGX (a tangent frame given and anisotropy ≠ 0): the frame, the roughnesses along T
    // and B, and the cosines D and Smith's G read.
    bool anisotropic = false;
    vec3 T{0.0f}, B{0.0f};
    float alphaX = 0, alphaY = 0;
    float HdotT = 0, HdotB = 0;
    float specularScale = 0;  // D·G/(k (N·L)(N·V)), k = 4 or π (model.denominator)
    float diffuseScale = 0;   // (1 − metalness)/π
    float fresnelCosine = 0;  // the cosine F was evaluated at: V·H or N·L (model.fresnelCosine)
    vec3 metalTint{1.0f};     // MetalBlend::TintedLobe: mix(1, c_base, metalness), times the specular lobe
    bool grazing = false;     // N·L ≤ kGrazingCosine: both lobes 0
    BrdfLobes<vec3> lobes{vec3(0.0f), vec3(0.0f)};
};

// `albedo` is the base colour the Lambert lobe reflects, per lane (a texture may vary it); F0 always
// comes from the material.
template <class F, class V3 = LaneVec3<F>, MathPrecision P = MathPrecision::Exact,
          Normalization kNormalization = Normalization::Exact, class... Recording>
BrdfLobes<V3> brdfLobes(const V3& n, const V3& l, const V3& v, const PbrMaterial& m, const V3& albedo,
                        const BrdfModel& model = {},
                        const TangentFrame<std::type_identity_t<V3>>* frame = nullptr,
                        Recording*... recording) {
    using Record = RecordOf<Recording...>;
    // The cosines, clamped away from the divisions' zeros.
    const V3 N = safeNormalize<F, V3, kNormalization>(n);
    const V3 L = safeNormalize<F, V3, kNormalization>(l);
    const V3 V = safeNormalize<F, V3, kNormalization>(v);
    const V3 H = safeNormalize<F, V3, kNormalization>(L + V);
    const F NdotLRaw = dot(N, L);
    const F NdotL = max(NdotLRaw, 1e-4f);
    const F NdotV = max(dot(N, V), 1e-4f);
    const F NdotH = dot(N, H);
    const F VdotH = saturate(dot(V, H));
    const float alpha = alphaFromRoughness(m.roughness);
    const vec3 f0 = model.metal == MetalBlend::F0 ? mix(m.f0, m.baseColor, m.metalness) : m.f0;

    // D, F, G. Anisotropic GGX where a tangent frame is given and the material asks for it (GGX only:
    // the other distributions stay isotropic).
    const bool anisotropic = frame && m.anisotropy != 0.0f && model.distribution == NormalDistribution::GGX;
    const AnisotropicAlpha alphas = anisotropicAlpha(alpha, m.anisotropy);
    const F HdotT = anisotropic ? dot(H, frame->T) : lanes<F>(0.0f);
    const F HdotB = anisotropic ? dot(H, frame->B) : lanes<F>(0.0f);
    const F D = anisotropic ? distributionGGXAnisotropic(HdotT, HdotB, NdotH, alphas.x, alphas.y)
                : model.distribution == NormalDistribution::GGX ? distributionGGX(NdotH, alpha)
                : model.distribution == NormalDistribution::Beckmann
                    ? distributionBeckmann<F, P>(NdotH, alpha)
                    : distributionGaussian<F, P>(NdotH, alpha);
    // F at V·H (the microfacet form) or at N·L (the lecture notes'), model.fresnelCosine.
    const F cosTheta = model.fresnelCosine == FresnelCosine::VdotH ? VdotH : NdotL;
    // A dielectric given its IOR: the exact term with η itself, else η recovered from F0 per channel.
    const bool exactWithIor = m.ior > 0.0f && m.metalness == 0.0f;
    const V3 fresnel = model.fresnel == FresnelModel::Schlick ? fresnelSchlick<F, V3>(f0, cosTheta)
                       : exactWithIor                         ? fresnelExactOneEta<F, V3>(cosTheta, m.ior)
                                                              : fresnelExact<F, V3>(f0, cosTheta);
    const F G = model.geometry != GeometryTerm::SmithGGX ? geometryCookTorrance(NdotH, NdotV, NdotL, VdotH)
                : anisotropic
                    ? smithG1GGXAnisotropic(dot(L, frame->T), dot(L, frame->B), NdotL, alphas.x, alphas.y) *
                          smithG1GGXAnisotropic(dot(V, frame->T), dot(V, frame->B), NdotV, alphas.x, alphas.y)
                    : geometrySmithGGX(NdotV, NdotL, alpha);

    // Diffuse and specular lobes, nothing where the light is behind the surface.
    const F specularScale = D * G / (microfacetConstant(model.denominator) * NdotL * NdotV);
    V3 specular = fresnel * specularScale;
    // lighting-deck-C.txt: metalness·(spec ⊗ c_base) + (1 − metalness)·spec = spec ⊗ mix(1, c_base,
    // metalness).
    if (model.metal == MetalBlend::TintedLobe)
        specular = specular * (V3(vec3(1.0f)) + (albedo - V3(vec3(1.0f))) * m.metalness);
    const float diffuseScale = (1.0f - m.metalness) / std::numbers::pi_v<float>;
    const V3 diffuse = (V3(vec3(1.0f)) - fresnel) * albedo * diffuseScale;
    const V3 zero(vec3(0.0f));
    if constexpr (Record::enabled)
        *recordOf(recording...) = {
            .N = N,
            .L = L,
            .V = V,
            .H = H,
            .NdotLRaw = NdotLRaw,
            .NdotL = NdotL,
            .NdotV = NdotV,
            .NdotH = NdotH,
            .VdotH = VdotH,
            .alpha = alpha,
            .f0 = f0,
            .model = model,
            .D = D,
            .F = fresnel,
            .G = G,
            .specularScale = specularScale,
            .diffuseScale = diffuseScale,
            .fresnelCosine = cosTheta,
            .metalTint = model.metal == MetalBlend::TintedLobe
                             ? vec3(1.0f) + (vec3(albedo) - vec3(1.0f)) * m.metalness
                             : vec3(1.0f),
            .grazing = !(NdotLRaw > kGrazingCosine),
            .lobes = brdfLobes<F, V3, P, kNormalization>(n, l, v, m, albedo, model, frame)};
    if constexpr (Record::enabled) {
        BrdfRecord& r = *recordOf(recording...);
        if (anisotropic) {
            r.anisotropic = true;
            r.T = frame->T;
            r.B = frame->B;
            r.alphaX = alphas.x;
            r.alphaY = alphas.y;
            r.HdotT = HdotT;
            r.HdotB = HdotB;
        }
        if (model.distribution == NormalDistribution::Gaussian) {
            r.gaussianC = gaussianNormalization(alpha);
            r.thetaH = angleFromCosine(std::clamp(float(NdotH), 0.0f, 1.0f));
        }
        if (model.fresnel == FresnelModel::Exact) {
            r.eta = exactWithIor ? vec3(m.ior) : vec3(etaFromF0(f0.x), etaFromF0(f0.y), etaFromF0(f0.z));
            for (int i = 0; i < 3; ++i) {
                const FresnelPolarized<float> p = fresnelPolarized(float(cosTheta), r.eta[i]);
                r.Rs[i] = p.s;
                r.Rp[i] = p.p;
            }
        }
    }
    return {select(NdotLRaw > kGrazingCosine, diffuse, zero),
            select(NdotLRaw > kGrazingCosine, specular, zero)};
}

template <class F, class V3 = LaneVec3<F>, MathPrecision P = MathPrecision::Exact,
          Normalization kNormalization = Normalization::Exact>
V3 brdf(const V3& n, const V3& l, const V3& v, const PbrMaterial& m, const BrdfModel& model = {}) {
    const BrdfLobes<V3> lobes = brdfLobes<F, V3, P, kNormalization>(n, l, v, m, V3(m.baseColor), model);
    return lobes.diffuse + lobes.specular;
}

// Outgoing radiance from punctual lights: L_o = Σ f(l, v) ⊗ (π c_light) · falloff · spot · max(n·l, 0),
// c_light = the light's l_d, π c_light the incoming radiance scaled so that a white Lambertian surface
// lit head-on shows c_light (Hoffman 2013), falloff = physicalFalloff: 1/r² for point and spot lights
// (1/(c0 + c1·r + c2·r²) where the scene gave an attenuation), times the range's window, 1 for
// directional ones.
//
// As terms for the component images: the diffuse and specular lobes summed over the lights, plus
//   emission = m_emission and ambient = a_global ⊗ albedo
// (a constant stand-in for the light that arrives from everywhere, as the standard equation's
// a_global ⊗ m_ambient; image-based ambient is out of scope). `albedo` is the base colour per lane.
// `visibility` as in standardLighting: the share of each light that reaches the point scales its
// irradiance (null: all of it). With a LightingRecord, LightRecord::attenuation is the falloff and the
// irradiance factor falloff·spot·max(N·L, 0), incoming π·c_light and the BRDF's numbers are recorded per
// light.
template <class F, class V3 = LaneVec3<F>, MathPrecision P = MathPrecision::Exact,
          Normalization kNormalization = Normalization::Exact, class... Recording>
LightingTerms<V3> physicallyBasedTerms(const V3& position, const V3& normal, const vec3& eye,
                                       const PbrMaterial& m, const V3& albedo, const vec3& emission,
                                       const vec3& globalAmbient, std::span<const LightParams> lights,
                                       const BrdfModel& model = {}, const F* visibility = nullptr,
                                       const std::type_identity_t<V3>* tangent = nullptr,
                                       Recording*... recording) {
    using Record = RecordOf<Recording...>;
    static_assert(!Record::enabled || std::is_same_v<F, float>, "records hold one lane");
    const V3 N = safeNormalize<F, V3, kNormalization>(normal);
    const V3 V = safeNormalize<F, V3, kNormalization>(eye - position);
    // Anisotropic GGX: the tangent (along ∂P/∂u, tangent.h) made an orthonormal frame about N.
    TangentFrame<V3> frame;
    const bool anisotropic = tangent && m.anisotropy != 0.0f;
    if (anisotropic) frame = orthonormalTangentFrame<F, V3>(N, *tangent);
    LightingTerms<V3> terms{V3(emission), albedo * globalAmbient, V3(vec3(0.0f)), V3(vec3(0.0f))};
    if constexpr (Record::enabled)
        *recordOf(recording...) = {.physicallyBased = true,
                                   .position = position,
                                   .normal = normal,
                                   .N = N,
                                   .V = V,
                                   .materialAmbient = albedo,
                                   .materialDiffuse = albedo,
                                   .pbr = m,
                                   .brdf = model,
                                   .globalAmbient = globalAmbient,
                                   .globalAmbientTerm = terms.ambient,
                                   .lightCount = static_cast<int>(lights.size())};
    for (const LightParams& light : lights) {
        const LightVector<F, V3> toLight = lightVector<F, V3, kNormalization>(light, position);
        const F falloff = physicalFalloff(light, toLight.distance);
        F irradiance =
            falloff *
            spotFactor<F, V3, P>(light, toLight.L, &recording->lights[&light - lights.data()].spot...) *
            max(dot(N, toLight.L), 0.0f);
        if (visibility) irradiance = irradiance * visibility[&light - lights.data()];
        const BrdfLobes<V3> lobes = brdfLobes<F, V3, P, kNormalization>(
            N, toLight.L, V, m, albedo, model, anisotropic ? &frame : nullptr,
            &recording->lights[&light - lights.data()].brdf...);
        const V3 incoming = V3(light.diffuse * std::numbers::pi_v<float>) * irradiance;
        const V3 diffuse = lobes.diffuse * incoming;
        terms.diffuse += diffuse;
        const V3 specular = lobes.specular * incoming;
        terms.specular += specular;
        if constexpr (Record::enabled) {
            auto& r = recordOf(recording...)->lights[&light - lights.data()];
            r.light = light;
            r.L = toLight.L;
            r.distance = toLight.distance;
            LightParams unwindowed = light;
            unwindowed.range = 0.0f;
            r.attenuation = physicalFalloff(unwindowed, toLight.distance);
            r.window = rangeWindow(light, toLight.distance);
            r.reach = irradiance;
            r.visibility = visibility ? visibility[&light - lights.data()] : 1.0f;
            r.shadowTested = visibility != nullptr;
            r.NdotL = dot(N, toLight.L);
            r.grazing = r.brdf.grazing;
            r.incoming = incoming;
            r.diffuse = diffuse;
            r.specular = specular;
        }
    }
    if constexpr (Record::enabled) recordOf(recording...)->terms = terms;
    return terms;
}

// ---- The record of one point's lighting (record.h), for the step mode's screens ---------------------

// One light's part in the lighting at a point.
struct LightRecord {
    LightParams light{};  // kind, position or direction, c0 c1 c2, spot settings, l_a l_d l_s
    vec3 L{0.0f};         // unit, towards the light
    float distance = 0;
    // Standard equation: att = 1/(c0 + c1·d + c2·d²). Cook-Torrance: the falloff 1/d² (1: directional).
    float attenuation = 1;
    // f_win(d): the range's window, which multiplies the attenuation (1: no range).
    float window = 1;
    SpotRecord spot{};
    // Standard equation: att·spot. Cook-Torrance: the irradiance factor falloff·spot·max(N·L, 0)·v.
    float reach = 1;
    float visibility = 1;       // v: the share of the light that reaches the point (shadows); 1 without
    bool shadowTested = false;  // some light of the scene casts shadows: v was computed
    float NdotL = 0;
    // Standard equation's specular: R = 2(N·L)N − L (Phong) or H = normalize(L + V) (Blinn-Phong), the
    // cosine R·V or N·H, and spec = max(cosine, 0)^n, 0 when grazing (N·L ≤ kGrazingCosine).
    vec3 reflected{0.0f};
    float cosine = 0;
    bool grazing = false;
    float spec = 0;
    BrdfRecord brdf{};    // Cook-Torrance
    vec3 incoming{0.0f};  // Cook-Torrance: π·c_light·irradiance factor
    vec3 ambient{0.0f};   // this light's terms: att·spot·l_a⊗m_a (0 for Cook-Torrance)
    vec3 diffuse{0.0f};   // att·spot·max(N·L,0)·l_d⊗m_d, or f_diffuse ⊗ incoming
    vec3 specular{0.0f};  // att·spot·spec·l_s⊗m_s, or f_specular ⊗ incoming
};

// Everything standardLighting or physicallyBasedTerms computed at one point.
struct LightingRecord {
    static constexpr bool enabled = true;
    bool physicallyBased = false;  // Cook-Torrance; else the standard equation with specularModel
    SpecularModel specularModel = SpecularModel::BlinnPhong;
    vec3 position{0.0f};         // P
    vec3 normal{0.0f};           // N as given
    vec3 N{0.0f};                // normalised
    vec3 V{0.0f};                // normalize(eye − P)
    vec3 materialAmbient{0.0f};  // m_ambient (Cook-Torrance: c_base)
    vec3 materialDiffuse{0.0f};  // m_diffuse or c_base, textured
    vec3 materialSpecular{0.0f};
    float shininess = 0;  // n
    BlinnExponent blinnExponent = BlinnExponent::Given;
    float specularExponent = 0;  // what the cosine is raised to: n, or Blinn-Phong's e′ = 4n when matched
    PbrMaterial pbr{};           // Cook-Torrance
    BrdfModel brdf{};
    vec3 globalAmbient{0.0f};
    vec3 globalAmbientTerm{0.0f};  // a_global ⊗ m_ambient
    int lightCount = 0;
    std::array<LightRecord, kMaxLights> lights{};
    LightingTerms<vec3> terms{vec3(0.0f), vec3(0.0f), vec3(0.0f), vec3(0.0f)};  // the result
};

// The reflected light alone (no emission, no ambient), the material's own base colour.
template <class F, class V3 = LaneVec3<F>, MathPrecision P = MathPrecision::Exact>
V3 physicallyBasedLighting(const V3& position, const V3& normal, const vec3& eye, const PbrMaterial& m,
                           std::span<const LightParams> lights, const BrdfModel& model = {}) {
    const LightingTerms<V3> terms = physicallyBasedTerms<F, V3, P>(position, normal, eye, m, V3(m.baseColor),
                                                                   vec3(0.0f), vec3(0.0f), lights, model);
    return terms.diffuse + terms.specular;
}

// ---- Material presets -------------------------------------------------------------------------------

struct MaterialPreset {
    std::string_view name;
    vec3 f0;     // reflectance at normal incidence, linear RGB
    bool metal;  // true: use as base colour with metalness 1; false: a dielectric's F0
    // A dielectric the table gives as a range: its ends (f0 is their midpoint); 0, 0 for one value.
    float low = 0, high = 0;
};

// F0 values from Real-Time Rendering, 4th ed. (Akenine-Möller et al. 2018): dielectrics from table 9.1,
// metals (linear RGB) from table 9.2 (lighting-deck-C.txt shows both). A row the table gives as a range
// takes its midpoint; "plastic" and "glass" are the one row "plastics, glass", "eyes" the dry cornea.
inline const std::array<MaterialPreset, 26> kMaterialPresets{{
    {"water", vec3(0.02f), false},
    {"living-tissue", vec3(0.03f), false, 0.02f, 0.04f},
    {"skin", vec3(0.028f), false},
    {"eyes", vec3(0.025f), false},
    {"hair", vec3(0.046f), false},
    {"teeth", vec3(0.058f), false},
    {"fabric", vec3(0.048f), false, 0.04f, 0.056f},
    {"stone", vec3(0.0455f), false, 0.035f, 0.056f},
    {"plastic", vec3(0.045f), false, 0.04f, 0.05f},
    {"glass", vec3(0.045f), false, 0.04f, 0.05f},
    {"crystal-glass", vec3(0.06f), false, 0.05f, 0.07f},
    {"gems", vec3(0.065f), false, 0.05f, 0.08f},
    {"diamond", vec3(0.165f), false, 0.13f, 0.2f},
    {"titanium", vec3(0.542f, 0.497f, 0.449f), true},
    {"chromium", vec3(0.549f, 0.556f, 0.554f), true},
    {"iron", vec3(0.562f, 0.565f, 0.578f), true},
    {"nickel", vec3(0.660f, 0.609f, 0.526f), true},
    {"platinum", vec3(0.673f, 0.637f, 0.585f), true},
    {"copper", vec3(0.955f, 0.638f, 0.538f), true},
    {"palladium", vec3(0.733f, 0.697f, 0.652f), true},
    {"mercury", vec3(0.781f, 0.780f, 0.778f), true},
    {"brass", vec3(0.910f, 0.778f, 0.423f), true},
    {"zinc", vec3(0.664f, 0.824f, 0.850f), true},
    {"gold", vec3(1.000f, 0.782f, 0.344f), true},
    {"aluminium", vec3(0.913f, 0.922f, 0.924f), true},
    {"silver", vec3(0.972f, 0.960f, 0.915f), true},
}};

// The preset of that name, ignoring case ("aluminum" is accepted too); nullopt for an unknown name.
inline std::optional<MaterialPreset> findMaterialPreset(std::string_view name) {
    const auto equalIgnoringCase = [](std::string_view a, std::string_view b) {
        return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
                   return std::tolower(static_cast<unsigned char>(x)) ==
                          std::tolower(static_cast<unsigned char>(y));
               });
    };
    if (equalIgnoringCase(name, "aluminum")) name = "aluminium";
    for (const MaterialPreset& preset : kMaterialPresets)
        if (equalIgnoringCase(name, preset.name)) return preset;
    return std::nullopt;
}

}  // namespace facet
