// The built-in shaders of `facet render`: the lighting models of lighting.h (Phong, Blinn-Phong,
// Cook-Torrance) at the three shading frequencies of the lectures:
//   SurfaceShader<ShadingFrequency::Phong>    the normal interpolated, lighting per pixel;
//   SurfaceShader<ShadingFrequency::Gouraud>  lighting per vertex, the colour interpolated;
//   SurfaceShader<ShadingFrequency::Flat>     lighting per vertex, the provoking vertex's colour on the
//                                             whole triangle (a flat varying).
// Lighting happens in eye space: the eye is at the origin, V = normalize(−P) (a local viewer).
//
// Each shader's fragment shader, and the per-vertex shaders' vertex lighting, is one body written over
// the lane type F (float: one fragment; Float8: eight), its Varyings one template VaryingsT<F>;
// LaneShader (pipeline/shader.h) makes the pipeline's fragment/fragmentBatch/vertexBatch of it. The
// precision of pow and exp is the draw's choice, SurfaceUniforms::precision, not the lane width's.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string_view>

#include "pipeline/names.h"
#include "pipeline/shader.h"
#include "pipeline/state.h"
#include "pipeline/texture.h"
#include "pipeline/wide.h"
#include "scene/mesh.h"
#include "shaders/shadowing.h"
#include "shading/environment.h"
#include "shading/fog.h"
#include "shading/lighting.h"
#include "shading/two_sided.h"

namespace facet {

// The terms of the lighting equation, as bits, to draw some of them alone (the component images).
enum LightingTerm : std::uint8_t {
    kEmissionTerm = 1,
    kAmbientTerm = 2,
    kDiffuseTerm = 4,
    kSpecularTerm = 8,
    kAllTerms = 15,
};
// The terms by the names the command line uses (--only, --components), in the order component images
// are written; kAllTerms, their sum, is the main image and has no name.
inline constexpr EnumName<LightingTerm> kLightingTermNames[] = {{kEmissionTerm, "emission"},
                                                                {kAmbientTerm, "ambient"},
                                                                {kDiffuseTerm, "diffuse"},
                                                                {kSpecularTerm, "specular"}};
constexpr std::span<const EnumName<LightingTerm>> enumNames(LightingTerm) {
    return kLightingTermNames;
}

struct SurfaceUniforms {
    mat4 clipFromObject{1.0f};
    mat4 viewFromObject{1.0f};
    mat3 normalFromObject{1.0f};  // transpose(inverse(mat3(viewFromObject)))
    vec3 globalAmbient{0.0f};     // a_global, linear
    int lightCount = 0;
    std::array<LightParams, kMaxLights> lights{};  // eye space
    ReflectionModel reflection = ReflectionModel::BlinnPhong;
    BrdfModel brdf;
    PhongMaterial material;  // the standard equation's; its emission is Cook-Torrance's too
    PbrMaterial pbr;         // Cook-Torrance's
    // The diffuse colour (m_diffuse, or Cook-Torrance's albedo c_base) is multiplied by this texture:
    // before lighting when lighting per pixel; per vertex, the interpolated diffuse term is.
    const Texture* diffuseMap = nullptr;
    // The emission term (m_emission) is multiplied by this texture's colour (MTL map_Ke), per pixel at
    // every shading frequency: per vertex, the emission is left out of the vertex colours and added
    // in the fragment, textured.
    const Texture* emissionMap = nullptr;
    // The size of a pixel in eye space (x rightwards, y down the rows), per unit of depth when
    // `perspective`, else the size itself: (2/(P₀₀·width), 2/(P₁₁·height)) of the projection P. An
    // anisotropic draw finds its tangent from the uv derivatives and these (tangent.h).
    vec2 pixelSpread{0.0f};
    bool perspective = true;
    // How both maps are filtered. Trilinear reads the fragment's uv derivatives (the back end computes
    // them for such a draw only: usesDerivatives) and the maps' mip chains (built by prepareScene).
    TextureFilter textureFilter = TextureFilter::Bilinear;
    // The footprint of one shading sample, in pixels per side: 1, or 1/√N under ssaaN, whose N passes
    // each sample 1/N of the pixel. Trilinear scales the uv derivatives by it, so that it picks the level
    // for the samples' spacing (λ lowered by ½·log2 N), as a frame drawn at √N times the size would;
    // with the level for a whole pixel, the average of the passes would filter the texture twice.
    float textureFootprint = 1.0f;
    // Constant shading (ShadingFrequency::Constant, drawn by the flat shader): no lighting; surfaceTerms
    // gives the diffuse colour (m_diffuse or c_base, textured as the diffuse term is) as the diffuse term
    // and m_emission as the emission, nothing else.
    bool unlit = false;
    bool twoSidedFlip = true;  // light the side of a surface that faces the viewer (N·V < 0: N = −N)
    // Instead of the flip: where N·V < 0 the viewer sees the surface's underside and N·V is clamped to 0,
    // so no light of the lights reaches the viewer: diffuse and specular 0 (lighting-deck-A.txt).
    bool clampNdotV = false;
    bool clampColor = false;  // clamp lit colours to [0, 1] (per vertex before interpolation), as OpenGL 1.x
    std::uint8_t terms = kAllTerms;        // LightingTerm bits: which terms reach the image
    float opacity = 1.0f;                  // α, times the diffuse map's alpha when there is one
    FogParams fog;                         // applied to the lit colour, before the blend's output form
    BlendMode blend = BlendMode::Replace;  // the draw's blend, which decides the output form (surfaceOutput)
    // pow and exp in the lighting and fog: Fast (wide.h's polynomials) is what every image has been
    // drawn with; one lane and eight give the same bits under either choice.
    MathPrecision precision = MathPrecision::Fast;
    // How the lighting makes N, L, V and H unit length (wide.h): Exact, 1/sqrt, is what every image has
    // been drawn with; Fast approximates the reciprocal square root.
    Normalization normalization = Normalization::Exact;
    // Which lights cast shadows and how (shadowing.h); null: none does, and the lighting skips the test.
    const SceneShadows* shadows = nullptr;
    // The environment map's mirror reflection (shading/environment.h), added to the lit colour with the
    // specular term's selection; environment.map null: none (one branch per batch).
    EnvironmentParams environment;

