// Shadow maps drawn with Facet's own pipeline: a depth-only draw of the scene's opaque triangles from a
// light (to be completed).
#pragma once

#include <memory>

#include "shaders/shadow_map.h"

namespace facet {

struct PreparedScene;

// The shadow map of light `light` (its index in the uniforms' lights) for the objects as placed now.
std::unique_ptr<ShadowMap> drawShadowMap(const PreparedScene& prepared, int light);

}  // namespace facet
