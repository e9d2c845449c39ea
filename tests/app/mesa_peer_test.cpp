// The benchmark's Mesa peer: compareImages() tells a like-for-like pair of renderings from a different
// silhouette, a flipped image or different shading; and where OSMesa can be loaded, Mesa llvmpipe and
// Facet draw the same scene to images that agree (skipped, with the reason, where it cannot).
#include <gtest/gtest.h>

#include <string>

#include "mesa_peer.h"
#include "renderer.h"

// Mesa and LLVM keep process-lifetime allocations (the loaded library is never closed): not leaks of ours.
extern "C" const char* __lsan_default_suppressions() {
    return "leak:libOSMesa\nleak:libLLVM\n";
}

namespace facet {
namespace {

const vec4 kBackground(0.1f, 0.1f, 0.1f, 1.0f);

// A disc of radius r centred at (cx, cy), shaded from left to right, on the background.
LinearImage disc(int width, int height, float cx, float cy, float r) {
    LinearImage image;
    image.width = width;
    image.height = height;
    image.pixels.assign(static_cast<std::size_t>(width) * height, kBackground);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float dx = x + 0.5f - cx, dy = y + 0.5f - cy;
            if (dx * dx + dy * dy <= r * r) image.at(x, y) = vec4(0.3f + 0.5f * x / width, 0.4f, 0.5f, 1.0f);
        }
    return image;
}

TEST(CompareImages, IdenticalImagesAgree) {
    const LinearImage a = disc(64, 48, 30.0f, 20.0f, 15.0f);
    const ImageAgreement agreement = compareImages(a, a, kBackground);
    EXPECT_TRUE(agreement.agrees());
    EXPECT_EQ(agreement.coverageAgreement, 1.0);
    EXPECT_EQ(agreement.colorWithinTolerance, 1.0);
    EXPECT_EQ(agreement.meanColorDifference, 0.0);
    EXPECT_EQ(agreement.foregroundA, agreement.foregroundB);
    EXPECT_GT(agreement.foregroundA, 600u);
}

TEST(CompareImages, EdgePixelsAloneDoNotMatter) {
    // Radius 15 vs 15.2: only a ring of edge pixels differs.
    const ImageAgreement agreement =
        compareImages(disc(64, 48, 30.0f, 20.0f, 15.0f), disc(64, 48, 30.0f, 20.0f, 15.2f), kBackground);
    EXPECT_TRUE(agreement.agrees());
    EXPECT_LT(agreement.coverageAgreement, 1.0);
}

TEST(CompareImages, AnotherSilhouetteDisagrees) {
    const ImageAgreement agreement =
        compareImages(disc(64, 48, 30.0f, 20.0f, 15.0f), disc(64, 48, 36.0f, 20.0f, 15.0f), kBackground);
    EXPECT_FALSE(agreement.agrees());
    EXPECT_LT(agreement.coverageAgreement, 0.98);
}

TEST(CompareImages, AnUpsideDownImageDisagrees) {
    // GL's row 0 is the bottom, Facet's the top: forgetting the flip moves an off-centre shape.
    const LinearImage a = disc(64, 48, 30.0f, 14.0f, 10.0f);
    LinearImage flipped = a;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            flipped.at(x, y) = a.at(x, a.height - 1 - y);
    EXPECT_FALSE(compareImages(a, flipped, kBackground).agrees());
}

TEST(CompareImages, OtherShadingDisagrees) {
    const LinearImage a = disc(64, 48, 30.0f, 20.0f, 15.0f);
    LinearImage brighter = a;
    for (vec4& p : brighter.pixels)
        if (p != kBackground) p += vec4(0.1f, 0.0f, 0.0f, 0.0f);
    const ImageAgreement agreement = compareImages(a, brighter, kBackground);
    EXPECT_EQ(agreement.coverageAgreement, 1.0);
    EXPECT_FALSE(agreement.agrees());
}

TEST(CompareImages, EmptyImagesDoNotAgree) {
    // Nothing drawn on either side proves nothing.
    const LinearImage empty = disc(16, 16, 0.0f, 0.0f, 0.0f);
    EXPECT_FALSE(compareImages(empty, empty, kBackground).agrees());
}

TEST(CompareImages, SizesMustMatch) {
    EXPECT_THROW(compareImages(disc(16, 16, 8, 8, 4), disc(16, 15, 8, 8, 4), kBackground),
                 std::invalid_argument);
}

// The cow, textured, lit by the default directional light and a point light, at 160×120.
TEST(MesaPeer, DrawsTheSameImageAsFacet) {
    std::string whyNot;
    const std::unique_ptr<MesaPeer> mesa = MesaPeer::open(1, whyNot);
    if (!mesa) GTEST_SKIP() << "Mesa llvmpipe (OSMesa) cannot be loaded: " << whyNot;
    EXPECT_NE(mesa->renderer().find("llvmpipe"), std::string::npos) << mesa->renderer();

    Scene scene = sceneForModel(FACET_SOURCE_DIR "/models/spot/spot_triangulated.obj");
    scene.width = 160;
    scene.height = 120;
    LightSpec key;  // the renderer's default key light
    key.direction = vec3(0.45f, -0.55f, -1.0f);
    key.cameraRelative = true;
    LightSpec point;
    point.type = LightType::Point;
    point.position = vec3(-2.0f, 2.0f, 0.5f);
    point.color = vec3(1.0f, 0.8f, 0.6f);
    point.cameraRelative = true;
    scene.lights = {key, point};
    const PreparedScene prepared = prepareScene(scene);
    ASSERT_NE(prepared.draws.front().uniforms.diffuseMap, nullptr);  // the texture is compared too

    Framebuffer framebuffer(scene.width, scene.height);
    DrawContext context(1);
    renderFrame(prepared, framebuffer, context);
    mesa->load(prepared);
    mesa->renderFrame();
    const LinearImage mesaImage = mesa->readImage();
    const float tolerance = mesa->floatColor() ? 1e-5f : 0.5f / 255.0f + 1e-5f;
    const ImageAgreement agreement =
        compareImages(toImage(framebuffer), mesaImage, prepared.clearColor, tolerance);
    EXPECT_TRUE(agreement.agrees()) << "coverage " << agreement.coverageAgreement << ", colour within "
                                    << agreement.colorWithinTolerance << ", mean difference "
                                    << agreement.meanColorDifference << ", foreground "
                                    << agreement.foregroundA << " vs " << agreement.foregroundB;
    EXPECT_GT(agreement.foregroundA, 2000u);  // the cow fills a good part of the frame

    // A second frame of a reloaded scene is the same.
    mesa->load(prepared);
    mesa->renderFrame();
    EXPECT_EQ(mesa->readImage().pixels, mesaImage.pixels);
}

}  // namespace
}  // namespace facet