    std::span<const LightParams> activeLights() const {
        return {lights.data(), static_cast<std::size_t>(lightCount)};
    }
    vec3 albedo() const {
        return reflection == ReflectionModel::CookTorrance ? pbr.baseColor : material.diffuse;
    }
    // Anisotropic GGX: Cook-Torrance with anisotropy ≠ 0 (lit per pixel: it needs a tangent frame).
    bool anisotropic() const {
        return reflection == ReflectionModel::CookTorrance && pbr.anisotropy != 0.0f && !unlit;
    }
    // The emission term as the selected terms have it, before its texture.
    vec3 emissionTerm() const { return (terms & kEmissionTerm) ? material.emission : vec3(0.0f); }
    // Whether the environment's reflection is added (a map, and the specular term selected).
    bool reflectsEnvironment() const { return environment.map && (terms & kSpecularTerm); }
};

// The environment's reflection at eye-space P with normal N (environment.h): Cook-Torrance surfaces
// weighted by Schlick's Fresnel with the material's F0 = mix(F0, c_base, metalness), the standard
// equation's by m_specular.
template <class F, class V3 = LaneVec3<F>, class... Recording>
V3 environmentTerm(const SurfaceUniforms& u, const V3& P, const V3& N, unsigned liveLanes,
                   Recording*... recording) {
    if (u.reflection == ReflectionModel::CookTorrance) {
        const vec3 f0 = mix(u.pbr.f0, u.pbr.baseColor, u.pbr.metalness);
        return environmentReflection<F, V3>(u.environment, P, N, u.twoSidedFlip, &f0, vec3(0.0f), liveLanes,
                                            recording...);
    }
    return environmentReflection<F, V3>(u.environment, P, N, u.twoSidedFlip, nullptr, u.material.specular,
                                        liveLanes, recording...);
}

// ---- Records of one fragment's shading (shading/record.h), for the step mode ------------------------

// surfaceTerms at one point: the normal and its two-sided flip, the lighting, the terms selected.
struct SurfaceTermsRecord {
    static constexpr bool enabled = true;
    vec3 position{0.0f};     // P, eye space
    vec3 normal{0.0f};       // N as it came (interpolated, or the vertex's), not unit length
    bool flipped = false;    // the two-sided flip turned it: N·V < 0, so N = −N
    bool underside = false;  // clampNdotV: N·V < 0, so the diffuse and specular terms are 0
    bool unlit = false;      // constant shading: no lighting, terms = (m_emission, 0, albedo, 0)
    ReflectionModel reflection = ReflectionModel::BlinnPhong;
    LightingRecord lighting{};
    std::uint8_t selectedTerms = kAllTerms;  // LightingTerm bits; the others were set to 0
    LightingTerms<vec3> terms{vec3(0.0f), vec3(0.0f), vec3(0.0f), vec3(0.0f)};  // after the selection
};

// surfaceOutput: fog, then the form the blend expects.
struct OutputRecord {
    static constexpr bool enabled = true;
    vec3 color{0.0f};  // the lit colour c
    float alpha = 1;   // α
    FogRecord fog{};
    BlendMode blend = BlendMode::Replace;
    vec3 output{0.0f};  // c_p, α·c_p or mix(1, c_p, α)
};

// A surface shader's fragment function (shade<float>) at one fragment.
struct FragmentRecord {
    static constexpr bool enabled = true;
    bool perPixel = true;  // lit here (Phong shading); else the colour came from the vertices
    vec2 uv{0.0f};
    float opacity = 1;           // the material's α
    bool diffuseMapped = false;  // a diffuse map tinted the diffuse colour and α
    vec4 diffuseTexel{1.0f};
    bool emissionMapped = false;  // an emission map tinted the emission
    vec4 emissionTexel{1.0f};
    float alpha = 1;  // opacity · the diffuse texel's α
    // Lit per pixel: the albedo (m_diffuse or c_base) before and after the texel, the lighting, the
    // emission after its texel, the sum of the terms and whether it was clamped to [0, 1].
    vec3 materialAlbedo{0.0f};
    vec3 albedo{0.0f};
    SurfaceTermsRecord lighting{};
    vec3 emission{0.0f};
    EnvironmentRecord environment{};  // the environment's reflection (used: a map), in the sum
    vec3 sum{0.0f};
    bool clamped = false;
    // Lit per vertex: the interpolated (or flat) parts, then with the texels: modulated ⊗ texel and
    // added + m_emission ⊗ emission texel.
    vec3 modulatedIn{0.0f};
    vec3 addedIn{0.0f};
    vec3 modulated{0.0f};
    vec3 added{0.0f};
    vec3 color{0.0f};  // the colour handed to surfaceOutput
    OutputRecord output{};
    vec4 result{0.0f};  // the fragment shader's output, recorded by the caller (shade returns it)
};

// The vertex lighting (lightVertex<float>) at one vertex.
struct VertexLightingRecord {
    static constexpr bool enabled = true;
    vec3 position{0.0f};  // eye space
    vec3 normal{0.0f};
    vec2 uv{0.0f};
    SurfaceTermsRecord lighting{};
    bool emissionDeferred = false;    // an emission map: the emission is added per fragment instead
    bool clamped = false;             // clampColor: the sum clamped to [0, 1], all of it modulated
    EnvironmentRecord environment{};  // the environment's reflection (used: a map), in the sum
    vec3 sum{0.0f};                   // the terms' sum
    vec3 modulated{0.0f};             // the varyings it hands on, recorded by the caller
    vec3 added{0.0f};
};

// The lighting equation's terms at one point (or eight), as the uniforms choose: the model, the
// two-sided flip, and only the selected terms (the others are zero). P and N are in eye space; N need
// not be unit length. `albedo` is m_diffuse or c_base, per lane. kPrecision is u.precision and
// kNormalization u.normalization (surfaceTerms below chooses them). A SurfaceTermsRecord, when given,
// receives every number.
template <class F, class V3, MathPrecision kPrecision, Normalization kNormalization, class... Recording>
[[gnu::always_inline]] inline LightingTerms<V3> surfaceTermsWith(const V3& P, const V3& normal,
                                                                 const V3& albedo, const SurfaceUniforms& u,
                                                                 const V3* tangent, Recording*... recording) {
    using Record = RecordOf<Recording...>;
    if constexpr (Record::enabled)
        *recordOf(recording...) = {
            .position = P, .normal = normal, .reflection = u.reflection, .selectedTerms = u.terms};
    if (u.unlit) {  // constant shading: the unlit colour, albedo + emission
        const V3 zero(vec3(0.0f));
        const LightingTerms<V3> t{V3(u.emissionTerm()), zero, (u.terms & kDiffuseTerm) ? albedo : zero, zero};
        if constexpr (Record::enabled) {
            recordOf(recording...)->unlit = true;
            recordOf(recording...)->terms = t;
        }
        return t;
    }
    V3 N = normal;
    if (u.twoSidedFlip) {
        const auto facingAway = seesUnderside(N, P);
        N = select(facingAway, -N, N);
        if constexpr (Record::enabled) recordOf(recording...)->flipped = facingAway;
    }
    const vec3 eye(0.0f);
    // Shadows: each light's share that reaches P (null: all of every light).
    F visibilities[kMaxLights];
    const F* visibility = nullptr;
    if (u.shadows) {
        lightVisibilities<F, V3>(*u.shadows, u.activeLights(), P, N, visibilities);
        visibility = visibilities;
    }
    LightingTerms<V3> t;
    switch (u.reflection) {
        case ReflectionModel::Phong:
            t = standardLighting<F, V3, kPrecision, kNormalization>(
                P, N, eye, u.material, albedo, u.globalAmbient, u.activeLights(), SpecularModel::Phong,
                visibility, &recording->lighting...);
            break;
        case ReflectionModel::BlinnPhong:
            t = standardLighting<F, V3, kPrecision, kNormalization>(
                P, N, eye, u.material, albedo, u.globalAmbient, u.activeLights(),
                SpecularFormula(SpecularModel::BlinnPhong, u.brdf.blinnExponent), visibility,
                &recording->lighting...);
            break;
        case ReflectionModel::CookTorrance:
            t = physicallyBasedTerms<F, V3, kPrecision, kNormalization>(
                P, N, eye, u.pbr, albedo, u.material.emission, u.globalAmbient, u.activeLights(), u.brdf,
                visibility, tangent, &recording->lighting...);
            break;
    }
    if (u.clampNdotV) {
        // N·V clamped to 0: the lights' terms vanish where the viewer sees the underside.
        const auto underside = seesUnderside(N, P);
        const V3 zero(vec3(0.0f));
        t.diffuse = select(underside, zero, t.diffuse);
        t.specular = select(underside, zero, t.specular);
        if constexpr (Record::enabled) recordOf(recording...)->underside = underside;
    }
    if (u.terms != kAllTerms) {
        const V3 zero(vec3(0.0f));
        if (!(u.terms & kEmissionTerm)) t.emission = zero;
        if (!(u.terms & kAmbientTerm)) t.ambient = zero;
        if (!(u.terms & kDiffuseTerm)) t.diffuse = zero;
        if (!(u.terms & kSpecularTerm)) t.specular = zero;
    }
    if constexpr (Record::enabled) recordOf(recording...)->terms = t;
    return t;
}

// The same with the uniforms' choices: u.precision for pow and exp, u.normalization for the unit
// vectors. Both are the draw's, so the branch goes the same way for every fragment of it.
template <class F, class V3 = LaneVec3<F>, class... Recording>
[[gnu::always_inline]] inline LightingTerms<V3> surfaceTerms(const V3& P, const V3& normal, const V3& albedo,
                                                             const SurfaceUniforms& u, const V3* tangent,
                                                             Recording*... recording) {
    if (u.normalization == Normalization::Fast)
        return u.precision == MathPrecision::Exact
                   ? surfaceTermsWith<F, V3, MathPrecision::Exact, Normalization::Fast>(P, normal, albedo, u,
                                                                                        tangent, recording...)
                   : surfaceTermsWith<F, V3, MathPrecision::Fast, Normalization::Fast>(P, normal, albedo, u,
                                                                                       tangent, recording...);
    return u.precision == MathPrecision::Exact
               ? surfaceTermsWith<F, V3, MathPrecision::Exact, Normalization::Exact>(P, normal, albedo, u,
                                                                                     tangent, recording...)
               : surfaceTermsWith<F, V3, MathPrecision::Fast, Normalization::Exact>(P, normal, albedo, u,
                                                                                    tangent, recording...);
}

// The same without a tangent (every reflection model but anisotropic GGX, which then stays isotropic):
// what shaders of one's own call.
template <class F, class V3 = LaneVec3<F>>
[[gnu::always_inline]] inline LightingTerms<V3> surfaceTerms(const V3& P, const V3& normal, const V3& albedo,
                                                             const SurfaceUniforms& u) {
    return surfaceTerms<F, V3>(P, normal, albedo, u, static_cast<const V3*>(nullptr));
}

// What a surface shader writes, from the lit colour c and its alpha α at eye-space point P: fog first,
// c = f·c + (1 − f)·c_fog (fog.h), then the form the draw's blend expects:
//   Replace, Over:               (c, α)            straight alpha
//   PremultipliedOver, Additive: (α·c, α)          premultiplied (Additive: c_d + α·c)
//   Multiply:                    (mix(1, c, α), α)  a filter that is clear (1) where α = 0
template <class F, class V3 = LaneVec3<F>, class... Recording>
[[gnu::always_inline]] inline V3 surfaceOutput(V3 c, F alpha, const V3& P, const SurfaceUniforms& u,
                                               Recording*... recording) {
    using Record = RecordOf<Recording...>;
    if constexpr (Record::enabled) *recordOf(recording...) = {.color = c, .alpha = alpha, .blend = u.blend};
    c = u.precision == MathPrecision::Exact
            ? applyFog<F, V3, MathPrecision::Exact>(u.fog, c, P, &recording->fog...)
            : applyFog<F, V3, MathPrecision::Fast>(u.fog, c, P, &recording->fog...);
    if constexpr (Record::enabled) {
        OutputRecord& record = *recordOf(recording...);
        record.output = surfaceOutput<F, V3>(record.color, alpha, P, u);
        return record.output;
    }
    switch (u.blend) {
        case BlendMode::Replace:
        case BlendMode::Over:
        case BlendMode::OverGL:
            return c;
        case BlendMode::PremultipliedOver:
        case BlendMode::Additive:
            return c * alpha;
        case BlendMode::Multiply:
            return V3(vec3(1.0f)) + (c - V3(vec3(1.0f))) * alpha;
    }
    return c;
}

namespace detail {

// sample(uv, ∂uv/∂x, ∂uv/∂y) at each live lane (bit i of liveLanes: lane i holds a fragment; the others
// are opaque white and their uv, which may be anything, is not read). Double lanes (the reference)
// sample at float uv.
template <class F, class Sample>
[[gnu::always_inline]] inline LaneVec4<F> sampleLanes(const LaneVec2<F>& uv, unsigned liveLanes,
                                                      const TexCoordDerivativesT<F>& d, Sample sample) {
    if constexpr (LaneTraits<F>::kCount == 1) {
        return sample(vec2(uv), vec2(d.dx), vec2(d.dy));
    } else {
        LaneVec4<F> texel{lanes<F>(1.0f), lanes<F>(1.0f), lanes<F>(1.0f), lanes<F>(1.0f)};
        for (int lane = 0; lane < LaneTraits<F>::kCount; ++lane) {
            if (!((liveLanes >> lane) & 1)) continue;
            const vec4 t = sample(vec2(uv.x[lane], uv.y[lane]), vec2(d.dx.x[lane], d.dx.y[lane]),
                                  vec2(d.dy.x[lane], d.dy.y[lane]));
            texel.x[lane] = t.r;
            texel.y[lane] = t.g;
            texel.z[lane] = t.b;
            texel.w[lane] = t.a;
        }
        return texel;
    }
}

// A texture's texels at uv with the draw's filter, chosen once for all the lanes.
template <class F>
LaneVec4<F> texels(const Texture& map, const LaneVec2<F>& uv, unsigned liveLanes, TextureFilter filter,
                   float footprint, const TexCoordDerivativesT<F>& d) {
    switch (filter) {
        case TextureFilter::Nearest:
            return sampleLanes<F>(uv, liveLanes, d,
                                  [&](vec2 at, vec2, vec2) { return sampleNearest(map, at); });
        case TextureFilter::Trilinear:
            return sampleLanes<F>(uv, liveLanes, d, [&](vec2 at, vec2 dx, vec2 dy) {
                return sampleTrilinear(map, at, footprint * dx, footprint * dy);
            });
        case TextureFilter::Bilinear:
            if constexpr (LaneTraits<F>::kCount > 1) return sampleBilinear(map, uv, liveLanes);
            break;
    }
    return sampleLanes<F>(uv, liveLanes, d, [&](vec2 at, vec2, vec2) { return sampleBilinear(map, at); });
}

template <class V3>
V3 clamp01(const V3& c) {
    return V3(saturate(c.x), saturate(c.y), saturate(c.z));
}

}  // namespace detail

template <ShadingFrequency kFrequency>
struct SurfaceShader;

// Phong shading: the eye-space position and normal are interpolated; lighting per pixel.
struct PerPixelSurface {
    using Attributes = MeshVertex;
    using Uniforms = SurfaceUniforms;
    static constexpr bool kSixteenLanes = true;
    template <class F>
    struct VaryingsT {
        LaneVec3<F> position;  // eye space
        LaneVec3<F> normal;    // eye space, renormalised per pixel by the lighting
        LaneVec2<F> uv;
    };
    // The varyings' floats by name, in VaryingsT's order (the step mode's screens show them).
    static constexpr std::array<std::string_view, 8> kVaryingNames = {
        "P_eye.x", "P_eye.y", "P_eye.z", "N_eye.x", "N_eye.y", "N_eye.z", "u", "v"};
    // uv's derivatives (pipeline/shader.h), for trilinear filtering and for an anisotropic draw's
    // tangent frame (surfaceTangent).
    static constexpr int kDerivativeVarying = 6;
    static bool usesDerivatives(const Uniforms& u) {
        return u.textureFilter == TextureFilter::Trilinear || u.anisotropic();
    }

