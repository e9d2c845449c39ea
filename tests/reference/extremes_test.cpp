// Whole scenes at the numerical extremes: models of size 1e7 and 1e-7, a model 1e7 from the origin,
// a ground plane through the eye (triangles crossing w = 0) and one wholly behind it, near/far ratios
// down to 1e-7, opacity 0 and 1, light far above 1 in EXR. Each is rendered through the whole
// renderer, checked to hold no NaN or Inf, and compared with a scene it must equal or with the exact
// (double-precision, ray-cast) reference, with the tolerance stated.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "io/image_io.h"
#include "pipeline/thread_pool.h"
#include "reference/reference.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

class RenderExtremesTest : public testing_support::TempFolderTest {
  protected:
    static constexpr int kWidth = 64, kHeight = 48;

    // The scene `document` (size and "model" filled in when absent) written, read and prepared.
    PreparedScene prepare(Json document, const std::string& name = "scene.json") {
        if (!document.contains("objects") && !document.contains("model"))
            document["model"] = FACET_SOURCE_DIR "/models/cube/cube.obj";
        document["width"] = kWidth;
        document["height"] = kHeight;
        const fs::path path = folder_ / name;
        std::ofstream(path) << document.dump();
        return prepareScene(loadScene(path));
    }
    LinearImage render(const Json& document) {
        const PreparedScene prepared = prepare(document);
        Framebuffer framebuffer(kWidth, kHeight);
        DrawContext context(1);
        renderFrame(prepared, framebuffer, context);
        return toImage(framebuffer);
    }
    LinearImage reference(const Json& document) {
        const PreparedScene prepared = prepare(document);
        ThreadPool pool(1);
        ReferenceOptions options;
        options.samples = 1;  // pixel centres, as the rasterizer samples
        return renderReference(prepared, options, pool);
    }
};

bool allFinite(const LinearImage& image) {
    for (const glm::vec4& p : image.pixels)
        for (int c = 0; c < 4; ++c)
            if (!std::isfinite(p[c])) return false;
    return true;
}

// The share of pixels whose colours differ by more than `tolerance` in some channel.
double shareDiffering(const LinearImage& a, const LinearImage& b, float tolerance) {
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        const glm::vec4 d = glm::abs(a.pixels[i] - b.pixels[i]);
        differing += glm::max(glm::max(d.r, d.g), glm::max(d.b, d.a)) > tolerance;
    }
    return static_cast<double>(differing) / static_cast<double>(a.pixels.size());
}

std::size_t pixelsUnlike(const LinearImage& image, glm::vec4 background) {
    std::size_t count = 0;
    for (const glm::vec4& p : image.pixels)
        count += p != background;
    return count;
}

// The cube scaled to 1e7 and to 1e-7 (the camera framed from its bounding box, near and far derived
// from it) draws the image of the unit cube: lighting by a directional light does not depend on scale,
// and float keeps 24 bits of relative precision at any magnitude. Tolerance: 2/255 in at most 1% of
// the pixels (a silhouette pixel may flip where the scaled vertices round differently).
TEST_F(RenderExtremesTest, ModelsOfSize1e7And1e_7DrawAsTheUnitModel) {
    const LinearImage unit = render(Json::object());
    ASSERT_GT(pixelsUnlike(unit, unit.pixels[0]), 500u);
    for (double scale : {1e7, 1e-7}) {
        SCOPED_TRACE(::testing::Message() << "scale " << scale);
        const LinearImage scaled = render(
            Json{{"objects", {{{"model", FACET_SOURCE_DIR "/models/cube/cube.obj"}, {"scale", scale}}}}});
        ASSERT_TRUE(allFinite(scaled));
        EXPECT_LT(shareDiffering(scaled, unit, 2.0f / 255.0f), 0.01);
    }
}

// The unit cube 1e7 from the origin, the camera beside it: a float world position there is only good
// to 1 unit (the camera's offsets here are whole numbers, so the scene file's floats hold them
// exactly), but the renderer composes view · model in double (PreparedDraw::viewFromObjectExact), so
// the eye-space positions — small numbers — are exact and the image is the unit cube's at the origin.
TEST_F(RenderExtremesTest, AModelFarFromTheOriginDrawsAsAtTheOrigin) {
    const Json camera = {{"eye", {2.0, 2.0, 3.0}}, {"target", {0.0, 0.0, 0.0}}, {"near", 0.5}, {"far", 20.0}};
    const LinearImage atOrigin = render(Json{{"camera", camera}});
    Json far = {{"objects",
                 {{{"model", FACET_SOURCE_DIR "/models/cube/cube.obj"}, {"translate", {1e7, -1e7, 1e7}}}}}};
    far["camera"] = {{"eye", {1e7 + 2.0, -1e7 + 2.0, 1e7 + 3.0}},
                     {"target", {1e7, -1e7, 1e7}},
                     {"near", 0.5},
                     {"far", 20.0}};
    const LinearImage farAway = render(far);
    ASSERT_TRUE(allFinite(farAway));
    ASSERT_GT(pixelsUnlike(atOrigin, atOrigin.pixels[0]), 300u);
    EXPECT_LT(shareDiffering(farAway, atOrigin, 2.0f / 255.0f), 0.01);
}

