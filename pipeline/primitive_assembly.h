// Primitive assembly: three indices of an indexed triangle list → a triangle of shaded vertices.
// In: ShadedVertices and three vertex indices. Out: a ClipPolygon of three vertices (the clipper's input),
// and the trivial-reject verdict from the vertices' outcodes.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "types.h"

namespace facet {

// Drawn (go on), NonFinite (a coordinate is NaN/Inf: drop) or OutsideFrustum (all three vertices are
// outside one plane, so no part of the triangle can be visible).
inline TriangleFate trivialReject(std::uint8_t outcodeAnd, std::uint8_t outcodeOr) {
    if (outcodeOr & kNonFinite) return TriangleFate::NonFinite;
    if (outcodeAnd) return TriangleFate::OutsideFrustum;
    return TriangleFate::Drawn;
}

inline void assembleTriangle(const ShadedVertices& shaded, const std::array<std::uint32_t, 3>& indices,
                             ClipPolygon& polygon) {
    polygon.count = 3;
    polygon.varyingCount = shaded.varyingCount;
    polygon.planesCut = 0;
    for (int k = 0; k < 3; ++k) {
        polygon.vertices[k].position = shaded.positions[indices[k]];
        std::copy_n(shaded.varyingsOf(indices[k]), shaded.varyingCount, polygon.vertices[k].varyings.begin());
    }
}

}  // namespace facet
