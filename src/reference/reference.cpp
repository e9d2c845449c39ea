#include "reference/reference.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "pipeline/blend.h"
#include "raycast/ray_scene.h"
#include "render/draw_geometry.h"
#include "shaders/shaders.h"

namespace facet {

namespace {

using glm::dmat3;
using glm::dmat4;
using glm::dvec2;
using glm::dvec3;
using glm::dvec4;

// A draw as the reference shades it: its corners in eye space in double, and uniforms asking for the
// exact formulas. A draw with a shader of one's own keeps its vertex part's output instead of normals
// and texture coordinates: its corners where the vertex part puts them (eyePositions), and its
// varyings, which each hit interpolates in double.
struct ReferenceDraw {
    std::vector<dvec3> positions;  // eye space
    std::vector<dvec3> normals;    // eye space, not unit length (the shader normalises)
    std::vector<dvec2> uvs;
    SurfaceUniforms uniforms;
    const ShaderModule* userShader = nullptr;
    std::size_t varyingCount = 0;  // floats per vertex
    std::vector<float> varyings;   // the vertex part's, varyingCount per vertex
    // An opaque draw whose shader may discard: traced as see-through, the nearest fragment it keeps
    // on a ray being the opaque surface there.
    bool discardsOpaque = false;
};

ReferenceDraw referenceDraw(const PreparedScene& prepared, const PreparedDraw& draw,
                            const SceneShadows* shadows, std::uint8_t terms) {
    ReferenceDraw out;
    out.uniforms = draw.uniforms;
    out.uniforms.precision = MathPrecision::Exact;      // std::pow and std::exp, in double
    out.uniforms.normalization = Normalization::Exact;  // 1/sqrt in double
    out.uniforms.brdf.fresnel = FresnelModel::Exact;    // the exact dielectric Fresnel, not Schlick's
    out.uniforms.shadows = shadows;                     // ray-cast, whatever the scene's method
    out.uniforms.terms = terms;
    // Bilinear at each ray's point, whatever the draw's filter: with N×N rays a pixel the reference
    // integrates the pixel's footprint itself, the truth a filter (nearest, trilinear) approximates.
    out.uniforms.textureFilter = TextureFilter::Bilinear;
    if (draw.userShader.module) {
        // The vertex part at every vertex: where it puts the corners, and the varyings.
        const ShaderModule& module = *draw.userShader.module;
        out.userShader = &module;
        out.varyingCount = module.varyingNames.size();
        out.discardsOpaque = module.discards && !draw.transparent;
        out.varyings.resize(draw.vertices.size() * out.varyingCount + 1);
        const ShaderCall call = userShaderCall(prepared, draw, &out.uniforms);
        out.positions.reserve(draw.vertices.size());
        for (std::size_t v = 0; v < draw.vertices.size(); ++v) {
            const vec4 clip = module.shadeVertex(draw.vertices[v], call, &out.varyings[v * out.varyingCount]);
            out.positions.push_back(eyeFromClip(prepared, clip));
        }
        return out;
    }
    const dmat4& viewFromObject = draw.viewFromObjectExact;
    // Normals transform by the inverse transpose; its scale does not matter (they are normalised).
    const dmat3 normalFromObject = glm::transpose(glm::inverse(dmat3(viewFromObject)));
    out.positions.reserve(draw.vertices.size());
    out.normals.reserve(draw.vertices.size());
    out.uvs.reserve(draw.vertices.size());
    for (const MeshVertex& v : draw.vertices) {
        out.positions.push_back(dvec3(viewFromObject * dvec4(dvec3(v.position), 1.0)));
        out.normals.push_back(normalFromObject * dvec3(v.normal));
        out.uvs.push_back(dvec2(v.uv));
    }
    return out;
}

// The ray o + t·d meets triangle (a, b, c) where t and the barycentrics (1 − u − v, u, v) solve
// o + t·d = a + u·(b − a) + v·(c − a) (Möller & Trumbore 1997), here in double. Embree decided that the
// ray hits this triangle; a hit it found on an edge may come out a hair outside in double, so the
// barycentrics are clamped onto the triangle.
struct Barycentric {
    double t;
    dvec3 weights;  // of a, b, c
};
Barycentric intersect(const dvec3& o, const dvec3& d, const dvec3& a, const dvec3& b, const dvec3& c,
                      double embreeT) {
    const dvec3 e1 = b - a, e2 = c - a;
    const dvec3 p = glm::cross(d, e2);
    const double det = glm::dot(e1, p);
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) {
        // Degenerate in double (Embree found it in float): the point Embree reported, weights equal.
        return {embreeT, dvec3(1.0 / 3.0)};
    }
    const double inverse = 1.0 / det;
    const dvec3 s = o - a;
    double u = glm::dot(s, p) * inverse;
    const dvec3 q = glm::cross(s, e1);
    double v = glm::dot(d, q) * inverse;
    const double t = glm::dot(e2, q) * inverse;
    u = std::max(u, 0.0);
    v = std::max(v, 0.0);
    if (u + v > 1.0) {
        const double sum = u + v;
        u /= sum;
        v /= sum;
    }
    return {t, dvec3(1.0 - u - v, u, v)};
}

// Sample (i, j) of pixel (x, y) on an N×N grid: one point per cell, at a position within its cell from a
// hash of the five numbers (so the image is the same whatever thread traces it); the cell centre for N = 1.
dvec2 samplePosition(int x, int y, int i, int j, int n) {
    if (n == 1) return {x + 0.5, y + 0.5};
    std::uint64_t h = (std::uint64_t(std::uint32_t(x)) << 32) ^ std::uint32_t(y);
    h ^= (std::uint64_t(i) << 48) ^ (std::uint64_t(j) << 40) ^ 0x9e3779b97f4a7c15ull;
    // splitmix64's finaliser: well mixed bits from nearby inputs.
    const auto mix = [](std::uint64_t z) {
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    };
    const std::uint64_t a = mix(h), b = mix(h + 0x632be59bd9b4e019ull);
    const double jitterX = double(a >> 11) * 0x1.0p-53, jitterY = double(b >> 11) * 0x1.0p-53;
    return {x + (i + jitterX) / n, y + (j + jitterY) / n};
}

using Ray = CameraRay;

}  // namespace

