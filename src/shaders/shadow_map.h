// Shadow maps (Williams 1978): the scene's depth seen from a light, drawn with Facet's own pipeline
// (render/shadow_maps.h), and the test the shaders make with it: a point is lit when it is no farther
// from the light than what the map saw in its direction. Percentage-closer filtering (Reeves, Salesin
// and Cook 1987) compares the point's depth with 1, 2×2 or 4×4 neighbouring texels and averages the
// 0/1 results, so a shadow's edge becomes a ramp instead of a staircase.
//
// The bias that keeps a lit surface from shadowing itself (acne) is in the map, not in the lookup: the
// map is drawn with a glPolygonOffset-style depth offset (pipeline/state.h, DepthOffset), which knows
// each caster triangle's exact depth slope per texel, in perspective too, where a receiver-side bias
// would have to rebuild it from N·L and the projection. So the lookup compares plain depths.
#pragma once

#include <cmath>
#include <vector>

#include "pipeline/depth_format.h"
#include "pipeline/viewport.h"
#include "pipeline/wide.h"
#include "shading/lighting.h"

namespace facet {

// One depth image of a shadow map: the light's clip space from the camera's eye space (the frame's
// shading happens in eye space), and size × size window depths, row 0 at the top, as the pipeline
// drew them.
struct ShadowMapFace {
    mat4 clipFromEye{1.0f};
    std::vector<DepthFormat::Stored> depth;
};

// A light's shadow map: one face (directional: orthographic; spot: perspective over the cone), or six
// (point lights and very wide spots: a cube map, faces +x, −x, +y, −y, +z, −z of eye space around the
// light, each a 90° frustum widened by a few texels so that a filter near a face's edge still reads
// the scene).
struct ShadowMap {
    int size = 0;              // texels per side of each face
    int filterTaps = 1;        // 1, 4 (2×2) or 16 (4×4)
    vec3 lightPosition{0.0f};  // eye space; picks a cube map's face
    std::vector<ShadowMapFace> faces;
};

// Which face of a cube map holds the direction `d` from the light: the axis of its largest coordinate.
inline int cubeFaceOf(const vec3& d) {
    const vec3 a = glm::abs(d);
    if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0f ? 0 : 1;
    if (a.y >= a.z) return d.y >= 0.0f ? 2 : 3;
    return d.z >= 0.0f ? 4 : 5;
}

// The share of the light that reaches eye-space point P by the map: the fraction of the filter's taps
// whose stored depth is not nearer the light than P. A point outside the map (beyond what was fitted
// around the scene, or outside a spot's cone) is lit: nothing there was drawn to shadow it.
inline float shadowMapLitShare(const ShadowMap& map, const vec3& P) {
    const ShadowMapFace& face = map.faces[map.faces.size() == 6 ? cubeFaceOf(P - map.lightPosition) : 0];
    const vec4 clip = face.clipFromEye * vec4(P, 1.0f);
    if (!(clip.w >= kMinClipW) || !(std::abs(clip.x) <= clip.w) || !(std::abs(clip.y) <= clip.w)) return 1.0f;
    // Where the map's draw put P: the pipeline's own viewport transform and depth mapping.
    const Viewport viewport{0, 0, map.size, map.size};
    const WindowVertex window = toWindow(clip, viewport, kMaxSubpixelBits);
    // The taps are the side × side texels whose centres (i + ½) lie nearest P: the first is
    // floor(x − (side − 1)/2); those beyond the map's edge repeat the edge.
    const int side = map.filterTaps == 16 ? 4 : map.filterTaps == 4 ? 2 : 1;
    const float shift = 0.5f * float(side - 1);
    const int firstX = int(std::floor(window.window.x - shift));
    const int firstY = int(std::floor(window.window.y - shift));
    int lit = 0;
    for (int j = 0; j < side; ++j) {
        const int y = std::clamp(firstY + j, 0, map.size - 1);
        const DepthFormat::Stored* row = &face.depth[std::size_t(y) * std::size_t(map.size)];
        for (int i = 0; i < side; ++i)
            lit += DepthFormat::passes(CompareOp::LessEqual, window.z,
                                       row[std::clamp(firstX + i, 0, map.size - 1)]);
    }
    return float(lit) / float(side * side);
}

// Each lane's share of `light` reaching P by the shadow map (N the normal the lighting uses). Lanes
// where N·L ≤ 0 get no diffuse or specular light from it anyway and are not looked up (1), nor are
// lanes with a non-finite P (eight-lane batches carry such dead lanes). Eight lanes are looked up one
// by one (a gather per lane); double lanes (the reference renderer never uses maps) look up in float.
template <class F, class V3 = LaneVec3<F>>
F shadowMapVisibility(const ShadowMap& map, const LightParams& light, const V3& P, const V3& N) {
    const F facing = dot(N, lightVector<F, V3>(light, P).L);
    if constexpr (LaneTraits<F>::kCount == 8) {
        Float8 v = splat(1.0f);
        for (int i = 0; i < 8; ++i) {
            const vec3 p(P.x[i], P.y[i], P.z[i]);
            if (facing[i] > 0.0f && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
                v[i] = shadowMapLitShare(map, p);
        }
        return v;
    } else {
        if (!(facing > 0.0f)) return lanes<F>(1.0f);
        return F(shadowMapLitShare(map, vec3(P)));
    }
}

}  // namespace facet