    static VertexOut<VaryingsT<float>> vertex(const Attributes& in, const Uniforms& u) {
        return {u.clipFromObject * vec4(in.position, 1.0f),
                {vec3(u.viewFromObject * vec4(in.position, 1.0f)), u.normalFromObject * in.normal, in.uv}};
    }

    // An anisotropic draw's tangent at the fragment, along ∂P/∂u (tangent.h): ∂P/∂x, ∂P/∂y from the
    // pixel's neighbours' view rays met with the plane normal to N, ∂(u, v)/∂x, ∂(u, v)/∂y from the
    // back end (exact, perspective-correct), t = (∂P/∂x·∂v/∂y − ∂P/∂y·∂v/∂x)/(∂u/∂x·∂v/∂y − ∂u/∂y·∂v/∂x),
    // the eye-space x axis projected where the texture coordinates give no tangent.
    template <class F>
    static LaneVec3<F> surfaceTangent(const VaryingsT<F>& in, const Uniforms& u,
                                      const TexCoordDerivativesT<F>& d) {
        using V3 = LaneVec3<F>;
        const ScreenDifferentials<V3> dP =
            screenDifferentials<F, V3>(in.position, in.normal, u.pixelSpread, u.perspective);
        return tangentFromDifferentials<F, V3>(dP.dPdx, dP.dPdy, d.dx.x, d.dx.y, d.dy.x, d.dy.y,
                                               fallbackTangent<F, V3>(in.normal));
    }

