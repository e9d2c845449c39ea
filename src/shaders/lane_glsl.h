// GLSL's functions over lanes, for shaders of one's own (user_shader.h): one name for F = float (one
// fragment) and F = Float8 (eight), and for their vectors vec2/vec3/vec4 and Vec2x8/Vec3x8/Vec4x8, so
// that a fragment part written once over F reads like GLSL.
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
// One trap stays: pow(Float8 x, float n) in wide.h is the fast polynomial pow, while pow(float, float)
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
        return {splat(v.x), splat(v.y)};
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
        return {splat(v.x), splat(v.y), splat(v.z), splat(v.w)};
}

// ---- Scalars ---------------------------------------------------------------------------------------------

// clamp(x, lo, hi) = min(max(x, lo), hi).
inline Float8 clamp(Float8 x, float lo, float hi) {
    return min(max(x, lo), hi);
}
inline Float8 clamp(Float8 x, Float8 lo, Float8 hi) {
    return min(max(x, lo), hi);
}

// mix(x, y, a) = x·(1 − a) + y·a, GLSL's linear blend (a = 0 gives x, a = 1 gives y, exactly).
inline Float8 mix(Float8 x, Float8 y, Float8 a) {
    return x * (1.0f - a) + y * a;
}
inline Float8 mix(float x, float y, Float8 a) {
    return x * (1.0f - a) + y * a;
}

// sign(x): −1, 0 or 1 (0 for ±0; NaN gives 0).
inline Float8 sign(Float8 x) {
    return select(x > 0.0f, splat(1.0f), select(x < 0.0f, -1.0f, 0.0f));
}

// The per-lane C library functions: floor, ceil, sin, cos, and pow with a power per lane. Each Float8
// lane calls the one-lane function (the rounding ones compile to one roundps).
namespace detail {
template <class Fn>
Float8 eachLane(Float8 x, Fn fn) {
    for (int i = 0; i < 8; ++i)
        x[i] = fn(x[i]);
    return x;
}
}  // namespace detail

inline Float8 floor(Float8 x) {
    return detail::eachLane(x, [](float v) { return std::floor(v); });
}
inline Float8 ceil(Float8 x) {
    return detail::eachLane(x, [](float v) { return std::ceil(v); });
}
inline Float8 sin(Float8 x) {
    return detail::eachLane(x, [](float v) { return std::sin(v); });
}
inline Float8 cos(Float8 x) {
    return detail::eachLane(x, [](float v) { return std::cos(v); });
}
// x^n with the C library's pow in each lane: the same bits as pow(float, float).
inline Float8 pow(Float8 x, Float8 n) {
    for (int i = 0; i < 8; ++i)
        x[i] = std::pow(x[i], n[i]);
    return x;
}

// fract(x) = x − floor(x), in [0, 1) (GLSL's; 1 − ε rounds to 1 for tiny negative x, as GLSL's does).
inline Float8 fract(Float8 x) {
    return x - floor(x);
}

// mod(x, y) = x − y·floor(x/y), GLSL's (the result takes y's sign, unlike C's fmod).
inline Float8 mod(Float8 x, Float8 y) {
    return x - y * floor(x / y);
}
inline Float8 mod(Float8 x, float y) {
    return x - y * floor(x / y);
}

// ---- Vectors -------------------------------------------------------------------------------------------

// Vec2x8 and Vec4x8 arithmetic (wide.h has Vec3x8's).
inline Vec2x8 operator+(const Vec2x8& a, const Vec2x8& b) {
    return {a.x + b.x, a.y + b.y};
}
inline Vec2x8 operator-(const Vec2x8& a, const Vec2x8& b) {
    return {a.x - b.x, a.y - b.y};
}
inline Vec2x8 operator-(const Vec2x8& a) {
    return {-a.x, -a.y};
}
inline Vec2x8 operator*(const Vec2x8& a, const Vec2x8& b) {
    return {a.x * b.x, a.y * b.y};
}
inline Vec2x8 operator*(const Vec2x8& a, Float8 s) {
    return {a.x * s, a.y * s};
}
inline Vec2x8 operator*(Float8 s, const Vec2x8& a) {
    return a * s;
}
inline Vec2x8 operator*(const Vec2x8& a, float s) {
    return {a.x * s, a.y * s};
}
inline Vec2x8 operator*(float s, const Vec2x8& a) {
    return a * s;
}
inline Vec4x8 operator+(const Vec4x8& a, const Vec4x8& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z, a.w + b.w};
}
inline Vec4x8 operator-(const Vec4x8& a, const Vec4x8& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z, a.w - b.w};
}
inline Vec4x8 operator*(const Vec4x8& a, const Vec4x8& b) {
    return {a.x * b.x, a.y * b.y, a.z * b.z, a.w * b.w};
}
inline Vec4x8 operator*(const Vec4x8& a, Float8 s) {
    return {a.x * s, a.y * s, a.z * s, a.w * s};
}
inline Vec4x8 operator*(Float8 s, const Vec4x8& a) {
    return a * s;
}
inline Vec4x8 operator*(const Vec4x8& a, float s) {
    return {a.x * s, a.y * s, a.z * s, a.w * s};
}
inline Vec3x8 operator-(const Vec3x8& a, const vec3& v) {
    return {a.x - v.x, a.y - v.y, a.z - v.z};
}
inline Vec3x8 operator/(const Vec3x8& a, Float8 s) {
    return {a.x / s, a.y / s, a.z / s};
}
inline Vec3x8 operator/(const Vec3x8& a, float s) {
    return {a.x / s, a.y / s, a.z / s};
}

