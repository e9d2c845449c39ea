// Fog: blending a fragment's colour towards a fog colour with its distance from the eye, as OpenGL's
// fixed-function fog (glFog; OpenGL 2.1 §3.10):
//   c = f·c_s + (1 − f)·c_fog,  f clamped to [0, 1],
//   linear:  f = (end − z)/(end − start)
//   exp:     f = e^(−density·z)
//   exp²:    f = e^(−(density·z)²)
// with z the fragment's distance from the eye: |z_eye| (the eye-space depth, OpenGL's default) or the
// radial distance |P_eye| (NV_fog_distance's GL_EYE_RADIAL_NV). Written once for 1 and 8 lanes; the
// exponential's precision P is the caller's choice (wide.h's MathPrecision), Exact by default.
#pragma once

#include "pipeline/glsl.h"
#include "pipeline/names.h"
#include "pipeline/wide.h"
#include "shading/record.h"

namespace facet {

enum class FogMode { None, Linear, Exponential, ExponentialSquared };
inline constexpr EnumName<FogMode> kFogModeNames[] = {{FogMode::None, "none"},
                                                      {FogMode::Linear, "linear"},
                                                      {FogMode::Exponential, "exp"},
                                                      {FogMode::ExponentialSquared, "exp2"}};
constexpr std::span<const EnumName<FogMode>> enumNames(FogMode) {
    return kFogModeNames;
}

enum class FogDistance {
    EyeDepth,  // |z_eye|: constant across a plane facing the viewer (OpenGL's default)
    Radial,    // |P_eye|: constant on a sphere around the eye, so fog does not change as the view turns
};
inline constexpr EnumName<FogDistance> kFogDistanceNames[] = {{FogDistance::EyeDepth, "depth"},
                                                              {FogDistance::Radial, "radial"}};
constexpr std::span<const EnumName<FogDistance>> enumNames(FogDistance) {
    return kFogDistanceNames;
}

struct FogParams {
    FogMode mode = FogMode::None;
    vec3 color{0.5f};                // c_fog, in the colour buffer's values (linear with the facet preset)
    float start = 0.0f, end = 1.0f;  // linear
    float density = 1.0f;            // exp, exp²
    FogDistance distance = FogDistance::EyeDepth;
};

// The distance fog uses for an eye-space position.
template <class F, class V3 = LaneVec3<F>>
F fogDistance(const FogParams& fog, const V3& eyePosition) {
    return fog.distance == FogDistance::Radial ? sqrt(dot(eyePosition, eyePosition)) : abs(eyePosition.z);
}

// The fog factor f: 1 = no fog, 0 = only fog.
template <class F, MathPrecision P = MathPrecision::Exact>
F fogFactor(const FogParams& fog, F z) {
    switch (fog.mode) {
        case FogMode::None:
            return lanes<F>(1.0f);
        case FogMode::Linear:
            // A degenerate range (end = start) is a wall: everything at or beyond it fully fogged.
            if (fog.end == fog.start) return select(z < fog.start, lanes<F>(1.0f), lanes<F>(0.0f));
            return saturate((fog.end - z) * (1.0f / (fog.end - fog.start)));
        case FogMode::Exponential:
            return saturate(Maths<P>::exp(-fog.density * z));
        case FogMode::ExponentialSquared: {
            const F dz = fog.density * z;
            return saturate(Maths<P>::exp(-(dz * dz)));
        }
    }
    return lanes<F>(1.0f);
}

// The record of the fog at one point (record.h).
struct FogRecord {
    static constexpr bool enabled = true;
    FogParams fog{};         // mode, distance kind, start, end, density, c_fog
    vec3 eyePosition{0.0f};  // P_eye
    float z = 0;             // the distance fog uses: |z_eye| or |P_eye|
    float f = 1;             // the fog factor, clamped to [0, 1]; 1 when fog is off
    vec3 color{0.0f};        // c_s, the colour before fog
    vec3 fogged{0.0f};       // c_p = f·c_s + (1 − f)·c_fog
};

// c = f·c_s + (1 − f)·c_fog. With a record, the fogged colour is recorded from this function called
// again without one: the one-lane code without a record stays the very code it is without records.
template <class F, class V3 = LaneVec3<F>, MathPrecision P = MathPrecision::Exact, class... Recording>
V3 applyFog(const FogParams& fog, const V3& color, const V3& eyePosition, Recording*... recording) {
    using Record = RecordOf<Recording...>;
    static_assert(!Record::enabled || std::is_same_v<F, float>, "records hold one lane");
    if constexpr (Record::enabled)
        *recordOf(recording...) = {.fog = fog, .eyePosition = eyePosition, .color = color, .fogged = color};
    if (fog.mode == FogMode::None) return color;
    const F f = fogFactor<F, P>(fog, fogDistance<F, V3>(fog, eyePosition));
    if constexpr (Record::enabled) {
        Record& record = *recordOf(recording...);
        record.z = fogDistance<F, V3>(fog, eyePosition);
        record.f = f;
        record.fogged = applyFog<F, V3, P>(fog, color, eyePosition);
        return record.fogged;
    }
    return color * f + V3(fog.color) * (1.0f - f);
}

}  // namespace facet
