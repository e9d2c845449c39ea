// The built-in shaders of `facet render`: the lighting models of lighting.h (Phong, Blinn-Phong,
// Cook-Torrance) at the three shading frequencies of the lectures:
//   SurfaceShader<ShadingFrequency::Phong>    the normal interpolated, lighting per pixel;
//   SurfaceShader<ShadingFrequency::Gouraud>  lighting per vertex, the colour interpolated;
//   SurfaceShader<ShadingFrequency::Flat>     lighting per vertex, the provoking vertex's colour on the
//                                             whole triangle (a flat varying).
// Lighting happens in eye space: the eye is at the origin, V = normalize(−P) (a local viewer).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "pipeline/shader.h"
#include "pipeline/state.h"
#include "pipeline/texture.h"
#include "pipeline/wide.h"
#include "scene/mesh.h"
#include "shading/fog.h"
#include "shading/lighting.h"

namespace facet {

// The terms of the lighting equation, as bits, to draw some of them alone (the component images).
enum LightingTerm : std::uint8_t {
    kEmissionTerm = 1,
    kAmbientTerm = 2,
    kDiffuseTerm = 4,
    kSpecularTerm = 8,
    kAllTerms = 15,
};

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
    bool twoSidedFlip = true;  // light the side of a surface that faces the viewer (N·V < 0: N = −N)
    bool clampColor = false;   // clamp lit colours to [0, 1] (per vertex before interpolation), as OpenGL 1.x
    std::uint8_t terms = kAllTerms;        // LightingTerm bits: which terms reach the image
    float opacity = 1.0f;                  // α, times the diffuse map's alpha when there is one
    FogParams fog;                         // applied to the lit colour, before the blend's output form
    BlendMode blend = BlendMode::Replace;  // the draw's blend, which decides the output form (surfaceOutput)

    std::span<const LightParams> activeLights() const {
        return {lights.data(), static_cast<std::size_t>(lightCount)};
    }
    vec3 albedo() const {
        return reflection == ReflectionModel::CookTorrance ? pbr.baseColor : material.diffuse;
    }
    // The emission term as the selected terms have it, before its texture.
    vec3 emissionTerm() const { return (terms & kEmissionTerm) ? material.emission : vec3(0.0f); }
};

// The lighting equation's terms at one point (or eight), as the uniforms choose: the model, the
// two-sided flip, and only the selected terms (the others are zero). P and N are in eye space; N need
// not be unit length. `albedo` is m_diffuse or c_base, per lane.
template <class F, class V3>
[[gnu::always_inline]] inline LightingTerms<V3> surfaceTerms(const V3& P, const V3& normal, const V3& albedo,
                                                             const SurfaceUniforms& u) {
    V3 N = normal;
    if (u.twoSidedFlip) N = select(dot(N, -P) < 0.0f, -N, N);
    const vec3 eye(0.0f);
    LightingTerms<V3> t;
    switch (u.reflection) {
        case ReflectionModel::Phong:
            t = standardLighting<F, V3>(P, N, eye, u.material, albedo, u.globalAmbient, u.activeLights(),
                                        SpecularModel::Phong);
            break;
        case ReflectionModel::BlinnPhong:
            t = standardLighting<F, V3>(P, N, eye, u.material, albedo, u.globalAmbient, u.activeLights(),
                                        SpecularModel::BlinnPhong);
            break;
        case ReflectionModel::CookTorrance:
            t = physicallyBasedTerms<F, V3>(P, N, eye, u.pbr, albedo, u.material.emission, u.globalAmbient,
                                            u.activeLights(), u.brdf);
            break;
    }
    if (u.terms != kAllTerms) {
        const V3 zero(vec3(0.0f));
        if (!(u.terms & kEmissionTerm)) t.emission = zero;
        if (!(u.terms & kAmbientTerm)) t.ambient = zero;
        if (!(u.terms & kDiffuseTerm)) t.diffuse = zero;
        if (!(u.terms & kSpecularTerm)) t.specular = zero;
    }
    return t;
}

