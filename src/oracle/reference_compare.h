// `facet compare --reference`: the rasterizer against the exact reference renderer (src/reference), both
// at one sample per pixel, through the pixel centre. It measures what the rasterizer promises:
//   - the same surface at every pixel, except where the centre lies within a hair of a triangle's edge
//     (where float snapping and a float ray test may each pick the other side), or where two surfaces
//     lie at the same depth (a face written twice, surfaces crossing), where the depth test may keep
//     either;
//   - the same colour within 1/255 there, the shading being the same formulas in float and in double;
//   - ray-cast shadows equal to the reference's except at the shadow boundaries;
//   - and how far shadow maps (size, bias, filter) are from ray-cast shadows.
// For an apples-to-apples comparison the rasterizer draws with the reference's formulas: per-pixel
// (Phong) shading, perspective-correct interpolation, exact pow/exp, exact Fresnel, exact transparency
// (fragment lists), and ray-cast shadows for every light that casts shadows.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "raycast/ray_scene.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace facet {

// A pixel centre this close to a triangle's edge, in pixels, may be covered by either side in one
// renderer and the other side in the other. The rasterizer snaps window vertices to 1/256 px, which
// moves an edge by at most √2/512 ≈ 0.0028 px; float vertex transforms and Embree's float ray test add
// about 1e-7 of the coordinates (≤ 0.001 px at 8192 px). 1/64 px is four times their sum, and small
// enough that only about 3% of the pixels along an edge fall within it (2/64 of a pixel's width).
inline constexpr double kEdgeTolerancePixels = 1.0 / 64.0;

// The scene prepared as the comparison draws it in the rasterizer: every draw shaded per pixel with
// exact maths and exact Fresnel, perspective-correct interpolation, exact transparency, and every light
// that casts shadows casting them by ray (as the reference always does).
PreparedScene prepareForReference(Scene scene);

// Draws the frame and records, per pixel (row by row), the surface of the last opaque fragment written
// (RayHit::mesh = draw, ::triangle = the draw's triangle; background: RayHit{}). Returns the image.
LinearImage rasterizeSurfaces(const PreparedScene& prepared, DrawContext& context,
                              std::vector<RayHit>& surfaces);

// The window-space distance (pixels, y down) from `window` to the nearest edge of `surface`'s triangle
// as the camera projects it, clipped to the near and far planes; infinity for the background.
double distanceToEdge(const PreparedScene& prepared, const RayHit& surface, glm::dvec2 window);

// The window depth (pipeline/viewport.h: (z_ndc + 1)/2) of `surface`'s triangle's plane where the ray
// through `window` meets it, in double; NaN for the background or a ray along the plane.
double windowDepthAt(const PreparedScene& prepared, const RayHit& surface, glm::dvec2 window);

// Whether two triangles have an edge in common (both of its corners at the same eye-space points).
bool shareEdge(const PreparedScene& prepared, const RayHit& a, const RayHit& b);

// A pixel where the rasterizer and the reference show different surfaces.
struct SurfaceDisagreement {
    int x = 0, y = 0;
    RayHit rasterized, traced;
    double edgeDistance = 0;  // of the pixel centre to the nearer edge of either triangle, pixels
    bool sharedEdge = false;  // the two triangles have an edge in common
    // Both show a surface and they lie at the same depth there (coincident faces, or two surfaces
    // crossing): the depth test may keep either. |Δz_w| against what the renderers' rounding allows:
    // snapping moves a plane's window depth at a point by up to (|∂z/∂x| + |∂z/∂y|)/512, and the float
    // depth buffer's rounding and interpolation by a few units of 2^-24; the tolerance is twice the
    // sum of both planes' shares (2^-22 each for rounding).
    double depthDifference = 0, depthTolerance = 0;
    bool atEdge() const { return edgeDistance < kEdgeTolerancePixels; }
    bool atEqualDepth() const { return !atEdge() && depthDifference <= depthTolerance; }
};

// Classifies one pixel where `rasterized` and `traced` differ.
SurfaceDisagreement classifyDisagreement(const PreparedScene& prepared, int x, int y,
                                         const RayHit& rasterized, const RayHit& traced);

