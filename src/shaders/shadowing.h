// The shaders' shadow test: per light, the share of it that reaches a point (1 lit, 0 shadowed), by a
// shadow ray through the scene's BVH or by a shadow map; the lighting formulas scale each light's
// diffuse and specular terms by it (lighting.h). A draw without shadowing lights has no SceneShadows
// and pays nothing.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>

#include "pipeline/wide.h"
#include "raycast/ray_scene.h"
#include "shaders/shadow_map.h"
#include "shading/lighting.h"
#include "shading/shadow.h"

namespace facet {

struct LightShadow {
    ShadowMethod method = ShadowMethod::None;
    const ShadowMap* map = nullptr;  // ShadowMethod::Map
};

// What the shaders read to shadow a frame: per light (in the uniforms' order) its method, the BVH of the
// scene's opaque triangles in eye space (ray-cast shadows), and the shadow rays' origin offset ε.
struct SceneShadows {
    std::array<LightShadow, kMaxLights> lights{};
    const RayScene* rays = nullptr;
    float rayOffset = 0;  // ε, eye space (shading/shadow.h's kShadowRayOffset of the scene's extent)
    bool any() const {
        for (const LightShadow& l : lights)
            if (l.method != ShadowMethod::None) return true;
        return false;
    }
};

namespace detail {

template <class F>
unsigned laneBits(F condition) {
    if constexpr (LaneTraits<F>::kCount == 1)
        return condition ? 1u : 0u;
    else
        return signMask(condition);
}

}  // namespace detail

// Whether the ray from P towards the light is blocked by an opaque triangle: 1 where the light is seen,
// 0 where not. The ray starts at P + ε·N and ends ε short of a point or spot light (a directional light
// is infinitely far). Lanes where N·L ≤ 0 get no light from it anyway and are not traced; nor are lanes
// with a non-finite P (eight-lane batches carry such dead lanes).
template <class F, class V3 = LaneVec3<F>>
F rayVisibility(const SceneShadows& shadows, const LightParams& light, const V3& P, const V3& N) {
    const LightVector<F, V3> toLight = lightVector<F, V3>(light, P);
    const F facing = dot(N, toLight.L);
    const V3 origin = P + N * lanes<F>(shadows.rayOffset);
    const F reach = light.kind == LightKind::Directional
                        ? lanes<F>(std::numeric_limits<float>::infinity())
                        : toLight.distance - lanes<F>(2.0f * shadows.rayOffset);
    if constexpr (LaneTraits<F>::kCount == 8) {
        const unsigned traced = signMask(facing > 0.0f) & signMask(reach > 0.0f);
        const unsigned blocked = shadows.rays->occluded8(origin, toLight.L, splat(0.0f), reach, traced);
        Float8 v = splat(1.0f);
        for (int i = 0; i < 8; ++i)
            if ((blocked >> i) & 1) v[i] = 0.0f;
        return v;
    } else {
        if (!(facing > 0.0f) || !(reach > 0.0f)) return lanes<F>(1.0f);
        return shadows.rays->occluded(vec3(origin), vec3(toLight.L), 0.0f, float(reach)) ? lanes<F>(0.0f)
                                                                                         : lanes<F>(1.0f);
    }
}

// An area light's visibility at P: the fraction of its n samples (areaLightSample, lighting.h) whose
// shadow ray reaches them. A sample counts where it lies in front of the surface (N·ω > 0), the point
// lies on its emitting side, and no opaque triangle blocks the segment from P + ε·N to ε short of it.
template <class F, class V3 = LaneVec3<F>>
F areaVisibility(const SceneShadows& shadows, const LightParams& light, const V3& P, const V3& N) {
    const int n = std::max(light.areaSamples, 1);
    const V3 origin = P + N * lanes<F>(shadows.rayOffset);
    if constexpr (LaneTraits<F>::kCount == 8) {
        Float8 visible = splat(0.0f);
        for (int k = 0; k < n; ++k) {
            const vec3 sample = areaLightSample(light, k, n);
            const Vec3x8 toSample = Vec3x8(sample) - origin;
            const Float8 distance = sqrt(dot(toSample, toSample));
            const Vec3x8 direction = toSample * (1.0f / max(distance, 1e-15f));
            const Float8 reach = distance - 2.0f * shadows.rayOffset;
            const unsigned traced = signMask(dot(N, direction) > 0.0f) &
                                    signMask(dot(direction, Vec3x8(light.areaNormal)) < 0.0f) &
                                    signMask(reach > 0.0f);
            const unsigned blocked = shadows.rays->occluded8(origin, direction, splat(0.0f), reach, traced);
            for (int i = 0; i < 8; ++i)
                if (((traced & ~blocked) >> i) & 1) visible[i] += 1.0f;
        }
        return visible * (1.0f / float(n));
    } else {
        int visible = 0;
        const vec3 o(origin), normal(N);
        for (int k = 0; k < n; ++k) {
            const vec3 toSample = areaLightSample(light, k, n) - o;
            const float distance = length(toSample);
            const float reach = distance - 2.0f * shadows.rayOffset;
            if (!(reach > 0.0f)) continue;
            const vec3 direction = toSample / distance;
            if (!(dot(normal, direction) > 0.0f) || !(dot(direction, light.areaNormal) < 0.0f)) continue;
            if (!shadows.rays->occluded(o, direction, 0.0f, reach)) ++visible;
        }
        return lanes<F>(float(visible) / float(n));
    }
}

// Light i's visibility at P; sixteen lanes (wide.h) as two halves of eight, the rays traced eight at a
// time as for one batch.
template <class F, class V3 = LaneVec3<F>>
F lightVisibility(const SceneShadows& shadows, std::span<const LightParams> lights, std::size_t i,
                  const V3& P, const V3& N) {
    if constexpr (LaneTraits<F>::kCount == 16) {
        return joinHalves(lightVisibility<Float8>(shadows, lights, i, lowHalf(P), lowHalf(N)),
                          lightVisibility<Float8>(shadows, lights, i, highHalf(P), highHalf(N)));
    } else {
        switch (shadows.lights[i].method) {
            case ShadowMethod::None:
                break;
            case ShadowMethod::Ray:
                return isAreaLight(lights[i].kind) ? areaVisibility<F, V3>(shadows, lights[i], P, N)
                                                   : rayVisibility<F, V3>(shadows, lights[i], P, N);
            case ShadowMethod::Map:
                return shadowMapVisibility<F, V3>(*shadows.lights[i].map, lights[i], P, N);
        }
        return lanes<F>(1.0f);
    }
}

// Each light's visibility at P (N the normal the lighting uses, turned towards the viewer).
template <class F, class V3 = LaneVec3<F>>
void lightVisibilities(const SceneShadows& shadows, std::span<const LightParams> lights, const V3& P,
                       const V3& N, F* visibility) {
    for (std::size_t i = 0; i < lights.size(); ++i)
        visibility[i] = lightVisibility<F, V3>(shadows, lights, i, P, N);
}

}  // namespace facet