ReferenceCamera::ReferenceCamera(const PreparedScene& prepared)
    : viewFromClip_(glm::inverse(prepared.camera.clipFromViewExact)),
      width_(prepared.scene.width),
      height_(prepared.scene.height),
      culling_{prepared.state.raster.cull == CullMode::Back, prepared.state.raster.cull == CullMode::Front} {
    // The rasterizer's front faces are counter-clockwise in window space (y down): seen from the eye
    // that is counter-clockwise too, as RayScene counts it.
    nearDepth_ = -eyePoint(0.0, 0.0, -1.0).z;
    farDepth_ = -eyePoint(0.0, 0.0, 1.0).z;
}

dvec3 ReferenceCamera::eyePoint(double ndcX, double ndcY, double ndcZ) const {
    const dvec4 p = viewFromClip_ * dvec4(ndcX, ndcY, ndcZ, 1.0);
    return dvec3(p) / p.w;
}

CameraRay ReferenceCamera::ray(dvec2 window) const {
    const double ndcX = 2.0 * window.x / width_ - 1.0, ndcY = 1.0 - 2.0 * window.y / height_;
    const dvec3 onNear = eyePoint(ndcX, ndcY, -1.0);
    return {dvec3(0.0), onNear / -onNear.z, nearDepth_, farDepth_};
}

