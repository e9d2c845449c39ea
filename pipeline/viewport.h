// Perspective divide and viewport transform: clip space → normalised device coordinates → window
// coordinates, snapped to the fixed-point grid the rasterizer works on.
// In: a clip-space position. Out: WindowVertex (fixed-point x, y; depth; 1/w).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "depth_format.h"
#include "state.h"
#include "types.h"

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

}  // namespace facet
