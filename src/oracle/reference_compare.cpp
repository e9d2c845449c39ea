#include "oracle/reference_compare.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>

#include "pipeline/observer.h"
#include "reference/reference.h"
#include "render/draw_geometry.h"
#include "shading/gamma.h"

namespace facet {

using glm::dvec2;
using glm::dvec3;
using glm::dvec4;

namespace {

// Records which opaque triangle wrote each pixel last: with the depth test, the nearest one.
class SurfaceRecorder final : public FrameWatcher {
  public:
    SurfaceRecorder(std::vector<RayHit>& surfaces, int width) : surfaces(surfaces), width(width) {}
    std::vector<RayHit>& surfaces;
    int width;
    std::uint32_t draw = 0;
    bool opaque = true;

    void onPlannedDraw(const PlannedDraw& call, const PreparedDraw& d) override {
        draw = call.draw;
        opaque = !d.transparent;
    }
    void onFragment(const FragmentEvent& e) override {
        if (!opaque || e.fate != FragmentFate::Written) return;
        RayHit& hit = surfaces[static_cast<std::size_t>(e.y) * width + e.x];
        hit.mesh = draw;
        hit.triangle = e.triangle;
        hit.t = e.depth;
    }
};

// The eye-space corners of a surface's triangle, in double as the reference has them (where a user
// shader's vertex part puts them).
std::array<dvec3, 3> eyeCorners(const PreparedScene& prepared, const RayHit& surface) {
    const PreparedDraw& d = prepared.draws[surface.mesh];
    std::array<dvec3, 3> corners;
    for (int k = 0; k < 3; ++k)
        corners[k] = eyePosition(prepared, d, d.indices[3 * std::size_t(surface.triangle) + k]);
    return corners;
}

// Where the ray through `window` meets the plane of `surface`'s triangle: the barycentric weights of its
// corners (not clamped: a point outside the triangle gets a negative one) and the point, in eye space,
// double. Nothing for a ray along the plane.
struct PlanePoint {
    dvec3 weights;
    dvec3 point;
};
std::optional<PlanePoint> planePointAt(const PreparedScene& prepared, const RayHit& surface, dvec2 window) {
    const std::array<dvec3, 3> c = eyeCorners(prepared, surface);
    const glm::dmat4& clipFromView = prepared.camera.clipFromViewExact;
    const dvec4 onNear =
        glm::inverse(clipFromView) * dvec4(2.0 * window.x / prepared.scene.width - 1.0,
                                           1.0 - 2.0 * window.y / prepared.scene.height, -1.0, 1.0);
    const dvec3 direction = dvec3(onNear) / onNear.w;
    const dvec3 normal = glm::cross(c[1] - c[0], c[2] - c[0]);
    const double along = glm::dot(normal, direction);
    const double area2 = glm::dot(normal, normal);
    if (!(std::abs(along) > 0.0) || !(area2 > 0.0)) return std::nullopt;
    const dvec3 point = (glm::dot(normal, c[0]) / along) * direction;
    // Each corner's weight: the area of the sub-triangle opposite it over the whole (signed).
    const dvec3 weights(glm::dot(glm::cross(c[1] - point, c[2] - point), normal) / area2,
                        glm::dot(glm::cross(c[2] - point, c[0] - point), normal) / area2,
                        glm::dot(glm::cross(c[0] - point, c[1] - point), normal) / area2);
    return PlanePoint{weights, point};
}

double distanceToSegment(dvec2 p, dvec2 a, dvec2 b) {
    const dvec2 ab = b - a;
    const double length2 = glm::dot(ab, ab);
    const double t = length2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / length2, 0.0, 1.0) : 0.0;
    return glm::length(p - (a + t * ab));
}

// Pixels are compared by the 8-bit codes the image file stores: the signed difference of the channel
// (R, G or B) that differs most, b − a.
int codeDifference(const vec4& a, const vec4& b, ColorEncoding encoding) {
    int largest = 0;
    for (int c = 0; c < 3; ++c) {
        const int d = int(encodeChannel(b[c], encoding)) - int(encodeChannel(a[c], encoding));
        if (std::abs(d) > std::abs(largest)) largest = d;
    }
    return largest;
}

// In the light's shadow: darker than with no shadows by more than 1/255 in some channel of the output
// (where the light adds less than that, at grazing angles, its shadow cannot be seen).
bool darker(const vec4& shadowed, const vec4& unshadowed, ColorEncoding encoding) {
    return codeDifference(unshadowed, shadowed, encoding) < -1;
}

LinearImage rasterize(const PreparedScene& prepared, DrawContext& context) {
    Framebuffer target(prepared.scene.width, prepared.scene.height);
    FrameMemory memory;
    renderFrame(prepared, target, context, memory);
    return toImage(target);
}

LinearImage trace(const PreparedScene& prepared, DrawContext& context,
                  std::vector<RayHit>* surfaces = nullptr) {
    ReferenceOptions options;
    options.samples = 1;  // the pixel centre, where the rasterizer samples
    options.nearestSurfaces = surfaces;
    return renderReference(prepared, options, context.pool);
}

void setShadowMethods(PreparedScene& prepared, const std::array<ShadowMethod, kMaxLights>& methods) {
    prepared.shadowMethods = methods;
    prepareShadows(prepared);
}

std::string percentOf(double fraction, int decimals = 3) {
    char text[32];
    std::snprintf(text, sizeof text, "%.*f%%", decimals, 100.0 * fraction);
    return text;
}

std::string surfaceName(const RayHit& s) {
    if (!s.hit()) return "background";
    std::string name = "draw ";
    name += std::to_string(s.mesh);
    name += " triangle ";
    name += std::to_string(s.triangle);
    return name;
}

}  // namespace

