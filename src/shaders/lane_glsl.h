// GLSL's functions over lanes, for shaders of one's own (user_shader.h): one name for F = float (one
// fragment), F = Float8 (eight) and F = Floatx16 (sixteen, in the AVX-512 copy: wide.h), and for their
// vectors vec2/vec3/vec4 and WideVec2/3/4<F> (Vec2x8, Vec3x8, Vec4x8, …), so that a fragment part
// written once over F reads like GLSL. The many-lane versions are templates over the lane type.
//
// What pipeline/wide.h and glsl.h already give is not repeated here: select, max, sqrt, abs, dot and
// normalize of Vec3x8, saturate, smoothstep(edge0, edge1, x) with float edges, the Vec3x8 operators,
// withAlpha and rgb, and GLM's length, dot, cross, normalize, reflect of vec3. This header adds the rest.
//
// The one-lane versions (float, vec2, vec3) that GLM or the C library would compute otherwise, and
// GLSL's step, are in namespace facet::glsl (at the end), which a shader brings in with
// `using namespace facet::glsl;`; the eight-lane ones are in namespace facet.
//
// The rule every function here keeps: the eight-lane version gives, lane by lane, the same bits as the
// one-lane version (tests/shaders/lane_glsl_test.cpp), so the step mode's trace of a pixel (F = float)
// shows the very numbers that drew it (F = Float8). Where GLM's one-lane function would compare or round
// in another order than the eight-lane one (min and max of a signed zero or a NaN, clamp, mix), the float
// version is defined here too, the same expression as the eight-lane one.
//
// One trap stays: pow(x, float n) of many lanes in wide.h is the fast polynomial pow, while pow(float, float)
// is the C library's. For the same bits in both, write pow(x, lanes<F>(n)) (the C library's, lane by
// lane), or Maths<P>::pow(x, n) with one precision P for both.
#pragma once

#include <cmath>

#include "pipeline/glsl.h"
#include "pipeline/wide.h"