// A ground plane of two triangles that reach behind the eye (their w crosses 0: clipping must cut
// them at the near plane, never divide by w ≤ 0) against the exact reference, which has no w at all:
// the same pixels show the ground, and their colours agree to 1/255 but for the horizon row and the
// edges (at most 3% of pixels). A triangle wholly behind the eye draws nothing: the image is the
// background, every pixel.
TEST_F(RenderExtremesTest, TrianglesCrossingWZeroMatchTheReferenceAndOnesBehindTheEyeVanish) {
    const fs::path ground = folder_ / "ground.obj";
    std::ofstream(ground) << "v -50 0 -50\nv 50 0 -50\nv 50 0 50\nv -50 0 50\nf 1 3 2\nf 1 4 3\n";
    const Json scene = {
        {"model", ground.string()},
        {"camera", {{"eye", {0.0, 1.0, 0.0}}, {"target", {0.0, 0.5, -4.0}}, {"near", 0.1}, {"far", 200.0}}},
        {"lighting", {{"shading", "phong"}}},
        {"lights", {{{"type", "directional"}, {"direction", {0.2, -1.0, -0.3}}}}}};
    const LinearImage raster = render(scene);
    const LinearImage exact = reference(scene);
    ASSERT_TRUE(allFinite(raster));
    const glm::vec4 background = raster.pixels[0];
    EXPECT_GT(pixelsUnlike(raster, background), static_cast<std::size_t>(kWidth * kHeight / 3));
    EXPECT_LT(shareDiffering(raster, exact, 1.0f / 255.0f), 0.03);

    const fs::path behind = folder_ / "behind.obj";
    std::ofstream(behind) << "v -1 -1 3\nv 1 -1 3\nv 0 1 3\nf 1 2 3\nf 1 3 2\n";
    const LinearImage none = render(
        {{"model", behind.string()},
         {"camera", {{"eye", {0.0, 0.0, 0.0}}, {"target", {0.0, 0.0, -1.0}}, {"near", 0.1}, {"far", 10.0}}}});
    EXPECT_EQ(pixelsUnlike(none, none.pixels[0]), 0u);
}

// Near/far ratios from 1e-1 to 1e-7 (far fixed, near down to 1e-6 of a 10-unit scene): the cube is
// drawn, finite, and its pixels are those of the ratio 1e-1 image but at the silhouette (float depth
// still orders the cube's own faces: they are far apart compared with its resolution there).
TEST_F(RenderExtremesTest, NearFarRatiosDownTo1e_7KeepTheImage) {
    auto withNear = [](double near) {
        return Json{{"camera",
                     {{"eye", {2.0, 1.5, 3.0}}, {"target", {0.0, 0.0, 0.0}}, {"near", near}, {"far", 10.0}}}};
    };
    const LinearImage base = render(withNear(1.0));
    for (double near : {1e-2, 1e-4, 1e-6}) {
        SCOPED_TRACE(::testing::Message() << "near/far " << near / 10.0);
        const LinearImage image = render(withNear(near));
        ASSERT_TRUE(allFinite(image));
        EXPECT_LT(shareDiffering(image, base, 2.0f / 255.0f), 0.01);
    }
}

// Opacity 0 and 1: a fully transparent cube leaves every pixel exactly as the background (over with
// α = 0 adds 0·c_s to 1·c_d), and opacity 1 draws exactly the opaque cube.
TEST_F(RenderExtremesTest, OpacityZeroIsInvisibleAndOneIsOpaque) {
    const LinearImage opaque = render(Json::object());
    auto withOpacity = [](double opacity) {
        return Json{
            {"objects",
             {{{"model", FACET_SOURCE_DIR "/models/cube/cube.obj"}, {"material", {{"opacity", opacity}}}}}}};
    };
    const LinearImage invisible = render(withOpacity(0.0));
    EXPECT_EQ(pixelsUnlike(invisible, opaque.pixels[0]), 0u);
    const LinearImage one = render(withOpacity(1.0));
    EXPECT_EQ(shareDiffering(one, opaque, 0.0f), 0.0);
}

// A light of intensity 1000 lights the cube far above 1: the EXR keeps those values (finite, above
// 1, read back unchanged), and the 8-bit PNG clamps them to 255 rather than wrapping or writing NaN.
TEST_F(RenderExtremesTest, ColoursAboveOneSurviveInEXRAndClampIn8Bit) {
    const LinearImage image = render(Json{
        {"lights", {{{"type", "directional"}, {"direction", {-0.4, -0.6, -0.7}}, {"intensity", 1000}}}}});
    ASSERT_TRUE(allFinite(image));
    float brightest = 0.0f;
    for (const glm::vec4& p : image.pixels)
        brightest = std::max(brightest, p.r);
    EXPECT_GT(brightest, 10.0f);
    writeImage(folder_ / "bright.exr", image);
    const LinearImage exr = readImage(folder_ / "bright.exr");
    ASSERT_EQ(exr.pixels.size(), image.pixels.size());
    EXPECT_EQ(shareDiffering(exr, image, 0.0f), 0.0);
    writeImage(folder_ / "bright.png", image);
    const LinearImage png = readImage(folder_ / "bright.png");
    float brightestCode = 0.0f;
    for (const glm::vec4& p : png.pixels) {
        ASSERT_LE(p.r, 1.0f);
        brightestCode = std::max(brightestCode, p.r);
    }
    EXPECT_EQ(brightestCode, 1.0f);
}

}  // namespace
}  // namespace facet