PreparedScene prepareForReference(Scene scene) {
    scene.pipeline.interpolation = Interpolation::PerspectiveCorrect;
    scene.transparency.mode = TransparencyMode::Exact;
    PreparedScene prepared = prepareScene(scene);
    for (PreparedDraw& d : prepared.draws) {
        // The reference shades every hit per pixel with the draw's own vertices (a flat draw's are
        // unwelded with face normals, so per pixel it stays flat), pow, exp and normalisation exact, Fresnel
        // exact.
        d.frequency = ShadingFrequency::Phong;
        d.uniforms.precision = MathPrecision::Exact;
        d.uniforms.normalization = Normalization::Exact;
        d.uniforms.brdf.fresnel = FresnelModel::Exact;
    }
    std::array<ShadowMethod, kMaxLights> methods = prepared.shadowMethods;
    for (ShadowMethod& m : methods)
        if (m == ShadowMethod::Map) m = ShadowMethod::Ray;  // the reference casts rays for every light
    setShadowMethods(prepared, methods);
    return prepared;
}

LinearImage rasterizeSurfaces(const PreparedScene& prepared, DrawContext& context,
                              std::vector<RayHit>& surfaces) {
    const int width = prepared.scene.width, height = prepared.scene.height;
    surfaces.assign(static_cast<std::size_t>(width) * height, RayHit{});
    Framebuffer target(width, height);
    FrameMemory memory;
    SurfaceRecorder recorder(surfaces, width);
    renderFrameWatched(prepared, target, context, memory, recorder);
    return toImage(target);
}

double distanceToEdge(const PreparedScene& prepared, const RayHit& surface, dvec2 window) {
    if (!surface.hit()) return std::numeric_limits<double>::infinity();
    const glm::dmat4& clipFromView = prepared.camera.clipFromViewExact;
    // The triangle in clip space, clipped to the near (z ≥ −w) and far (z ≤ w) planes as both renderers
    // limit it (Sutherland–Hodgman); the cut is an edge of what is drawn.
    std::vector<dvec4> polygon;
    for (const dvec3& p : eyeCorners(prepared, surface))
        polygon.push_back(clipFromView * dvec4(p, 1.0));
    for (const double side : {1.0, -1.0}) {
        const auto inside = [side](const dvec4& c) { return c.w + side * c.z; };
        std::vector<dvec4> clipped;
        for (std::size_t i = 0; i < polygon.size(); ++i) {
            const dvec4& a = polygon[i];
            const dvec4& b = polygon[(i + 1) % polygon.size()];
            const double da = inside(a), db = inside(b);
            if (da >= 0) clipped.push_back(a);
            if ((da >= 0) != (db >= 0)) clipped.push_back(a + (da / (da - db)) * (b - a));
        }
        polygon = std::move(clipped);
    }
    if (polygon.empty()) return std::numeric_limits<double>::infinity();
    // The viewport transform (pipeline/viewport.h), window y down, without snapping.
    const double width = prepared.scene.width, height = prepared.scene.height;
    std::vector<dvec2> corners;
    for (const dvec4& c : polygon)
        corners.push_back({(c.x / c.w + 1.0) * 0.5 * width, (1.0 - c.y / c.w) * 0.5 * height});
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < corners.size(); ++i)
        nearest = std::min(nearest, distanceToSegment(window, corners[i], corners[(i + 1) % corners.size()]));
    return nearest;
}

