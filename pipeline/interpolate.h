// Interpolation: a fragment's depth and varyings from its barycentric weights λ1, λ2 (λ0 = 1 − λ1 − λ2).
// In: TriangleSetup + λ. Out: window depth, and the varyings as a flat float array.
#pragma once

#include "types.h"
#include "wide.h"

namespace facet {

// Window depth is an affine function of screen position: z = z0 + λ1·(z1 − z0) + λ2·(z2 − z0).
inline float interpolateDepth(const TriangleSetup& s, float b1, float b2) {
    return s.z0 + b1 * s.dz1 + b2 * s.dz2;
}

// Perspective-correct: a = (Σ λᵢ·aᵢ/wᵢ) / (Σ λᵢ/wᵢ); the planes already hold aᵢ/wᵢ (triangle_setup).
// Affine: a = Σ λᵢ·aᵢ, which is only right when w is the same at all three vertices.
// After clipping every wᵢ ≥ kMinClipW and λᵢ ≥ 0, so Σ λᵢ/wᵢ > 0 and the divide is safe.
// Flat varyings (the first s.flatVaryingCount) are copied: the provoking vertex's value, exactly.
inline void interpolateVaryings(const TriangleSetup& s, float b1, float b2, float* out) {
    const float* plane = s.varyingPlanes;
    for (int k = 0; k < s.flatVaryingCount; ++k, plane += 3)
        out[k] = plane[0];
    if (s.perspective) {
        const float w = 1.0f / (s.invW0 + b1 * s.dInvW1 + b2 * s.dInvW2);
        for (int k = s.flatVaryingCount; k < s.varyingCount; ++k, plane += 3)
            out[k] = (plane[0] + b1 * plane[1] + b2 * plane[2]) * w;
    } else {
        for (int k = s.flatVaryingCount; k < s.varyingCount; ++k, plane += 3)
            out[k] = plane[0] + b1 * plane[1] + b2 * plane[2];
    }
}

// The same for eight fragments at once, into a FragmentBatch (structure of arrays).
inline void interpolateVaryings(const TriangleSetup& s, Float8 b1, Float8 b2, FragmentBatch& out) {
    const float* plane = s.varyingPlanes;
    for (int k = 0; k < s.flatVaryingCount; ++k, plane += 3)
        out.varyings[k] = splat(plane[0]);
    if (s.perspective) {
        const Float8 w = 1.0f / (s.invW0 + b1 * s.dInvW1 + b2 * s.dInvW2);
        for (int k = s.flatVaryingCount; k < s.varyingCount; ++k, plane += 3)
            out.varyings[k] = (plane[0] + b1 * plane[1] + b2 * plane[2]) * w;
    } else {
        for (int k = s.flatVaryingCount; k < s.varyingCount; ++k, plane += 3)
            out.varyings[k] = plane[0] + b1 * plane[1] + b2 * plane[2];
    }
}

}  // namespace facet