    // vertex() for eight vertices at once (the vertex stage's groups): each matrix row applied to eight
    // vertices in one pass. The same bits as vertex(), lane by lane: GLM computes M·v as
    // (M[0]·x + M[1]·y) + (M[2]·z + M[3]·w) and M·n as M[0]·x + M[1]·y + M[2]·z, and so does this.
    static void vertexBatch(const Attributes* in, const Uniforms& u, VertexOut<VaryingsT<float>>* out) {
        // A vertex is eight floats (position, normal, uv) and so are its varyings (eye position,
        // normal, uv): eight vertices in, eight out, each an 8×8 transpose.
        static_assert(sizeof(Attributes) == 8 * sizeof(float) &&
                      sizeof(VaryingsT<float>) == 8 * sizeof(float));
        static_assert(kVertexBatch == 8);
        Float8 field[8];  // vertex k's floats; transposed, float k of the eight vertices
        std::memcpy(field, in, sizeof field);
        transpose8x8(field);
        const Float8 &px = field[0], &py = field[1], &pz = field[2];
        const Float8 &nx = field[3], &ny = field[4], &nz = field[5];
        // Row r of M·(p, 1), with w = 1: M[3][r]·1 is M[3][r] exactly.
        auto point = [&](const mat4& m, int r) {
            return (m[0][r] * px + m[1][r] * py) + (m[2][r] * pz + m[3][r]);
        };
        auto direction = [&](const mat3& m, int r) { return m[0][r] * nx + m[1][r] * ny + m[2][r] * nz; };
        const Float8 clip[4] = {point(u.clipFromObject, 0), point(u.clipFromObject, 1),
                                point(u.clipFromObject, 2), point(u.clipFromObject, 3)};
        const Float8 eye[3] = {point(u.viewFromObject, 0), point(u.viewFromObject, 1),
                               point(u.viewFromObject, 2)};
        const Float8 normal[3] = {direction(u.normalFromObject, 0), direction(u.normalFromObject, 1),
                                  direction(u.normalFromObject, 2)};
        vec4 positions[kVertexBatch];
        storeTransposed({clip[0], clip[1], clip[2], clip[3]}, positions);
        Float8 varyings[8] = {eye[0], eye[1], eye[2], normal[0], normal[1], normal[2], field[6], field[7]};
        transpose8x8(varyings);  // row k: vertex k's varyings
        for (int lane = 0; lane < kVertexBatch; ++lane) {
            out[lane].position = positions[lane];
            std::memcpy(&out[lane].varyings, &varyings[lane], sizeof varyings[lane]);
        }
    }