double windowDepthAt(const PreparedScene& prepared, const RayHit& surface, dvec2 window) {
    if (!surface.hit()) return std::numeric_limits<double>::quiet_NaN();
    // The ray from the eye through the window point, as the reference casts it, met with the plane.
    const std::optional<PlanePoint> at = planePointAt(prepared, surface, window);
    if (!at) return std::numeric_limits<double>::quiet_NaN();
    const dvec4 clip = prepared.camera.clipFromViewExact * dvec4(at->point, 1.0);
    return (clip.z / clip.w + 1.0) * 0.5;
}

bool shareEdge(const PreparedScene& prepared, const RayHit& a, const RayHit& b) {
    if (!a.hit() || !b.hit()) return false;
    const std::array<dvec3, 3> ca = eyeCorners(prepared, a), cb = eyeCorners(prepared, b);
    int common = 0;
    for (const dvec3& p : ca)
        common += std::find(cb.begin(), cb.end(), p) != cb.end();
    return common >= 2;
}

SurfaceDisagreement classifyDisagreement(const PreparedScene& prepared, int x, int y,
                                         const RayHit& rasterized, const RayHit& traced) {
    SurfaceDisagreement d;
    d.x = x;
    d.y = y;
    d.rasterized = rasterized;
    d.traced = traced;
    const dvec2 centre(x + 0.5, y + 0.5);
    d.edgeDistance =
        std::min(distanceToEdge(prepared, rasterized, centre), distanceToEdge(prepared, traced, centre));
    d.sharedEdge = shareEdge(prepared, rasterized, traced);
    d.depthDifference = std::numeric_limits<double>::infinity();
    if (rasterized.hit() && traced.hit()) {
        const auto depth = [&](const RayHit& s, double dx, double dy) {
            return windowDepthAt(prepared, s, centre + dvec2(dx, dy));
        };
        const auto share = [&](const RayHit& s) {
            const double z = depth(s, 0, 0);
            const double slopes = std::abs(depth(s, 1, 0) - z) + std::abs(depth(s, 0, 1) - z);
            return slopes / 512.0 + 0x1.0p-22;
        };
        d.depthDifference = std::abs(depth(rasterized, 0, 0) - depth(traced, 0, 0));
        d.depthTolerance = 2.0 * (share(rasterized) + share(traced));
        if (!std::isfinite(d.depthDifference)) d.depthDifference = std::numeric_limits<double>::infinity();
    }
    return d;
}

SurfaceAgreement compareSurfaces(const PreparedScene& prepared, const std::vector<RayHit>& rasterized,
                                 const std::vector<RayHit>& traced) {
    const int width = prepared.scene.width, height = prepared.scene.height;
    SurfaceAgreement result;
    result.pixels = static_cast<std::size_t>(width) * height;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * width + x;
            const RayHit &r = rasterized[i], &t = traced[i];
            if (!r.hit() && !t.hit()) {
                ++result.bothBackground;
                continue;
            }
            ++result.covered;
            if (r.mesh == t.mesh && r.triangle == t.triangle) {
                ++result.same;
                continue;
            }
            const SurfaceDisagreement d = classifyDisagreement(prepared, x, y, r, t);
            if (d.atEdge()) {
                ++result.atEdge;
                result.onSharedEdge += d.sharedEdge;
                result.largestEdgeDistance = std::max(result.largestEdgeDistance, d.edgeDistance);
            } else if (d.atEqualDepth()) {
                ++result.atEqualDepth;
            } else {
                ++result.elsewhere;
                if (result.firstElsewhere.size() < SurfaceAgreement::kListed)
                    result.firstElsewhere.push_back(d);
            }
        }
    return result;
}

