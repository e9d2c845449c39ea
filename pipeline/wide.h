// Eight lanes at a time: the value types the pipeline's SIMD paths and the built-in shaders are written
// with. Float8 is a GCC/Clang vector extension, so `a * b + c` on it reads like scalar code and compiles
// to one AVX2 instruction per operation (two SSE ones in a portable build). The vector types and
// functions mirror GLSL's (vec3, dot, normalize, max, pow), so a shader body can be written once, as a
// template, for float lanes and for Float8 lanes.
#pragma once

#include <immintrin.h>  // x86 only: the reciprocal square root estimate, the sign mask
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <span>
#include <string_view>

#include "glsl.h"
#include "names.h"
#include "types.h"

namespace facet {

using Float8 = float __attribute__((vector_size(32)));
using Int8 = std::int32_t __attribute__((vector_size(32)));

// Sixteen lanes, where the instruction set has 512-bit registers (the AVX-512 copy of the hot path,
// frame_kernels.h): the fragment shader then runs on two batches of eight at once (back_end.h), one
// instruction per operation for sixteen fragments. Elsewhere a 64-byte vector would be split by the
// compiler into single lanes for every comparison, so only the AVX-512 copy has them. Every operation
// is the same correctly rounded one lane by lane, so sixteen lanes give the bits eight give.
#if defined(__AVX512F__)
#define FACET_SIXTEEN_LANES 1
using Floatx16 = float __attribute__((vector_size(64)));
using Intx16 = std::int32_t __attribute__((vector_size(64)));
#endif

// The float lane vectors (Float8, and Floatx16 where there is one) and their comparison results.
template <class F>
struct WideMaskOf;
template <>
struct WideMaskOf<Float8> {
    using type = Int8;
};
#if FACET_SIXTEEN_LANES
template <>
struct WideMaskOf<Floatx16> {
    using type = Intx16;
};
#endif
template <class F>
concept WideLanes = requires {
    typename WideMaskOf<F>::type;
};
template <class F>
using WideMask = typename WideMaskOf<F>::type;
// How many lanes F has.
template <WideLanes F>
inline constexpr int kLaneCount = int(sizeof(F) / sizeof(float));
// Their comparison results: Int8, and Intx16 where there is one.
template <class I>
concept WideMaskLanes = std::same_as<I, Int8>
#if FACET_SIXTEEN_LANES
    || std::same_as<I, Intx16>
#endif
    ;

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

#if FACET_SIXTEEN_LANES
inline unsigned signMask(Intx16 v) {
    return static_cast<unsigned>(_mm512_cmplt_epi32_mask(std::bit_cast<__m512i>(v), _mm512_setzero_si512()));
}
#endif

inline Float8 splat(float v) {
    return Float8{v, v, v, v, v, v, v, v};
}
// v in every lane of a lane vector.
template <WideLanes F>
F splatLanes(float v) {
    return F{} + v;
}

// Lane-wise choice: cond ? a : b, with cond a comparison result. The scalar overload lets templates
// written for both lane types use the same word.
template <WideLanes F>
F select(WideMask<F> cond, F a, F b) {
    return cond ? a : b;
}
inline float select(bool cond, float a, float b) {
    return cond ? a : b;
}
inline Float8 select(Int8 cond, float a, float b) {
    return cond ? splat(a) : splat(b);
}

template <WideLanes F>
F max(F a, F b) {
    return a > b ? a : b;
}
template <WideLanes F>
F min(F a, F b) {
    return a < b ? a : b;
}
template <WideLanes F>
F max(F a, float b) {
    return max(a, splatLanes<F>(b));
}

template <WideLanes F>
F sqrt(F v) {
    F r{};
    for (int i = 0; i < kLaneCount<F>; ++i)
        r[i] = std::sqrt(v[i]);  // one vsqrtps: the loop is vectorised
    return r;
}

// vec2, vec3 and vec4 of lane vectors: one lane vector per component (structure of arrays).
template <WideLanes F>
struct WideVec2 {
    F x, y;
};

template <WideLanes F>
struct WideVec3 {
    F x, y, z;
    WideVec3() = default;
    WideVec3(F x_, F y_, F z_) : x(x_), y(y_), z(z_) {}
    explicit WideVec3(const vec3& v) : x(splatLanes<F>(v.x)), y(splatLanes<F>(v.y)), z(splatLanes<F>(v.z)) {}
};

template <WideLanes F>
struct WideVec4 {
    F x, y, z, w;
};

using Vec2x8 = WideVec2<Float8>;
using Vec3x8 = WideVec3<Float8>;
using Vec4x8 = WideVec4<Float8>;
#if FACET_SIXTEEN_LANES
using Vec2x16 = WideVec2<Floatx16>;
using Vec3x16 = WideVec3<Floatx16>;
using Vec4x16 = WideVec4<Floatx16>;

// The halves of sixteen lanes (lanes 0–7, 8–15) and sixteen lanes from two halves.
inline Float8 lowHalf(Floatx16 v) {
    return __builtin_shufflevector(v, v, 0, 1, 2, 3, 4, 5, 6, 7);
}
inline Float8 highHalf(Floatx16 v) {
    return __builtin_shufflevector(v, v, 8, 9, 10, 11, 12, 13, 14, 15);
}
inline Floatx16 joinHalves(Float8 low, Float8 high) {
    return __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
}
inline Vec2x8 lowHalf(const Vec2x16& v) {
    return {lowHalf(v.x), lowHalf(v.y)};
}
inline Vec2x8 highHalf(const Vec2x16& v) {
    return {highHalf(v.x), highHalf(v.y)};
}
inline Vec3x8 lowHalf(const Vec3x16& v) {
    return {lowHalf(v.x), lowHalf(v.y), lowHalf(v.z)};
}
inline Vec3x8 highHalf(const Vec3x16& v) {
    return {highHalf(v.x), highHalf(v.y), highHalf(v.z)};
}
inline Vec3x16 joinHalves(const Vec3x8& low, const Vec3x8& high) {
    return {joinHalves(low.x, high.x), joinHalves(low.y, high.y), joinHalves(low.z, high.z)};
}
inline Vec4x16 joinHalves(const Vec4x8& low, const Vec4x8& high) {
    return {joinHalves(low.x, high.x), joinHalves(low.y, high.y), joinHalves(low.z, high.z),
            joinHalves(low.w, high.w)};
}
inline Vec4x8 lowHalf(const Vec4x16& v) {
    return {lowHalf(v.x), lowHalf(v.y), lowHalf(v.z), lowHalf(v.w)};
}
inline Vec4x8 highHalf(const Vec4x16& v) {
    return {highHalf(v.x), highHalf(v.y), highHalf(v.z), highHalf(v.w)};
}
#endif

// The eight lanes of a Vec4x8 as eight vec4 (structure of arrays to array of structures): a 4×8
// transpose in registers, twelve shuffles and four 32-byte stores instead of 32 single-float moves.
inline void storeTransposed(const Vec4x8& v, vec4 (&out)[8]) {
    // (x0 y0 x1 y1 | x4 y4 x5 y5), (x2 y2 x3 y3 | x6 y6 x7 y7), and the same for z and w.
    const Float8 xyLow = __builtin_shufflevector(v.x, v.y, 0, 8, 1, 9, 4, 12, 5, 13);
    const Float8 xyHigh = __builtin_shufflevector(v.x, v.y, 2, 10, 3, 11, 6, 14, 7, 15);
    const Float8 zwLow = __builtin_shufflevector(v.z, v.w, 0, 8, 1, 9, 4, 12, 5, 13);
    const Float8 zwHigh = __builtin_shufflevector(v.z, v.w, 2, 10, 3, 11, 6, 14, 7, 15);
    // Lanes (0 | 4), (1 | 5), (2 | 6), (3 | 7), each a whole vec4 per half.
    const Float8 lanes04 = __builtin_shufflevector(xyLow, zwLow, 0, 1, 8, 9, 4, 5, 12, 13);
    const Float8 lanes15 = __builtin_shufflevector(xyLow, zwLow, 2, 3, 10, 11, 6, 7, 14, 15);
    const Float8 lanes26 = __builtin_shufflevector(xyHigh, zwHigh, 0, 1, 8, 9, 4, 5, 12, 13);
    const Float8 lanes37 = __builtin_shufflevector(xyHigh, zwHigh, 2, 3, 10, 11, 6, 7, 14, 15);
    const Float8 lanes01 = __builtin_shufflevector(lanes04, lanes15, 0, 1, 2, 3, 8, 9, 10, 11);
    const Float8 lanes23 = __builtin_shufflevector(lanes26, lanes37, 0, 1, 2, 3, 8, 9, 10, 11);
    const Float8 lanes45 = __builtin_shufflevector(lanes04, lanes15, 4, 5, 6, 7, 12, 13, 14, 15);
    const Float8 lanes67 = __builtin_shufflevector(lanes26, lanes37, 4, 5, 6, 7, 12, 13, 14, 15);
    static_assert(sizeof(vec4) == 4 * sizeof(float));
    std::memcpy(&out[0], &lanes01, sizeof lanes01);
    std::memcpy(&out[2], &lanes23, sizeof lanes23);
    std::memcpy(&out[4], &lanes45, sizeof lanes45);
    std::memcpy(&out[6], &lanes67, sizeof lanes67);
}

// Eight vec4 as the four lanes of a Vec4x8 (array of structures to structure of arrays): four 32-byte
// loads and eight shuffles, storeTransposed's inverse.
[[gnu::always_inline]] inline Vec4x8 loadTransposed(const vec4* in) {
    static_assert(sizeof(vec4) == 4 * sizeof(float));
    Float8 rows[4];  // vertices (0, 1), (2, 3), (4, 5), (6, 7)
    std::memcpy(rows, in, sizeof rows);
    // (v0 | v4), (v1 | v5), (v2 | v6), (v3 | v7): each half of the register then a 4×4 transpose.
    const Float8 v04 = __builtin_shufflevector(rows[0], rows[2], 0, 1, 2, 3, 8, 9, 10, 11);
    const Float8 v15 = __builtin_shufflevector(rows[0], rows[2], 4, 5, 6, 7, 12, 13, 14, 15);
    const Float8 v26 = __builtin_shufflevector(rows[1], rows[3], 0, 1, 2, 3, 8, 9, 10, 11);
    const Float8 v37 = __builtin_shufflevector(rows[1], rows[3], 4, 5, 6, 7, 12, 13, 14, 15);
    // (x0 x1 y0 y1 | x4 x5 y4 y5), (z0 z1 w0 w1 | z4 z5 w4 w5), and the same for vertices 2, 3, 6, 7.
    const Float8 xy01 = __builtin_shufflevector(v04, v15, 0, 8, 1, 9, 4, 12, 5, 13);
    const Float8 zw01 = __builtin_shufflevector(v04, v15, 2, 10, 3, 11, 6, 14, 7, 15);
    const Float8 xy23 = __builtin_shufflevector(v26, v37, 0, 8, 1, 9, 4, 12, 5, 13);
    const Float8 zw23 = __builtin_shufflevector(v26, v37, 2, 10, 3, 11, 6, 14, 7, 15);
    return {__builtin_shufflevector(xy01, xy23, 0, 1, 8, 9, 4, 5, 12, 13),
            __builtin_shufflevector(xy01, xy23, 2, 3, 10, 11, 6, 7, 14, 15),
            __builtin_shufflevector(zw01, zw23, 0, 1, 8, 9, 4, 5, 12, 13),
            __builtin_shufflevector(zw01, zw23, 2, 3, 10, 11, 6, 7, 14, 15)};
}

// An 8×8 matrix of 32-bit lanes transposed in registers: rows[k][j] becomes rows[j][k]. Eight structures
// of eight floats (or ints) loaded as rows come out as eight lanes of each field, and the other way
// round: 24 shuffles instead of 64 single-element moves. Three rounds: pairs of rows interleaved, pairs
// of pairs, then the 128-bit halves exchanged.
template <class V>
[[gnu::always_inline]] inline void transpose8x8(V (&rows)[8]) {
    V a[8], b[8];
    for (int k = 0; k < 8; k += 2) {
        a[k] = __builtin_shufflevector(rows[k], rows[k + 1], 0, 8, 1, 9, 4, 12, 5, 13);
        a[k + 1] = __builtin_shufflevector(rows[k], rows[k + 1], 2, 10, 3, 11, 6, 14, 7, 15);
    }
    for (int k = 0; k < 8; k += 4)
        for (int j = 0; j < 2; ++j) {
            b[k + 2 * j] = __builtin_shufflevector(a[k + j], a[k + j + 2], 0, 1, 8, 9, 4, 5, 12, 13);
            b[k + 2 * j + 1] = __builtin_shufflevector(a[k + j], a[k + j + 2], 2, 3, 10, 11, 6, 7, 14, 15);
        }
    for (int j = 0; j < 4; ++j) {
        rows[j] = __builtin_shufflevector(b[j], b[j + 4], 0, 1, 2, 3, 8, 9, 10, 11);
        rows[j + 4] = __builtin_shufflevector(b[j], b[j + 4], 4, 5, 6, 7, 12, 13, 14, 15);
    }
}

template <class F>
WideVec3<F> operator+(const WideVec3<F>& a, const WideVec3<F>& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class F>
WideVec3<F> operator-(const WideVec3<F>& a, const WideVec3<F>& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class F>
WideVec3<F> operator-(const WideVec3<F>& a) {
    return {-a.x, -a.y, -a.z};
}
template <class F>
WideVec3<F> operator*(const WideVec3<F>& a, const WideVec3<F>& b) {
    return {a.x * b.x, a.y * b.y, a.z * b.z};
}
template <class F>
WideVec3<F> operator*(const WideVec3<F>& a, F s) {
    return {a.x * s, a.y * s, a.z * s};
}
template <class F>
WideVec3<F> operator*(F s, const WideVec3<F>& a) {
    return a * s;
}
template <class F>
WideVec3<F> operator*(const WideVec3<F>& a, const vec3& v) {
    return {a.x * v.x, a.y * v.y, a.z * v.z};
}
template <class F>
WideVec3<F> operator*(const vec3& v, const WideVec3<F>& a) {
    return a * v;
}
template <WideLanes F>
WideVec3<F> operator*(const vec3& v, F s) {
    return {v.x * s, v.y * s, v.z * s};
}
template <class F>
WideVec3<F> operator+(const WideVec3<F>& a, const vec3& v) {
    return {a.x + v.x, a.y + v.y, a.z + v.z};
}
template <class F>
WideVec3<F> operator-(const vec3& v, const WideVec3<F>& a) {
    return {v.x - a.x, v.y - a.y, v.z - a.z};
}
template <class F>
WideVec3<F>& operator+=(WideVec3<F>& a, const WideVec3<F>& b) {
    return a = a + b;
}

template <class F>
F dot(const WideVec3<F>& a, const WideVec3<F>& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class F>
F dot(const WideVec3<F>& a, const vec3& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class F>
WideVec3<F> normalize(const WideVec3<F>& v) {
    return v * (1.0f / sqrt(dot(v, v)));
}
template <class F>
WideVec3<F> select(WideMask<F> cond, const WideVec3<F>& a, const WideVec3<F>& b) {
    return {select(cond, a.x, b.x), select(cond, a.y, b.y), select(cond, a.z, b.z)};
}

// Lane i all ones where bit i of `bits` is set: a lane mask (FragmentBatch::mask) as a comparison result.
inline Int8 laneMaskOf(unsigned bits) {
    const Int8 laneBits = {1, 2, 4, 8, 16, 32, 64, 128};
    return (laneBits & static_cast<std::int32_t>(bits)) != 0;
}
// The same for the lanes of F: laneMaskOf<F>(bits).
template <WideLanes F>
WideMask<F> laneMaskOf(unsigned bits) {
    WideMask<F> laneBits;
    for (int lane = 0; lane < kLaneCount<F>; ++lane)
        laneBits[lane] = 1 << lane;
    return (laneBits & static_cast<std::int32_t>(bits)) != 0;
}

// table[index[i]] in each lane: one gather instruction with AVX2, eight loads without. Every index
// must be valid, dead lanes' too.
inline Float8 gather(const float* table, Int8 index) {
#if defined(__AVX2__)
    return std::bit_cast<Float8>(_mm256_i32gather_ps(table, std::bit_cast<__m256i>(index), 4));
#else
    Float8 r;
    for (int i = 0; i < 8; ++i)
        r[i] = table[index[i]];
    return r;
#endif
}
#if FACET_SIXTEEN_LANES
// (The masked form with every lane set: GCC 12's plain one reads an uninitialised register.)
inline Floatx16 gather(const float* table, Intx16 index) {
    return std::bit_cast<Floatx16>(
        _mm512_mask_i32gather_ps(_mm512_setzero_ps(), 0xffff, std::bit_cast<__m512i>(index), table, 4));
}
#endif
// table[code[i]] in each lane for a table of 256 entries and codes 0–255 (an 8-bit code's decoded
// value): a gather on eight lanes; on sixteen, eight two-register permutes, each reading the 32 entries
// of one eighth of the table by the code's low five bits, then the code's bits 5, 6 and 7 choosing among
// their results: the same entries, with register operations in place of a gather's sixteen loads
// (a bilinear sample decodes twelve of these per sixteen samples).
inline Float8 lookupByteCodes(const std::array<float, 256>& table, Int8 code) {
    return gather(table.data(), code);
}
#if FACET_SIXTEEN_LANES
inline Floatx16 lookupByteCodes(const std::array<float, 256>& table, Intx16 code) {
    const __m512i index = std::bit_cast<__m512i>(code);
    const float* t = table.data();
    auto eighth = [&](int k) {  // entries 32k … 32k + 31 by the code's low five bits
        return _mm512_permutex2var_ps(_mm512_loadu_ps(t + 32 * k), index, _mm512_loadu_ps(t + 32 * k + 16));
    };
    const __mmask16 bit5 = _mm512_test_epi32_mask(index, _mm512_set1_epi32(32));
    const __mmask16 bit6 = _mm512_test_epi32_mask(index, _mm512_set1_epi32(64));
    const __mmask16 bit7 = _mm512_test_epi32_mask(index, _mm512_set1_epi32(128));
    const __m512 quarter0 = _mm512_mask_blend_ps(bit5, eighth(0), eighth(1));
    const __m512 quarter1 = _mm512_mask_blend_ps(bit5, eighth(2), eighth(3));
    const __m512 quarter2 = _mm512_mask_blend_ps(bit5, eighth(4), eighth(5));
    const __m512 quarter3 = _mm512_mask_blend_ps(bit5, eighth(6), eighth(7));
    const __m512 half0 = _mm512_mask_blend_ps(bit6, quarter0, quarter1);
    const __m512 half1 = _mm512_mask_blend_ps(bit6, quarter2, quarter3);
    return std::bit_cast<Floatx16>(_mm512_mask_blend_ps(bit7, half0, half1));
}
#endif
// For each 8-bit mask, the indices of its set bits in ascending order, then zeros: lane i of a vector
// permuted by entry `mask` is the lane of the i-th set bit (a "compress" of the lanes the mask keeps).
inline constexpr auto kPackedLaneIndices = [] {
    std::array<std::array<std::int32_t, 8>, 256> table{};
    for (unsigned mask = 0; mask < 256; ++mask) {
        int next = 0;
        for (int lane = 0; lane < 8; ++lane)
            if ((mask >> lane) & 1u) table[mask][static_cast<std::size_t>(next++)] = lane;
    }
    return table;
}();

inline Int8 packedLaneIndices(unsigned mask) {
    Int8 indices;
    std::memcpy(&indices, kPackedLaneIndices[mask & 0xffu].data(), sizeof indices);
    return indices;
}

// v[index[i]] in each lane (indices 0–7): one permute instruction with AVX2, eight moves without.
inline Float8 permuteLanes(Float8 v, Int8 index) {
#if defined(__AVX2__)
    return std::bit_cast<Float8>(
        _mm256_permutevar8x32_ps(std::bit_cast<__m256>(v), std::bit_cast<__m256i>(index)));
#else
    Float8 r;
    for (int i = 0; i < 8; ++i)
        r[i] = v[index[i] & 7];
    return r;
#endif
}

// The lowest k set bits of an 8-bit `mask` (k ≥ 0): all of it when it has no more than k.
inline unsigned lowestSetBits(unsigned mask, int k) {
    if (std::popcount(mask) <= k) return mask;
    const int beyond = kPackedLaneIndices[mask & 0xffu][static_cast<std::size_t>(k)];  // the (k+1)-th
    return mask & ((1u << beyond) - 1u);
}

// The 4-byte word at bytes + 4·index[i] in each lane, as the bytes lie in memory (any 4-byte element,
// read without regard to its type: memcpy's semantics, one gather with AVX2).
inline Int8 gatherWords(const void* bytes, Int8 index) {
#if defined(__AVX2__)
    return std::bit_cast<Int8>(
        _mm256_i32gather_epi32(static_cast<const int*>(bytes), std::bit_cast<__m256i>(index), 4));
#else
    Int8 r;
    for (int i = 0; i < 8; ++i) {
        std::int32_t word;
        std::memcpy(&word,
                    static_cast<const unsigned char*>(bytes) + 4 * std::size_t(std::uint32_t(index[i])), 4);
        r[i] = word;
    }
    return r;
#endif
}

#if FACET_SIXTEEN_LANES
inline Intx16 gatherWords(const void* bytes, Intx16 index) {
    return std::bit_cast<Intx16>(
        _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), 0xffff, std::bit_cast<__m512i>(index), bytes, 4));
}
#endif

// Scalar counterparts, so shader templates can use the same names for both lane types.
inline vec3 select(bool cond, const vec3& a, const vec3& b) {
    return cond ? a : b;
}
inline float max(float a, float b) {
    return a > b ? a : b;
}

// The interpolated varyings of eight fragments, one Float8 per varying float (structure of arrays); a
// shader reads them as its VaryingsT<Float8> (shader.h's loadLanes).
struct FragmentBatch {
    Float8 varyings[kMaxVaryingFloats];
    // ∂u/∂x, ∂v/∂x, ∂u/∂y, ∂v/∂y of the shader's texture coordinates (its kDerivativeVarying pair, per
    // pixel), filled only in a draw whose shader asks for them (shader.h); otherwise not written.
    Float8 uvDerivatives[4];
    // λ1, λ2 of each lane's pixel in its window triangle (λ0 = 1 − λ1 − λ2), in the setup's vertex order
    // (FragmentEvent::barycentrics'), filled only in a draw whose shader asks (shader.h's
    // wantsBarycentrics); otherwise not written.
    Float8 barycentrics[2];
    std::uint32_t mask = 0;  // bit i: lane i is a live fragment (others hold meaningless values)
};

// ---- Lane-generic helpers: one name for float and Float8 lanes, for formulas written as templates ---

template <class F>
struct LaneTraits;
template <>
struct LaneTraits<float> {
    using Int = std::int32_t;
    using Vec2 = vec2;
    using Vec3 = vec3;
    using Vec4 = vec4;
    static constexpr int kCount = 1;
    static float splat(float v) { return v; }
    static float toFloat(std::int32_t v) { return static_cast<float>(v); }
    static std::int32_t toInt(float v) { return static_cast<std::int32_t>(v); }
};
template <WideLanes F>
struct LaneTraits<F> {
    using Int = WideMask<F>;
    using Vec2 = WideVec2<F>;
    using Vec3 = WideVec3<F>;
    using Vec4 = WideVec4<F>;
    static constexpr int kCount = kLaneCount<F>;
    static F splat(float v) { return splatLanes<F>(v); }
    static F toFloat(Int v) { return __builtin_convertvector(v, F); }
    static Int toInt(F v) { return __builtin_convertvector(v, Int); }
};

// The vector types that go with the lane type F: vec2/vec3/vec4 for one lane, Vec2x8/Vec3x8/Vec4x8 for
// eight.
template <class F>
using LaneVec2 = typename LaneTraits<F>::Vec2;
template <class F>
using LaneVec3 = typename LaneTraits<F>::Vec3;
template <class F>
using LaneVec4 = typename LaneTraits<F>::Vec4;

// v in every lane of F.
template <class F>
F lanes(float v) {
    return LaneTraits<F>::splat(v);
}

// GLSL's c.rgb and vec4(c, a), for both lane types.
inline vec3 rgb(const vec4& c) {
    return vec3(c);
}
template <class F>
WideVec3<F> rgb(const WideVec4<F>& c) {
    return {c.x, c.y, c.z};
}
inline vec4 withAlpha(const vec3& c, float alpha) {
    return vec4(c, alpha);
}
template <class F>
WideVec4<F> withAlpha(const WideVec3<F>& c, F alpha) {
    return {c.x, c.y, c.z, alpha};
}

template <class F>
WideVec3<F> operator*(const WideVec3<F>& a, float s) {
    return {a.x * s, a.y * s, a.z * s};
}
template <class F>
WideVec3<F> operator*(float s, const WideVec3<F>& a) {
    return a * s;
}
template <class F>
WideVec3<F> operator+(const vec3& v, const WideVec3<F>& a) {
    return a + v;
}

template <WideLanes F>
F min(F a, float b) {
    return min(a, splatLanes<F>(b));
}
template <WideLanes F>
F select(WideMask<F> cond, F a, float b) {
    return select(cond, a, splatLanes<F>(b));
}
template <WideLanes F>
F select(WideMask<F> cond, float a, F b) {
    return select(cond, splatLanes<F>(a), b);
}

inline float sqrt(float x) {
    return std::sqrt(x);
}

inline float abs(float x) {
    return std::fabs(x);
}
// The sign bit cleared, as fabs does (max(x, −x) would give −0 for +0 and −NaN for a NaN).
template <WideLanes F>
F abs(F x) {
    return std::bit_cast<F>(std::bit_cast<WideMask<F>>(x) & 0x7fffffff);
}

// ---- Double: one lane in double precision, the exact reference renderer's -------------------------
// The formulas' templates run on F = double, V3 = glm::dvec3 as they do on float. Every function a
// formula calls on its lanes has a double overload here, declared before the formulas so that their
// unqualified calls find it (a double would otherwise be rounded to float on the way into the float
// overload); the mixed double/float vector operators are in namespace glm, found by argument lookup.
// The float code's overloads are untouched: every double overload takes a double first.

template <>
struct LaneTraits<double> {
    using Int = std::int64_t;
    using Vec2 = glm::dvec2;
    using Vec3 = glm::dvec3;
    using Vec4 = glm::dvec4;
    static constexpr int kCount = 1;
    static double splat(float v) { return v; }
};

inline double select(bool cond, double a, double b) {
    return cond ? a : b;
}
inline double select(bool cond, double a, float b) {
    return cond ? a : b;
}
inline double select(bool cond, float a, double b) {
    return cond ? a : b;
}
inline glm::dvec3 select(bool cond, const glm::dvec3& a, const glm::dvec3& b) {
    return cond ? a : b;
}
inline double max(double a, double b) {
    return a > b ? a : b;
}
inline double max(double a, float b) {
    return max(a, double(b));
}
inline double min(double a, double b) {
    return a < b ? a : b;
}
inline double min(double a, float b) {
    return min(a, double(b));
}
inline double sqrt(double x) {
    return std::sqrt(x);
}
inline double abs(double x) {
    return std::fabs(x);
}
inline glm::dvec3 rgb(const glm::dvec4& c) {
    return glm::dvec3(c);
}
inline glm::dvec4 withAlpha(const glm::dvec3& c, double alpha) {
    return glm::dvec4(c, alpha);
}

// clamp(x, 0, 1) (HLSL's saturate): min(x, 1), then max(·, 0), as the eight-lane min and max compare.
template <class F>
F saturate(F x) {
    const F below = select(x < 1.0f, x, lanes<F>(1.0f));
    return select(below > 0.0f, below, lanes<F>(0.0f));
}

// ---- Exact or fast transcendental functions, chosen explicitly -------------------------------------

// How pow and exp are computed. The choice is the caller's (a shader takes it from its uniforms, the
// same for the whole draw), never implied by the lane width: one lane and eight lanes give the same
// bits under either choice.
enum class MathPrecision : std::uint8_t {
    Exact,  // the C library's powf and expf, lane by lane (correctly rounded or nearly so)
    Fast,   // polynomials on the float's bits (fastLog2, fastExp2 below): within 2e−5 relative for
            // the exponents lighting uses (pow's error grows with n)
};
inline constexpr EnumName<MathPrecision> kMathPrecisionNames[] = {{MathPrecision::Exact, "exact"},
                                                                  {MathPrecision::Fast, "fast"}};
constexpr std::span<const EnumName<MathPrecision>> enumNames(MathPrecision) {
    return kMathPrecisionNames;
}
inline constexpr std::string_view mathPrecisionName(MathPrecision p) {
    return nameOf(p);
}

// log2(x) for x > 0: x = m·2^e with m in [√½, √2), ln m = 2·atanh(t), t = (m − 1)/(m + 1), |t| ≤ 0.172,
// from the series 2(t + t³/3 + t⁵/5 + t⁷/7 + t⁹/9); the error is below 1e−9 of a unit.
template <class F>
F fastLog2(F x) {
    using Traits = LaneTraits<F>;
    using Int = typename Traits::Int;
    const Int bits = std::bit_cast<Int>(x);
    Int exponent = ((bits >> 23) & 0xff) - 127;
    F m = std::bit_cast<F>((bits & 0x007fffff) | 0x3f800000);  // mantissa in [1, 2)
    const auto big = m > 1.41421356f;                          // bool, or all ones per lane
    m = select(big, m * 0.5f, m);
    exponent = exponent + (big & 1);
    const F t = (m - 1.0f) / (m + 1.0f);
    const F t2 = t * t;
    const F lnM = t * (2.0f + t2 * (2.0f / 3 + t2 * (2.0f / 5 + t2 * (2.0f / 7 + t2 * (2.0f / 9)))));
    return Traits::toFloat(exponent) + lnM * 1.44269504f;
}

// 2^y: y = n + f with n an integer and |f| ≤ ½, 2^f = e^(f·ln 2) from its Taylor series to degree 7
// (relative error below 1e−8), 2^n assembled in the exponent bits. Clamped to the float range.
template <class F>
F fastExp2(F y) {
    using Traits = LaneTraits<F>;
    const F atMost = select(y < 127.0f, y, lanes<F>(127.0f));
    y = select(atMost > -126.0f, atMost, lanes<F>(-126.0f));
    // Round to the nearest integer by adding and removing 1.5·2^23, which leaves no fraction bits
    // (exact for |y| < 2^22, in the default rounding mode).
    const F rounded = (y + 12582912.0f) - 12582912.0f;
    const F u = (y - rounded) * 0.693147181f;
    const F p =
        1.0f +
        u * (1.0f +
             u * (1.0f / 2 + u * (1.0f / 6 + u * (1.0f / 24 +
                                                  u * (1.0f / 120 + u * (1.0f / 720 + u * (1.0f / 5040)))))));
    const typename Traits::Int n = Traits::toInt(rounded);
    return p * std::bit_cast<F>((n + 127) << 23);
}

// Double lanes have no approximation of their own: there, Fast is the exact function too (the
// reference renderer asks for Exact anyway; this only lets the formulas' Fast branches compile).
template <>
inline double fastLog2<double>(double x) {
    return std::log2(x);
}
template <>
inline double fastExp2<double>(double y) {
    return std::exp2(y);
}

template <MathPrecision P>
struct Maths;

template <>
struct Maths<MathPrecision::Exact> {
    // x^n for x ≥ 0, n ≥ 0, as GLSL's pow: 0 where x = 0 and n > 0, 1 where n = 0.
    static float pow(float x, float n) { return std::pow(x, n); }
    template <WideLanes F>
    static F pow(F x, float n) {
        for (int i = 0; i < LaneTraits<F>::kCount; ++i)
            x[i] = std::pow(x[i], n);
        return x;
    }
    static float exp(float x) { return std::exp(x); }
    template <WideLanes F>
    static F exp(F x) {
        for (int i = 0; i < LaneTraits<F>::kCount; ++i)
            x[i] = std::exp(x[i]);
        return x;
    }
    static double pow(double x, float n) { return std::pow(x, double(n)); }
    static double exp(double x) { return std::exp(x); }
};

template <>
struct Maths<MathPrecision::Fast> {
    // x^n = 2^(n·log2 x), with pow's edges: 0 where x = 0 and n > 0, 1 where n = 0. Always inlined
    // into the shaders (GCC otherwise splits off the body and calls it per batch of fragments).
    template <class F>
    [[gnu::always_inline]] static F pow(F x, float n) {
        if (n == 0.0f) return lanes<F>(1.0f);
        const F r = fastExp2(fastLog2(x) * n);
        return select(x > 0.0f, r, lanes<F>(0.0f));
    }
    // e^x = 2^(x·log2 e).
    template <class F>
    static F exp(F x) {
        return fastExp2(x * std::numbers::log2e_v<float>);
    }
};

// The eight-lane log2, exp2 and pow of GLSL's vocabulary are the fast ones.
template <WideLanes F>
F log2(F x) {
    return fastLog2(x);
}
template <WideLanes F>
F exp2(F y) {
    return fastExp2(y);
}
template <WideLanes F>
F pow(F x, float n) {
    return Maths<MathPrecision::Fast>::pow(x, n);
}

// ---- Exact or fast normalisation, chosen explicitly -----------------------------------------------

// How the shaders make N, L, V and H unit length: v·(1/√(v·v)) with the square root and the division
// correctly rounded, or with the reciprocal square root approximated. The choice is the draw's, as
// MathPrecision's is; one lane and eight give the same bits under either.
enum class Normalization : std::uint8_t {
    Exact,  // 1/sqrt(x): two correctly rounded operations, within 1 ulp
    Fast,   // vrsqrtps (12 bits) and one Newton–Raphson step: within 2^-21 relative (fastInverseSqrt)
};
inline constexpr EnumName<Normalization> kNormalizationNames[] = {{Normalization::Exact, "exact"},
                                                                  {Normalization::Fast, "fast"}};
constexpr std::span<const EnumName<Normalization>> enumNames(Normalization) {
    return kNormalizationNames;
}

// 1/√x for normal floats x > 0: the hardware estimate y₀ (rsqrtps, relative error at most 1.5·2⁻¹²,
// Intel SDM), then one Newton–Raphson step for f(y) = 1/y² − x, y₁ = y₀·(1.5 − 0.5·x·y₀²), which
// squares the relative error: |e₁| ≈ 1.5·e₀² + rounding, within 2⁻²¹ (tests/shaders measure it). The
// single-lane version uses rsqrtss, the same estimate, so one lane and eight agree bit for bit.
inline float fastInverseSqrt(float x) {
    const float y = _mm_cvtss_f32(_mm_rsqrt_ss(_mm_set_ss(x)));
    return y * (1.5f - 0.5f * x * y * y);
}
inline Float8 fastInverseSqrt(Float8 x) {
#if defined(__AVX__)
    const Float8 y = std::bit_cast<Float8>(_mm256_rsqrt_ps(std::bit_cast<__m256>(x)));
#else
    // Without AVX, two rsqrtps of four lanes: the same estimate per lane as vrsqrtps of eight.
    using Float4 = float __attribute__((vector_size(16)));
    const auto halves = std::bit_cast<std::array<Float4, 2>>(x);
    const std::array<Float4, 2> estimates{
        std::bit_cast<Float4>(_mm_rsqrt_ps(std::bit_cast<__m128>(halves[0]))),
        std::bit_cast<Float4>(_mm_rsqrt_ps(std::bit_cast<__m128>(halves[1])))};
    const Float8 y = std::bit_cast<Float8>(estimates);
#endif
    return y * (1.5f - 0.5f * x * y * y);
}
#if FACET_SIXTEEN_LANES
// Sixteen lanes: the eight-lane estimate of each half (vrsqrt14ps would give other bits).
inline Floatx16 fastInverseSqrt(Floatx16 x) {
    const Float8 low = fastInverseSqrt(Float8(__builtin_shufflevector(x, x, 0, 1, 2, 3, 4, 5, 6, 7)));
    const Float8 high = fastInverseSqrt(Float8(__builtin_shufflevector(x, x, 8, 9, 10, 11, 12, 13, 14, 15)));
    return __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
}
#endif
// Double lanes (the reference renderer) have no approximation: the exact 1/√x.
inline double fastInverseSqrt(double x) {
    return 1.0 / std::sqrt(x);
}

// 1/√x under the choice kNormalization.
template <Normalization kNormalization, class F>
F inverseSqrt(F x) {
    if constexpr (kNormalization == Normalization::Fast)
        return fastInverseSqrt(x);
    else
        return 1.0f / sqrt(x);
}

// v/|v|, and the zero vector for the zero vector (normalize would give NaN): the squared length is
// clamped to 1e−30, so the zero vector is scaled by 1e15 and stays zero.
template <class F, class V3 = LaneVec3<F>, Normalization kNormalization = Normalization::Exact>
V3 safeNormalize(const V3& v) {
    return v * inverseSqrt<kNormalization>(max(dot(v, v), 1e-30f));
}

// GLSL's smoothstep: t = clamp((x − e0)/(e1 − e0), 0, 1), t²(3 − 2t).
template <class F>
F smoothstep(float edge0, float edge1, F x) {
    const float width = edge1 - edge0;
    const F t = saturate((x - edge0) * (1.0f / (width != 0.0f ? width : 1e-7f)));
    return t * t * (3.0f - 2.0f * t);
}

}  // namespace facet

// Double lanes meet the scene's float parameters (a light's position, a material's colour): the float
// operand is widened exactly, never the double narrowed.
namespace glm {
inline dvec3 operator+(const dvec3& a, const vec3& b) {
    return a + dvec3(b);
}
inline dvec3 operator+(const vec3& a, const dvec3& b) {
    return dvec3(a) + b;
}
inline dvec3 operator-(const dvec3& a, const vec3& b) {
    return a - dvec3(b);
}
inline dvec3 operator-(const vec3& a, const dvec3& b) {
    return dvec3(a) - b;
}
inline dvec3 operator*(const dvec3& a, const vec3& b) {
    return a * dvec3(b);
}
inline dvec3 operator*(const vec3& a, const dvec3& b) {
    return dvec3(a) * b;
}
inline dvec3 operator*(const dvec3& a, float s) {
    return a * double(s);
}
inline dvec3 operator*(float s, const dvec3& a) {
    return double(s) * a;
}
inline dvec3 operator*(const vec3& a, double s) {
    return dvec3(a) * s;
}
inline dvec3 operator*(double s, const vec3& a) {
    return s * dvec3(a);
}
inline double dot(const dvec3& a, const vec3& b) {
    return dot(a, dvec3(b));
}
inline double dot(const vec3& a, const dvec3& b) {
    return dot(dvec3(a), b);
}
}  // namespace glm