namespace facet {

// ---- Broadcasting: a uniform in every lane -------------------------------------------------------------

// lanes<F>(0.5f) exists in wide.h; these give a vector in every lane: lanes<F>(u.ink) is a LaneVec3<F>.
template <class F>
LaneVec2<F> lanes(const vec2& v) {
    if constexpr (std::is_same_v<F, float>)
        return v;
    else
        return {lanes<F>(v.x), lanes<F>(v.y)};
}
template <class F>
LaneVec3<F> lanes(const vec3& v) {
    return LaneVec3<F>(v);
}
template <class F>
LaneVec4<F> lanes(const vec4& v) {
    if constexpr (std::is_same_v<F, float>)
        return v;
    else
        return {lanes<F>(v.x), lanes<F>(v.y), lanes<F>(v.z), lanes<F>(v.w)};
}

// ---- Scalars ---------------------------------------------------------------------------------------------

// clamp(x, lo, hi) = min(max(x, lo), hi).
template <WideLanes F>
F clamp(F x, float lo, float hi) {
    return min(max(x, lo), hi);
}
template <WideLanes F>
F clamp(F x, F lo, F hi) {
    return min(max(x, lo), hi);
}

// mix(x, y, a) = x·(1 − a) + y·a, GLSL's linear blend (a = 0 gives x, a = 1 gives y, exactly).
template <WideLanes F>
F mix(F x, F y, F a) {
    return x * (1.0f - a) + y * a;
}
template <WideLanes F>
F mix(float x, float y, F a) {
    return x * (1.0f - a) + y * a;
}

// sign(x): −1, 0 or 1 (0 for ±0; NaN gives 0).
template <WideLanes F>
F sign(F x) {
    return select(x > 0.0f, lanes<F>(1.0f), select(x < 0.0f, lanes<F>(-1.0f), lanes<F>(0.0f)));
}

// The per-lane C library functions: floor, ceil, sin, cos, and pow with a power per lane. Each lane
// calls the one-lane function (the rounding ones compile to one roundps).
namespace detail {
template <WideLanes F, class Fn>
F eachLane(F x, Fn fn) {
    for (int i = 0; i < LaneTraits<F>::kCount; ++i)
        x[i] = fn(x[i]);
    return x;
}
}  // namespace detail

template <WideLanes F>
F floor(F x) {
    return detail::eachLane(x, [](float v) { return std::floor(v); });
}
template <WideLanes F>
F ceil(F x) {
    return detail::eachLane(x, [](float v) { return std::ceil(v); });
}
template <WideLanes F>
F sin(F x) {
    return detail::eachLane(x, [](float v) { return std::sin(v); });
}
template <WideLanes F>
F cos(F x) {
    return detail::eachLane(x, [](float v) { return std::cos(v); });
}
// x^n with the C library's pow in each lane: the same bits as pow(float, float).
template <WideLanes F>
F pow(F x, F n) {
    for (int i = 0; i < LaneTraits<F>::kCount; ++i)
        x[i] = std::pow(x[i], n[i]);
    return x;
}

// fract(x) = x − floor(x), in [0, 1) (GLSL's; 1 − ε rounds to 1 for tiny negative x, as GLSL's does).
template <WideLanes F>
F fract(F x) {
    return x - floor(x);
}

// mod(x, y) = x − y·floor(x/y), GLSL's (the result takes y's sign, unlike C's fmod).
template <WideLanes F>
F mod(F x, F y) {
    return x - y * floor(x / y);
}
template <WideLanes F>
F mod(F x, float y) {
    return x - y * floor(x / y);
}

// ---- Vectors -------------------------------------------------------------------------------------------

// Vec2x8 and Vec4x8 arithmetic (wide.h has Vec3x8's).
template <class F>
WideVec2<F> operator+(const WideVec2<F>& a, const WideVec2<F>& b) {
    return {a.x + b.x, a.y + b.y};
}
template <class F>
WideVec2<F> operator-(const WideVec2<F>& a, const WideVec2<F>& b) {
    return {a.x - b.x, a.y - b.y};
}
template <class F>
WideVec2<F> operator-(const WideVec2<F>& a) {
    return {-a.x, -a.y};
}
template <class F>
WideVec2<F> operator*(const WideVec2<F>& a, const WideVec2<F>& b) {
    return {a.x * b.x, a.y * b.y};
}
template <class F>
WideVec2<F> operator*(const WideVec2<F>& a, F s) {
    return {a.x * s, a.y * s};
}
template <class F>
WideVec2<F> operator*(F s, const WideVec2<F>& a) {
    return a * s;
}
template <class F>
WideVec2<F> operator*(const WideVec2<F>& a, float s) {
    return {a.x * s, a.y * s};
}
template <class F>
WideVec2<F> operator*(float s, const WideVec2<F>& a) {
    return a * s;
}
template <class F>
WideVec4<F> operator+(const WideVec4<F>& a, const WideVec4<F>& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z, a.w + b.w};
}
template <class F>
WideVec4<F> operator-(const WideVec4<F>& a, const WideVec4<F>& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z, a.w - b.w};
}
template <class F>
WideVec4<F> operator*(const WideVec4<F>& a, const WideVec4<F>& b) {
    return {a.x * b.x, a.y * b.y, a.z * b.z, a.w * b.w};
}
template <class F>
WideVec4<F> operator*(const WideVec4<F>& a, F s) {
    return {a.x * s, a.y * s, a.z * s, a.w * s};
}
template <class F>
WideVec4<F> operator*(F s, const WideVec4<F>& a) {
    return a * s;
}
template <class F>
WideVec4<F> operator*(const WideVec4<F>& a, float s) {
    return {a.x * s, a.y * s, a.z * s, a.w * s};
}
template <class F>
WideVec3<F> operator-(const WideVec3<F>& a, const vec3& v) {
    return {a.x - v.x, a.y - v.y, a.z - v.z};
}
template <class F>
WideVec3<F> operator/(const WideVec3<F>& a, F s) {
    return {a.x / s, a.y / s, a.z / s};
}
template <class F>
WideVec3<F> operator/(const WideVec3<F>& a, float s) {
    return {a.x / s, a.y / s, a.z / s};
}

