// Perspective divide and viewport transform: clip space → normalised device coordinates → window
// coordinates, snapped to the fixed-point grid the rasterizer works on.
// In: a clip-space position. Out: WindowVertex (fixed-point x, y; depth; 1/w).
#pragma once

#include "state.h"
#include "types.h"

namespace facet {

// x_w = x_vp + (x_ndc + 1)/2 · width,  y_w = y_vp + (1 − y_ndc)/2 · height  (window y grows downwards),
// z_w = minDepth + (z_ndc + 1)/2 · (maxDepth − minDepth), clamped to the depth range as OpenGL does
// (DepthFormat::windowDepth).
// x and y are rounded to the nearest 1/2^subpixelBits of a pixel. Requires w ≥ kMinClipW (clipped).
WindowVertex toWindow(const vec4& clipPosition, const Viewport& viewport, int subpixelBits,
                      DepthBufferFormat depthFormat = DepthBufferFormat::Float);

}  // namespace facet
