// The exact reference renderer: the same prepared scene as the rasterizer (objects, materials, lights,
// textures, fog, gamma), but visibility decided by casting rays through Embree and every number of the
// shading computed in double. It is the image that the rasterizer's approximations are scored against
// (docs/reference.md):
//   - N×N samples per pixel on a stratified grid (one jittered sample per cell; the cell centre when N = 1,
//     the pixel centre, where the rasterizer samples), averaged with a box filter in linear light;
//   - camera rays in packets of eight, from the eye through the sample, limited to [near, far] as the
//     rasterizer's clipping is; faces culled as the scene's pipeline culls them;
//   - the hit point, barycentrics, normal and texture coordinates recomputed in double from the triangle
//     Embree reports; shaded with the rasterizer's own per-pixel surface shader instantiated for double,
//     pow and exp exact, Fresnel exact, at every hit (per-pixel lighting whatever the draw's frequency);
//   - transparency exact: every see-through surface on the ray, composited in depth order over the
//     nearest opaque one, each with its own blend;
//   - shadows from every light that casts them, always by a ray to the light (never a map);
//   - a draw with a shader of one's own (--shader): its vertex part run at every vertex, the triangles
//     traced where it puts them (its clip positions mapped back to eye space in double), its varyings
//     interpolated at the hit in double (perspective-correct: linear in eye space) and handed to its
//     fragment part, which runs in float as the shader's code is written: for such a draw the reference
//     is exact in coverage, depth and interpolation, not in the shading's arithmetic. Where the fragment
//     part discards, the ray goes on to what lies behind.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "io/image_io.h"
#include "pipeline/names.h"
#include "pipeline/thread_pool.h"
#include "render/renderer.h"

namespace facet {

// Which renderer makes the image (facet render --renderer).
enum class RendererKind {
    Rasterizer,  // Facet's pipeline: fast, the approximations the scene asks for
    Reference,   // this: ray casting, double precision, no approximation
};
inline constexpr EnumName<RendererKind> kRendererKindNames[] = {{RendererKind::Rasterizer, "rasterizer"},
                                                                {RendererKind::Reference, "reference"}};
constexpr std::span<const EnumName<RendererKind>> enumNames(RendererKind) {
    return kRendererKindNames;
}

struct ReferenceOptions {
    int samples = 4;                 // N: N×N rays per pixel
    std::uint8_t terms = kAllTerms;  // LightingTerm bits: the terms drawn (a component image: one)
    // When set (and samples = 1): per pixel, row by row, the nearest opaque surface its centre's ray met
    // (RayHit::mesh is the draw's index in PreparedScene::draws; no hit: RayHit{}), for comparing which
    // surface each pixel shows with the rasterizer's.
    std::vector<RayHit>* nearestSurfaces = nullptr;
    // When set: per pixel (row by row; renderReferencePixels: per pixel asked for), the largest difference
    // between two of its N×N rays' colours in any of R, G, B, linear: where the pixel is not one colour
    // (an edge, a shadow's border, texture detail), which is where N×N rays leave an error.
    std::vector<float>* raySpread = nullptr;
    // Shadow rays per point of every area light (a square), whatever the scene's count: many, so that
    // the reference's own error in a soft shadow is small.
    int areaSamples = kReferenceAreaSamples;
    // Told how far the image is (facet trade's progress): called with the rows traced so far and the
    // image's rows, from the calling thread only (after each row it traces itself, so never two calls at
    // once and never more often than rows), with a count that only rises, and a last time with every row
    // traced. It should be cheap: the rows wait for it.
    std::function<void(int rowsDone, int rows)> onRows = nullptr;
};
inline constexpr int kMaxReferenceSamples = 16;  // 256 rays per pixel
// A chosen set of pixels may take twice as many (32×32 rays): enough to check a 16×16 image's own error.
inline constexpr int kMaxReferencePixelSamples = 2 * kMaxReferenceSamples;

// A camera ray of the reference: from the eye (eye space's origin) through a point of the near plane,
// the direction scaled so that its z is −1 (t is then the eye-space depth), t limited to [near, far] as
// the rasterizer's clipping limits depth.
struct CameraRay {
    glm::dvec3 origin;
    glm::dvec3 direction;
    double tnear, tfar;
};

// The camera rays of a prepared scene, as renderReference casts them (and a benchmark times them).
class ReferenceCamera {
  public:
    explicit ReferenceCamera(const PreparedScene& prepared);
    // The ray through `window` (pixels, y down: pixel (x, y)'s centre is (x + 0.5, y + 0.5)).
    CameraRay ray(glm::dvec2 window) const;
    // Faces culled as the scene's pipeline culls them.
    RayScene::Culling culling() const { return culling_; }

  private:
    glm::dvec3 eyePoint(double ndcX, double ndcY, double ndcZ) const;

    glm::dmat4 viewFromClip_;
    double width_, height_;
    double nearDepth_ = 0, farDepth_ = 0;
    RayScene::Culling culling_;
};

struct ReferenceStats {
    double buildMilliseconds = 0;   // the BVHs
    double renderMilliseconds = 0;  // tracing and shading, BVH excluded
    std::uint64_t cameraRays = 0;
    std::uint64_t shadowRays = 0;
    std::uint64_t surfaceHits = 0;  // samples whose ray met any surface (0: only the background)
    std::uint64_t transparentHits = 0;
    std::size_t nonFiniteSkipped = 0;  // triangles with a non-finite corner in eye space, left out
};

// The scene as prepared (and turned) now, traced. `pool` spreads rows over threads; the image is the
// same for any thread count.
LinearImage renderReference(const PreparedScene& prepared, const ReferenceOptions& options, ThreadPool& pool,
                            ReferenceStats* stats = nullptr);

// Only the given pixels (x, y) of the same image: their colours, in the order given, each exactly the
// colour renderReference gives that pixel with the same options (the same rays, jitter and packets).
// N up to kMaxReferencePixelSamples. Throws std::invalid_argument for a pixel outside the image.
std::vector<vec4> renderReferencePixels(const PreparedScene& prepared, const ReferenceOptions& options,
                                        std::span<const glm::ivec2> pixels, ThreadPool& pool,
                                        ReferenceStats* stats = nullptr);

}  // namespace facet