LinearImage renderReference(const PreparedScene& prepared, const ReferenceOptions& options, ThreadPool& pool,
                            ReferenceStats* stats) {
    const int n = std::clamp(options.samples, 1, kMaxReferenceSamples);
    const int width = prepared.scene.width, height = prepared.scene.height;

    // The BVHs, of the scene as placed now (a user shader's triangles where its vertex part puts them).
    std::vector<std::vector<vec3>> positions;
    std::vector<RayMesh> meshes = rayMeshes(prepared, positions);
    // Opaque draws whose shader may discard are traced as see-through by the camera rays (the nearest
    // fragment they keep is the opaque surface); the shadow rays see them opaque, as the rasterizer's
    // ray-cast shadows do, through a BVH of their own.
    bool anyDiscardingOpaque = false;
    for (std::size_t k = 0; k < prepared.draws.size(); ++k) {
        const PreparedDraw& d = prepared.draws[k];
        if (d.userShader.module && d.userShader.module->discards && !d.transparent) {
            meshes[k].opaque = false;
            anyDiscardingOpaque = true;
        }
    }
    const RayScene rays(meshes);
    std::unique_ptr<RayScene> shadowRays;
    if (anyDiscardingOpaque) {
        std::vector<RayMesh> shadowMeshes = meshes;
        for (std::size_t k = 0; k < prepared.draws.size(); ++k)
            shadowMeshes[k].opaque = !prepared.draws[k].transparent;
        shadowRays = std::make_unique<RayScene>(shadowMeshes);
    }

    // Shadows: every light that casts them, by a ray.
    SceneShadows shadows;
    shadows.rays = shadowRays ? shadowRays.get() : &rays;
    shadows.rayOffset = kShadowRayOffset * prepared.sceneExtent;
    bool anyShadows = false;
    for (std::size_t i = 0; i < kMaxLights; ++i) {
        if (prepared.shadowMethods[i] == ShadowMethod::None) continue;
        shadows.lights[i].method = ShadowMethod::Ray;
        anyShadows = true;
    }
    std::vector<ReferenceDraw> draws;
    draws.reserve(prepared.draws.size());
    for (const PreparedDraw& d : prepared.draws) {
        draws.push_back(referenceDraw(prepared, d, anyShadows ? &shadows : nullptr, options.terms));
        for (LightParams& light : draws.back().uniforms.lights)
            if (isAreaLight(light.kind)) light.areaSamples = std::max(options.areaSamples, 1);
    }

    // Camera rays: from the eye through the near plane's point of each sample, t from near to far.
    const ReferenceCamera camera(prepared);
    const RayScene::Culling culling = camera.culling();
    const dvec4 background(prepared.clearColor);

    // The colour seen along one ray, and the shading of one hit: nothing where a user shader discards.
    // A user shader's varyings are interpolated in double with the hit's barycentrics (in eye space,
    // which is perspective-correct interpolation) and its fragment part runs in float: the reference is
    // exact for it in coverage, depth and interpolation, and shades as the shader's own code does.
    const auto shadeHit = [&](const Ray& ray, const RayHit& hit) -> std::optional<dvec4> {
        const ReferenceDraw& draw = draws[hit.mesh];
        const std::uint32_t* corner = &prepared.draws[hit.mesh].indices[3 * hit.triangle];
        const Barycentric b = intersect(ray.origin, ray.direction, draw.positions[corner[0]],
                                        draw.positions[corner[1]], draw.positions[corner[2]], hit.t);
        if (draw.userShader) {
            // A shader has at most kMaxVaryingFloats (pipeline/types.h: its VaryingsT is checked).
            float varyings[kMaxVaryingFloats + 1] = {};
            const std::size_t count = std::min(draw.varyingCount, std::size_t(kMaxVaryingFloats));
            const float* v0 = &draw.varyings[corner[0] * draw.varyingCount];
            const float* v1 = &draw.varyings[corner[1] * draw.varyingCount];
            const float* v2 = &draw.varyings[corner[2] * draw.varyingCount];
            for (std::size_t i = 0; i < count; ++i)
                varyings[i] = float(b.weights.x * double(v0[i]) + b.weights.y * double(v1[i]) +
                                    b.weights.z * double(v2[i]));
            FragmentInput in;
            in.varyings = varyings;
            in.barycentric = vec3(b.weights);
            const ShaderCall call = userShaderCall(prepared, prepared.draws[hit.mesh], &draw.uniforms);
            vec4 color(0.0f);
            if (!draw.userShader->shadeFragment(in, call, color, nullptr)) return std::nullopt;
            return dvec4(color);
        }
        PerPixelSurface::VaryingsT<double> in;
        in.position = b.weights.x * draw.positions[corner[0]] + b.weights.y * draw.positions[corner[1]] +
                      b.weights.z * draw.positions[corner[2]];
        in.normal = b.weights.x * draw.normals[corner[0]] + b.weights.y * draw.normals[corner[1]] +
                    b.weights.z * draw.normals[corner[2]];
        in.uv = b.weights.x * draw.uvs[corner[0]] + b.weights.y * draw.uvs[corner[1]] +
                b.weights.z * draw.uvs[corner[2]];
        if (!draw.uniforms.anisotropic()) return PerPixelSurface::shade<double>(in, draw.uniforms, 1u);
        // Anisotropic GGX: the triangle's exact tangent ∂P/∂u from its corners' positions and uvs
        // (Lengyel 2001, tangent.h), made a frame about the interpolated normal by the lighting.
        const dvec3 a = draw.positions[corner[0]], b1 = draw.positions[corner[1]],
                    c = draw.positions[corner[2]];
        const dvec2 ta = draw.uvs[corner[0]], tb = draw.uvs[corner[1]], tc = draw.uvs[corner[2]];
        const dvec3 tangent =
            tangentFromDifferentials<double, dvec3>(b1 - a, c - a, tb.x - ta.x, tb.y - ta.y, tc.x - ta.x,
                                                    tc.y - ta.y, fallbackTangent<double, dvec3>(in.normal));
        return PerPixelSurface::shadeWithTangent<double>(in, draw.uniforms, 1u, {}, &tangent);
    };

    const auto start = std::chrono::steady_clock::now();
    LinearImage image;
    image.width = width;
    image.height = height;
    image.pixels.assign(static_cast<std::size_t>(width) * height, vec4(0.0f));
    std::atomic<std::uint64_t> transparentHits{0}, surfaceHits{0};
    const bool anyTransparent = rays.hasTransparent();
    const std::size_t samplesPerPixel = static_cast<std::size_t>(n) * n;

    if (options.nearestSurfaces && n == 1)
        options.nearestSurfaces->assign(static_cast<std::size_t>(width) * height, RayHit{});
    std::atomic<int> rowsDone{0};
    int rowsReported = 0;  // by the calling thread, the only one that reports
    pool.parallelFor(static_cast<std::size_t>(height), [&](std::size_t row, int thread) {
        const int y = static_cast<int>(row);
        std::vector<Ray> rowRays(static_cast<std::size_t>(width) * samplesPerPixel);
        std::vector<RayHit> opaque(rowRays.size());
        std::vector<RayHit> see;
        std::uint64_t rowTransparentHits = 0, rowSurfaceHits = 0;
        for (int x = 0; x < width; ++x)
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i)
                    rowRays[(static_cast<std::size_t>(x) * n + j) * n + i] =
                        camera.ray(samplePosition(x, y, i, j, n));
        // The nearest opaque surface of eight rays at a time.
        for (std::size_t first = 0; first < rowRays.size(); first += 8) {
            const std::size_t count = std::min<std::size_t>(8, rowRays.size() - first);
            dvec3 origins[8], directions[8];
            double tnear[8], tfar[8];
            for (std::size_t k = 0; k < count; ++k) {
                origins[k] = rowRays[first + k].origin;
                directions[k] = rowRays[first + k].direction;
                tnear[k] = rowRays[first + k].tnear;
                tfar[k] = rowRays[first + k].tfar;
            }
            rays.nearestOpaque8(origins, directions, tnear, tfar, (1u << count) - 1u, culling,
                                &opaque[first]);
        }
        // Each sample's colour: the opaque surface (or the background), then every see-through surface
        // in front of it, farthest first; the pixel is their mean.
        for (int x = 0; x < width; ++x) {
            dvec4 sum(0.0);
            for (std::size_t s = 0; s < samplesPerPixel; ++s) {
                const std::size_t k = static_cast<std::size_t>(x) * samplesPerPixel + s;
                const Ray& ray = rowRays[k];
                // A ray that meets nothing shows the background: the environment map along it, or the colour.
                dvec4 color =
                    prepared.environmentBackground
                        ? dvec4(dvec3(environmentColor(prepared.environment, ray.direction)), background.a)
                        : background;
                RayHit& front = opaque[k];  // the opaque surface the sample shows
                std::optional<dvec4> frontColor;
                if (front.hit()) frontColor = shadeHit(ray, front);  // never discarded: see above
                std::size_t inFront = 0;  // of `see`, the hits in front of the opaque surface
                if (anyTransparent) {
                    const double until = front.hit() ? double(front.t) : ray.tfar;
                    rays.allTransparent(ray.origin, ray.direction, ray.tnear, until, culling, see);
                    // The nearest fragment an opaque draw that discards keeps is the opaque surface.
                    inFront = see.size();
                    for (std::size_t h = 0; h < see.size(); ++h) {
                        if (!draws[see[h].mesh].discardsOpaque) continue;
                        if (std::optional<dvec4> kept = shadeHit(ray, see[h])) {
                            front = see[h];
                            frontColor = kept;
                            inFront = h;
                            break;
                        }
                    }
                }
                if (frontColor) {
                    color = *frontColor;
                    ++rowSurfaceHits;
                }
                if (inFront > 0) {
                    bool any = false;
                    for (std::size_t h = inFront; h-- > 0;) {
                        const RayHit& hit = see[h];
                        if (draws[hit.mesh].discardsOpaque) continue;  // discarded (above)
                        ++rowTransparentHits;
                        if (std::optional<dvec4> shaded = shadeHit(ray, hit)) {
                            color = blend(prepared.draws[hit.mesh].uniforms.blend, *shaded, color);
                            any = true;
                        }
                    }
                    if (!frontColor && any) ++rowSurfaceHits;
                }
                sum += color;
            }
            image.at(x, y) = vec4(sum / double(samplesPerPixel));
        }
        if (options.nearestSurfaces && n == 1)
            std::copy(opaque.begin(), opaque.end(),
                      options.nearestSurfaces->begin() + static_cast<std::ptrdiff_t>(row) * width);
        transparentHits += rowTransparentHits;
        surfaceHits += rowSurfaceHits;
        const int done = ++rowsDone;
        if (options.onRows && thread == 0) {  // thread 0: the calling thread (ThreadPool::parallelFor)
            rowsReported = done;
            options.onRows(done, height);
        }
    });
    if (options.onRows && rowsReported < height) options.onRows(height, height);

    if (stats) {
        stats->buildMilliseconds = rays.stats().buildMilliseconds;
        stats->renderMilliseconds =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        stats->cameraRays = static_cast<std::uint64_t>(width) * height * samplesPerPixel;
        stats->transparentHits = transparentHits;
        stats->surfaceHits = surfaceHits;
        stats->nonFiniteSkipped = rays.stats().nonFiniteSkipped;
    }
    return image;
}

}  // namespace facet
