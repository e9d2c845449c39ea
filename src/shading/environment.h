// Environment maps: the light arriving from far away in every direction, stored as an equirectangular
// (latitude-longitude) image, and read along a direction (Blinn & Newell 1976; Akenine-Möller et al.,
// Real-Time Rendering 4th ed. §10.4.1, "Latitude-Longitude Mapping"; lighting-deck-C.txt, "Environment
// maps (reflection maps)"). The map's frame has +y up; a direction d = (x, y, z), |d| = 1, is at
//   u = ½ + atan2(x, −z)/(2π)     (longitude: −z, straight ahead of a default camera, is the centre)
//   v = ½ + asin(y)/π             (latitude: v = 1, the image's top row, is straight up)
// and (u, v) is at d = (cos θ sin φ, sin θ, −cos θ cos φ) with φ = 2π(u − ½), θ = π(v − ½).
// The lookup is bilinear, wrapping in u (the seam at ±z behind the map's centre) and clamped to the
// first and last rows' centres in v (no wrapping over the poles).
//
// A mirror reflection of the map: R = 2(N·V)N − V (N, V unit, eye space), the map read along R turned into
// the map's frame, weighted by w: Schlick's Fresnel F0 + (1 − F0)(1 − N·V)^5 for Cook-Torrance surfaces,
// the material's m_specular for the standard equation's. One template over the lane type (float, Float8,
// double); the texture is read lane by lane.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pipeline/glsl.h"
#include "pipeline/texture.h"
#include "pipeline/wide.h"
#include "shading/record.h"
#include "shading/two_sided.h"