struct SurfaceAgreement {
    std::size_t pixels = 0;          // width × height
    std::size_t covered = 0;         // pixels where either shows a surface
    std::size_t same = 0;            // both show the same triangle
    std::size_t bothBackground = 0;  // neither shows a surface
    std::size_t atEdge = 0;          // disagreeing, the centre within kEdgeTolerancePixels of an edge
    std::size_t onSharedEdge = 0;    // of those, between two triangles sharing an edge
    std::size_t atEqualDepth = 0;    // disagreeing, not at an edge: two surfaces at the same depth
    std::size_t elsewhere = 0;       // disagreeing anywhere else: a real error
    double largestEdgeDistance = 0;  // over the atEdge pixels
    std::vector<SurfaceDisagreement> firstElsewhere;  // the first few, row by row
    static constexpr std::size_t kListed = 8;
    double edgeShare() const { return covered ? double(atEdge) / double(covered) : 0.0; }
};

// Compares the per-pixel surfaces of the two renderers (row by row, scene-sized).
SurfaceAgreement compareSurfaces(const PreparedScene& prepared, const std::vector<RayHit>& rasterized,
                                 const std::vector<RayHit>& traced);

// The colours of the pixels where both show the same triangle, in the 8-bit output (codes) and linear.
struct ColorAgreement {
    std::size_t compared = 0;  // pixels showing the same triangle
    std::size_t within1 = 0;   // every channel's code within 1
    int largestCodeDifference = 0;
    double largestLinearDifference = 0;
    double within1Share() const { return compared ? double(within1) / double(compared) : 1.0; }
};

// Ray-cast shadows of the rasterizer against the reference's, on the pixels showing the same triangle.
// A pixel is in a light's shadow in one renderer when it is darker there with only that light casting
// shadows than with none, by more than 1/255 in the output (a shadow that cannot be seen is no shadow); it is
// at a shadow boundary when, within 1 pixel (its 3×3 neighbourhood), the reference has it in shadow of some
// light at one pixel and lit at another.
struct ShadowAgreement {
    int lights = 0;            // lights casting shadows (0: nothing compared)
    std::size_t inShadow = 0;  // same-surface pixels the reference shadows from some light
    // Pixel and light where one renderer shadows and the other not, on pixels whose colours differ by
    // more than 1/255 (elsewhere the two agree in what the image shows).
    std::size_t maskDifferences = 0;
    std::size_t maskAtBoundary = 0;               // of those, at a shadow boundary
    std::size_t colorDiffering = 0;               // same-surface pixels more than 1/255 apart
    std::size_t colorAtBoundary = 0;              // of those, at a shadow boundary
    std::vector<glm::ivec2> firstColorElsewhere;  // the first few of the others, row by row
    std::size_t maskElsewhere() const { return maskDifferences - maskAtBoundary; }
    std::size_t colorElsewhere() const { return colorDiffering - colorAtBoundary; }
};

// One setting of the shadow maps against ray-cast shadows, both drawn by the rasterizer.
struct ShadowMapRow {
    int size = 0;
    std::string bias;  // "none", "constant", "default", "large"
    float constantBias = 0, slopeBias = 0;
    int filterTaps = 1;
    double meanError = 0;             // mean |Δ| (linear, over R, G, B) over the pixels showing a surface
    std::size_t wronglyLit = 0;       // brighter than with ray shadows by more than 2/255 (a code step)
    std::size_t wronglyShadowed = 0;  // darker by more than 2/255
};

// Why two colours at a pixel differ, as far as the numbers at that pixel tell (the first that holds, in
// this order; docs/reference.md, "Where the largest differences lie"):
enum class DifferenceReason {
    OtherSurface,     // the renderers show different triangles there (at an edge, at equal depth, or not)
    ShadowOneOnly,    // the same triangle, in a light's ray-cast shadow in one image and lit in the other
    EdgeOn,           // the surface is seen edge-on: |N·V| < kEdgeOnNdotV at the reference's hit
    TextureMinified,  // a texture minified: more than kMinifiedTexels texels per pixel
    NearEdge,         // the centre within kNearEdgePixels of the triangle's edge
    Unexplained,      // none of these
};

// |N·V| below this (the interpolated normal at the reference's hit, unit length) is "seen edge-on": the
// lighting then changes fastest with the point and the normal, and the two-sided flip's sign
// (twoSidedFlipTurns, shaders.h) turns on rounding. 0.02 is 1.1° from grazing.
inline constexpr double kEdgeOnNdotV = 0.02;
// A texture read across more than this many texels per pixel (along the footprint's longer side) is
// minified: a shift of the sample point by a fraction of a pixel then reads other texels.
inline constexpr double kMinifiedTexels = 2.0;
// A centre this close to its own triangle's edge (pixels) may be interpolated from a snapped corner.
inline constexpr double kNearEdgePixels = 0.5;

