// What a shader is: a struct with Attributes, Varyings, Uniforms and two static functions, written
// like GLSL with GLM (see README "Writing a shader"). The pipeline takes it as a template parameter, so
// both functions are inlined into the hot loops: no virtual or std::function call per vertex or pixel.
//
//   struct MyShader {
//       struct Attributes { vec3 position; ... };   // one per vertex of the mesh
//       struct Varyings { vec3 normal; ... };       // floats only; interpolated across the triangle
//       struct Uniforms { mat4 clipFromObject; ... };
//       static VertexOut<Varyings> vertex(const Attributes&, const Uniforms&);
//       static vec4 fragment(const Varyings&, const Uniforms&);                 // or, to be able to
//       static std::optional<vec4> fragment(const Varyings&, const Uniforms&);  // discard: nullopt
//   };
#pragma once

#include <concepts>
#include <cstring>
#include <optional>
#include <type_traits>

#include "glsl.h"
#include "types.h"
#include "wide.h"

namespace facet {

template <class Varyings>
struct VertexOut {
    vec4 position;      // clip space: gl_Position
    Varyings varyings;  // passed on to the fragment shader, interpolated
};

// Varyings travel as floats through the middle of the pipeline: they must be nothing but floats.
template <class V>
inline constexpr bool kIsFloatBundle = std::is_trivially_copyable_v<V> &&
                                       (std::is_empty_v<V> ||
                                        (sizeof(V) % sizeof(float) == 0 && alignof(V) == alignof(float) &&
                                         sizeof(V) <= kMaxVaryingFloats * sizeof(float)));

template <class V>
inline constexpr int kVaryingFloatCount = std::is_empty_v<V> ? 0
                                                             : static_cast<int>(sizeof(V) / sizeof(float));

template <class S>
concept Shader = requires(const typename S::Attributes& attributes, const typename S::Varyings& varyings,
                          const typename S::Uniforms& uniforms) {
    { S::vertex(attributes, uniforms) } -> std::same_as<VertexOut<typename S::Varyings>>;
    requires std::same_as<decltype(S::fragment(varyings, uniforms)), vec4> ||
        std::same_as<decltype(S::fragment(varyings, uniforms)), std::optional<vec4>>;
    requires kIsFloatBundle<typename S::Varyings>;
};

// A shader may declare `static constexpr int kFlatVaryingFloats = n;`: the first n floats of its
// Varyings are then flat (GLSL's `flat` qualifier), the provoking vertex's values across the whole
// triangle, not interpolated. Flat shading is a flat colour varying computed by the vertex shader.
template <class S>
constexpr int flatVaryingFloats() {
    if constexpr (requires { S::kFlatVaryingFloats; }) {
        static_assert(
            S::kFlatVaryingFloats >= 0 && S::kFlatVaryingFloats <= kVaryingFloatCount<typename S::Varyings>,
            "kFlatVaryingFloats must count floats of Varyings");
        return S::kFlatVaryingFloats;
    } else {
        return 0;
    }
}

// A shader may declare `static constexpr int kDerivativeVarying = k;`: floats k and k + 1 of its
// Varyings are texture coordinates (u, v) whose screen-space derivatives it wants, for a texture's
// level of detail (GLSL's dFdx/dFdy of them, computed exactly from the triangle's planes:
// interpolate.h). It may add `static bool usesDerivatives(const Uniforms&)`: whether a draw with
// these uniforms reads them, asked once per draw, so a draw that does not pays nothing.
template <class S>
constexpr int derivativeVarying() {
    if constexpr (requires { S::kDerivativeVarying; }) {
        static_assert(S::kDerivativeVarying >= flatVaryingFloats<S>() &&
                          S::kDerivativeVarying + 2 <= kVaryingFloatCount<typename S::Varyings>,
                      "kDerivativeVarying must be the first of two interpolated floats of Varyings");
        return S::kDerivativeVarying;
    } else {
        return -1;
    }
}
template <class S>
bool drawUsesDerivatives(const typename S::Uniforms& uniforms) {
    if constexpr (derivativeVarying<S>() < 0) {
        return false;
    } else if constexpr (requires { S::usesDerivatives(uniforms); }) {
        return S::usesDerivatives(uniforms);
    } else {
        return true;
    }
}

// A shader may declare `static constexpr bool kBarycentrics = true;` (GLSL's gl_BaryCoordEXT): each
// batch then carries its lanes' barycentrics λ1, λ2 (FragmentBatch::barycentrics), the very values an
// observer's FragmentEvent reports. A shader that does not declare it gets nothing written, at no cost.
template <class S>
constexpr bool wantsBarycentrics() {
    if constexpr (requires { S::kBarycentrics; })
        return S::kBarycentrics;
    else
        return false;
}

// The screen-space derivatives of a texture coordinate pair at one fragment or eight: ∂uv/∂x and ∂uv/∂y
// (per pixel; y down the rows). Zero (the default): a point, which a texture samples at level 0.
template <class F>
struct TexCoordDerivativesT {
    LaneVec2<F> dx{};
    LaneVec2<F> dy{};
};

// A shader may also shade eight vertices at once, to run per-vertex work (Gouraud lighting) in eight
// lanes as fragmentBatch does for fragments:
//   static void vertexBatch(const Attributes* in, const Uniforms&, VertexOut<Varyings>* out);
// reads in[0..7] and writes out[0..7], each exactly what vertex() gives for it (up to rounding). The
// vertex stage then calls it for groups of eight; a last, shorter group is padded with copies of its
// last vertex, whose results are dropped.
inline constexpr int kVertexBatch = 8;
template <class S>
concept BatchVertexShader = Shader<S> &&
    requires(const typename S::Attributes* in, const typename S::Uniforms& u,
             VertexOut<typename S::Varyings>* out) {
    { S::vertexBatch(in, u, out) } -> std::same_as<void>;
};

// A shader whose fragment function returns std::optional<vec4> may discard fragments.
template <Shader S>
inline constexpr bool kMayDiscard =
    std::same_as<decltype(S::fragment(std::declval<const typename S::Varyings&>(),
                                      std::declval<const typename S::Uniforms&>())),
                 std::optional<vec4>>;

// ---- Shaders written once for one lane and for eight ------------------------------------------------
//
// A bundle of floats declared once as a template over the lane type F (float or Float8), its members
// vec2/vec3/vec4 for one lane and Vec2x8/Vec3x8/Vec4x8 for eight (LaneVec2<F>…):
//   template <class F> struct VaryingsT { LaneVec3<F> normal; LaneVec2<F> uv; };
// Bundle<float> is then n floats (a Varyings as the pipeline wants it) and Bundle<Float8> the same n
// members as Float8 lanes in the same order, so one is the other transposed: no per-member copies.
template <template <class> class Bundle>
inline constexpr int kLaneBundleFloats = kVaryingFloatCount<Bundle<float>>;

template <template <class> class Bundle>
inline constexpr bool kIsLaneBundle = [] {
    const bool floatsAtOneLane = kIsFloatBundle<Bundle<float>>;
    return floatsAtOneLane && std::is_trivially_copyable_v<Bundle<Float8>> &&
           sizeof(Bundle<Float8>) == kLaneBundleFloats<Bundle> * sizeof(Float8);
}();

// Lane `lane` of an eight-lane bundle, as the one-lane bundle.
template <template <class> class Bundle>
Bundle<float> laneOf(const Bundle<Float8>& wide, int lane) {
    static_assert(kIsLaneBundle<Bundle>, "a lane bundle has the same float members at both lane types");
    constexpr int kFloats = kLaneBundleFloats<Bundle>;
    Float8 columns[kFloats];
    std::memcpy(columns, &wide, sizeof wide);
    float floats[kFloats];
    for (int k = 0; k < kFloats; ++k)
        floats[k] = columns[k][lane];
    Bundle<float> one;
    std::memcpy(&one, floats, sizeof one);
    return one;
}

// Eight one-lane bundles as one eight-lane bundle.
template <template <class> class Bundle>
Bundle<Float8> gatherLanes(const Bundle<float> (&perLane)[8]) {
    static_assert(kIsLaneBundle<Bundle>, "a lane bundle has the same float members at both lane types");
    constexpr int kFloats = kLaneBundleFloats<Bundle>;
    Float8 columns[kFloats];
    for (int lane = 0; lane < 8; ++lane) {
        float floats[kFloats];
        std::memcpy(floats, &perLane[lane], sizeof floats);
        for (int k = 0; k < kFloats; ++k)
            columns[k][lane] = floats[k];
    }
    Bundle<Float8> wide;
    std::memcpy(&wide, columns, sizeof wide);
    return wide;
}

// A FragmentBatch's interpolated varyings (one Float8 per varying float) as the eight-lane bundle.
template <template <class> class Bundle>
Bundle<Float8> loadLanes(const FragmentBatch& batch) {
    static_assert(kIsLaneBundle<Bundle>, "a lane bundle has the same float members at both lane types");
    Bundle<Float8> wide;
    std::memcpy(&wide, batch.varyings, sizeof wide);
    return wide;
}

#if FACET_SIXTEEN_LANES
// Two FragmentBatches' varyings as one sixteen-lane bundle: a's lanes, then b's.
template <template <class> class Bundle>
Bundle<Floatx16> loadLanePair(const FragmentBatch& a, const FragmentBatch& b) {
    constexpr int kFloats = kLaneBundleFloats<Bundle>;
    static_assert(kIsLaneBundle<Bundle> && sizeof(Bundle<Floatx16>) == kFloats * sizeof(Floatx16),
                  "a lane bundle has the same float members at every lane type");
    Floatx16 columns[kFloats];
    for (int k = 0; k < kFloats; ++k)
        columns[k] = joinHalves(a.varyings[k], b.varyings[k]);
    Bundle<Floatx16> wide;
    std::memcpy(&wide, columns, sizeof wide);
    return wide;
}

// Two batches' texture coordinate derivatives (FragmentBatch::uvDerivatives) as sixteen lanes.
inline TexCoordDerivativesT<Floatx16> derivativesOfPair(const FragmentBatch& a, const FragmentBatch& b) {
    Floatx16 columns[4];
    for (int k = 0; k < 4; ++k)
        columns[k] = joinHalves(a.uvDerivatives[k], b.uvDerivatives[k]);
    TexCoordDerivativesT<Floatx16> derivatives;
    static_assert(sizeof derivatives == sizeof columns);
    std::memcpy(&derivatives, columns, sizeof derivatives);
    return derivatives;
}
#endif

// Whether a body's shade() compiles for sixteen lanes too (it declares kSixteenLanes): the back end
// then shades two batches in one call where the instruction set has them (wide.h).
template <class Body>
constexpr bool shadesSixteenLanes() {
    if constexpr (requires { Body::kSixteenLanes; })
        return Body::kSixteenLanes;
    else
        return false;
}

// The pipeline's entry points of a shader whose fragment shader (and per-vertex lighting) is one body
// for both lane types. Body declares Attributes, Uniforms, vertex(), and
//   template <class F> struct VaryingsT;  // a lane bundle; Varyings is VaryingsT<float>
//   template <class F>
//   static LaneVec4<F> shade(const VaryingsT<F>&, const Uniforms&, unsigned liveLanes);
// (liveLanes: bit i set where lane i holds a fragment; 1 for one lane). LaneShader<Body> adds
// fragment() (F = float) and fragmentBatch() (F = Float8), so the pipeline, a test or a trace of one
// pixel runs the very lighting the others run. A Body that lights its vertices declares as well
//   template <class F> struct VertexInputsT;  // a lane bundle of what the lighting reads
//   static VertexOut<VertexInputsT<float>> vertexInputs(const Attributes&, const Uniforms&);
//   template <class F> static VaryingsT<F> lightVertex(const VertexInputsT<F>&, const Uniforms&);
// and gets vertexBatch(): vertexInputs one vertex at a time (the matrices), lightVertex on eight lanes.
template <class Body>
concept LanewiseVertexLighting = requires(const typename Body::Attributes& in,
                                          const typename Body::Uniforms& u,
                                          const typename Body::template VertexInputsT<Float8>& wide) {
    { Body::vertexInputs(in, u) } -> std::same_as<VertexOut<typename Body::template VertexInputsT<float>>>;
    {
        Body::template lightVertex<Float8>(wide, u)
        } -> std::same_as<typename Body::template VaryingsT<Float8>>;
};

// A body that shades eight vertices at once itself (the matrices eight lanes at a time).
template <class Body>
concept HasVertexBatch = requires(const typename Body::Attributes* in, const typename Body::Uniforms& u,
                                  VertexOut<typename Body::template VaryingsT<float>>* out) {
    { Body::vertexBatch(in, u, out) } -> std::same_as<void>;
};

template <class Body>
struct LaneShader : Body {
    using Varyings = typename Body::template VaryingsT<float>;
    using Uniforms = typename Body::Uniforms;
    using Attributes = typename Body::Attributes;

