// Shadows: which lights cast them and how visibility is decided. The lecture's test ("cast a ray from
// the point towards the light; if another renderable blocks it, add no diffuse or specular light from
// it") and the real-time approximation of it, the shadow map.
#pragma once

#include <span>

#include "pipeline/names.h"

namespace facet {

enum class ShadowMethod {
    None,  // the light reaches every point that faces it
    Ray,   // a ray from the point to the light, through the scene's BVH (raycast/): exact visibility
    Map,   // a depth image drawn from the light (shadow map), compared with the point's depth from it
};
inline constexpr EnumName<ShadowMethod> kShadowMethodNames[] = {
    {ShadowMethod::None, "none"}, {ShadowMethod::Ray, "ray"}, {ShadowMethod::Map, "map"}};
constexpr std::span<const EnumName<ShadowMethod>> enumNames(ShadowMethod) {
    return kShadowMethodNames;
}

// The largest shadow map side: a point light's six 8192² float faces are 1.5 GB.
inline constexpr int kMaxShadowMapSize = 8192;

// How shadow maps are drawn and read (every light whose shadows are a map).
// The map is drawn with a glPolygonOffset-style depth offset (pipeline/state.h, DepthOffset; see
// render/shadow_maps.h's shadowMapDrawState): units = constantBias, factor = slopeBias × the filter's
// width in texels (1, 2 or 4), since the filter's taps lie up to that many texels from the point.
struct ShadowMapOptions {
    int size = 2048;  // texels per side (of each of a point light's six faces)
    // Depth offset in units of the depth buffer's resolution r = 2^-24 (DepthFormat::kResolution):
    // for surfaces facing the light, whose slope is 0.
    float constantBias = 1;
    // Depth offset per texel of the caster's depth slope m = max(|∂z/∂x|, |∂z/∂y|), per texel of the
    // filter's width: what cures acne on surfaces tilted from the light; 1 is the least that does for
    // a plane, the default leaves room for the rounding of curved surfaces.
    float slopeBias = 1.5f;
    int filterTaps = 4;  // percentage-closer filtering: 1, 4 (2×2) or 16 (4×4) depth comparisons
};

// A shadow ray leaves the surface at P + ε·N (N the shading normal, turned towards the viewer), so that
// the surface never shadows itself through the rounding of P: ε is this share of the scene's extent in
// eye space (the distance from the eye to the far side of the scene's bounding sphere). The rasterizer's
// P is within about 1e−6 of that extent of the true surface, so 1e−4 leaves a hundredfold margin while
// lifting the origin by a tenth of a millimetre in a ten-metre scene.
inline constexpr float kShadowRayOffset = 1e-4f;

}  // namespace facet