// One of the largest colour differences, and what is at its pixel.
struct DifferenceSpot {
    int x = 0, y = 0;
    int codes = 0;  // reference − rasterizer in 8-bit codes, the channel that differs most
    RayHit rasterized, traced;
    DifferenceReason reason = DifferenceReason::Unexplained;
    SurfaceDisagreement surfaces;  // OtherSurface: how the surfaces differ
    double normalDotView = 0;      // N·V at the reference's hit (NaN: no normal, e.g. a user shader)
    double texelsPerPixel = 0;     // the diffuse or emission map's texels across one pixel (0: none)
    double edgeDistance = 0;       // of the centre to its triangle's nearest edge, pixels
    int light = -1;                // ShadowOneOnly: the light (index in the scene's list)
    bool shadowedInReference = false;
    std::size_t nearby = 0;  // other pixels more than 1/255 apart within kSpotRadius of this one
};
// The largest differences listed, at least kSpotRadius pixels apart (in x or y) so that one blob is
// one spot.
inline constexpr std::size_t kSpots = 5;
inline constexpr int kSpotRadius = 8;

// The spots: the pixels whose colours differ most (more than 1/255), largest first (ties in reading
// order), each at least kSpotRadius from those before it. `codes`: reference − rasterizer per pixel
// (codeDifference); `shadowMasks`: per casting light (its index, then per pixel rasterizer and reference
// in shadow), empty without shadows.
struct ShadowMasks {
    int light = 0;
    std::vector<bool> rasterized, traced;
};
std::vector<DifferenceSpot> findDifferenceSpots(const PreparedScene& prepared, const std::vector<int>& codes,
                                                const std::vector<RayHit>& rasterized,
                                                const std::vector<RayHit>& traced,
                                                const std::vector<ShadowMasks>& shadowMasks);

// N·V (unit vectors) of `surface`'s interpolated normal at the point the ray through `window` meets
// its triangle's plane, in double; NaN for the background or a draw without normals.
double normalDotViewAt(const PreparedScene& prepared, const RayHit& surface, glm::dvec2 window);

// Texels of the draw's diffuse (else emission) map across one pixel at `window`: the longer of the
// texture-coordinate steps to the next pixel right and down, times the map's size; 0 without a map.
double texelsPerPixelAt(const PreparedScene& prepared, const RayHit& surface, glm::dvec2 window);

// The reason in words for a person, with its number ("the surface is seen edge-on (N·V = +0.0043)").
std::string describeReason(const DifferenceSpot& spot);

struct ReferenceCompareOptions {
    std::vector<int> shadowMapSizes{256, 512, 1024, 2048, 4096};
    bool shadowMapTable = true;  // false: skip the table (it renders 12 frames per size)
    int threads = 0;             // 0: one per hardware thread
};

struct ReferenceComparison {
    int width = 0, height = 0;
    ColorEncoding encoding = kSrgbEncoding;
    LinearImage rasterized, reference;
    SurfaceAgreement surfaces;
    ColorAgreement color;
    ShadowAgreement shadows;
    std::vector<ShadowMapRow> shadowMaps;  // empty when no light casts shadows or the table was skipped
    std::vector<DifferenceSpot> spots;     // where the largest colour differences lie (findDifferenceSpots)
    std::vector<std::string> warnings;     // the scene's loading warnings (PreparedScene::warnings)

    // The bars: something drawn (two empty frames prove nothing), no disagreement away from edges, edge ones
    // under 1% of the covered pixels, 99% of the same-surface pixels within 1/255, shadows equal off
    // boundaries.
    static constexpr double kMaxEdgeShare = 0.01;
    static constexpr double kMinColorWithin1 = 0.99;
    bool agrees() const {
        return surfaces.covered > 0 && surfaces.elsewhere == 0 && surfaces.edgeShare() < kMaxEdgeShare &&
               color.within1Share() >= kMinColorWithin1 && shadows.maskElsewhere() == 0;
    }
};

// Prepares `scene` (prepareForReference), rasterizes and traces it, compares. Throws InputError for an
// unusable scene.
ReferenceComparison compareWithReference(const Scene& scene, const ReferenceCompareOptions& options = {});

// The comparison as text for a person: what was set, each figure with a line on what it means.
std::string describe(const ReferenceComparison& comparison);

// The shadow-map table as CSV (a header line, then one line per row).
std::string shadowMapCsv(const ReferenceComparison& comparison);

}  // namespace facet
