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
#include <optional>
#include <type_traits>

#include "glsl.h"
#include "types.h"

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

}  // namespace facet
