// Eight lanes at a time: the value types the pipeline's SIMD paths and the built-in shaders are written
// with. Float8 is a GCC/Clang vector extension, so `a * b + c` on it reads like scalar code and compiles
// to one AVX2 instruction per operation (two SSE ones in a portable build). The vector types and
// functions mirror GLSL's (vec3, dot, normalize, max, pow), so a shader body can be written once, as a
// template, for float lanes and for Float8 lanes.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#if defined(__AVX__)
#include <immintrin.h>
#endif

#include "glsl.h"
#include "types.h"

namespace facet {

using Float8 = float __attribute__((vector_size(32)));
using Int8 = std::int32_t __attribute__((vector_size(32)));

// One bit per lane, set where the lane is negative (comparison results are all ones or all zeros).
inline unsigned signMask(Int8 v) {
#if defined(__AVX__)
    return static_cast<unsigned>(_mm256_movemask_ps(std::bit_cast<__m256>(v)));
#else
    unsigned bits = 0;
    for (int i = 0; i < 8; ++i)
        bits |= (static_cast<std::uint32_t>(v[i]) >> 31) << i;
    return bits;
#endif
}

inline Float8 splat(float v) {
    return Float8{v, v, v, v, v, v, v, v};
}

// Lane-wise choice: cond ? a : b, with cond a comparison result. The scalar overload lets templates
// written for both lane types use the same word.
inline Float8 select(Int8 cond, Float8 a, Float8 b) {
    return cond ? a : b;
}
inline float select(bool cond, float a, float b) {
    return cond ? a : b;
}
inline Float8 select(Int8 cond, float a, float b) {
    return cond ? splat(a) : splat(b);
}

inline Float8 max(Float8 a, Float8 b) {
    return a > b ? a : b;
}
inline Float8 min(Float8 a, Float8 b) {
    return a < b ? a : b;
}
inline Float8 max(Float8 a, float b) {
    return max(a, splat(b));
}

inline Float8 sqrt(Float8 v) {
    Float8 r{};
    for (int i = 0; i < 8; ++i)
        r[i] = std::sqrt(v[i]);  // one vsqrtps: the loop is vectorised
    return r;
}

// log2(x) for x > 0: x = m·2^e with m in [√½, √2), ln m = 2·atanh(t), t = (m − 1)/(m + 1), |t| ≤ 0.172,
// from the series 2(t + t³/3 + t⁵/5 + t⁷/7 + t⁹/9); the error is below 1e−9 of a unit.
inline Float8 log2(Float8 x) {
    const Int8 bits = std::bit_cast<Int8>(x);
    Int8 exponent = ((bits >> 23) & 0xff) - 127;
    Float8 m = std::bit_cast<Float8>((bits & 0x007fffff) | 0x3f800000);  // mantissa in [1, 2)
    const Int8 big = m > 1.41421356f;
    m = big ? m * 0.5f : m;
    exponent = exponent + (big & 1);
    const Float8 t = (m - 1.0f) / (m + 1.0f);
    const Float8 t2 = t * t;
    const Float8 lnM = t * (2.0f + t2 * (2.0f / 3 + t2 * (2.0f / 5 + t2 * (2.0f / 7 + t2 * (2.0f / 9)))));
    return __builtin_convertvector(exponent, Float8) + lnM * 1.44269504f;
}

// 2^y: y = n + f with n an integer and |f| ≤ ½, 2^f = e^(f·ln 2) from its Taylor series to degree 7
// (relative error below 1e−8), 2^n assembled in the exponent bits. Clamped to the float range.
inline Float8 exp2(Float8 y) {
    y = max(min(y, splat(127.0f)), splat(-126.0f));
    // Round to the nearest integer by adding and removing 1.5·2^23, which leaves no fraction bits
    // (exact for |y| < 2^22, in the default rounding mode).
    const Float8 rounded = (y + 12582912.0f) - 12582912.0f;
    const Float8 u = (y - rounded) * 0.693147181f;
    const Float8 p =
        1.0f +
        u * (1.0f +
             u * (1.0f / 2 + u * (1.0f / 6 + u * (1.0f / 24 +
                                                  u * (1.0f / 120 + u * (1.0f / 720 + u * (1.0f / 5040)))))));
    const Int8 n = __builtin_convertvector(rounded, Int8);
    return p * std::bit_cast<Float8>((n + 127) << 23);
}

// x^n for x ≥ 0, n ≥ 0, as GLSL's pow: 0 where x = 0 and n > 0, 1 where n = 0.
inline Float8 pow(Float8 x, float n) {
    if (n == 0.0f) return splat(1.0f);
    const Float8 r = exp2(log2(x) * n);
    return x > 0.0f ? r : splat(0.0f);
}

struct Vec2x8 {
    Float8 x, y;
};

struct Vec3x8 {
    Float8 x, y, z;
    Vec3x8() = default;
    Vec3x8(Float8 x_, Float8 y_, Float8 z_) : x(x_), y(y_), z(z_) {}
    explicit Vec3x8(const vec3& v) : x(splat(v.x)), y(splat(v.y)), z(splat(v.z)) {}
};

struct Vec4x8 {
    Float8 x, y, z, w;
};

inline Vec3x8 operator+(const Vec3x8& a, const Vec3x8& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec3x8 operator-(const Vec3x8& a, const Vec3x8& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec3x8 operator-(const Vec3x8& a) {
    return {-a.x, -a.y, -a.z};
}
inline Vec3x8 operator*(const Vec3x8& a, const Vec3x8& b) {
    return {a.x * b.x, a.y * b.y, a.z * b.z};
}
inline Vec3x8 operator*(const Vec3x8& a, Float8 s) {
    return {a.x * s, a.y * s, a.z * s};
}
inline Vec3x8 operator*(Float8 s, const Vec3x8& a) {
    return a * s;
}
inline Vec3x8 operator*(const Vec3x8& a, const vec3& v) {
    return {a.x * v.x, a.y * v.y, a.z * v.z};
}
inline Vec3x8 operator*(const vec3& v, const Vec3x8& a) {
    return a * v;
}
inline Vec3x8 operator*(const vec3& v, Float8 s) {
    return {v.x * s, v.y * s, v.z * s};
}
inline Vec3x8 operator+(const Vec3x8& a, const vec3& v) {
    return {a.x + v.x, a.y + v.y, a.z + v.z};
}
inline Vec3x8 operator-(const vec3& v, const Vec3x8& a) {
    return {v.x - a.x, v.y - a.y, v.z - a.z};
}
inline Vec3x8& operator+=(Vec3x8& a, const Vec3x8& b) {
    return a = a + b;
}

inline Float8 dot(const Vec3x8& a, const Vec3x8& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Float8 dot(const Vec3x8& a, const vec3& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3x8 normalize(const Vec3x8& v) {
    return v * (1.0f / sqrt(dot(v, v)));
}
inline Vec3x8 select(Int8 cond, const Vec3x8& a, const Vec3x8& b) {
    return {select(cond, a.x, b.x), select(cond, a.y, b.y), select(cond, a.z, b.z)};
}

// Scalar counterparts, so shader templates can use the same names for both lane types.
inline vec3 select(bool cond, const vec3& a, const vec3& b) {
    return cond ? a : b;
}
inline float max(float a, float b) {
    return a > b ? a : b;
}

// The interpolated varyings of eight fragments, one Float8 per varying float (structure of arrays).
struct FragmentBatch {
    Float8 varyings[kMaxVaryingFloats];
    std::uint32_t mask = 0;  // bit i: lane i is a live fragment (others hold meaningless values)

    Vec2x8 vec2At(int offset) const { return {varyings[offset], varyings[offset + 1]}; }
    Vec3x8 vec3At(int offset) const { return {varyings[offset], varyings[offset + 1], varyings[offset + 2]}; }
};

// ---- Lane-generic helpers: one name for float and Float8 lanes, for formulas written as templates ---

template <class F>
struct LaneTraits;
template <>
struct LaneTraits<float> {
    using Vec3 = vec3;
    static float splat(float v) { return v; }
};
template <>
struct LaneTraits<Float8> {
    using Vec3 = Vec3x8;
    static Float8 splat(float v) { return facet::splat(v); }
};

// The three-component vector type that goes with the lane type F.
template <class F>
using LaneVec3 = typename LaneTraits<F>::Vec3;

// v in every lane of F.
template <class F>
F lanes(float v) {
    return LaneTraits<F>::splat(v);
}

inline Vec3x8 operator*(const Vec3x8& a, float s) {
    return {a.x * s, a.y * s, a.z * s};
}
inline Vec3x8 operator*(float s, const Vec3x8& a) {
    return a * s;
}
inline Vec3x8 operator+(const vec3& v, const Vec3x8& a) {
    return a + v;
}

inline Float8 min(Float8 a, float b) {
    return min(a, splat(b));
}
inline Float8 select(Int8 cond, Float8 a, float b) {
    return select(cond, a, splat(b));
}
inline Float8 select(Int8 cond, float a, Float8 b) {
    return select(cond, splat(a), b);
}

inline float sqrt(float x) {
    return std::sqrt(x);
}

inline float abs(float x) {
    return std::fabs(x);
}
inline Float8 abs(Float8 x) {
    return max(x, -x);
}

// e^x = 2^(x·log2 e).
inline float exp(float x) {
    return std::exp(x);
}
inline Float8 exp(Float8 x) {
    return exp2(x * std::numbers::log2e_v<float>);
}

// clamp(x, 0, 1) (HLSL's saturate).
inline float saturate(float x) {
    return std::clamp(x, 0.0f, 1.0f);
}
inline Float8 saturate(Float8 x) {
    return max(min(x, 1.0f), 0.0f);
}

// v/|v|, and the zero vector for the zero vector (normalize would give NaN).
template <class F, class V3 = LaneVec3<F>>
V3 safeNormalize(const V3& v) {
    return v * (1.0f / sqrt(max(dot(v, v), 1e-30f)));
}

// GLSL's smoothstep: t = clamp((x − e0)/(e1 − e0), 0, 1), t²(3 − 2t).
template <class F>
F smoothstep(float edge0, float edge1, F x) {
    const float width = edge1 - edge0;
    const F t = saturate((x - edge0) * (1.0f / (width != 0.0f ? width : 1e-7f)));
    return t * t * (3.0f - 2.0f * t);
}

}  // namespace facet
