// Clipping. Cuts a clip-space polygon by the frustum planes −w ≤ x, y, z ≤ w and by w ≥ kMinClipW
// (Sutherland–Hodgman in homogeneous coordinates, before any divide, so w ≤ 0 needs no special case).
// In: ClipPolygon (a triangle). Out: the same ClipPolygon, convex, winding kept, 0 or ≥ 3 vertices.
#pragma once

#include <cstdint>

#include "types.h"

namespace facet {

// Which planes `position` lies outside of (ClipPlaneBit mask); kNonFinite if any coordinate is NaN/Inf.
std::uint8_t computeOutcode(const vec4& position);

// Signed distance-like value of `position` to one plane: ≥ 0 inside. `plane` is a single ClipPlaneBit.
float planeDistance(const vec4& position, std::uint8_t plane);

// Clips `polygon` in place against every plane in `planes` (a ClipPlaneBit mask), in the fixed order
// left, right, bottom, top, near, far, w. Varyings are interpolated in clip space with the position,
// which keeps them perspective-correct. Each new vertex is computed from the edge's inside vertex toward
// its outside one, so two triangles that share an edge get bit-identical new vertices on it.
// A result with a non-finite coordinate (from inputs near the float range) is emptied.
void clipPolygon(ClipPolygon& polygon, std::uint8_t planes);

}  // namespace facet