    // A FragmentRecord, when given (F = float), receives every number of the shading. `uvDerivatives`:
    // for trilinear filtering; zero (a point) samples the maps' level 0.
    template <class F, class... Recording>
    static LaneVec4<F> shade(const VaryingsT<F>& in, const Uniforms& u, unsigned liveLanes,
                             const TexCoordDerivativesT<F>& uvDerivatives = {}, Recording*... recording) {
        return shadeWithTangent<F>(in, u, liveLanes, uvDerivatives, nullptr, recording...);
    }

    // shade with the tangent given (the reference's exact one, from the triangle's corners); null:
    // surfaceTangent's, for an anisotropic draw.
    template <class F, class... Recording>
    static LaneVec4<F> shadeWithTangent(const VaryingsT<F>& in, const Uniforms& u, unsigned liveLanes,
                                        const TexCoordDerivativesT<F>& uvDerivatives,
                                        const LaneVec3<F>* givenTangent, Recording*... recording) {
        using Record = RecordOf<Recording...>;
        using V3 = LaneVec3<F>;
        V3 albedo(u.albedo());
        F alpha = lanes<F>(u.opacity);
        if constexpr (Record::enabled)
            *recordOf(recording...) = {
                .perPixel = true, .uv = in.uv, .opacity = u.opacity, .materialAlbedo = albedo};
        if (u.diffuseMap) {
            const LaneVec4<F> texel = detail::texels<F>(*u.diffuseMap, in.uv, liveLanes, u.textureFilter,
                                                        u.textureFootprint, uvDerivatives);
            albedo = albedo * rgb(texel);
            alpha = alpha * texel.w;
            if constexpr (Record::enabled) {
                recordOf(recording...)->diffuseMapped = true;
                recordOf(recording...)->diffuseTexel = texel;
            }
        }
        V3 tangent;
        const V3* tangentUsed = givenTangent;
        if (u.anisotropic() && !givenTangent) {
            tangent = surfaceTangent<F>(in, u, uvDerivatives);
            tangentUsed = &tangent;
        }
        LightingTerms<V3> t =
            surfaceTerms<F>(in.position, in.normal, albedo, u, tangentUsed, &recording->lighting...);
        if (u.emissionMap) {
            const LaneVec4<F> texel = detail::texels<F>(*u.emissionMap, in.uv, liveLanes, u.textureFilter,
                                                        u.textureFootprint, uvDerivatives);
            t.emission = t.emission * rgb(texel);
            if constexpr (Record::enabled) {
                recordOf(recording...)->emissionMapped = true;
                recordOf(recording...)->emissionTexel = texel;
            }
        }
        V3 c = t.sum();
        if (u.reflectsEnvironment())
            c = c + environmentTerm<F>(u, in.position, in.normal, liveLanes, &recording->environment...);
        if constexpr (Record::enabled) recordOf(recording...)->sum = c;
        if (u.clampColor) c = detail::clamp01(c);
        if constexpr (Record::enabled) {
            auto& record = *recordOf(recording...);
            record.alpha = alpha;
            record.albedo = albedo;
            record.emission = t.emission;
            record.clamped = u.clampColor;
            record.color = c;
        }
        // The output (FragmentRecord::result) is the caller's to record: returned as an expression, it
        // is built in place.
        return withAlpha(surfaceOutput<F>(c, alpha, in.position, u, &recording->output...), alpha);
    }
};

template <>
struct SurfaceShader<ShadingFrequency::Phong> : LaneShader<PerPixelSurface> {};

// Lighting per vertex (Gouraud 1971). The colour travels in two parts so that a diffuse map can tint
// the diffuse light only: `modulated` (the diffuse term) is multiplied by the texel, `added`
// (emission + ambient + specular) is not. With clampColor (OpenGL 1.x) the clamped sum is modulated
// whole, as fixed function's GL_MODULATE does. With an emission map the emission is neither: it is
// added per fragment, m_emission ⊗ the emission texel. Flat shading is the same with the colour flat:
// the provoking vertex's colour fills the triangle.
template <ShadingFrequency kFrequency>
struct PerVertexSurface {
    using Attributes = MeshVertex;
    using Uniforms = SurfaceUniforms;
    static constexpr bool kSixteenLanes = true;
    template <class F>
    struct VaryingsT {
        LaneVec3<F> modulated;  // flat when kFrequency is Flat
        LaneVec3<F> added;      // flat when kFrequency is Flat
        LaneVec3<F> position;   // eye space, for fog
        LaneVec2<F> uv;
    };
    // The varyings' floats by name, in VaryingsT's order: c_mod multiplies the diffuse map, c_add is added.
    static constexpr std::array<std::string_view, 11> kVaryingNames = {
        "c_mod.r", "c_mod.g", "c_mod.b", "c_add.r", "c_add.g", "c_add.b",
        "P_eye.x", "P_eye.y", "P_eye.z", "u",       "v"};
    static constexpr int kFlatVaryingFloats = kFrequency == ShadingFrequency::Flat ? 6 : 0;
    // uv's derivatives, for trilinear filtering (pipeline/shader.h).
    static constexpr int kDerivativeVarying = 9;
    static bool usesDerivatives(const Uniforms& u) { return u.textureFilter == TextureFilter::Trilinear; }