double normalDotViewAt(const PreparedScene& prepared, const RayHit& surface, dvec2 window) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (!surface.hit()) return nan;
    const PreparedDraw& d = prepared.draws[surface.mesh];
    if (d.userShader.module) return nan;  // its vertex part makes what it likes of the normals
    const std::optional<PlanePoint> at = planePointAt(prepared, surface, window);
    if (!at) return nan;
    // The normal as the reference interpolates it: each corner's through the inverse transpose.
    const glm::dmat3 normalFromObject = glm::transpose(glm::inverse(glm::dmat3(d.viewFromObjectExact)));
    dvec3 normal(0.0);
    for (int k = 0; k < 3; ++k)
        normal +=
            at->weights[k] *
            (normalFromObject * dvec3(d.vertices[d.indices[3 * std::size_t(surface.triangle) + k]].normal));
    const double lengths = glm::length(normal) * glm::length(at->point);
    return lengths > 0.0 ? glm::dot(normal, -at->point) / lengths : nan;
}

double texelsPerPixelAt(const PreparedScene& prepared, const RayHit& surface, dvec2 window) {
    if (!surface.hit()) return 0.0;
    const PreparedDraw& d = prepared.draws[surface.mesh];
    const Texture* map = d.uniforms.diffuseMap ? d.uniforms.diffuseMap : d.uniforms.emissionMap;
    if (!map || d.userShader.module) return 0.0;
    const auto uvAt = [&](dvec2 w) -> std::optional<dvec2> {
        const std::optional<PlanePoint> at = planePointAt(prepared, surface, w);
        if (!at) return std::nullopt;
        dvec2 uv(0.0);
        for (int k = 0; k < 3; ++k)
            uv += at->weights[k] * dvec2(d.vertices[d.indices[3 * std::size_t(surface.triangle) + k]].uv);
        return uv;
    };
    const std::optional<dvec2> here = uvAt(window), right = uvAt(window + dvec2(1, 0)),
                               below = uvAt(window + dvec2(0, 1));
    if (!here || !right || !below) return 0.0;
    const dvec2 size(map->width, map->height);
    return std::max(glm::length((*right - *here) * size), glm::length((*below - *here) * size));
}

std::vector<DifferenceSpot> findDifferenceSpots(const PreparedScene& prepared, const std::vector<int>& codes,
                                                const std::vector<RayHit>& rasterized,
                                                const std::vector<RayHit>& traced,
                                                const std::vector<ShadowMasks>& shadowMasks) {
    const int width = prepared.scene.width, height = prepared.scene.height;
    std::vector<std::size_t> differing;  // more than 1/255 apart: what the colour bar counts
    for (std::size_t i = 0; i < codes.size(); ++i)
        if (std::abs(codes[i]) > 1) differing.push_back(i);
    std::stable_sort(differing.begin(), differing.end(),
                     [&](std::size_t a, std::size_t b) { return std::abs(codes[a]) > std::abs(codes[b]); });
    const auto close = [](int ax, int ay, int bx, int by) {
        return std::abs(ax - bx) < kSpotRadius && std::abs(ay - by) < kSpotRadius;
    };
    std::vector<DifferenceSpot> spots;
    for (const std::size_t i : differing) {
        if (spots.size() == kSpots) break;
        const int x = int(i % std::size_t(width)), y = int(i / std::size_t(width));
        if (std::any_of(spots.begin(), spots.end(),
                        [&](const DifferenceSpot& s) { return close(s.x, s.y, x, y); }))
            continue;
        DifferenceSpot spot;
        spot.x = x;
        spot.y = y;
        spot.codes = codes[i];
        spot.rasterized = rasterized[i];
        spot.traced = traced[i];
        const dvec2 centre(x + 0.5, y + 0.5);
        spot.normalDotView = normalDotViewAt(prepared, traced[i], centre);
        spot.texelsPerPixel = texelsPerPixelAt(prepared, traced[i], centre);
        spot.edgeDistance = distanceToEdge(prepared, traced[i], centre);
        const bool sameSurface = rasterized[i].mesh == traced[i].mesh &&
                                 rasterized[i].triangle == traced[i].triangle &&
                                 rasterized[i].hit() == traced[i].hit();
        const auto shadowDiffers =
            std::find_if(shadowMasks.begin(), shadowMasks.end(),
                         [&](const ShadowMasks& m) { return m.rasterized[i] != m.traced[i]; });
        if (!sameSurface) {
            spot.reason = DifferenceReason::OtherSurface;
            spot.surfaces = classifyDisagreement(prepared, x, y, rasterized[i], traced[i]);
        } else if (shadowDiffers != shadowMasks.end()) {
            spot.reason = DifferenceReason::ShadowOneOnly;
            spot.light = shadowDiffers->light;
            spot.shadowedInReference = shadowDiffers->traced[i];
        } else if (std::abs(spot.normalDotView) < kEdgeOnNdotV) {
            spot.reason = DifferenceReason::EdgeOn;
        } else if (spot.texelsPerPixel > kMinifiedTexels) {
            spot.reason = DifferenceReason::TextureMinified;
        } else if (spot.edgeDistance < kNearEdgePixels) {
            spot.reason = DifferenceReason::NearEdge;
        }
        spots.push_back(spot);
    }
    for (DifferenceSpot& spot : spots)
        for (int y = std::max(0, spot.y - kSpotRadius + 1); y < std::min(height, spot.y + kSpotRadius); ++y)
            for (int x = std::max(0, spot.x - kSpotRadius + 1); x < std::min(width, spot.x + kSpotRadius);
                 ++x)
                spot.nearby += (x != spot.x || y != spot.y) &&
                               std::abs(codes[static_cast<std::size_t>(y) * width + x]) > 1;
    return spots;
}