namespace facet {

struct EnvironmentParams {
    const Texture* map = nullptr;  // null: no environment, nothing is read or added
    float intensity = 1.0f;        // the texels' scale
    // Eye-space directions to the map's frame: the eye-to-world rotation, then the map's turn about up.
    mat3 mapFromEye{1.0f};
};

// (u, v) of a direction in the map's frame (need not be unit length; 0 gives the centre).
template <class T>
glm::vec<2, T> equirectUv(const glm::vec<3, T>& d) {
    const T length = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    const T y = length > T(0) ? std::clamp(d.y / length, T(-1), T(1)) : T(0);
    const T pi = std::numbers::pi_v<T>;
    return {T(0.5) + std::atan2(d.x, -d.z) / (T(2) * pi), T(0.5) + std::asin(y) / pi};
}

// The unit direction at (u, v): equirectUv's inverse.
template <class T>
glm::vec<3, T> equirectDirection(const glm::vec<2, T>& uv) {
    const T pi = std::numbers::pi_v<T>;
    const T phi = T(2) * pi * (uv.x - T(0.5)), theta = pi * (uv.y - T(0.5));
    return {std::cos(theta) * std::sin(phi), std::sin(theta), -std::cos(theta) * std::cos(phi)};
}

// v kept between the centres of the first and last rows, so that bilinear filtering never wraps over a
// pole; u wraps (the texture's repeat).
inline vec2 environmentLookupUv(const Texture& map, vec2 uv) {
    const float half = 0.5f / static_cast<float>(std::max(map.height, 1));
    return {uv.x, std::clamp(uv.y, half, 1.0f - half)};
}

// The map's colour along an eye-space direction (any length), times the intensity.
template <class T>
vec3 environmentColor(const EnvironmentParams& env, const glm::vec<3, T>& eyeDirection) {
    const glm::vec<3, T> d = glm::mat<3, 3, T>(env.mapFromEye) * eyeDirection;
    const vec2 uv = environmentLookupUv(*env.map, vec2(equirectUv<T>(d)));
    return vec3(sampleBilinear(*env.map, uv)) * env.intensity;
}

// The record of the environment's reflection at one point (record.h).
struct EnvironmentRecord {
    static constexpr bool enabled = true;
    bool used = false;      // the draw has an environment map
    bool fresnel = false;   // w is Schlick's Fresnel (Cook-Torrance); else m_specular
    vec3 N{0.0f}, V{0.0f};  // unit, N after the two-sided flip
    float NdotV = 0;        // clamped to [0, 1]
    vec3 R{0.0f};           // 2(N·V)N − V, eye space
    vec3 direction{0.0f};   // R in the map's frame
    vec2 uv{0.0f};          // where it reads (v clamped to the rows' centres)
    ivec2 texel{0};         // the nearest texel (column, row from the top)
    vec3 color{0.0f};       // the bilinear texel times the intensity
    vec3 f0{0.0f};          // Cook-Torrance: F0
    vec3 weight{0.0f};      // w: F or m_specular
    vec3 term{0.0f};        // w ⊗ colour, added to the lit colour
};

namespace detail {

template <class F>
auto laneValue(const F& x, int lane) {
    if constexpr (LaneTraits<F>::kCount == 1)
        return x;
    else
        return x[lane];
}

}  // namespace detail

// The reflection term w ⊗ E(R) at eye-space point P with normal `normal` (not unit; flipped towards the
// viewer when `twoSided` and it faces away). `fresnelF0`: Cook-Torrance's F0, w = Schlick's F at N·V;
// null: w = `weight` (m_specular). Live lanes only (bit i: lane i); the others get 0.
template <class F, class V3 = LaneVec3<F>, class... Recording>
V3 environmentReflection(const EnvironmentParams& env, const V3& P, const V3& normal, bool twoSided,
                         const vec3* fresnelF0, const vec3& weight, unsigned liveLanes,
                         Recording*... recording) {
    using Record = RecordOf<Recording...>;
    static_assert(!Record::enabled || LaneTraits<F>::kCount == 1, "records hold one lane");
    V3 N = safeNormalize<F, V3>(normal);
    const V3 V = safeNormalize<F, V3>(-P);
    if (twoSided) N = select(seesUnderside(normal, P), -N, N);
    const F NdotV = saturate(dot(N, V));
    const V3 R = N * (2.0f * dot(N, V)) - V;
    V3 w;
    if (fresnelF0) {
        const F m = 1.0f - NdotV, m2 = m * m;
        w = (V3(vec3(1.0f) - *fresnelF0) * (m2 * m2 * m)) + V3(*fresnelF0);
    } else {
        w = V3(weight);
    }
    V3 color;
    if constexpr (LaneTraits<F>::kCount == 1) {
        color = V3(environmentColor(env, R));
    } else {
        color = V3(vec3(0.0f));
        for (int lane = 0; lane < LaneTraits<F>::kCount; ++lane) {
            if (!((liveLanes >> lane) & 1)) continue;
            const vec3 c = environmentColor(env, vec3(R.x[lane], R.y[lane], R.z[lane]));
            color.x[lane] = c.x;
            color.y[lane] = c.y;
            color.z[lane] = c.z;
        }
    }
    const V3 term = w * color;
    if constexpr (Record::enabled) {
        using T = decltype(detail::laneValue(NdotV, 0));
        const glm::vec<3, T> d = glm::mat<3, 3, T>(env.mapFromEye) * glm::vec<3, T>(R);
        const vec2 uv = environmentLookupUv(*env.map, vec2(equirectUv<T>(d)));
        const int column =
            std::clamp(static_cast<int>(std::floor(uv.x * env.map->width)), 0, env.map->width - 1);
        const int row =
            std::clamp(static_cast<int>(std::floor((1.0f - uv.y) * env.map->height)), 0, env.map->height - 1);
        *recordOf(recording...) = {.used = true,
                                   .fresnel = fresnelF0 != nullptr,
                                   .N = vec3(N),
                                   .V = vec3(V),
                                   .NdotV = float(NdotV),
                                   .R = vec3(R),
                                   .direction = vec3(d),
                                   .uv = uv,
                                   .texel = ivec2(column, row),
                                   .color = vec3(color),
                                   .f0 = fresnelF0 ? *fresnelF0 : vec3(0.0f),
                                   .weight = vec3(w),
                                   .term = vec3(term)};
    }
    return term;
}

}  // namespace facet
