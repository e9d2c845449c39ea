// Shadow maps drawn with Facet's own pipeline: a depth-only draw of the scene's opaque triangles from a
// light, into one size × size depth image (directional and spot lights) or six (point lights).
#pragma once

#include <cstdint>
#include <memory>

#include "pipeline/state.h"
#include "shaders/shadow_map.h"
#include "shading/shadow.h"

namespace facet {

struct PreparedScene;

// A spot light whose cone is wider than this (half-angle) gets a cube map like a point light: one
// perspective image over a wider cone spends most of its texels on its rim (their footprint grows as
// 1/cos² of the angle off the axis) and cannot reach 90°.
inline constexpr float kWidestSingleMapSpotDegrees = 60.0f;

// Texels added on every side of a spot's or a cube face's frustum, so that a 4×4 filter at the edge of
// the cone or of a face still reads depths drawn from the scene.
inline constexpr int kShadowMapMarginTexels = 3;

// The state the shadow map draws run with: the map's viewport, no culling (a one-sided sheet casts a
// shadow from both sides, and a closed mesh's faces turned away from the light are drawn too), Less
// depth test, and the options' bias as a depth offset: factor = slopeBias × the filter's width in
// texels (1, 2 or 4: the taps lie up to that many texels of the surface's slope from the point),
// units = constantBias.
DrawState shadowMapDrawState(const ShadowMapOptions& options);

// The faces of a light's shadow map: 1 for a directional light and a spot light of a cone up to
// kWidestSingleMapSpotDegrees, 6 (a cube map) for a point light and a wider spot. drawShadowMap draws
// this many; the memory estimate counts them.
int shadowMapFaces(const LightParams& light);
// The bytes the shadow maps of lights with `faces` faces in all take at `size` texels a side: each
// face's depths, and the one size x size framebuffer they are drawn in (Framebuffer::bytesFor).
std::uint64_t shadowMapBytes(std::uint64_t faces, int size);

// The shadow map of light `light` (its index in the uniforms' lights) for the objects as placed now.
std::unique_ptr<ShadowMap> drawShadowMap(const PreparedScene& prepared, int light);

}  // namespace facet