std::string describeReason(const DifferenceSpot& spot) {
    char text[160];
    switch (spot.reason) {
        case DifferenceReason::OtherSurface: {
            const SurfaceDisagreement& d = spot.surfaces;
            std::string where;
            if (d.atEdge()) {
                std::snprintf(text, sizeof text, "at an edge (the centre %.4f px from it)", d.edgeDistance);
                where = text;
            } else if (d.atEqualDepth()) {
                where = "at equal depth (coincident or crossing surfaces)";
            } else {
                where = "neither at an edge nor at equal depth";
            }
            return "another surface in each: rasterizer " + surfaceName(d.rasterized) + ", reference " +
                   surfaceName(d.traced) + ", " + where;
        }
        case DifferenceReason::ShadowOneOnly:
            std::snprintf(text, sizeof text, "in the shadow of light %d in the %s only", spot.light + 1,
                          spot.shadowedInReference ? "reference" : "rasterizer");
            return text;
        case DifferenceReason::EdgeOn:
            std::snprintf(text, sizeof text,
                          "the surface is seen edge-on (N·V = %+.4f): the lighting changes fastest there",
                          spot.normalDotView);
            return text;
        case DifferenceReason::TextureMinified:
            std::snprintf(text, sizeof text,
                          "texture minified, %.1f texels per pixel: a fraction of a pixel reads other texels",
                          spot.texelsPerPixel);
            return text;
        case DifferenceReason::NearEdge:
            std::snprintf(text, sizeof text,
                          "near the triangle's edge (%.2f px): interpolated from corners snapped to 1/256 px",
                          spot.edgeDistance);
            return text;
        case DifferenceReason::Unexplained:
            break;
    }
    return "unexplained";
}

