// Perspective divide and viewport transform: clip space → normalised device coordinates → window
// coordinates, snapped to the fixed-point grid the rasterizer works on.
// In: a clip-space position. Out: WindowVertex (fixed-point x, y; depth; 1/w).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "depth_format.h"
#include "state.h"
#include "types.h"
#include "wide.h"

namespace facet {

namespace detail {

// Rounds a window coordinate to the sub-pixel grid: multiples of 2^(8 − bits) in 8-fraction-bit units.
inline std::int64_t snapToSubpixels(float windowCoordinate, int subpixelBits) {
    const int dropBits = kFixedFractionBits - subpixelBits;
    // × 2^bits by a multiplication: exact in double like std::ldexp, which is a call into libm per
    // coordinate (two per vertex of every draw).
    const double scaled =
        static_cast<double>(windowCoordinate) * static_cast<double>(std::int64_t{1} << subpixelBits);
    return static_cast<std::int64_t>(std::nearbyint(scaled)) << dropBits;
}

}  // namespace detail

// x_w = x_vp + (x_ndc + 1)/2 · width,  y_w = y_vp + (1 − y_ndc)/2 · height  (window y grows downwards),
// z_w = minDepth + (z_ndc + 1)/2 · (maxDepth − minDepth), clamped to the depth range as OpenGL does
// (DepthFormat::windowDepth).
// x and y are rounded to the nearest 1/2^subpixelBits of a pixel. Requires w ≥ kMinClipW (clipped).
// Inline: the vertex stage asks it of every vertex inside the frustum.
inline WindowVertex toWindow(const vec4& clip, const Viewport& viewport, int subpixelBits,
                             DepthBufferFormat depthFormat = DepthBufferFormat::Float) {
    // Perspective divide: clip space → normalised device coordinates in [−1, 1]³.
    const float invW = 1.0f / clip.w;
    const vec3 ndc = vec3(clip) * invW;

    // Viewport transform.
    WindowVertex v;
    v.window.x = static_cast<float>(viewport.x) + (ndc.x + 1.0f) * 0.5f * static_cast<float>(viewport.width);
    v.window.y = static_cast<float>(viewport.y) + (1.0f - ndc.y) * 0.5f * static_cast<float>(viewport.height);
    // Reversed Z maps 0..1 clip depth, the other formats OpenGL's −1..1 (the unorm ones round later,
    // when the back end stores the depth).
    v.z = depthFormat == DepthBufferFormat::ReversedFloat
              ? DepthFormatOf<DepthBufferFormat::ReversedFloat>::windowDepth(ndc.z, viewport.minDepth,
                                                                             viewport.maxDepth)
              : DepthFormat::windowDepth(ndc.z, viewport.minDepth, viewport.maxDepth);
    v.invW = invW;

    // Snap to fixed point. Clipping keeps |x_ndc|, |y_ndc| ≤ 1 up to rounding, so the values stay far
    // inside the budget of types.h; clamping guards the rounding.
    const float limit = static_cast<float>(2 * kMaxViewportSide);
    v.xFixed = detail::snapToSubpixels(std::clamp(v.window.x, -limit, limit), subpixelBits);
    v.yFixed = detail::snapToSubpixels(std::clamp(v.window.y, -limit, limit), subpixelBits);
    return v;
}

namespace detail {

// std::clamp(v, low, high) lane by lane, with its comparisons (a NaN lane stays NaN).
inline Float8 clampLanes(Float8 v, float low, float high) {
    return select(v < low, splat(low), select(high < v, splat(high), v));
}

// snapToSubpixels of eight window coordinates already clamped to ±2·kMaxViewportSide, as the two
// 32-bit halves of each lane's int64. Scaling by 2^bits is exact in float as in double, and rounding
// to nearest even gives the same integer from either: |v|·2^bits ≤ 2^23, so adding and removing 2^23
// rounds its magnitude (the float spacing there is 1), and the sign is put back (ties to even are
// symmetric).
[[gnu::always_inline]] inline void snapToSubpixels(Float8 windowCoordinate, int subpixelBits, Int8& low,
                                                   Int8& high) {
    const Float8 scaled = windowCoordinate * static_cast<float>(1 << subpixelBits);
    const Int8 bits = std::bit_cast<Int8>(scaled);
    const Float8 magnitude = std::bit_cast<Float8>(bits & 0x7fffffff);
    constexpr float kRound = 0x1p23f;
    const Float8 rounded = select(magnitude < kRound, (magnitude + kRound) - kRound, magnitude);
    const Int8 whole = __builtin_convertvector(
        std::bit_cast<Float8>(std::bit_cast<Int8>(rounded) | (bits & static_cast<std::int32_t>(0x80000000u))),
        Int8);
    // whole · 2^(kFixedFractionBits − subpixelBits) is the snapped coordinate in units of
    // 2^−kFixedFractionBits pixel, at most 2^23 in size: the low half holds it, the high half is its sign.
    static_assert(2 * kMaxViewportSide * (1 << kFixedFractionBits) <= (1 << 23));
    low = whole << (kFixedFractionBits - subpixelBits);
    high = low >> 31;
}

}  // namespace detail

// toWindow of the eight clip positions at `clip` into `out`, the same bits lane by lane (the vertex
// stage's groups: a vertex inside the frustum, outcode 0, is meaningful; the lanes of the others are
// computed from a stand-in position (0, 0, 0, 1) and are not).
[[gnu::always_inline]] inline void toWindow(const vec4* clip, const std::uint8_t* outcodes,
                                            const Viewport& viewport, int subpixelBits,
                                            DepthBufferFormat depthFormat, WindowVertex* out) {
    Vec4x8 p = loadTransposed(clip);
    using Bytes8 = std::uint8_t __attribute__((vector_size(8)));
    Bytes8 codes;
    std::memcpy(&codes, outcodes, sizeof codes);
    const Int8 inside = __builtin_convertvector(codes, Int8) == 0;
    p.x = select(inside, p.x, splat(0.0f));
    p.y = select(inside, p.y, splat(0.0f));
    p.z = select(inside, p.z, splat(0.0f));
    p.w = select(inside, p.w, splat(1.0f));

    const Float8 invW = 1.0f / p.w;
    const Float8 ndcX = p.x * invW, ndcY = p.y * invW, ndcZ = p.z * invW;
    const Float8 windowX =
        static_cast<float>(viewport.x) + (ndcX + 1.0f) * 0.5f * static_cast<float>(viewport.width);
    const Float8 windowY =
        static_cast<float>(viewport.y) + (1.0f - ndcY) * 0.5f * static_cast<float>(viewport.height);
    // DepthFormat::windowDepth: (z_ndc + 1)/2, or reversed Z's z_ndc, clamped to [0, 1], then mapped
    // to the viewport's depth range.
    const Float8 depth01 = depthFormat == DepthBufferFormat::ReversedFloat
                               ? detail::clampLanes(ndcZ, 0.0f, 1.0f)
                               : detail::clampLanes((ndcZ + 1.0f) * 0.5f, 0.0f, 1.0f);
    const Float8 z = viewport.minDepth + depth01 * (viewport.maxDepth - viewport.minDepth);

    const float limit = static_cast<float>(2 * kMaxViewportSide);
    // WindowVertex's eight 32-bit words, field by field: x, y (int64 halves), z, 1/w, the unsnapped x, y.
    static_assert(sizeof(WindowVertex) == 8 * sizeof(float) && offsetof(WindowVertex, yFixed) == 8 &&
                  offsetof(WindowVertex, z) == 16 && offsetof(WindowVertex, invW) == 20 &&
                  offsetof(WindowVertex, window) == 24);
    Int8 words[8];
    detail::snapToSubpixels(detail::clampLanes(windowX, -limit, limit), subpixelBits, words[0], words[1]);
    detail::snapToSubpixels(detail::clampLanes(windowY, -limit, limit), subpixelBits, words[2], words[3]);
    words[4] = std::bit_cast<Int8>(z);
    words[5] = std::bit_cast<Int8>(invW);
    words[6] = std::bit_cast<Int8>(windowX);
    words[7] = std::bit_cast<Int8>(windowY);
    transpose8x8(words);  // row k: lane k's eight words, one WindowVertex
    std::memcpy(out, words, sizeof words);
}

}  // namespace facet