// dot, length and normalize as GLM computes them for vec2/vec3: the products summed from x on,
// length = sqrt(dot(v, v)), normalize = v·(1/sqrt(dot(v, v))).
inline Float8 dot(const Vec2x8& a, const Vec2x8& b) {
    return a.x * b.x + a.y * b.y;
}
inline Float8 length(const Vec2x8& v) {
    return sqrt(dot(v, v));
}
inline Float8 length(const Vec3x8& v) {
    return sqrt(dot(v, v));
}
inline Vec2x8 normalize(const Vec2x8& v) {
    return v * (1.0f / sqrt(dot(v, v)));
}

// cross(a, b), in GLM's order of operations.
inline Vec3x8 cross(const Vec3x8& a, const Vec3x8& b) {
    return {a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y};
}

// reflect(I, N) = I − 2(N·I)N: I mirrored about the plane of the unit normal N (GLSL's, GLM's order).
inline Vec3x8 reflect(const Vec3x8& I, const Vec3x8& N) {
    return I - N * dot(N, I) * 2.0f;
}

// Component-wise min, max, clamp, mix, floor, fract of vec3 and Vec3x8, with the scalar functions
// above (so both lane widths compare in the same order).
inline Vec3x8 min(const Vec3x8& a, const Vec3x8& b) {
    return {min(a.x, b.x), min(a.y, b.y), min(a.z, b.z)};
}
inline Vec3x8 max(const Vec3x8& a, const Vec3x8& b) {
    return {max(a.x, b.x), max(a.y, b.y), max(a.z, b.z)};
}
inline Vec3x8 clamp(const Vec3x8& v, float lo, float hi) {
    return {clamp(v.x, lo, hi), clamp(v.y, lo, hi), clamp(v.z, lo, hi)};
}
inline Vec3x8 mix(const Vec3x8& x, const Vec3x8& y, Float8 a) {
    return {mix(x.x, y.x, a), mix(x.y, y.y, a), mix(x.z, y.z, a)};
}
inline Vec3x8 mix(const Vec3x8& x, const Vec3x8& y, float a) {
    return mix(x, y, splat(a));
}
inline Vec3x8 floor(const Vec3x8& v) {
    return {floor(v.x), floor(v.y), floor(v.z)};
}
inline Vec3x8 fract(const Vec3x8& v) {
    return {fract(v.x), fract(v.y), fract(v.z)};
}
inline Vec2x8 fract(const Vec2x8& v) {
    return {fract(v.x), fract(v.y)};
}
inline Vec2x8 floor(const Vec2x8& v) {
    return {floor(v.x), floor(v.y)};
}

// select for the other vectors (wide.h has float, Float8, vec3 and Vec3x8).
inline Vec2x8 select(Int8 cond, const Vec2x8& a, const Vec2x8& b) {
    return {select(cond, a.x, b.x), select(cond, a.y, b.y)};
}
inline Vec4x8 select(Int8 cond, const Vec4x8& a, const Vec4x8& b) {
    return {select(cond, a.x, b.x), select(cond, a.y, b.y), select(cond, a.z, b.z), select(cond, a.w, b.w)};
}

// The lanes' masks combined: a && b, a || b, !a for one lane (bool) and eight (Int8, all ones where
// true), for conditions written once.
inline Int8 both(Int8 a, Int8 b) {
    return a & b;
}
inline Int8 either(Int8 a, Int8 b) {
    return a | b;
}
inline Int8 negate(Int8 a) {
    return ~a;
}

// One lane of a lane value (lane 0 of eight; the value itself for one): what record() and tests read.
inline float laneOf(Float8 v, int lane) {
    return v[lane];
}
inline vec3 laneOf(const Vec3x8& v, int lane) {
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

inline Float8 step(float edge, Float8 x) {
    return facet::select(x < edge, 0.0f, 1.0f);
}

inline Float8 step(Float8 edge, Float8 x) {
    return facet::select(x < edge, 0.0f, 1.0f);
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