    static vec4 fragment(const Varyings& in, const Uniforms& u) {
        return Body::template shade<float>(in, u, 1u);
    }
    // With kDerivativeVarying, the batch's uvDerivatives (filled when the draw uses them) go to shade().
    static Vec4x8 fragmentBatch(const FragmentBatch& in, const Uniforms& u) {
        if constexpr (requires { Body::kDerivativeVarying; }) {
            TexCoordDerivativesT<Float8> derivatives;
            static_assert(sizeof derivatives == sizeof in.uvDerivatives);
            std::memcpy(&derivatives, in.uvDerivatives, sizeof derivatives);
            return Body::template shade<Float8>(loadLanes<Body::template VaryingsT>(in), u, in.mask,
                                                derivatives);
        } else {
            return Body::template shade<Float8>(loadLanes<Body::template VaryingsT>(in), u, in.mask);
        }
    }
#if FACET_SIXTEEN_LANES
    // Two batches in one call, sixteen lanes (a's, then b's), each lane the bits fragmentBatch gives it.
    static Vec4x16 fragmentBatchPair(const FragmentBatch& a, const FragmentBatch& b,
                                     const Uniforms& u) requires(shadesSixteenLanes<Body>()) {
        const unsigned liveLanes = a.mask | (b.mask << 8);
        const auto varyings = loadLanePair<Body::template VaryingsT>(a, b);
        if constexpr (requires { Body::kDerivativeVarying; }) {
            return Body::template shade<Floatx16>(varyings, u, liveLanes, derivativesOfPair(a, b));
        } else {
            return Body::template shade<Floatx16>(varyings, u, liveLanes);
        }
    }
#endif
    // Eight vertices at once: the body's own vertexBatch when it has one, else vertexInputs lane by
    // lane and lightVertex on eight lanes (LanewiseVertexLighting).
    static void vertexBatch(const Attributes* in, const Uniforms& u,
                            VertexOut<Varyings>* out) requires(LanewiseVertexLighting<Body> ||
                                                               HasVertexBatch<Body>) {
        if constexpr (HasVertexBatch<Body>) {
            Body::vertexBatch(in, u, out);
        } else {
            using Inputs = typename Body::template VertexInputsT<float>;
            Inputs inputs[kVertexBatch];
            for (int lane = 0; lane < kVertexBatch; ++lane) {
                const VertexOut<Inputs> prepared = Body::vertexInputs(in[lane], u);
                out[lane].position = prepared.position;
                inputs[lane] = prepared.varyings;
            }
            const typename Body::template VaryingsT<Float8> lit =
                Body::template lightVertex<Float8>(gatherLanes<Body::template VertexInputsT>(inputs), u);
            for (int lane = 0; lane < kVertexBatch; ++lane)
                out[lane].varyings = laneOf<Body::template VaryingsT>(lit, lane);
        }
    }
};

}  // namespace facet
