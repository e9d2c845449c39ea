// Shadow maps: depth images of the scene drawn from a light with Facet's own pipeline, read by the
// shaders. (To be completed: drawing, bias, percentage-closer filtering.)
#pragma once

#include "pipeline/wide.h"
#include "shading/lighting.h"

namespace facet {

struct ShadowMap {};

template <class F, class V3 = LaneVec3<F>>
F shadowMapVisibility(const ShadowMap&, const LightParams&, const V3&, const V3&) {
    return lanes<F>(1.0f);
}

}  // namespace facet
