// Clipping. Cuts a clip-space polygon by the frustum planes −w ≤ x, y, z ≤ w and by w ≥ kMinClipW
// (Sutherland–Hodgman in homogeneous coordinates, before any divide, so w ≤ 0 needs no special case).
// Under reversed Z the depth planes are 0 ≤ z ≤ w instead, the near plane at z = w (ClipDepthRange).
// In: ClipPolygon (a triangle). Out: the same ClipPolygon, convex, winding kept, 0 or ≥ 3 vertices.
#pragma once

#include <cmath>
#include <cstdint>

#include "state.h"
#include "types.h"

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

// Signed distance-like value of `position` to one plane: ≥ 0 inside. `plane` is a single ClipPlaneBit.
float planeDistance(const vec4& position, std::uint8_t plane,
                    ClipDepthRange depth = ClipDepthRange::MinusWToW);

// Where the edge from a vertex inside a plane (distance dInside ≥ 0) to one outside it (dOutside < 0)
// crosses the plane: P = P_in + t·(P_out − P_in) with t = d_in / (d_in − d_out), 0 ≤ t < 1.
inline float clipEdgeT(float dInside, float dOutside) {
    return dInside / (dInside - dOutside);
}

// The clip position made at `t` on the edge inside → outside: interpolated, except its depth z_c, which
// is fromW's z_c(w) of the interpolated w when the projection ties them (state.h, DepthFromW: a huge
// triangle's corners can carry z_c = w in float, which interpolation would hand on to every vertex made
// on its edges).
inline vec4 clipEdgePoint(const vec4& inside, const vec4& outside, float t, const DepthFromW& fromW) {
    vec4 p = inside + t * (outside - inside);
    if (fromW.known) p.z = fromW.at(p.w);
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
