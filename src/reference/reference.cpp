#include "reference/reference.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>
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
    // Normals transform by the inverse transpose, scaled to determinant 1 as the rasterizer's: the
    // view's scale (2^60 for a 1e-18 model) would otherwise shrink them below the lighting's smallest
    // normalisable length (wide.h's safeNormalize), a dim model.
    const dmat3 normalFromObject = normalMatrix(viewFromObject).scaled;
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

namespace {

// The scene made ready for tracing (BVHs, shadows, the draws in double, the camera) and the colour of
// a run of pixels of one row: the one per-pixel code of the reference, which the whole image and a
// chosen set of pixels both go through.
class Tracer {
  public:
    Tracer(const PreparedScene& prepared, const ReferenceOptions& options, int maxSamples)
        : prepared_(prepared),
          n_(std::clamp(options.samples, 1, maxSamples)),
          samplesPerPixel_(static_cast<std::size_t>(n_) * n_),
          width_(prepared.scene.width),
          meshes_(cameraMeshes(prepared, positions_, anyDiscardingOpaque_)),
          rays_(meshes_),
          camera_(prepared),
          culling_(camera_.culling()),
          background_(prepared.clearColor),
          anyTransparent_(rays_.hasTransparent()) {
        // Opaque draws whose shader may discard are traced as see-through by the camera rays (the nearest
        // fragment they keep is the opaque surface); the shadow rays see them opaque, as the rasterizer's
        // ray-cast shadows do, through a BVH of their own.
        if (anyDiscardingOpaque_) {
            std::vector<RayMesh> shadowMeshes = meshes_;
            for (std::size_t k = 0; k < prepared.draws.size(); ++k)
                shadowMeshes[k].opaque = !prepared.draws[k].transparent;
            shadowRays_ = std::make_unique<RayScene>(shadowMeshes);
        }
        // Shadows: every light that casts them, by a ray.
        shadows_.rays = shadowRays_ ? shadowRays_.get() : &rays_;
        shadows_.rayOffset = kShadowRayOffset * prepared.sceneExtent;
        bool anyShadows = false;
        for (std::size_t i = 0; i < kMaxLights; ++i) {
            if (prepared.shadowMethods[i] == ShadowMethod::None) continue;
            shadows_.lights[i].method = ShadowMethod::Ray;
            anyShadows = true;
        }
        draws_.reserve(prepared.draws.size());
        for (const PreparedDraw& d : prepared.draws) {
            draws_.push_back(referenceDraw(prepared, d, anyShadows ? &shadows_ : nullptr, options.terms));
            for (LightParams& light : draws_.back().uniforms.lights)
                if (isAreaLight(light.kind)) light.areaSamples = std::max(options.areaSamples, 1);
        }
    }
    Tracer(const Tracer&) = delete;  // the draws point at shadows_, which points at rays_
    Tracer& operator=(const Tracer&) = delete;

    int samples() const { return n_; }
    std::size_t samplesPerPixel() const { return samplesPerPixel_; }
    const RayScene& rays() const { return rays_; }

    struct Counts {
        std::uint64_t surfaceHits = 0, transparentHits = 0;
    };
    // Buffers of one thread, kept from one span to the next.
    struct Scratch {
        std::vector<Ray> rays;
        std::vector<RayHit> opaque, see;
    };