    // What the vertex lighting reads: the vertex in eye space.
    template <class F>
    struct VertexInputsT {
        LaneVec3<F> position;
        LaneVec3<F> normal;  // not unit length
        LaneVec2<F> uv;
    };

    // The matrices, one vertex at a time (the eight-lane vertex shader too).
    static VertexOut<VertexInputsT<float>> vertexInputs(const Attributes& in, const Uniforms& u) {
        return {u.clipFromObject * vec4(in.position, 1.0f),
                {vec3(u.viewFromObject * vec4(in.position, 1.0f)), u.normalFromObject * in.normal, in.uv}};
    }

    // The lighting of one vertex or eight: isotropic always, anisotropy has no tangent frame here (a
    // vertex has its normal and uv but no derivatives of them; anisotropic GGX is lit per pixel). A
    // VertexLightingRecord, when given (F = float), receives
    // every number of it.
    template <class F, class... Recording>
    static VaryingsT<F> lightVertex(const VertexInputsT<F>& in, const Uniforms& u, Recording*... recording) {
        using Record = RecordOf<Recording...>;
        using V3 = LaneVec3<F>;
        LightingTerms<V3> t = surfaceTerms<F>(in.position, in.normal, V3(u.albedo()), u,
                                              static_cast<const V3*>(nullptr), &recording->lighting...);
        if (u.emissionMap) t.emission = V3(vec3(0.0f));  // added, textured, per fragment
        // The environment's reflection per vertex, with the specular term (interpolated as it is).
        if (u.reflectsEnvironment())
            t.specular =
                t.specular + environmentTerm<F>(u, in.position, in.normal, ~0u, &recording->environment...);
        if constexpr (Record::enabled) {
            auto& record = *recordOf(recording...);
            record.position = in.position;
            record.normal = in.normal;
            record.uv = in.uv;
            record.emissionDeferred = u.emissionMap != nullptr;
            record.clamped = u.clampColor;
            record.sum = t.sum();
        }
        // What it hands on (VertexLightingRecord::modulated, added) is the caller's to record.
        if (u.clampColor) return {detail::clamp01(t.sum()), V3(vec3(0.0f)), in.position, in.uv};
        return {t.diffuse, t.emission + t.ambient + t.specular, in.position, in.uv};
    }