ReferenceComparison compareWithReference(const Scene& scene, const ReferenceCompareOptions& options) {
    PreparedScene prepared = prepareForReference(scene);
    DrawContext context(options.threads);
    const int width = prepared.scene.width, height = prepared.scene.height;
    const std::size_t pixels = static_cast<std::size_t>(width) * height;

    ReferenceComparison result;
    result.warnings = prepared.warnings;
    result.width = width;
    result.height = height;
    result.encoding = prepared.encoding;
    std::vector<RayHit> rasterized, traced;
    result.rasterized = rasterizeSurfaces(prepared, context, rasterized);
    result.reference = trace(prepared, context, &traced);
    result.surfaces = compareSurfaces(prepared, rasterized, traced);

    const auto sameSurface = [&](std::size_t i) {
        return rasterized[i].hit() && rasterized[i].mesh == traced[i].mesh &&
               rasterized[i].triangle == traced[i].triangle;
    };
    std::vector<bool> colorDiffers(pixels, false);
    std::vector<int> pixelCodes(pixels);  // reference − rasterizer, every pixel (for the spots)
    for (std::size_t i = 0; i < pixels; ++i) {
        const vec4 &a = result.rasterized.pixels[i], &b = result.reference.pixels[i];
        pixelCodes[i] = codeDifference(a, b, result.encoding);
        if (!sameSurface(i)) continue;
        const int codes = std::abs(pixelCodes[i]);
        ColorAgreement& c = result.color;
        ++c.compared;
        c.within1 += codes <= 1;
        colorDiffers[i] = codes > 1;
        c.largestCodeDifference = std::max(c.largestCodeDifference, codes);
        for (int channel = 0; channel < 3; ++channel)
            c.largestLinearDifference =
                std::max(c.largestLinearDifference, double(std::abs(a[channel] - b[channel])));
    }

    // Shadows: per casting light, where each renderer has the point in its shadow.
    const std::array<ShadowMethod, kMaxLights> casting = prepared.shadowMethods;
    std::array<ShadowMethod, kMaxLights> none{};
    none.fill(ShadowMethod::None);
    std::vector<int> lights;
    for (std::size_t l = 0; l < kMaxLights; ++l)
        if (casting[l] != ShadowMethod::None) lights.push_back(int(l));
    ShadowAgreement& s = result.shadows;
    s.lights = int(lights.size());
    std::vector<ShadowMasks> masks;  // per casting light
    if (!lights.empty()) {
        setShadowMethods(prepared, none);
        const LinearImage rasterLit = rasterize(prepared, context), traceLit = trace(prepared, context);
        // masks[k].rasterized[i], .traced[i]: light lights[k] shadows pixel i.
        for (const int light : lights) {
            std::array<ShadowMethod, kMaxLights> only = none;
            only[light] = ShadowMethod::Ray;
            setShadowMethods(prepared, only);
            const LinearImage r = rasterize(prepared, context), t = trace(prepared, context);
            std::vector<bool> rm(pixels), tm(pixels);
            for (std::size_t i = 0; i < pixels; ++i) {
                rm[i] = darker(r.pixels[i], rasterLit.pixels[i], result.encoding);
                tm[i] = darker(t.pixels[i], traceLit.pixels[i], result.encoding);
            }
            masks.push_back({light, std::move(rm), std::move(tm)});
        }
        setShadowMethods(prepared, casting);
        const auto atBoundary = [&](int x, int y) {
            const std::size_t i = static_cast<std::size_t>(y) * width + x;
            for (const ShadowMasks& m : masks)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int nx = x + dx, ny = y + dy;
                        if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
                        if (m.traced[static_cast<std::size_t>(ny) * width + nx] != m.traced[i]) return true;
                    }
            return false;
        };
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const std::size_t i = static_cast<std::size_t>(y) * width + x;
                if (!sameSurface(i)) continue;
                bool shadowed = false;
                std::size_t maskDifferences = 0;
                for (std::size_t k = 0; k < lights.size(); ++k) {
                    shadowed = shadowed || masks[k].traced[i];
                    // Only where it shows: a shadow the colours do not tell apart is a rounding tie.
                    maskDifferences += colorDiffers[i] && masks[k].rasterized[i] != masks[k].traced[i];
                }
                s.inShadow += shadowed;
                if (!maskDifferences && !colorDiffers[i]) continue;
                const bool boundary = atBoundary(x, y);
                s.maskDifferences += maskDifferences;
                if (boundary) s.maskAtBoundary += maskDifferences;
                if (colorDiffers[i]) {
                    ++s.colorDiffering;
                    s.colorAtBoundary += boundary;
                    if (!boundary && s.firstColorElsewhere.size() < SurfaceAgreement::kListed)
                        s.firstColorElsewhere.push_back({x, y});
                }
            }
    }

    result.spots = findDifferenceSpots(prepared, pixelCodes, rasterized, traced, masks);

    // Shadow maps against ray-cast shadows, both in the rasterizer.
    if (options.shadowMapTable && !lights.empty()) {
        std::array<ShadowMethod, kMaxLights> maps = casting;
        for (const int light : lights)
            maps[light] = ShadowMethod::Map;
        const ShadowMapOptions defaults;
        struct Bias {
            const char* name;
            float constant, slope;
        };
        // The default bias, none, constant only, and four times the default (a large one).
        const Bias biases[] = {{"none", 0.0f, 0.0f},
                               {"constant", defaults.constantBias, 0.0f},
                               {"default", defaults.constantBias, defaults.slopeBias},
                               {"large", 4.0f * defaults.constantBias, 4.0f * defaults.slopeBias}};
        std::size_t surfacePixels = 0;
        for (const RayHit& h : rasterized)
            surfacePixels += h.hit();
        for (const int size : options.shadowMapSizes)
            for (const Bias& bias : biases)
                for (const int taps : {1, 4, 16}) {
                    prepared.shadowMapOptions = {size, bias.constant, bias.slope, taps};
                    setShadowMethods(prepared, maps);
                    const LinearImage image = rasterize(prepared, context);
                    ShadowMapRow row{size, bias.name, bias.constant, bias.slope, taps, 0.0, 0, 0};
                    double sum = 0;
                    for (std::size_t i = 0; i < pixels; ++i) {
                        const vec4 &ray = result.rasterized.pixels[i], &map = image.pixels[i];
                        if (rasterized[i].hit())
                            sum += (std::abs(map.r - ray.r) + std::abs(map.g - ray.g) +
                                    std::abs(map.b - ray.b)) /
                                   3.0;
                        const int codes = codeDifference(ray, map, result.encoding);
                        row.wronglyLit += codes > 2;
                        row.wronglyShadowed += codes < -2;
                    }
                    row.meanError = surfacePixels ? sum / double(surfacePixels) : 0.0;
                    result.shadowMaps.push_back(row);
                }
        prepared.shadowMapOptions = prepared.scene.shadowMap;
        setShadowMethods(prepared, casting);
    }
    return result;
}

