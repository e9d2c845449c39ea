// Face culling and triangle setup: from three window vertices to edge functions and attribute planes.
// In: WindowTriangle. Out: TriangleSetup, or a TriangleFate saying why the triangle draws nothing.
// Edge functions follow Pineda (1988); the fill rule is the top-left rule (as in Direct3D), applied
// as a bias on the edge constant (Giesen, "Triangle rasterization in practice", 2013).
#pragma once

#include "state.h"
#include "types.h"

namespace facet {

// Twice the signed area of the snapped triangle, in fixed units²: orient2d(v0, v1, v2) =
// (x1 − x0)(y2 − y0) − (y1 − y0)(x2 − x0), exact in int64 (types.h budget).
// With window y growing downwards, a triangle that winds counter-clockwise on screen has a negative value.
inline std::int64_t signedDoubleArea(const WindowVertex& v0, const WindowVertex& v1, const WindowVertex& v2) {
    return (v1.xFixed - v0.xFixed) * (v2.yFixed - v0.yFixed) -
           (v1.yFixed - v0.yFixed) * (v2.xFixed - v0.xFixed);
}
inline std::int64_t signedDoubleArea(const WindowTriangle& triangle) {
    return signedDoubleArea(triangle.vertices[0], triangle.vertices[1], triangle.vertices[2]);
}

// Whether a triangle of the given signed double area faces the viewer, and whether `raster` culls it.
inline bool isFrontFacing(std::int64_t signedDoubleArea, FrontFace frontFace) {
    // Counter-clockwise on a y-down screen is a negative orient2d.
    const bool counterClockwise = signedDoubleArea < 0;
    return frontFace == FrontFace::CounterClockwise ? counterClockwise : !counterClockwise;
}
inline bool isCulled(bool frontFacing, CullMode cull) {
    return (cull == CullMode::Back && !frontFacing) || (cull == CullMode::Front && frontFacing);
}

// What the signed area alone decides, setupTriangle's first step: ZeroArea (zero area in fixed point
// covers no sample, whatever its float size), Culled (its facing, as OpenGL culls before
// rasterization), or Drawn: the triangle goes on to be set up. The front end asks this of a triangle
// before gathering it, so that the half of a closed mesh that faces away costs only its area.
inline TriangleFate areaFate(std::int64_t signedDoubleArea, const RasterState& raster) {
    if (signedDoubleArea == 0) return TriangleFate::ZeroArea;
    if (isCulled(isFrontFacing(signedDoubleArea, raster.frontFace), raster.cull)) return TriangleFate::Culled;
    return TriangleFate::Drawn;
}

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
