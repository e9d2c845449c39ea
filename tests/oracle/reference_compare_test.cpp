// The rasterizer against the exact reference renderer (src/oracle/reference_compare.h): on the bundled
// and the shared models, one sample per pixel in both, every pixel shows the same triangle except at
// edges, and the same colour within 1/255 almost everywhere; the edge classification itself; shadow
// maps against ray-cast shadows.
#include "oracle/reference_compare.h"

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "reference/reference.h"
#include "support/bundled_models.h"

namespace facet {
namespace {

using testing_support::kModels;
const std::filesystem::path kSharedModels = FACET_SHARED_MODELS;

Scene sceneAt(const std::filesystem::path& path, int width, int height) {
    Scene scene = loadSceneOrModel(path);
    scene.width = width;
    scene.height = height;
    return scene;
}

ReferenceComparison compareWithoutTable(const Scene& scene) {
    ReferenceCompareOptions options;
    options.shadowMapTable = false;
    return compareWithReference(scene, options);
}

// The agreement every scene must show: no disagreement away from an edge, few at edges, and at least
// `minWithin1` of the same-surface pixels within 1/255 (each scene's measured share, just under it).
void expectAgreement(const ReferenceComparison& c, double minWithin1) {
    SCOPED_TRACE(describe(c));
    EXPECT_GT(c.surfaces.covered, c.surfaces.pixels / 10);  // the scene is in view
    EXPECT_EQ(c.surfaces.elsewhere, 0u);
    EXPECT_LT(c.surfaces.edgeShare(), ReferenceComparison::kMaxEdgeShare);
    EXPECT_GE(c.color.within1Share(), minWithin1);
    EXPECT_EQ(c.shadows.maskElsewhere(), 0u);
    EXPECT_TRUE(c.agrees());
}

// Breaks caught: the observer keeping depth-failed fragments as the pixel's surface (fate not checked);
// distances measured from the pixel's left side instead of its centre, or with window y not flipped
// (edge pixels counted elsewhere); the shadow boundary taken as the pixel itself instead of its 3×3
// neighbourhood (the mask differences lie beside the reference's boundary, not on it); the colour bar:
// the rasterizer's draws left at Gouraud shading instead of per pixel, or codes counted as within 1/255
// only when equal.
TEST(ReferenceCompare, ShadowsSceneAgrees) {
    const ReferenceComparison c = compareWithoutTable(sceneAt(kModels / "shadows.json", 200, 150));
    EXPECT_EQ(c.shadows.lights, 2);
    EXPECT_GT(c.shadows.inShadow, 1000u);  // the shadows are in view
    // Measured: 99.837% (20 221 of 20 254); 32 of the 33 others at a shadow boundary, one where the
    // texture's UV lands on another texel.
    expectAgreement(c, 0.998);
}

// Transparency (exact in both) and fog: the glass cube's triangles are not the pixels' surfaces (the
// opaque surface behind them is). Breaks caught: as for the shadows scene (depth-failed fragments
// kept, distances from the pixel's side, y not flipped).
TEST(ReferenceCompare, FogAndGlassAgrees) {
    const ReferenceComparison c = compareWithoutTable(sceneAt(kModels / "fog-and-glass.json", 200, 150));
    expectAgreement(c, 0.994);  // measured: 99.484%, the rest where the glass's own edges fall
}

// The shared edge lies exactly on the pixel centres of column 10: each renderer gives those pixels to one
// of the two triangles, not necessarily the same one; the disagreement must count as an edge.
// Breaks caught: distanceToEdge measuring from the pixel's left side (x) instead of its centre (x + ½);
// shareEdge asking for three common corners instead of two.
TEST(ReferenceCompare, PixelOnASharedEdgeIsAnEdgePixel) {
    const PreparedScene prepared = prepareForReference(loadSceneOrModel(kModels / "shared-edge.json"));
    ASSERT_EQ(prepared.draws.size(), 2u);  // left, right: one triangle each
    RayHit left, right;
    left.mesh = 0;
    left.triangle = 0;
    right.mesh = 1;
    right.triangle = 0;
    const SurfaceDisagreement d = classifyDisagreement(prepared, 10, 7, left, right);
    EXPECT_TRUE(d.atEdge()) << d.edgeDistance;
    EXPECT_LT(d.edgeDistance, 1e-9);
    EXPECT_TRUE(d.sharedEdge);
    // One column over, the centre is a pixel from the shared edge: not an edge pixel.
    const SurfaceDisagreement off = classifyDisagreement(prepared, 11, 7, left, right);
    EXPECT_NEAR(off.edgeDistance, 1.0, 1e-9);
    EXPECT_FALSE(off.atEdge());
    // The whole image agrees, the column on the edge included.
    expectAgreement(compareWithoutTable(loadSceneOrModel(kModels / "shared-edge.json")), 1.0);
}

// A renderer looking from a slightly different place shows other surfaces far from any edge: the
// comparison must call that a real disagreement. Breaks caught: the edge tolerance a pixel instead of
// 1/64 (every disagreement counted as an edge one); distances from the pixel's side; y not flipped.
TEST(ReferenceCompare, MovedCameraDisagreesElsewhere) {
    const Scene scene = sceneAt(kModels / "shadows.json", 200, 150);
    Scene moved = scene;
    moved.camera.eye = scene.camera.eye.value_or(glm::vec3(0.0f)) + glm::vec3(0.05f, 0.0f, 0.0f);
    ASSERT_TRUE(scene.camera.eye);
    const PreparedScene prepared = prepareForReference(scene), preparedMoved = prepareForReference(moved);
    DrawContext context(2);
    std::vector<RayHit> rasterized, traced;
    rasterizeSurfaces(preparedMoved, context, rasterized);
    ReferenceOptions options;
    options.samples = 1;
    options.nearestSurfaces = &traced;
    renderReference(prepared, options, context.pool);
    const SurfaceAgreement moving = compareSurfaces(prepared, rasterized, traced);
    EXPECT_GT(moving.elsewhere, 100u);
    ASSERT_FALSE(moving.firstElsewhere.empty());
    EXPECT_GE(moving.firstElsewhere.front().edgeDistance, kEdgeTolerancePixels);
    // The same camera in both: no disagreement away from an edge.
    rasterizeSurfaces(prepared, context, rasterized);
    EXPECT_EQ(compareSurfaces(prepared, rasterized, traced).elsewhere, 0u);
}

// The shared models at a small size: curved meshes with thousands of small triangles (the bunny, the
// teapot, whose lid and body meet at many edges) and the Cornell box's large walls meeting at corners.
// Skipped when ../shared/models is absent. Breaks caught: depth-failed fragments kept; distances from
// the pixel's side; for the Cornell box, the edge tolerance a pixel (its edge share passes 1%).
void expectSharedModelAgrees(const std::filesystem::path& model, double minWithin1) {
    if (!std::filesystem::exists(model)) GTEST_SKIP() << model << " is not there";
    expectAgreement(compareWithoutTable(sceneAt(model, 160, 120)), minWithin1);
}
// Catches: the spots not naming the pixel or the triangle where a difference was planted, one blob listed
// twice (the separation missing), differences of 1/255 listed, the neighbours not counted, or a pixel
// where the two show different triangles given another reason.
TEST(ReferenceCompare, SpotsNameThePlantedDifferences) {
    const PreparedScene prepared = prepareForReference(sceneAt(kModels / "shared-edge.json", 42, 30));
    DrawContext context(1);
    std::vector<RayHit> surfaces;
    rasterizeSurfaces(prepared, context, surfaces);
    // A pixel of each triangle (the left one's draw is 0, the right one's 1), on the middle row; the
    // three planted spots at least 8 px apart (a spot's radius), by x or by y.
    const int row = 14;
    const std::size_t left = std::size_t(row) * 42 + 12, right = std::size_t(row) * 42 + 30;
    ASSERT_TRUE(surfaces[left].hit() && surfaces[right].hit());
    ASSERT_NE(surfaces[left].mesh, surfaces[right].mesh);
    std::vector<int> codes(surfaces.size(), 0);
    codes[left] = 40;
    codes[left + 1] = 30;  // the same blob: counted as nearby, not listed
    codes[right] = -20;
    codes[std::size_t(1) * 42 + 1] = 1;  // within 1/255: never listed
    std::vector<RayHit> traced = surfaces;
    const std::size_t other = std::size_t(27) * 42 + 21;  // where the reference shows something else
    traced[other] = surfaces[other].hit() ? RayHit{} : surfaces[left];
    codes[other] = 10;
    const std::vector<DifferenceSpot> spots = findDifferenceSpots(prepared, codes, surfaces, traced, {});
    ASSERT_EQ(spots.size(), 3u);
    EXPECT_EQ(spots[0].x, 12);
    EXPECT_EQ(spots[0].y, row);
    EXPECT_EQ(spots[0].codes, 40);
    EXPECT_EQ(spots[0].traced.mesh, surfaces[left].mesh);
    EXPECT_EQ(spots[0].traced.triangle, surfaces[left].triangle);
    EXPECT_EQ(spots[0].nearby, 1u);
    EXPECT_NE(spots[0].reason, DifferenceReason::OtherSurface);
    EXPECT_EQ(spots[1].x, 30);
    EXPECT_EQ(spots[1].codes, -20);
    EXPECT_EQ(spots[1].traced.mesh, surfaces[right].mesh);
    EXPECT_EQ(spots[2].x, 21);
    EXPECT_EQ(spots[2].y, 27);
    EXPECT_EQ(spots[2].reason, DifferenceReason::OtherSurface);
    EXPECT_NE(describeReason(spots[2]).find("another surface"), std::string::npos);
}

TEST(ReferenceCompare, StanfordBunnyAgrees) {
    // Measured: 3 652 of 3 653 within 1/255 (99.973%); edge pixels 0.545% of the covered ones.
    expectSharedModelAgrees(kSharedModels / "stanford-bunny" / "stanford-bunny.obj", 0.999);
}
TEST(ReferenceCompare, UtahTeapotAgrees) {
    expectSharedModelAgrees(kSharedModels / "utah-teapot" / "teapot.obj", 0.999);  // measured: all 3 428
}
TEST(ReferenceCompare, CornellBoxAgrees) {
    // Measured: all 6 092. The file writes one face of the short box twice: 771 pixels show one copy in
    // one renderer and the other copy in the other, at equal depth, which the depth test may do.
    expectSharedModelAgrees(kSharedModels / "cornell-box" / "CornellBox-Original.obj", 0.999);
}

// A 256² map's texels are eight times as large as a 2048² one's on the ground: its shadows' edges are
// coarser, so more pixels are wrongly lit or shadowed. Break caught (checked with the shadow maps of
// the helper-maps branch, where this test passes: 256² worse than 2048²): every row drawn at the scene's
// own map size (the table's size not applied). Skipped while shadow maps are a placeholder that draws
// no shadow (every setting then gives the same image).
TEST(ReferenceCompare, SmallShadowMapsAreWorse) {
    ReferenceCompareOptions options;
    options.shadowMapSizes = {256, 2048};
    const ReferenceComparison c = compareWithReference(sceneAt(kModels / "shadows.json", 200, 150), options);
    ASSERT_EQ(c.shadowMaps.size(), 2u * 4u * 3u);  // sizes × biases × filters
    const auto wrong = [&](int size) {
        for (const ShadowMapRow& row : c.shadowMaps)
            if (row.size == size && row.bias == "default" && row.filterTaps == 4)
                return row.wronglyLit + row.wronglyShadowed;
        return std::size_t(0);
    };
    bool mapsDrawn = false;
    for (const ShadowMapRow& row : c.shadowMaps)
        mapsDrawn = mapsDrawn || row.meanError != c.shadowMaps.front().meanError;
    if (!mapsDrawn) GTEST_SKIP() << "shadow maps are not drawn yet (every setting gives the same image)";
    EXPECT_GT(wrong(256), wrong(2048)) << describe(c);
}

}  // namespace
}  // namespace facet