// dot, length and normalize as GLM computes them for vec2/vec3: the products summed from x on,
// length = sqrt(dot(v, v)), normalize = v·(1/sqrt(dot(v, v))).
template <class F>
F dot(const WideVec2<F>& a, const WideVec2<F>& b) {
    return a.x * b.x + a.y * b.y;
}
template <class F>
F length(const WideVec2<F>& v) {
    return sqrt(dot(v, v));
}
template <class F>
F length(const WideVec3<F>& v) {
    return sqrt(dot(v, v));
}
template <class F>
WideVec2<F> normalize(const WideVec2<F>& v) {
    return v * (1.0f / sqrt(dot(v, v)));
}

// cross(a, b), in GLM's order of operations.
template <class F>
WideVec3<F> cross(const WideVec3<F>& a, const WideVec3<F>& b) {
    return {a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y};
}

// reflect(I, N) = I − 2(N·I)N: I mirrored about the plane of the unit normal N (GLSL's, GLM's order).
template <class F>
WideVec3<F> reflect(const WideVec3<F>& I, const WideVec3<F>& N) {
    return I - N * dot(N, I) * 2.0f;
}

// Component-wise min, max, clamp, mix, floor, fract of vec3 and Vec3x8, with the scalar functions
// above (so both lane widths compare in the same order).
template <class F>
WideVec3<F> min(const WideVec3<F>& a, const WideVec3<F>& b) {
    return {min(a.x, b.x), min(a.y, b.y), min(a.z, b.z)};
}
template <class F>
WideVec3<F> max(const WideVec3<F>& a, const WideVec3<F>& b) {
    return {max(a.x, b.x), max(a.y, b.y), max(a.z, b.z)};
}
template <class F>
WideVec3<F> clamp(const WideVec3<F>& v, float lo, float hi) {
    return {clamp(v.x, lo, hi), clamp(v.y, lo, hi), clamp(v.z, lo, hi)};
}
template <class F>
WideVec3<F> mix(const WideVec3<F>& x, const WideVec3<F>& y, F a) {
    return {mix(x.x, y.x, a), mix(x.y, y.y, a), mix(x.z, y.z, a)};
}
template <class F>
WideVec3<F> mix(const WideVec3<F>& x, const WideVec3<F>& y, float a) {
    return mix(x, y, lanes<F>(a));
}
template <class F>
WideVec3<F> floor(const WideVec3<F>& v) {
    return {floor(v.x), floor(v.y), floor(v.z)};
}
template <class F>
WideVec3<F> fract(const WideVec3<F>& v) {
    return {fract(v.x), fract(v.y), fract(v.z)};
}
template <class F>
WideVec2<F> fract(const WideVec2<F>& v) {
    return {fract(v.x), fract(v.y)};
}
template <class F>
WideVec2<F> floor(const WideVec2<F>& v) {
    return {floor(v.x), floor(v.y)};
}

// select for the other vectors (wide.h has float, Float8, vec3 and Vec3x8).
template <class F>
WideVec2<F> select(WideMask<F> cond, const WideVec2<F>& a, const WideVec2<F>& b) {
    return {select(cond, a.x, b.x), select(cond, a.y, b.y)};
}
template <class F>
WideVec4<F> select(WideMask<F> cond, const WideVec4<F>& a, const WideVec4<F>& b) {
    return {select(cond, a.x, b.x), select(cond, a.y, b.y), select(cond, a.z, b.z), select(cond, a.w, b.w)};
}

// The lanes' masks combined: a && b, a || b, !a for one lane (bool) and many (Int8, all ones where
// true), for conditions written once.
template <WideMaskLanes I>
I both(I a, I b) {
    return a & b;
}
template <WideMaskLanes I>
I either(I a, I b) {
    return a | b;
}
template <WideMaskLanes I>
I negate(I a) {
    return ~a;
}

