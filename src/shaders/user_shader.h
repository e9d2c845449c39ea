// What a shader of your own is written with (docs/shaders.md): `facet render MODEL --shader toon.cpp`
// compiles a file that includes this header and ends with FACET_SHADER(Name) (shaders/shader_module.h)
// into a module that the renderer, the step mode, the benchmarks, the trade and the reference run.
//
//   struct Toon {
//       struct Uniforms : SceneUniforms {   // the scene's (matrices, lights, material, fog) and yours
//           int bands = 4;                  // defaults, overridden by --uniform bands=3 or the scene
//       };
//       static constexpr std::tuple kUniforms{uniform("bands", &Uniforms::bands, "steps of light")};
//       template <class F>
//       struct VaryingsT {                  // floats only, interpolated across the triangle
//           LaneVec3<F> position;           // eye space
//           LaneVec3<F> normal;
//       };
//       static constexpr VaryingName kVaryings[] = {{"P_eye", 3}, {"N_eye", 3}};
//       static VertexOut<VaryingsT<float>> vertex(const MeshVertex& in, const Uniforms& u);
//       template <class F>                  // F = float (one fragment), Float8 (eight at once) or
//                                           // Floatx16 (sixteen, with kSixteenLanes: docs/shaders.md)
//       static LaneVec4<F> fragment(const VaryingsT<F>& in, const Uniforms& u, Fragment<F>& gl);
//   };
//   FACET_SHADER(Toon)
//
// The fragment part is one body over lanes: the pipeline runs it on eight fragments at once (F = Float8)
// and the step mode on the one it traces (F = float), so what the trace shows is what drew the pixel.
// It returns LaneVec4<F>, or FragmentOut<F> to be able to discard.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <vector>

#include "pipeline/names.h"
#include "pipeline/shader.h"
#include "pipeline/texture.h"
#include "pipeline/wide.h"
#include "scene/mesh.h"
#include "shaders/shaders.h"
#include "shading/fog.h"
#include "shading/gamma.h"
#include "shading/lighting.h"

// The built-in formulas by term, and GLSL's functions over lanes (their one-lane versions in namespace
// facet::glsl, which a shader's file brings in: `using namespace facet::glsl;`).
#include "shaders/formulas.h"
#include "shaders/lane_glsl.h"

