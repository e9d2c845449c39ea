// The two-sided test, once for every renderer: whether the viewer sees the underside of a surface,
// which the two-sided flip turns round (N = −N, docs/lighting.md) and the clamp of N·V darkens. The
// rasterizer runs it in float on its interpolated normal and point, the reference (src/reference) in
// double on its own at the ray's hit: the same function, the same threshold (the sign of N·V, no
// margin) and the same normal (the interpolated one, as both shade with it).
#pragma once

namespace facet {

// N·V < 0 with V = (eye − P)/|eye − P| and the eye at the origin of eye space: the sign of N·(−P), so
// that neither N nor V need be unit length (normalising cannot change a sign, only round it). One lane
// (float, double: bool) or eight (a lane mask).
template <class V3>
auto seesUnderside(const V3& normal, const V3& P) {
    return dot(normal, -P) < 0.0f;
}

}  // namespace facet
