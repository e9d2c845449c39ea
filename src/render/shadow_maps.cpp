#include "render/shadow_maps.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

#include "base/memory_limit.h"
#include "pipeline/pipeline.h"
#include "render/renderer.h"

namespace facet {

namespace {

// Position only, no varyings: the map keeps depth and nothing else. The colour buffer the pipeline
// writes anyway (it has no colour mask) is thrown away.
struct DepthOnlyShader {
    using Attributes = MeshVertex;
    struct Varyings {};
    struct Uniforms {
        mat4 clipFromObject{1.0f};
    };
    static VertexOut<Varyings> vertex(const Attributes& in, const Uniforms& u) {
        return {u.clipFromObject * vec4(in.position, 1.0f), {}};
    }
    static vec4 fragment(const Varyings&, const Uniforms&) { return vec4(0.0f); }
};

// The scene's bounding sphere in eye space (every draw, transparent ones too: they receive shadows).
struct Sphere {
    glm::dvec3 centre{0.0};
    double radius = 0;
};

Sphere sceneSphere(const PreparedScene& prepared) {
    glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-std::numeric_limits<double>::infinity());
    for (const PreparedDraw& d : prepared.draws)
        for (const MeshVertex& v : d.vertices) {
            const glm::dvec3 p(d.viewFromObjectExact * glm::dvec4(glm::dvec3(v.position), 1.0));
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
            low = glm::min(low, p);
            high = glm::max(high, p);
        }
    if (!(low.x <= high.x)) return {glm::dvec3(0.0), 1.0};  // nothing drawable
    const double radius = 0.5 * glm::length(high - low);
    // A hair wider, so that rounding never puts a vertex on the near or far plane.
    return {0.5 * (low + high), std::max(radius * 1.01, 1e-6)};
}

// An up vector not parallel to `forward`.
glm::dvec3 upFor(const glm::dvec3& forward) {
    return std::abs(forward.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
}

// A perspective projection from `eye` towards `forward` whose square frustum has half-angle tangent
// `tanHalf`, widened by kShadowMapMarginTexels, near and far fitted to the sphere: far its far side,
// near its near side, or a thousandth of far when the light is inside it (nearer casters are clipped).
glm::dmat4 perspectiveFrom(const glm::dvec3& eye, const glm::dvec3& forward, double tanHalf,
                           const Sphere& scene, int size) {
    const double widened = tanHalf * double(size) / double(size - 2 * kShadowMapMarginTexels);
    const double distance = glm::length(scene.centre - eye);
    const double far = distance + scene.radius;
    const double near = std::max(distance - scene.radius, far * 1e-3);
    return glm::perspective(2.0 * std::atan(widened), 1.0, near, far) *
           glm::lookAt(eye, eye + forward, upFor(forward));
}

}  // namespace

int shadowMapFaces(const LightParams& light) {
    if (light.kind == LightKind::Directional) return 1;
    const float cone =
        light.spotProfile == SpotProfile::Smooth ? light.spotOuterDegrees : light.spotCutoffDegrees;
    return light.kind == LightKind::Spot && cone <= kWidestSingleMapSpotDegrees ? 1 : 6;
}

std::uint64_t shadowMapBytes(std::uint64_t faces, int size) {
    const std::uint64_t texels = std::uint64_t(size) * std::uint64_t(size);
    return plusSaturating(timesSaturating(faces, timesSaturating(texels, sizeof(DepthFormat::Stored))),
                          Framebuffer::bytesFor(size, size, 1));
}

DrawState shadowMapDrawState(const ShadowMapOptions& options) {
    DrawState state;
    state.viewport = {0, 0, options.size, options.size};
    state.raster.cull = CullMode::None;
    const int width = options.filterTaps == 16 ? 4 : options.filterTaps == 4 ? 2 : 1;
    state.depth.offset = {options.slopeBias * float(width), options.constantBias};
    return state;
}

std::unique_ptr<ShadowMap> drawShadowMap(const PreparedScene& prepared, int lightIndex) {
    const ShadowMapOptions& options = prepared.shadowMapOptions;
    auto map = std::make_unique<ShadowMap>();
    map->size = options.size;
    map->filterTaps = options.filterTaps;
    if (prepared.draws.empty()) return map;
    // Lights are in eye space in every draw's uniforms.
    const LightParams& light = prepared.draws.front().uniforms.lights[std::size_t(lightIndex)];
    map->lightPosition = light.position;
    const Sphere scene = sceneSphere(prepared);

    // The light's clip space from eye space, per face.
    std::vector<glm::dmat4> clipFromEye;
    const glm::dvec3 position(light.position);
    const double cone =
        light.spotProfile == SpotProfile::Smooth ? light.spotOuterDegrees : light.spotCutoffDegrees;
    const int faces = shadowMapFaces(light);
    if (faces == 1 && light.kind == LightKind::Directional) {
        // Orthographic, along the light, over the scene's bounding sphere: the eye 2r behind the centre,
        // near and far r either side of it (a tenth of r to spare for the depth offset).
        const glm::dvec3 along = glm::normalize(glm::dvec3(light.direction));
        const glm::dvec3 eye = scene.centre - along * (2.0 * scene.radius);
        const double r = scene.radius;
        clipFromEye.push_back(glm::ortho(-r, r, -r, r, 0.9 * r, 3.1 * r) *
                              glm::lookAt(eye, scene.centre, upFor(along)));
    } else if (faces == 1) {  // a spot light of a narrow cone
        // Perspective over the cone (fovy = 2 × its half-angle, plus the margin).
        const glm::dvec3 axis = glm::normalize(glm::dvec3(light.spotDirection));
        clipFromEye.push_back(
            perspectiveFrom(position, axis, std::tan(glm::radians(double(cone))), scene, options.size));
    } else {
        // Six 90° faces around the light, in cubeFaceOf's order.
        const glm::dvec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        for (const glm::dvec3& axis : axes)
            clipFromEye.push_back(perspectiveFrom(position, axis, 1.0, scene, options.size));
    }

    map->faces.reserve(clipFromEye.size());
    const DrawState state = shadowMapDrawState(options);
    DrawContext context;
    Framebuffer target(options.size, options.size);
    for (const glm::dmat4& face : clipFromEye) {
        target.clear(vec4(0.0f), DepthFormat::kClear, context.pool);
        for (const PreparedDraw& d : prepared.draws) {
            if (d.transparent) continue;  // see-through surfaces cast no shadow
            const DepthOnlyShader::Uniforms uniforms{mat4(face * d.viewFromObjectExact)};
            draw<DepthOnlyShader>(state, uniforms, std::span<const MeshVertex>(d.vertices), d.indices, target,
                                  context);
        }
        target.finishClear(context.pool);  // the cells no triangle reached
        map->faces.push_back({mat4(face), target.depthPixels()});
    }
    return map;
}

}  // namespace facet
