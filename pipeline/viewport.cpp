#include "viewport.h"

#include <algorithm>
#include <cmath>

#include "depth_format.h"

namespace facet {

namespace {

// Rounds a window coordinate to the sub-pixel grid: multiples of 2^(8 − bits) in 8-fraction-bit units.
std::int64_t snap(float windowCoordinate, int subpixelBits) {
    const int dropBits = kFixedFractionBits - subpixelBits;
    // × 2^bits by a multiplication: exact in double like std::ldexp, which is a call into libm per
    // coordinate (two per vertex of every draw).
    const double scaled =
        static_cast<double>(windowCoordinate) * static_cast<double>(std::int64_t{1} << subpixelBits);
    return static_cast<std::int64_t>(std::nearbyint(scaled)) << dropBits;
}

}  // namespace

WindowVertex toWindow(const vec4& clip, const Viewport& viewport, int subpixelBits,
                      DepthBufferFormat depthFormat) {
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
    v.xFixed = snap(std::clamp(v.window.x, -limit, limit), subpixelBits);
    v.yFixed = snap(std::clamp(v.window.y, -limit, limit), subpixelBits);
    return v;
}

}  // namespace facet
