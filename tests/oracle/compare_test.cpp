// facet compare's verdict (src/oracle/compare.h), without Mesa: a comparison is built from two images
// as compareWithMesa builds it, and its verdict and description are checked.
#include "oracle/compare.h"

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "oracle/gl_scene.h"

namespace facet {
namespace {

const vec4 kClearColour(0.2f, 0.2f, 0.2f, 0.0f);

LinearImage filled(vec4 color) {
    LinearImage image;
    image.width = 8;
    image.height = 6;
    image.pixels.assign(48, color);
    return image;
}

MesaComparison comparison(const LinearImage& facet, const LinearImage& mesa) {
    MesaComparison c;
    c.facet = facet;
    c.mesa = mesa;
    c.difference = comparePixels(facet, mesa, c.encoding, kClearColour);
    return c;
}

// Two empty frames agree pixel for pixel, and prove nothing: a renderer that draws nothing must not pass
// (breaks caught: agrees() without drewSomething(); comparePixels not counting covered pixels).
TEST(MesaComparison, TwoEmptyFramesAreNotAnAgreement) {
    const MesaComparison empty = comparison(filled(kClearColour), filled(kClearColour));
    EXPECT_EQ(empty.difference.within2, 1.0);
    EXPECT_FALSE(empty.drewSomething());
    EXPECT_FALSE(empty.agrees());
    EXPECT_NE(describe(empty).find("verdict    NOTHING DRAWN"), std::string::npos) << describe(empty);

    // One side drawing and the other not is a difference, not agreement on nothing.
    LinearImage drawn = filled(kClearColour);
    drawn.at(3, 3) = vec4(0.8f, 0.5f, 0.1f, 1.0f);
    EXPECT_FALSE(comparison(drawn, filled(kClearColour)).agrees());
}

TEST(MesaComparison, EqualDrawnFramesAgree) {
    const LinearImage drawn = filled(vec4(0.8f, 0.5f, 0.1f, 1.0f));
    const MesaComparison same = comparison(drawn, drawn);
    EXPECT_TRUE(same.agrees());
    const std::string text = describe(same);
    EXPECT_NE(text.find("verdict    agrees"), std::string::npos) << text;
    EXPECT_NE(text.find("drawn      Facet 48 pixels (100.000%), OpenGL 48"), std::string::npos) << text;
}

// OpenGL's side of a comparison is told the scene's depth and colour formats and its texture filter
// (without them `facet compare --depth unorm16` would compare against a float depth buffer). Catches
// toGlScene leaving any of the three at its default.
TEST(MesaComparison, OpenGlSceneTakesTheBufferFormatsAndTheFilter) {
    Scene scene =
        sceneForModel(std::filesystem::path(FACET_SOURCE_DIR) / "models/spot/spot_triangulated.obj");
    scene.width = 32;
    scene.height = 24;
    scene.pipeline.depth = DepthBufferFormat::Unorm16;
    scene.pipeline.colorBuffer = ColorBufferFormat::Half;
    scene.textures.filter = TextureFilter::Trilinear;
    GlScene gl = toGlScene(prepareScene(scene));
    EXPECT_EQ(gl.depthFormat, DepthBufferFormat::Unorm16);
    EXPECT_EQ(gl.colorFormat, ColorBufferFormat::Half);
    EXPECT_EQ(gl.textureFilter, TextureFilter::Trilinear);
    scene.pipeline.depth = DepthBufferFormat::ReversedFloat;
    scene.pipeline.colorBuffer = ColorBufferFormat::Unorm8;
    scene.textures.filter = TextureFilter::Nearest;
    gl = toGlScene(prepareScene(scene));
    EXPECT_EQ(gl.depthFormat, DepthBufferFormat::ReversedFloat);
    EXPECT_EQ(gl.colorFormat, ColorBufferFormat::Unorm8);
    EXPECT_EQ(gl.textureFilter, TextureFilter::Nearest);
}

}  // namespace
}  // namespace facet
