// The tangent frame of a surface from its texture coordinates, for anisotropic reflection (lighting.h's
// distributionGGXAnisotropic): the tangent t points along ∂P/∂u, the direction in which u grows on the
// surface, and b = n × t. One formula serves the rasterizer and the reference:
//
//   t = (dP₁·dv₂ − dP₂·dv₁) / (du₁·dv₂ − du₂·dv₁)
//
// for any two differentials (dP₁, du₁, dv₁), (dP₂, du₂, dv₂) of the position and the texture coordinates
// along the surface. The reference gives it a triangle's two edges (Lengyel 2001, "Computing Tangent
// Space Basis Vectors for an Arbitrary Mesh"); the rasterizer the screen-space derivatives ∂/∂x, ∂/∂y of
// one pixel step (Schüler 2006, "Normal Mapping without Precomputed Tangents", ShaderX5 §2.6). For a
// planar triangle with affine texture coordinates both are the same vector. Templated over the lane
// type as lighting.h (float, Float8, double).
#pragma once

#include "pipeline/wide.h"

namespace facet {

// The fixed tangent where the texture coordinates give none (no UVs, or a mapping that degenerates
// to a line): the eye-space x axis projected onto the plane normal to n, or the y axis where n is
// within 26° of x. n need not be unit length.
template <class F, class V3 = LaneVec3<F>>
V3 fallbackTangent(const V3& n) {
    const F nn = max(dot(n, n), 1e-30f);
    const V3 alongX = V3(vec3(1.0f, 0.0f, 0.0f)) - n * (n.x / nn);
    const V3 alongY = V3(vec3(0.0f, 1.0f, 0.0f)) - n * (n.y / nn);
    return select(n.x * n.x < 0.8f * nn, alongX, alongY);
}

// t = (dP₁·dv₂ − dP₂·dv₁)/(du₁·dv₂ − du₂·dv₁), not unit length; `fallback` where the determinant is
// (nearly) zero: the gradients of u and v within 0.01° of parallel, or zero.
template <class F, class V3 = LaneVec3<F>>
V3 tangentFromDifferentials(const V3& dP1, const V3& dP2, F du1, F dv1, F du2, F dv2, const V3& fallback) {
    const F det = du1 * dv2 - du2 * dv1;
    const F scale = (du1 * du1 + du2 * du2) * (dv1 * dv1 + dv2 * dv2);
    const auto usable = det * det > 3e-8f * scale;  // sin² of the angle between ∇u and ∇v
    const V3 t = (dP1 * dv2 - dP2 * dv1) * (1.0f / select(usable, det, lanes<F>(1.0f)));
    return select(usable, t, fallback);
}

// The change of the surface point P (eye space, eye at the origin) from one pixel to the next, in x
// (rightwards) and y (down the rows, as the rasterizer's derivatives count y): the neighbouring pixel's
// view ray met with the plane through P normal to n. `pixelSpread` is the size of a pixel in eye space,
// per unit of depth under a perspective projection, (2/(P₀₀·width), 2/(P₁₁·height)); under an
// orthographic projection the size itself. Where the neighbour's ray runs (nearly) along the plane,
// the step projected onto the plane instead.
template <class V3>
struct ScreenDifferentials {
    V3 dPdx, dPdy;
};
template <class F, class V3 = LaneVec3<F>>
ScreenDifferentials<V3> screenDifferentials(const V3& P, const V3& n, vec2 pixelSpread, bool perspective) {
    const F scale = perspective ? -P.z : lanes<F>(1.0f);
    const F zero = lanes<F>(0.0f);
    const V3 steps[2] = {V3(scale * pixelSpread.x, zero, zero), V3(zero, scale * -pixelSpread.y, zero)};
    const F nn = max(dot(n, n), 1e-30f);
    V3 out[2];
    for (int i = 0; i < 2; ++i) {
        const V3& step = steps[i];
        const V3 projected = step - n * (dot(n, step) / nn);
        if (perspective) {
            // The ray t·(P + step) meets the plane where t = (P·n)/((P + step)·n).
            const V3 Q = P + step;
            const F qn = dot(Q, n);
            const F t = dot(P, n) / select(qn * qn > 0.0f, qn, lanes<F>(1.0f));
            const auto hits = (t > 0.0f) & (t < 16.0f);
            out[i] = select(hits, Q * t - P, projected);
        } else {
            // The ray (P + step) + s·z, parallel to the view direction.
            const F s = -dot(step, n) / select(n.z * n.z > 0.0f, n.z, lanes<F>(1.0f));
            const auto hits = n.z * n.z > 0.0025f * nn;  // the plane within 87° of facing the eye
            out[i] = select(hits, step + V3(zero, zero, s), projected);
        }
    }
    return {out[0], out[1]};
}

// The unit tangent and bitangent about the unit normal n: t Gram-Schmidt'ed against n, b = n × t
// (fallbackTangent where t lies along n).
template <class V3>
struct TangentFrame {
    V3 T, B;
};
template <class F, class V3 = LaneVec3<F>>
TangentFrame<V3> orthonormalTangentFrame(const V3& n, const V3& t) {
    const V3 inPlane = t - n * dot(n, t);
    const F length2 = dot(inPlane, inPlane);
    const V3 chosen = select(length2 > 1e-12f * max(dot(t, t), 1e-30f), inPlane, fallbackTangent<F, V3>(n));
    const V3 T = chosen * (1.0f / sqrt(max(dot(chosen, chosen), 1e-30f)));
    const V3 B(n.y * T.z - n.z * T.y, n.z * T.x - n.x * T.z, n.x * T.y - n.y * T.x);
    return {T, B};
}

}  // namespace facet