// One lane of a lane value (lane 0 of eight; the value itself for one): what record() and tests read.
template <WideLanes F>
float laneOf(F v, int lane) {
    return v[lane];
}
template <class F>
vec3 laneOf(const WideVec3<F>& v, int lane) {
    return {v.x[lane], v.y[lane], v.z[lane]};
}

// ---- One lane: namespace facet::glsl ---------------------------------------------------------------------

// The one-lane (float, vec2, vec3, bool) versions of the functions above, and GLSL's step, live in
// namespace facet::glsl, which a shader's file brings in beside facet:
//   using namespace facet;
//   using namespace facet::glsl;
// Kept out of namespace facet itself, so that facet's own code, which sees these headers through the
// renderer's, keeps calling GLM's and the C library's functions as before (and facet::step, the step
// mode's namespace, keeps its name).
namespace glsl {

// min, as the eight-lane min compares (a < b ? a : b; GLM's would keep a where the two are equal, so a
// +0 and a −0, or a NaN, would come out differently in one lane and in eight).
inline float min(float a, float b) {
    return a < b ? a : b;
}

inline float clamp(float x, float lo, float hi) {
    return min(facet::max(x, lo), hi);
}

inline float mix(float x, float y, float a) {
    return x * (1.0f - a) + y * a;
}

// step(edge, x): 0 where x < edge, else 1 (all three here: a function facet::step would clash with the
// step mode's namespace).
inline float step(float edge, float x) {
    return x < edge ? 0.0f : 1.0f;
}

template <WideLanes F>
F step(float edge, F x) {
    return facet::select(x < edge, lanes<F>(0.0f), lanes<F>(1.0f));
}

template <WideLanes F>
F step(F edge, F x) {
    return facet::select(x < edge, lanes<F>(0.0f), lanes<F>(1.0f));
}

inline float sign(float x) {
    return x > 0.0f ? 1.0f : (x < 0.0f ? -1.0f : 0.0f);
}

inline float floor(float x) {
    return std::floor(x);
}

inline float ceil(float x) {
    return std::ceil(x);
}

inline float sin(float x) {
    return std::sin(x);
}

inline float cos(float x) {
    return std::cos(x);
}

inline float fract(float x) {
    return x - floor(x);
}

inline float mod(float x, float y) {
    return x - y * floor(x / y);
}

inline vec3 min(const vec3& a, const vec3& b) {
    return {min(a.x, b.x), min(a.y, b.y), min(a.z, b.z)};
}

inline vec3 max(const vec3& a, const vec3& b) {
    return {facet::max(a.x, b.x), facet::max(a.y, b.y), facet::max(a.z, b.z)};
}

inline vec3 clamp(const vec3& v, float lo, float hi) {
    return {clamp(v.x, lo, hi), clamp(v.y, lo, hi), clamp(v.z, lo, hi)};
}

inline vec3 mix(const vec3& x, const vec3& y, float a) {
    return {mix(x.x, y.x, a), mix(x.y, y.y, a), mix(x.z, y.z, a)};
}

inline vec3 floor(const vec3& v) {
    return {floor(v.x), floor(v.y), floor(v.z)};
}

inline vec3 fract(const vec3& v) {
    return {fract(v.x), fract(v.y), fract(v.z)};
}

inline vec2 fract(const vec2& v) {
    return {fract(v.x), fract(v.y)};
}

inline vec2 floor(const vec2& v) {
    return {floor(v.x), floor(v.y)};
}

inline vec2 select(bool cond, const vec2& a, const vec2& b) {
    return cond ? a : b;
}

inline vec4 select(bool cond, const vec4& a, const vec4& b) {
    return cond ? a : b;
}

inline bool both(bool a, bool b) {
    return a && b;
}

inline bool either(bool a, bool b) {
    return a || b;
}

inline bool negate(bool a) {
    return !a;
}

inline float laneOf(float v, int) {
    return v;
}

inline vec3 laneOf(const vec3& v, int) {
    return v;
}

}  // namespace glsl

}  // namespace facet