namespace facet {

// The scene's uniforms, which a user shader's Uniforms derive from: clipFromObject, viewFromObject,
// normalFromObject; the lights in eye space (activeLights()); the material (MTL values: material, pbr)
// and its texture maps (diffuseMap, emissionMap: null when the material has none); textureFilter; fog.
using SceneUniforms = SurfaceUniforms;

// ---- Uniforms of one's own ----------------------------------------------------------------------------

// The types a uniform of one's own may have.
enum class UniformType : std::uint8_t { Float, Int, Bool, Vec2, Vec3, Vec4 };
inline constexpr EnumName<UniformType> kUniformTypeNames[] = {
    {UniformType::Float, "float"}, {UniformType::Int, "int"},   {UniformType::Bool, "bool"},
    {UniformType::Vec2, "vec2"},   {UniformType::Vec3, "vec3"}, {UniformType::Vec4, "vec4"}};
constexpr std::span<const EnumName<UniformType>> enumNames(UniformType) {
    return kUniformTypeNames;
}
// How many numbers a value of the type has.
constexpr int componentCount(UniformType type) {
    switch (type) {
        case UniformType::Vec2:
            return 2;
        case UniformType::Vec3:
            return 3;
        case UniformType::Vec4:
            return 4;
        default:
            return 1;
    }
}

template <class T>
constexpr bool kIsUniformType =
    std::is_same_v<T, float> || std::is_same_v<T, int> || std::is_same_v<T, bool> ||
    std::is_same_v<T, vec2> || std::is_same_v<T, vec3> || std::is_same_v<T, vec4>;

template <class T>
constexpr UniformType uniformTypeOf() {
    static_assert(kIsUniformType<T>, "a uniform of one's own is a float, int, bool, vec2, vec3 or vec4");
    if constexpr (std::is_same_v<T, float>) return UniformType::Float;
    if constexpr (std::is_same_v<T, int>) return UniformType::Int;
    if constexpr (std::is_same_v<T, bool>) return UniformType::Bool;
    if constexpr (std::is_same_v<T, vec2>) return UniformType::Vec2;
    if constexpr (std::is_same_v<T, vec3>) return UniformType::Vec3;
    return UniformType::Vec4;
}

// One uniform of a shader's own, declared in its kUniforms: the name the scene file and --uniform use,
// the member of its Uniforms, and one line saying what it does.
template <class U, class T>
struct UniformField {
    const char* name;
    T U::*member;
    const char* help;
};
template <class U, class T>
constexpr UniformField<U, T> uniform(const char* name, T U::*member, const char* help = "") {
    static_assert(kIsUniformType<T>, "a uniform of one's own is a float, int, bool, vec2, vec3 or vec4");
    return {name, member, help};
}

// ---- Varyings ---------------------------------------------------------------------------------------

// A member of VaryingsT by the name the step mode shows and its number of floats, in VaryingsT's order:
// {"N_eye", 3} names floats N_eye.x, N_eye.y, N_eye.z.
struct VaryingName {
    const char* name;
    int floats;
};

// ---- The fragment part --------------------------------------------------------------------------------

// The comparison result of lane type F: bool for one lane, Int8 (all bits set where true) for eight.
template <class F>
using LaneMask = decltype(std::declval<F>() < std::declval<F>());

// What a fragment part returns to be able to discard: its colour, and where `discard` is true the
// fragment is dropped (GLSL's discard): no depth, no colour written.
template <class F>
struct FragmentOut {
    LaneVec4<F> color;
    LaneMask<F> discard;
};

// A value a traced fragment recorded (Fragment::record): up to four floats.
struct RecordedValue {
    std::string_view name;
    int count = 1;
    std::array<float, 4> values{};
};
struct ShaderTrace {
    std::vector<RecordedValue> values;  // in the order the shader recorded them
};

// What the fragment part has besides its varyings and uniforms, GLSL's built-ins among them: the live
// lanes, the texture coordinate derivatives (when the shader declares kDerivativeVarying), the
// barycentrics (when it declares kBarycentrics), texture lookups with the scene's filter, and record()
// for the step mode.
template <class F>
struct Fragment {
    unsigned liveLanes = 1;  // bit i: lane i holds a fragment
    TexCoordDerivativesT<F> uvDerivatives{};
    // GLSL's gl_BaryCoordEXT, for a shader that declares `static constexpr bool kBarycentrics = true;`:
    // λ0, λ1, λ2 of the pixel in its window triangle (the triangle as clipped and set up, its vertices in
    // the setup's order; affine in screen space, not perspective-corrected), summing to 1. Without the
    // declaration it stays (⅓, ⅓, ⅓).
    LaneVec3<F> barycentric = LaneVec3<F>(vec3(1.0f / 3.0f));
    ShaderTrace* trace = nullptr;  // set by the step mode for the one fragment it traces

    // Shows `value` (a float, int, bool or vec2/3/4) under `name` (a string literal) on the step mode's
    // screen for the traced fragment. Eight lanes at once are never traced: then it compiles to nothing.
    template <class T>
    void record([[maybe_unused]] std::string_view name, [[maybe_unused]] const T& value) const {
        if constexpr (std::is_same_v<F, float>) {
            if (!trace) return;
            RecordedValue v{name};
            if constexpr (std::is_arithmetic_v<T>) {
                v.values[0] = static_cast<float>(value);
            } else {
                v.count = static_cast<int>(T::length());
                for (int k = 0; k < v.count; ++k)
                    v.values[static_cast<std::size_t>(k)] = value[k];
            }
            trace->values.push_back(v);
        }
    }

    // map's colour at uv with the scene's filter (textureFilter), white when there is no map: GLSL's
    // texture(sampler, uv). Trilinear filtering reads uvDerivatives.
    LaneVec4<F> texture(const Texture* map, const LaneVec2<F>& uv, const SceneUniforms& u) const {
        if (!map) return LaneVec4<F>{lanes<F>(1.0f), lanes<F>(1.0f), lanes<F>(1.0f), lanes<F>(1.0f)};
        return detail::texels<F>(*map, uv, liveLanes, u.textureFilter, u.textureFootprint, uvDerivatives);
    }
};

}  // namespace facet