// What a surface shader writes, from the lit colour c and its alpha α at eye-space point P: fog first,
// c = f·c + (1 − f)·c_fog (fog.h), then the form the draw's blend expects:
//   Replace, Over:               (c, α)            straight alpha
//   PremultipliedOver, Additive: (α·c, α)          premultiplied (Additive: c_d + α·c)
//   Multiply:                    (mix(1, c, α), α)  a filter that is clear (1) where α = 0
template <class F, class V3>
[[gnu::always_inline]] inline V3 surfaceOutput(V3 c, F alpha, const V3& P, const SurfaceUniforms& u) {
    c = applyFog<F, V3>(u.fog, c, P);
    switch (u.blend) {
        case BlendMode::Replace:
        case BlendMode::Over:
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

// A texture's texels for the batch's lanes (opaque white where the lane is empty).
inline Vec4x8 texels(const Texture& map, const Vec2x8& uv, unsigned mask) {
    Vec4x8 texel{splat(1.0f), splat(1.0f), splat(1.0f), splat(1.0f)};
    for (int lane = 0; lane < 8; ++lane) {
        if (!((mask >> lane) & 1)) continue;
        const vec4 t = sampleBilinear(map, vec2(uv.x[lane], uv.y[lane]));
        texel.x[lane] = t.r;
        texel.y[lane] = t.g;
        texel.z[lane] = t.b;
        texel.w[lane] = t.a;
    }
    return texel;
}

template <class V3>
V3 clamp01(const V3& c) {
    return V3(saturate(c.x), saturate(c.y), saturate(c.z));
}

}  // namespace detail

template <ShadingFrequency kFrequency>
struct SurfaceShader;

// Phong shading: the eye-space position and normal are interpolated; lighting per pixel.
template <>
struct SurfaceShader<ShadingFrequency::Phong> {
    using Attributes = MeshVertex;
    using Uniforms = SurfaceUniforms;
    struct Varyings {
        vec3 position;  // eye space
        vec3 normal;    // eye space, renormalised per pixel by the lighting
        vec2 uv;
    };

    static VertexOut<Varyings> vertex(const Attributes& in, const Uniforms& u) {
        return {u.clipFromObject * vec4(in.position, 1.0f),
                {vec3(u.viewFromObject * vec4(in.position, 1.0f)), u.normalFromObject * in.normal, in.uv}};
    }

    static vec4 fragment(const Varyings& in, const Uniforms& u) {
        vec3 albedo = u.albedo();
        float alpha = u.opacity;
        if (u.diffuseMap) {
            const vec4 texel = sampleBilinear(*u.diffuseMap, in.uv);
            albedo *= vec3(texel);
            alpha *= texel.a;
        }
        LightingTerms<vec3> t = surfaceTerms<float, vec3>(in.position, in.normal, albedo, u);
        if (u.emissionMap) t.emission *= vec3(sampleBilinear(*u.emissionMap, in.uv));
        vec3 c = t.sum();
        if (u.clampColor) c = detail::clamp01(c);
        return vec4(surfaceOutput<float, vec3>(c, alpha, in.position, u), alpha);
    }

    // The same for eight fragments at once (the pipeline prefers this when a shader has it).
    static Vec4x8 fragmentBatch(const FragmentBatch& in, const Uniforms& u) {
        constexpr int kPosition = offsetof(Varyings, position) / sizeof(float);
        constexpr int kNormal = offsetof(Varyings, normal) / sizeof(float);
        constexpr int kUv = offsetof(Varyings, uv) / sizeof(float);
        Vec3x8 albedo(u.albedo());
        Float8 alpha = splat(u.opacity);
        if (u.diffuseMap) {
            const Vec4x8 texel = detail::texels(*u.diffuseMap, in.vec2At(kUv), in.mask);
            albedo = albedo * Vec3x8{texel.x, texel.y, texel.z};
            alpha = alpha * texel.w;
        }
        const Vec3x8 P = in.vec3At(kPosition);
        LightingTerms<Vec3x8> t = surfaceTerms<Float8, Vec3x8>(P, in.vec3At(kNormal), albedo, u);
        if (u.emissionMap) {
            const Vec4x8 texel = detail::texels(*u.emissionMap, in.vec2At(kUv), in.mask);
            t.emission = t.emission * Vec3x8{texel.x, texel.y, texel.z};
        }
        Vec3x8 c = t.sum();
        if (u.clampColor) c = detail::clamp01(c);
        c = surfaceOutput<Float8, Vec3x8>(c, alpha, P, u);
        return {c.x, c.y, c.z, alpha};
    }
};

// Lighting per vertex (Gouraud 1971). The colour travels in two parts so that a diffuse map can tint
// the diffuse light only: `modulated` (the diffuse term) is multiplied by the texel, `added`
// (emission + ambient + specular) is not. With clampColor (OpenGL 1.x) the clamped sum is modulated
// whole, as fixed function's GL_MODULATE does. With an emission map the emission is neither: it is
// added per fragment, m_emission ⊗ the emission texel. Flat shading is the same with the colour flat:
// the provoking vertex's colour fills the triangle.
template <ShadingFrequency kFrequency>
struct PerVertexSurfaceShader {
    using Attributes = MeshVertex;
    using Uniforms = SurfaceUniforms;
    struct Varyings {
        vec3 modulated;  // flat when kFrequency is Flat
        vec3 added;      // flat when kFrequency is Flat
        vec3 position;   // eye space, for fog
        vec2 uv;
    };
    static constexpr int kFlatVaryingFloats = kFrequency == ShadingFrequency::Flat ? 6 : 0;

    static VertexOut<Varyings> vertex(const Attributes& in, const Uniforms& u) {
        const vec3 P(u.viewFromObject * vec4(in.position, 1.0f));
        LightingTerms<vec3> t = surfaceTerms<float, vec3>(P, u.normalFromObject * in.normal, u.albedo(), u);
        if (u.emissionMap) t.emission = vec3(0.0f);  // added, textured, per fragment
        Varyings out{t.diffuse, t.emission + t.ambient + t.specular, P, in.uv};
        if (u.clampColor) out = {detail::clamp01(t.sum()), vec3(0.0f), P, in.uv};
        return {u.clipFromObject * vec4(in.position, 1.0f), out};
    }

    // The same for eight vertices: the lighting in eight lanes, the matrices one vertex at a time.
    static void vertexBatch(const Attributes* in, const Uniforms& u, VertexOut<Varyings>* out) {
        Vec3x8 P, N;
        for (int lane = 0; lane < kVertexBatch; ++lane) {
            const vec3 p(u.viewFromObject * vec4(in[lane].position, 1.0f));
            const vec3 n = u.normalFromObject * in[lane].normal;
            P.x[lane] = p.x;
            P.y[lane] = p.y;
            P.z[lane] = p.z;
            N.x[lane] = n.x;
            N.y[lane] = n.y;
            N.z[lane] = n.z;
        }
        LightingTerms<Vec3x8> t = surfaceTerms<Float8, Vec3x8>(P, N, Vec3x8(u.albedo()), u);
        if (u.emissionMap) t.emission = Vec3x8(vec3(0.0f));  // added, textured, per fragment
        Vec3x8 modulated = t.diffuse, added = t.emission + t.ambient + t.specular;
        if (u.clampColor) {
            modulated = detail::clamp01(t.sum());
            added = Vec3x8(vec3(0.0f));
        }
        const auto at = [](const Vec3x8& v, int lane) { return vec3(v.x[lane], v.y[lane], v.z[lane]); };
        for (int lane = 0; lane < kVertexBatch; ++lane)
            out[lane] = {u.clipFromObject * vec4(in[lane].position, 1.0f),
                         {at(modulated, lane), at(added, lane), at(P, lane), in[lane].uv}};
    }

    static vec4 fragment(const Varyings& in, const Uniforms& u) {
        vec3 modulated = in.modulated;
        float alpha = u.opacity;
        if (u.diffuseMap) {
            const vec4 texel = sampleBilinear(*u.diffuseMap, in.uv);
            modulated *= vec3(texel);
            alpha *= texel.a;
        }
        vec3 added = in.added;
        if (u.emissionMap) added += u.emissionTerm() * vec3(sampleBilinear(*u.emissionMap, in.uv));
        return vec4(surfaceOutput<float, vec3>(modulated + added, alpha, in.position, u), alpha);
    }

    static Vec4x8 fragmentBatch(const FragmentBatch& in, const Uniforms& u) {
        constexpr int kModulated = offsetof(Varyings, modulated) / sizeof(float);
        constexpr int kAdded = offsetof(Varyings, added) / sizeof(float);
        constexpr int kPosition = offsetof(Varyings, position) / sizeof(float);
        constexpr int kUv = offsetof(Varyings, uv) / sizeof(float);
        Vec3x8 modulated = in.vec3At(kModulated);
        Float8 alpha = splat(u.opacity);
        if (u.diffuseMap) {
            const Vec4x8 texel = detail::texels(*u.diffuseMap, in.vec2At(kUv), in.mask);
            modulated = modulated * Vec3x8{texel.x, texel.y, texel.z};
            alpha = alpha * texel.w;
        }
        Vec3x8 added = in.vec3At(kAdded);
        if (u.emissionMap) {
            const Vec4x8 texel = detail::texels(*u.emissionMap, in.vec2At(kUv), in.mask);
            added = added + Vec3x8(u.emissionTerm()) * Vec3x8{texel.x, texel.y, texel.z};
        }
        const Vec3x8 c = surfaceOutput<Float8, Vec3x8>(modulated + added, alpha, in.vec3At(kPosition), u);
        return {c.x, c.y, c.z, alpha};
    }
};

template <>
struct SurfaceShader<ShadingFrequency::Gouraud> : PerVertexSurfaceShader<ShadingFrequency::Gouraud> {};
template <>
struct SurfaceShader<ShadingFrequency::Flat> : PerVertexSurfaceShader<ShadingFrequency::Flat> {};

}  // namespace facet