    // Pixels xBegin to xEnd − 1 of row y: their colours into color[0 ..], the largest difference between
    // two of a pixel's rays in any of R, G, B into spread[0 ..] (when given), the nearest opaque surface
    // of each ray into nearest[0 ..] (when given; N×N per pixel). The rays are traced in the packets of
    // eight that tracing the whole row makes (the row's k-th ray in packet k / 8), so that a pixel comes
    // out the same, bit for bit, whichever of its row's pixels are traced with it.
    void traceSpan(int y, int xBegin, int xEnd, Scratch& scratch, Counts& counts, vec4* color, float* spread,
                   RayHit* nearest) const {
        const std::size_t rowRays = static_cast<std::size_t>(width_) * samplesPerPixel_;
        const std::size_t first = static_cast<std::size_t>(xBegin) * samplesPerPixel_ / 8 * 8;
        const std::size_t last =
            std::min(rowRays, (static_cast<std::size_t>(xEnd) * samplesPerPixel_ + 7) / 8 * 8);
        std::vector<Ray>& rays = scratch.rays;
        std::vector<RayHit>& opaque = scratch.opaque;
        rays.resize(last - first);
        opaque.assign(last - first, RayHit{});
        // The row's ray k: sample (i, j) = (s mod N, s / N) of pixel k / (N×N), s = k mod (N×N).
        for (std::size_t k = first; k < last; ++k) {
            const int x = static_cast<int>(k / samplesPerPixel_);
            const int s = static_cast<int>(k % samplesPerPixel_);
            rays[k - first] = camera_.ray(samplePosition(x, y, s % n_, s / n_, n_));
        }
        // The nearest opaque surface of eight rays at a time.
        for (std::size_t packet = 0; packet < rays.size(); packet += 8) {
            const std::size_t count = std::min<std::size_t>(8, rays.size() - packet);
            dvec3 origins[8], directions[8];
            double tnear[8], tfar[8];
            for (std::size_t k = 0; k < count; ++k) {
                origins[k] = rays[packet + k].origin;
                directions[k] = rays[packet + k].direction;
                tnear[k] = rays[packet + k].tnear;
                tfar[k] = rays[packet + k].tfar;
            }
            rays_.nearestOpaque8(origins, directions, tnear, tfar, (1u << count) - 1u, culling_,
                                 &opaque[packet]);
        }
        // Each sample's colour: the opaque surface (or the background), then every see-through surface
        // in front of it, farthest first; the pixel is their mean.
        for (int x = xBegin; x < xEnd; ++x) {
            dvec4 sum(0.0);
            dvec3 lowest(std::numeric_limits<double>::infinity()), highest(-lowest);
            const std::size_t pixelFirst = static_cast<std::size_t>(x) * samplesPerPixel_ - first;
            for (std::size_t s = 0; s < samplesPerPixel_; ++s) {
                const std::size_t k = pixelFirst + s;
                const dvec4 c = sampleColor(rays[k], opaque[k], scratch.see, counts);
                sum += c;
                lowest = glm::min(lowest, dvec3(c));
                highest = glm::max(highest, dvec3(c));
            }
            color[x - xBegin] = vec4(sum / double(samplesPerPixel_));
            if (spread) {
                const dvec3 range = highest - lowest;
                spread[x - xBegin] = float(std::max({range.r, range.g, range.b}));
            }
            if (nearest)
                std::copy_n(opaque.begin() + static_cast<std::ptrdiff_t>(pixelFirst), samplesPerPixel_,
                            nearest + static_cast<std::ptrdiff_t>(x - xBegin) * samplesPerPixel_);
        }
    }

  private:
    static std::vector<RayMesh> cameraMeshes(const PreparedScene& prepared,
                                             std::vector<std::vector<vec3>>& positions,
                                             bool& anyDiscardingOpaque) {
        // The BVHs, of the scene as placed now (a user shader's triangles where its vertex part puts them).
        std::vector<RayMesh> meshes = rayMeshes(prepared, positions);
        anyDiscardingOpaque = false;
        for (std::size_t k = 0; k < prepared.draws.size(); ++k) {
            const PreparedDraw& d = prepared.draws[k];
            if (d.userShader.module && d.userShader.module->discards && !d.transparent) {
                meshes[k].opaque = false;
                anyDiscardingOpaque = true;
            }
        }
        return meshes;
    }

    // The colour seen along one ray, and the shading of one hit: nothing where a user shader discards.
    // A user shader's varyings are interpolated in double with the hit's barycentrics (in eye space,
    // which is perspective-correct interpolation) and its fragment part runs in float: the reference is
    // exact for it in coverage, depth and interpolation, and shades as the shader's own code does.
    std::optional<dvec4> shadeHit(const Ray& ray, const RayHit& hit) const {
        const ReferenceDraw& draw = draws_[hit.mesh];
        const std::uint32_t* corner = &prepared_.draws[hit.mesh].indices[3 * hit.triangle];
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
            const ShaderCall call = userShaderCall(prepared_, prepared_.draws[hit.mesh], &draw.uniforms);
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
    }

