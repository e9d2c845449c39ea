// Shaders of one's own under the comparisons: the exact reference traces a user shader's draw where its
// vertex part puts the triangles and goes on behind a discarded fragment, so that facet compare
// --reference agrees with the rasterizer as it does for the built-in shaders; facet compare --against
// finds no difference for a shader that computes the built-in formula and the first one for a shader
// that leaves a term out.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "oracle/reference_compare.h"
#include "oracle/shader_compare.h"
#include "shading/gamma.h"
#include "support/user_shader_files.h"

namespace facet {
namespace {

using testing_support::kUserShaders;
using testing_support::SharedShaderCache;

const std::filesystem::path kSpot =
    std::filesystem::path(FACET_SOURCE_DIR) / "models/spot/spot_triangulated.obj";

UniformValue number(const std::string& name, double value) {
    return {name, {value}, false, "test: " + name};
}

// The spot model at 160×120, drawn by displace_cutout.cpp with these uniforms.
Scene displaceCutoutScene(double displacement, double cut) {
    Scene scene = loadSceneOrModel(kSpot);
    scene.width = 160;
    scene.height = 120;
    scene.shader = ShaderSpec{kUserShaders / "displace_cutout.cpp", {}};
    scene.uniforms = {number("displacement", displacement), number("cut", cut)};
    return scene;
}

ReferenceComparison compareWithoutShadowMapTable(const Scene& scene) {
    ReferenceCompareOptions options;
    options.shadowMapTable = false;
    return compareWithReference(scene, options);
}

void expectAgreement(const ReferenceComparison& c) {
    SCOPED_TRACE(describe(c));
    EXPECT_GT(c.surfaces.covered, c.surfaces.pixels / 20);  // the model is in view
    EXPECT_EQ(c.surfaces.elsewhere, 0u);
    EXPECT_LT(c.surfaces.edgeShare(), ReferenceComparison::kMaxEdgeShare);
    EXPECT_TRUE(c.agrees());
}

// Breaks caught: the reference tracing a user shader's draw at its mesh's own positions instead of where
// the vertex part moves them (the displaced silhouette would show other surfaces, or the background,
// far from any edge); the clip positions mapped back through the wrong projection (clipFromViewExact
// instead of the drawn one, or without the division by w); varyings interpolated with the wrong
// barycentrics (the colours would be off by more than 1/255 across the model).
TEST(UserShaderReference, DisplacedTrianglesAgreeWithTheRasterizer) {
    const SharedShaderCache cache;
    const ReferenceComparison flat = compareWithoutShadowMapTable(displaceCutoutScene(0.0, 2.0));
    expectAgreement(flat);
    const ReferenceComparison displaced = compareWithoutShadowMapTable(displaceCutoutScene(0.04, 2.0));
    expectAgreement(displaced);
    // The vertices did move: the swollen model covers more pixels, in both renderers.
    EXPECT_GT(displaced.surfaces.covered, flat.surfaces.covered + 100);
}

// Flat shading (face normals: the cut is decided per triangle, never between a pixel's float and double
// interpolation of the normal, a boundary the rasterizer's snapped vertices may move) and no culling:
// through the holes the inside of the model shows.
// Breaks caught: a discarded hit shown as the surface (or as the background) instead of what lies
// behind it; the discarding draw left opaque in the camera rays' BVH, which stops them at the discarded
// fragment; nearestSurfaces not told about the surface behind (every hole counted as a disagreement).
TEST(UserShaderReference, DiscardedFragmentsShowWhatIsBehind) {
    const SharedShaderCache cache;
    const auto scene = [](double cut) {
        Scene s = displaceCutoutScene(0.0, cut);
        s.lighting.shading = ShadingFrequency::Flat;
        s.pipeline.cull = CullMode::None;
        return s;
    };
    const ReferenceComparison whole = compareWithoutShadowMapTable(scene(2.0));
    const ReferenceComparison cut = compareWithoutShadowMapTable(scene(0.3));
    expectAgreement(cut);
    // Fragments were discarded: the images differ from the whole model's ...
    std::size_t changed = 0;
    for (std::size_t k = 0; k < cut.reference.pixels.size(); ++k)
        changed += cut.reference.pixels[k] != whole.reference.pixels[k];
    EXPECT_GT(changed, 200u);
    // ... and of the changed pixels, many show the inside (seen through a hole) rather than the
    // background: measured 387 changed, 243 of them now background.
    EXPECT_GT(cut.surfaces.covered + changed, whole.surfaces.covered + 100) << changed;
}

Scene ownPhongScene(bool specular) {
    Scene scene = loadSceneOrModel(kSpot);
    scene.width = 160;
    scene.height = 120;
    scene.shader = ShaderSpec{kUserShaders / "own_phong.cpp", {}};
    scene.uniforms = {{"specular", {specular ? 1.0 : 0.0}, true, "test: specular"}};
    return scene;
}

// Breaks caught: --against drawing the built-in side with the scene's shading (Gouraud, flat) or its
// own reflection model instead of the one named per pixel, or leaving the user's shader on the built-in
// side; a shader of one's own written with the built-in formula functions not giving the built-in's
// bits (the module compiled with other floating-point flags than the frame's code, or the uniforms it
// sees not the built-in draw's).
TEST(ShaderAgainstBuiltIn, TheBuiltInFormulaWrittenAsAShaderIsIdentical) {
    const SharedShaderCache cache;
    for (const ReflectionModel model :
         {ReflectionModel::Phong, ReflectionModel::BlinnPhong, ReflectionModel::CookTorrance}) {
        SCOPED_TRACE(std::string(nameOf(model)));
        const ShaderComparison c =
            compareShaderWithBuiltIn(shaderAgainstScenes(ownPhongScene(true), model), 0);
        EXPECT_EQ(c.differing, 0u);
        EXPECT_EQ(c.largest, 0);
        EXPECT_FALSE(c.first.has_value());
    }
}

// Breaks caught: the count, the largest difference or the first pixel taken from the wrong image or
// in column order; a pixel counted as differing when its codes are the same (linear values compared).
TEST(ShaderAgainstBuiltIn, LeavingOutTheSpecularTermDiffersFromTheFirstHighlight) {
    const SharedShaderCache cache;
    const ShaderComparison c =
        compareShaderWithBuiltIn(shaderAgainstScenes(ownPhongScene(false), ReflectionModel::Phong), 0);
    ASSERT_TRUE(c.first.has_value());
    EXPECT_GT(c.differing, 0u);
    EXPECT_GT(c.largest, 0);
    // Every pixel before the first in reading order has the same codes; the first does not; the
    // built-in's (with the highlight) is the brighter.
    const auto codes = [&](const LinearImage& image, int x, int y) {
        return std::array{encodeChannel(image.at(x, y).r, c.encoding),
                          encodeChannel(image.at(x, y).g, c.encoding),
                          encodeChannel(image.at(x, y).b, c.encoding)};
    };
    const auto [fx, fy] = *c.first;
    for (int y = 0; y <= fy; ++y)
        for (int x = 0; x < (y == fy ? fx : c.width); ++x)
            ASSERT_EQ(codes(c.mine, x, y), codes(c.builtIn, x, y)) << x << "," << y;
    EXPECT_NE(codes(c.mine, fx, fy), codes(c.builtIn, fx, fy));
    EXPECT_GT(c.builtIn.at(fx, fy).r + c.builtIn.at(fx, fy).g + c.builtIn.at(fx, fy).b,
              c.mine.at(fx, fy).r + c.mine.at(fx, fy).g + c.mine.at(fx, fy).b);
}

}  // namespace
}  // namespace facet