    static VertexOut<VaryingsT<float>> vertex(const Attributes& in, const Uniforms& u) {
        const VertexOut<VertexInputsT<float>> prepared = vertexInputs(in, u);
        return {prepared.position, lightVertex<float>(prepared.varyings, u)};
    }

    // A FragmentRecord, when given (F = float), receives every number of the fragment's part.
    // `uvDerivatives`: for trilinear filtering; zero (a point) samples the maps' level 0.
    template <class F, class... Recording>
    static LaneVec4<F> shade(const VaryingsT<F>& in, const Uniforms& u, unsigned liveLanes,
                             const TexCoordDerivativesT<F>& uvDerivatives = {}, Recording*... recording) {
        using Record = RecordOf<Recording...>;
        using V3 = LaneVec3<F>;
        V3 modulated = in.modulated;
        F alpha = lanes<F>(u.opacity);
        if constexpr (Record::enabled)
            *recordOf(recording...) = {.perPixel = false,
                                       .uv = in.uv,
                                       .opacity = u.opacity,
                                       .modulatedIn = in.modulated,
                                       .addedIn = in.added};
        if (u.diffuseMap) {
            const LaneVec4<F> texel = detail::texels<F>(*u.diffuseMap, in.uv, liveLanes, u.textureFilter,
                                                        u.textureFootprint, uvDerivatives);
            modulated = modulated * rgb(texel);
            alpha = alpha * texel.w;
            if constexpr (Record::enabled) {
                recordOf(recording...)->diffuseMapped = true;
                recordOf(recording...)->diffuseTexel = texel;
            }
        }
        V3 added = in.added;
        if (u.emissionMap) {
            const LaneVec4<F> texel = detail::texels<F>(*u.emissionMap, in.uv, liveLanes, u.textureFilter,
                                                        u.textureFootprint, uvDerivatives);
            const V3 emission = V3(u.emissionTerm()) * rgb(texel);
            added = added + emission;
            if constexpr (Record::enabled) {
                recordOf(recording...)->emissionMapped = true;
                recordOf(recording...)->emissionTexel = texel;
                recordOf(recording...)->emission = emission;
            }
        }
        if constexpr (Record::enabled) {
            auto& record = *recordOf(recording...);
            record.alpha = alpha;
            record.modulated = modulated;
            record.added = added;
            record.color = modulated + added;
        }
        // The output (FragmentRecord::result) is the caller's to record.
        return withAlpha(surfaceOutput<F>(modulated + added, alpha, in.position, u, &recording->output...),
                         alpha);
    }
};

template <>
struct SurfaceShader<ShadingFrequency::Gouraud> : LaneShader<PerVertexSurface<ShadingFrequency::Gouraud>> {};
template <>
struct SurfaceShader<ShadingFrequency::Flat> : LaneShader<PerVertexSurface<ShadingFrequency::Flat>> {};

// A name for every float of the varyings: a varying added without its name fails to compile.
static_assert(PerPixelSurface::kVaryingNames.size() * sizeof(float) ==
              sizeof(PerPixelSurface::VaryingsT<float>));
static_assert(PerVertexSurface<ShadingFrequency::Gouraud>::kVaryingNames.size() * sizeof(float) ==
              sizeof(PerVertexSurface<ShadingFrequency::Gouraud>::VaryingsT<float>));

// The varyings' names of the surface shader of a shading frequency, in their order.
inline std::span<const std::string_view> varyingNamesOf(ShadingFrequency frequency) {
    switch (frequency) {
        case ShadingFrequency::Flat:
        case ShadingFrequency::Constant:
            return PerVertexSurface<ShadingFrequency::Flat>::kVaryingNames;
        case ShadingFrequency::Gouraud:
            return PerVertexSurface<ShadingFrequency::Gouraud>::kVaryingNames;
        case ShadingFrequency::Phong:
            break;
    }
    return PerPixelSurface::kVaryingNames;
}

}  // namespace facet
