// Fog: blending a fragment's colour towards a fog colour with its distance from the eye, as OpenGL's
// fixed-function fog (glFog; OpenGL 2.1 §3.10):
//   c = f·c_s + (1 − f)·c_fog,  f clamped to [0, 1],
//   linear:  f = (end − z)/(end − start)
//   exp:     f = e^(−density·z)
//   exp²:    f = e^(−(density·z)²)
// with z the fragment's distance from the eye: |z_eye| (the eye-space depth, OpenGL's default) or the
// radial distance |P_eye| (NV_fog_distance's GL_EYE_RADIAL_NV). Written once for 1 and 8 lanes; the
// exponential's precision P is the caller's choice (wide.h's MathPrecision), Exact by default.
//
// Height fog ("fog in the up direction", lighting-deck-C.txt): a density that falls exponentially with
// the height h above a base h0, ρ(h) = a·e^(−b·(h − h0)), integrated in closed form along the segment
// from the eye (height y_e) to the point (height y_e + Δy, at distance d): with h(s) = y_e + Δy·s/d,
//   τ = ∫₀^d ρ(h(s)) ds = a·e^(−b·(y_e − h0))·d·(1 − e^(−b·Δy))/(b·Δy),   f = e^(−τ)
// (Quílez, "Better fog", 2010; Wenzel, "Real-time atmospheric effects in games", SIGGRAPH 2006 course;
// Unreal Engine's exponential height fog). With x = b·Δy, g(x) = (1 − e^(−x))/x tends to 1 as the ray
// turns horizontal: below |x| < 0.1 it is its series 1 − x/2 + x²/6 − x³/24 + x⁴/120, free of the
// cancellation 1 − e^(−x) suffers there, so a horizontal ray gets the limit a·e^(−b·(y_e − h0))·d.
#pragma once

#include <cmath>

#include "pipeline/glsl.h"
#include "pipeline/names.h"
#include "pipeline/wide.h"
#include "shading/record.h"

namespace facet {

enum class FogMode { None, Linear, Exponential, ExponentialSquared, Height };
inline constexpr EnumName<FogMode> kFogModeNames[] = {{FogMode::None, "none"},
                                                      {FogMode::Linear, "linear"},
                                                      {FogMode::Exponential, "exp"},
                                                      {FogMode::ExponentialSquared, "exp2"},
                                                      {FogMode::Height, "height"}};
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
    float density = 1.0f;            // exp, exp²; height: a, the density at the base height
    FogDistance distance = FogDistance::EyeDepth;
    // Height fog: the falloff b (per unit of height), the base height h0, the world's up direction in
    // eye space (unit) and the eye's height y_e, all in eye-space units (the renderer scales them).
    float falloff = 1.0f;
    float baseHeight = 0.0f;
    vec3 up{0.0f, 1.0f, 0.0f};
    float eyeHeight = 0.0f;
};

// g(x) = (1 − e^(−x))/x, g(0) = 1: the series where |x| < 0.1, and x ≥ −60 so that e^(−x) stays finite
// (τ is then so large that f is 0 anyway).
template <class F, MathPrecision P = MathPrecision::Exact>
F heightFogShape(F x) {
    x = max(x, -60.0f);
    const F series = 1.0f - x * (0.5f - x * ((1.0f / 6.0f) - x * ((1.0f / 24.0f) - x * (1.0f / 120.0f))));
    const auto small = abs(x) < 0.1f;
    const F safeX = select(small, lanes<F>(1.0f), x);
    return select(small, series, (1.0f - Maths<P>::exp(-safeX)) / safeX);
}

// Height fog's optical depth τ from the eye to the eye-space point P.
template <class F, class V3 = LaneVec3<F>, MathPrecision P = MathPrecision::Exact>
F heightFogDepth(const FogParams& fog, const V3& eyePosition) {
    const F distance = sqrt(dot(eyePosition, eyePosition));
    const F rise = dot(eyePosition, V3(fog.up));  // Δy
    const float base = fog.density * std::exp(-fog.falloff * (fog.eyeHeight - fog.baseHeight));
    return base * distance * heightFogShape<F, P>(fog.falloff * rise);
}

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
        case FogMode::Height:
            break;  // needs the point, not a distance: applyFog
    }
    return lanes<F>(1.0f);
}

// The fog factor at the eye-space point: height fog's from the point, the others' from its distance.
template <class F, class V3 = LaneVec3<F>, MathPrecision P = MathPrecision::Exact>
F fogFactorAt(const FogParams& fog, const V3& eyePosition) {
    if (fog.mode == FogMode::Height)
        return saturate(Maths<P>::exp(-heightFogDepth<F, V3, P>(fog, eyePosition)));
    return fogFactor<F, P>(fog, fogDistance<F, V3>(fog, eyePosition));
}

// The record of the fog at one point (record.h).
struct FogRecord {
    static constexpr bool enabled = true;
    FogParams fog{};         // mode, distance kind, start, end, density, c_fog
    vec3 eyePosition{0.0f};  // P_eye
    float z = 0;             // the distance fog uses: |z_eye| or |P_eye|
    float f = 1;             // the fog factor, clamped to [0, 1]; 1 when fog is off
    float rise = 0;          // height fog: Δy, the point's height above the eye's
    float tau = 0;           // height fog: the optical depth τ
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
    const F f = fogFactorAt<F, V3, P>(fog, eyePosition);
    if constexpr (Record::enabled) {
        Record& record = *recordOf(recording...);
        record.z = fog.mode == FogMode::Height ? sqrt(dot(eyePosition, eyePosition))
                                               : fogDistance<F, V3>(fog, eyePosition);
        if (fog.mode == FogMode::Height) {
            record.rise = dot(eyePosition, V3(fog.up));
            record.tau = heightFogDepth<F, V3, P>(fog, eyePosition);
        }
        record.f = f;
        record.fogged = applyFog<F, V3, P>(fog, color, eyePosition);
        return record.fogged;
    }
    return color * f + V3(fog.color) * (1.0f - f);
}

}  // namespace facet
