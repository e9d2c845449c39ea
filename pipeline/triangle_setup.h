// Face culling and triangle setup: from three window vertices to edge functions and attribute planes.
// In: WindowTriangle. Out: TriangleSetup, or a TriangleFate saying why the triangle draws nothing.
// Edge functions follow Pineda (1988); the fill rule is the top-left rule (as in Direct3D), applied
// as a bias on the edge constant (Giesen, "Triangle rasterization in practice", 2013).
#pragma once

#include "state.h"
#include "types.h"

namespace facet {

// Twice the signed area of the snapped triangle, in fixed units²: orient2d(v0, v1, v2).
// With window y growing downwards, a triangle that winds counter-clockwise on screen has a negative value.
std::int64_t signedDoubleArea(const WindowTriangle& triangle);

// Whether a triangle of the given signed double area faces the viewer, and whether `raster` culls it.
bool isFrontFacing(std::int64_t signedDoubleArea, FrontFace frontFace);
bool isCulled(bool frontFacing, CullMode cull);

// Culls (facing, zero area) and, for a triangle that survives, computes its TriangleSetup:
// orientation made positive, edge functions with fill-rule bias, the pixel bounding box clamped to
// the viewport, and the attribute planes for depth, 1/w and each varying (written to `varyingPlanes`,
// room for 3 · varyingCount floats; setup.varyingPlaneOffset is set to 0, an offset into that buffer).
// Returns the fate: Drawn when `setup` was filled in.
// The depth offset of a triangle set up in `setup` (its edges, doubleArea and depth plane), window
// depth units: offset.factor · max(|∂z/∂x|, |∂z/∂y|) + offset.units · DepthFormat::kResolution.
// r is that of the draw's depth buffer format (DepthFormatOf::kResolution).
float depthOffset(const TriangleSetup& setup, const DepthOffset& offset,
                  DepthBufferFormat format = DepthBufferFormat::Float);

TriangleFate setupTriangle(const WindowTriangle& triangle, const DrawState& state, TriangleSetup& setup,
                           float* varyingPlanes);

}  // namespace facet