    // One sample: `front` is the nearest opaque surface of its ray (replaced by the nearest fragment a
    // discarding opaque draw keeps, if nearer).
    dvec4 sampleColor(const Ray& ray, RayHit& front, std::vector<RayHit>& see, Counts& counts) const {
        // A ray that meets nothing shows the background: the environment map along it, or the colour.
        dvec4 color =
            prepared_.environmentBackground
                ? dvec4(dvec3(environmentColor(prepared_.environment, ray.direction)), background_.a)
                : background_;
        std::optional<dvec4> frontColor;
        if (front.hit()) frontColor = shadeHit(ray, front);  // never discarded: see above
        std::size_t inFront = 0;  // of `see`, the hits in front of the opaque surface
        if (anyTransparent_) {
            const double until = front.hit() ? double(front.t) : ray.tfar;
            rays_.allTransparent(ray.origin, ray.direction, ray.tnear, until, culling_, see);
            // The nearest fragment an opaque draw that discards keeps is the opaque surface.
            inFront = see.size();
            for (std::size_t h = 0; h < see.size(); ++h) {
                if (!draws_[see[h].mesh].discardsOpaque) continue;
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
            ++counts.surfaceHits;
        }
        if (inFront > 0) {
            bool any = false;
            for (std::size_t h = inFront; h-- > 0;) {
                const RayHit& hit = see[h];
                if (draws_[hit.mesh].discardsOpaque) continue;  // discarded (above)
                ++counts.transparentHits;
                if (std::optional<dvec4> shaded = shadeHit(ray, hit)) {
                    color = blend(prepared_.draws[hit.mesh].uniforms.blend, *shaded, color);
                    any = true;
                }
            }
            if (!frontColor && any) ++counts.surfaceHits;
        }
        return color;
    }

    const PreparedScene& prepared_;
    const int n_;
    const std::size_t samplesPerPixel_;
    const int width_;
    std::vector<std::vector<vec3>> positions_;  // what the BVHs' meshes point into
    bool anyDiscardingOpaque_ = false;
    std::vector<RayMesh> meshes_;
    RayScene rays_;
    std::unique_ptr<RayScene> shadowRays_;
    SceneShadows shadows_;
    std::vector<ReferenceDraw> draws_;
    const ReferenceCamera camera_;
    const RayScene::Culling culling_;
    const dvec4 background_;
    const bool anyTransparent_;
};

void fillStats(ReferenceStats* stats, const Tracer& tracer, std::chrono::steady_clock::time_point start,
               std::uint64_t cameraRays, const std::atomic<std::uint64_t>& surfaceHits,
               const std::atomic<std::uint64_t>& transparentHits) {
    if (!stats) return;
    stats->buildMilliseconds = tracer.rays().stats().buildMilliseconds;
    stats->renderMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    stats->cameraRays = cameraRays;
    stats->transparentHits = transparentHits;
    stats->surfaceHits = surfaceHits;
    stats->nonFiniteSkipped = tracer.rays().stats().nonFiniteSkipped;
}

}  // namespace

LinearImage renderReference(const PreparedScene& prepared, const ReferenceOptions& options, ThreadPool& pool,
                            ReferenceStats* stats) {
    const Tracer tracer(prepared, options, kMaxReferenceSamples);
    const int width = prepared.scene.width, height = prepared.scene.height;
    const std::size_t pixels = static_cast<std::size_t>(width) * height;

    const auto start = std::chrono::steady_clock::now();
    LinearImage image;
    image.width = width;
    image.height = height;
    image.pixels.assign(pixels, vec4(0.0f));
    std::atomic<std::uint64_t> transparentHits{0}, surfaceHits{0};
    const bool nearest = options.nearestSurfaces && tracer.samples() == 1;
    if (nearest) options.nearestSurfaces->assign(pixels, RayHit{});
    if (options.raySpread) options.raySpread->assign(pixels, 0.0f);
    std::atomic<int> rowsDone{0};
    int rowsReported = 0;  // by the calling thread, the only one that reports
    pool.parallelFor(static_cast<std::size_t>(height), [&](std::size_t row, int thread) {
        Tracer::Scratch scratch;
        Tracer::Counts counts;
        const std::size_t offset = row * static_cast<std::size_t>(width);
        tracer.traceSpan(static_cast<int>(row), 0, width, scratch, counts, &image.pixels[offset],
                         options.raySpread ? options.raySpread->data() + offset : nullptr,
                         nearest ? options.nearestSurfaces->data() + offset : nullptr);
        transparentHits += counts.transparentHits;
        surfaceHits += counts.surfaceHits;
        const int done = ++rowsDone;
        if (options.onRows && thread == 0) {  // thread 0: the calling thread (ThreadPool::parallelFor)
            rowsReported = done;
            options.onRows(done, height);
        }
    });
    if (options.onRows && rowsReported < height) options.onRows(height, height);
    fillStats(stats, tracer, start, pixels * tracer.samplesPerPixel(), surfaceHits, transparentHits);
    return image;
}

std::vector<vec4> renderReferencePixels(const PreparedScene& prepared, const ReferenceOptions& options,
                                        std::span<const glm::ivec2> pixels, ThreadPool& pool,
                                        ReferenceStats* stats) {
    const Tracer tracer(prepared, options, kMaxReferencePixelSamples);
    const int width = prepared.scene.width, height = prepared.scene.height;
    for (const glm::ivec2 p : pixels)
        if (p.x < 0 || p.y < 0 || p.x >= width || p.y >= height)
            throw std::invalid_argument("renderReferencePixels: a pixel outside the image");
    // Runs of neighbouring pixels of one row, traced together (their shared packets once): the pixels'
    // indices in row order, cut where the row changes or a pixel is skipped.
    std::vector<std::size_t> order(pixels.size());
    for (std::size_t k = 0; k < order.size(); ++k)
        order[k] = k;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return std::make_pair(pixels[a].y, pixels[a].x) < std::make_pair(pixels[b].y, pixels[b].x);
    });
    struct Run {
        std::size_t begin, end;  // in `order`
    };
    std::vector<Run> runs;
    for (std::size_t k = 0; k < order.size(); ++k) {
        const glm::ivec2 p = pixels[order[k]];
        if (!runs.empty()) {
            const glm::ivec2 last = pixels[order[k - 1]];
            if (last.y == p.y && (last.x == p.x || last.x + 1 == p.x)) {
                runs.back().end = k + 1;
                continue;
            }
        }
        runs.push_back({k, k + 1});
    }

    const auto start = std::chrono::steady_clock::now();
    std::vector<vec4> colors(pixels.size());
    if (options.raySpread) options.raySpread->assign(pixels.size(), 0.0f);
    std::atomic<std::uint64_t> transparentHits{0}, surfaceHits{0};
    pool.parallelFor(runs.size(), [&](std::size_t r, int) {
        Tracer::Scratch scratch;
        Tracer::Counts counts;
        const int y = pixels[order[runs[r].begin]].y;
        const int xBegin = pixels[order[runs[r].begin]].x, xEnd = pixels[order[runs[r].end - 1]].x + 1;
        std::vector<vec4> spanColors(static_cast<std::size_t>(xEnd - xBegin));
        std::vector<float> spanSpread(spanColors.size());
        tracer.traceSpan(y, xBegin, xEnd, scratch, counts, spanColors.data(), spanSpread.data(), nullptr);
        for (std::size_t k = runs[r].begin; k < runs[r].end; ++k) {
            const std::size_t at = static_cast<std::size_t>(pixels[order[k]].x - xBegin);
            colors[order[k]] = spanColors[at];
            if (options.raySpread) (*options.raySpread)[order[k]] = spanSpread[at];
        }
        transparentHits += counts.transparentHits;
        surfaceHits += counts.surfaceHits;
    });
    std::size_t distinct = 0;
    for (const Run& run : runs)
        distinct += static_cast<std::size_t>(pixels[order[run.end - 1]].x - pixels[order[run.begin]].x + 1);
    fillStats(stats, tracer, start, distinct * tracer.samplesPerPixel(), surfaceHits, transparentHits);
    return colors;
}

}  // namespace facet
