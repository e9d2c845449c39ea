// Clipping. Cuts a clip-space polygon by the frustum planes −w ≤ x, y, z ≤ w and by w ≥ kMinClipW
// (Sutherland–Hodgman in homogeneous coordinates, before any divide, so w ≤ 0 needs no special case).
// Under reversed Z the depth planes are 0 ≤ z ≤ w instead, the near plane at z = w (ClipDepthRange).
// In: ClipPolygon (a triangle). Out: the same ClipPolygon, convex, winding kept, 0 or ≥ 3 vertices.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "state.h"
#include "types.h"
#include "wide.h"

namespace facet {

// The clip-space depths inside the frustum: OpenGL's −w ≤ z ≤ w (near at z = −w), or reversed Z's
// 0 ≤ z ≤ w with the near plane at z = w and the far one at z = 0 (glClipControl GL_ZERO_TO_ONE;
// DepthBufferFormat::ReversedFloat). kClipNear and kClipFar keep naming the near and far planes.
enum class ClipDepthRange : std::uint8_t { MinusWToW, ReversedZeroToW };

// Which planes `p` lies outside of (ClipPlaneBit mask); kNonFinite if any coordinate is NaN/Inf. Inline:
// the vertex stage asks it of every vertex.
inline std::uint8_t computeOutcode(const vec4& p, ClipDepthRange depth = ClipDepthRange::MinusWToW) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(p.w))
        return kNonFinite;
    std::uint8_t code = 0;
    if (p.x < -p.w) code |= kClipLeft;
    if (p.x > p.w) code |= kClipRight;
    if (p.y < -p.w) code |= kClipBottom;
    if (p.y > p.w) code |= kClipTop;
    if (depth == ClipDepthRange::MinusWToW) {
        if (p.z < -p.w) code |= kClipNear;
        if (p.z > p.w) code |= kClipFar;
    } else {
        if (p.z > p.w) code |= kClipNear;
        if (p.z < 0.0f) code |= kClipFar;
    }
    if (p.w < kMinClipW) code |= kClipW;
    return code;
}

// computeOutcode of eight positions at once (the vertex stage's groups), the same codes: the four
// coordinates' lanes compared whole, each plane's bit where its comparison holds, kNonFinite alone
// where a coordinate's exponent bits are all ones (NaN or ±Inf), as std::isfinite tells.
[[gnu::always_inline]] inline void computeOutcodes(const vec4* positions, std::uint8_t* codes,
                                                   ClipDepthRange depth = ClipDepthRange::MinusWToW) {
    const Vec4x8 p = loadTransposed(positions);
    const auto bit = [](Int8 holds, ClipPlaneBit plane) { return holds & static_cast<std::int32_t>(plane); };
    const Float8 minusW = -p.w;
    Int8 code = bit(p.x < minusW, kClipLeft) | bit(p.x > p.w, kClipRight) | bit(p.y < minusW, kClipBottom) |
                bit(p.y > p.w, kClipTop) | bit(p.w < kMinClipW, kClipW);
    if (depth == ClipDepthRange::MinusWToW)
        code |= bit(p.z < minusW, kClipNear) | bit(p.z > p.w, kClipFar);
    else
        code |= bit(p.z > p.w, kClipNear) | bit(p.z < 0.0f, kClipFar);
    constexpr std::int32_t kExponent = 0x7f800000;
    const auto nonFinite = [&](Float8 v) { return (std::bit_cast<Int8>(v) & kExponent) == kExponent; };
    const Int8 anyNonFinite = nonFinite(p.x) | nonFinite(p.y) | nonFinite(p.z) | nonFinite(p.w);
    code = anyNonFinite ? Int8{} + static_cast<std::int32_t>(kNonFinite) : code;
    using Bytes8 = std::uint8_t __attribute__((vector_size(8)));
    const Bytes8 bytes = __builtin_convertvector(code, Bytes8);
    std::memcpy(codes, &bytes, sizeof bytes);
}

// Signed distance-like value of `position` to one plane: ≥ 0 inside. `plane` is a single ClipPlaneBit.
float planeDistance(const vec4& position, std::uint8_t plane,
                    ClipDepthRange depth = ClipDepthRange::MinusWToW);

// Where the edge from a vertex inside a plane (distance dInside ≥ 0) to one outside it (dOutside < 0)
// crosses the plane: P = P_in + t·(P_out − P_in) with t = d_in / (d_in − d_out), 0 ≤ t < 1.
inline float clipEdgeT(float dInside, float dOutside) {
    return dInside / (dInside - dOutside);
}

// The share of the depth left before the far plane that the rounding of an interpolated depth may take
// before the clipper sets the depth from w instead (clipEdgePoint): 2^-10, a thousandth. Interpolation is
// kept below it, so that ordinary scenes keep the depths (and the ties between coplanar surfaces) that
// interpolating the corners gives; above it the depth buffer could no longer tell such a vertex from the
// far plane.
inline constexpr float kInterpolatedDepthRoundingShare = 0x1p-10f;

// The clip position made at `t` on the edge inside → outside: interpolated, except its depth z_c where
// interpolating cannot resolve it and the projection ties it to w (state.h, DepthFromW): there z_c is
// fromW's z_c(w) of the interpolated w. Interpolating rounds z_c by up to about 2^-22 of the corners'
// sizes, |z_in| + |z_out| + |w_in| + |w_out| (each corner is rounded to 2^-24 of itself, the lerp adds a
// few roundings); the depth that matters is what is left before the far plane, w − z_c (window depth
// 1 − z_w = (w − z_c)/2w) under OpenGL's range, z_c itself (z_w = z_c/w) under reversed Z. A huge
// triangle's corners can carry z_c = w in float, which interpolation would hand on to every vertex made
// on its edges: window depth 1, drawn nowhere.
// `depthFromW`, when given, is told whether the depth was set from w.
inline vec4 clipEdgePoint(const vec4& inside, const vec4& outside, float t, const DepthFromW& fromW,
                          ClipDepthRange depth = ClipDepthRange::MinusWToW, bool* depthFromW = nullptr) {
    vec4 p = inside + t * (outside - inside);
    if (!fromW.known) return p;
    const float projected = fromW.at(p.w);
    const float depthLeft = depth == ClipDepthRange::ReversedZeroToW ? projected : p.w - projected;
    const float rounding =
        0x1p-22f * (std::abs(inside.z) + std::abs(outside.z) + std::abs(inside.w) + std::abs(outside.w));
    const bool fromProjection = rounding > kInterpolatedDepthRoundingShare * std::abs(depthLeft);
    if (fromProjection) p.z = projected;
    if (depthFromW) *depthFromW = fromProjection;
    return p;
}

// Clips `polygon` in place against every plane in `planes` (a ClipPlaneBit mask), in the fixed order
// left, right, bottom, top, near, far, w. Varyings are interpolated in clip space with the position,
// which keeps them perspective-correct; a new vertex's depth follows its w where `fromW` is known
// (clipEdgePoint). Each new vertex is computed from the edge's inside vertex toward its outside one, so
// two triangles that share an edge get bit-identical new vertices on it.
// A result with a non-finite coordinate (from inputs near the float range) is emptied.
void clipPolygon(ClipPolygon& polygon, std::uint8_t planes, ClipDepthRange depth = ClipDepthRange::MinusWToW,
                 const DepthFromW& fromW = {});

}  // namespace facet