std::string describe(const ReferenceComparison& c) {
    std::ostringstream out;
    const SurfaceAgreement& s = c.surfaces;
    out << "  " << c.width << "×" << c.height
        << ", one sample per pixel at its centre in both. The rasterizer draws with the reference's "
           "formulas\n"
           "  here: per-pixel (Phong) shading, perspective-correct interpolation, exact pow/exp and "
           "Fresnel,\n"
           "  exact transparency (fragment lists), ray-cast shadows for every light that casts shadows.\n";
    out << "Surfaces (which triangle each pixel shows):\n";
    out << "  pixels showing a surface in either:  " << s.covered << " of " << s.pixels << "\n";
    out << "  the same triangle in both:           " << s.same << " ("
        << percentOf(s.covered ? double(s.same) / s.covered : 1.0) << " of those)\n";
    out << "  different, at an edge:               " << s.atEdge << " (" << percentOf(s.edgeShare())
        << "; bar < " << percentOf(ReferenceComparison::kMaxEdgeShare, 0)
        << ")  the centre within 1/64 px of an edge,\n"
        << "                                       where either side may cover it; " << s.onSharedEdge
        << " of them between two triangles sharing that edge\n";
    if (s.atEdge) {
        char text[64];
        std::snprintf(text, sizeof text, "%.5f", s.largestEdgeDistance);
        out << "  farthest of those from its edge:     " << text << " px (the tolerance is 0.01563 px)\n";
    }
    out << "  different, at equal depth:           " << s.atEqualDepth
        << "  two surfaces at the same depth there (coincident or crossing):\n"
           "                                       the depth test may keep either\n";
    out << "  different, elsewhere:                " << s.elsewhere << "  (must be 0: a real disagreement)\n";
    for (const SurfaceDisagreement& d : s.firstElsewhere) {
        char text[64];
        std::snprintf(text, sizeof text, "%.3f px from an edge, depths %.3g apart", d.edgeDistance,
                      d.depthDifference);
        out << "    pixel " << d.x << "," << d.y << ": rasterizer " << surfaceName(d.rasterized)
            << ", reference " << surfaceName(d.traced) << ", " << text << "\n";
    }
    const ColorAgreement& col = c.color;
    out << "Colour (the pixels showing the same triangle, float shading against double):\n";
    out << "  within 1/255 on every channel:       " << col.within1 << " of " << col.compared << " ("
        << percentOf(col.within1Share()) << "; bar ≥ " << percentOf(ReferenceComparison::kMinColorWithin1, 0)
        << ")\n";
    char linear[64];
    std::snprintf(linear, sizeof linear, "%.3g", col.largestLinearDifference);
    out << "  largest difference:                  " << col.largestCodeDifference << "/255 in the image, "
        << linear << " in linear values\n";
    const ShadowAgreement& sh = c.shadows;
    if (sh.lights == 0) {
        out << "Shadows: no light casts shadows (try --shadows ray).\n";
    } else {
        out << "Ray-cast shadows (" << sh.lights << (sh.lights == 1 ? " light" : " lights")
            << ";\n  a pixel is in a light's shadow where it is darker than with no shadows, by more than "
               "1/255):\n";
        out << "  same-triangle pixels in a shadow:    " << sh.inShadow << " (in the reference)\n";
        out << "  shadowed in one, lit in the other:   " << sh.maskDifferences << " (pixel and light), "
            << sh.maskAtBoundary
            << " at a shadow boundary (within 1 px of the reference's edge of a shadow), "
            << sh.maskElsewhere() << " elsewhere (must be 0)\n";
        out << "  colours more than 1/255 apart:       " << sh.colorDiffering << ", " << sh.colorAtBoundary
            << " at a shadow boundary, " << sh.colorElsewhere() << " elsewhere\n";
        for (const glm::ivec2& p : sh.firstColorElsewhere) {
            const std::size_t i = static_cast<std::size_t>(p.y) * c.width + p.x;
            char text[160];
            std::snprintf(text, sizeof text,
                          "    pixel %d,%d: rasterizer %.4f %.4f %.4f, reference %.4f %.4f %.4f (linear)\n",
                          p.x, p.y, double(c.rasterized.pixels[i].r), double(c.rasterized.pixels[i].g),
                          double(c.rasterized.pixels[i].b), double(c.reference.pixels[i].r),
                          double(c.reference.pixels[i].g), double(c.reference.pixels[i].b));
            out << text;
        }
    }
    if (!c.shadowMaps.empty()) {
        out << "Shadow maps against ray-cast shadows (both in the rasterizer; error: mean |Δ| in linear "
               "values\n"
               "over the pixels showing a surface; wrongly lit / shadowed: brighter / darker by more than "
               "2/255):\n";
        out << "   size  bias      constant  slope  filter  mean error  wrongly lit  wrongly shadowed\n";
        for (const ShadowMapRow& r : c.shadowMaps) {
            char line[160];
            std::snprintf(line, sizeof line, "  %5d  %-8s  %8g  %5g  %6d  %10.6f  %11zu  %16zu\n", r.size,
                          r.bias.c_str(), double(r.constantBias), double(r.slopeBias), r.filterTaps,
                          r.meanError, r.wronglyLit, r.wronglyShadowed);
            out << line;
        }
    }
    if (!c.spots.empty()) {
        out << "Largest differences (8-bit codes, reference − rasterizer; spots at least " << kSpotRadius
            << " px apart;\n  \"nearby\": other pixels more than 1/255 apart within " << kSpotRadius - 1
            << " px):\n";
        for (const DifferenceSpot& spot : c.spots) {
            char head[96];
            std::snprintf(head, sizeof head, "  pixel %d,%d: %+d/255, %s, %zu nearby\n", spot.x, spot.y,
                          spot.codes, surfaceName(spot.traced.hit() ? spot.traced : spot.rasterized).c_str(),
                          spot.nearby);
            out << head << "    " << describeReason(spot) << "\n";
        }
    }
    out << (c.agrees() ? "Agreement: yes\n" : "Agreement: NO\n");
    return out.str();
}

std::string shadowMapCsv(const ReferenceComparison& c) {
    std::string csv = "size,bias,constant_bias,slope_bias,filter,mean_error,wrongly_lit,wrongly_shadowed\n";
    for (const ShadowMapRow& r : c.shadowMaps) {
        char line[160];
        std::snprintf(line, sizeof line, "%d,%s,%g,%g,%d,%.8f,%zu,%zu\n", r.size, r.bias.c_str(),
                      double(r.constantBias), double(r.slopeBias), r.filterTaps, r.meanError, r.wronglyLit,
                      r.wronglyShadowed);
        csv += line;
    }
    return csv;
}

}  // namespace facet
