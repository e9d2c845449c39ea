// The stage images (step/stage_images.h) on small scenes built here, whose pixels are known: a camera
// at (0, 0, 5) looking down −z at triangles near z = 0. Each test names the one-line break it catches.
#include "step/stage_images.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "pipeline/viewport.h"
#include "support/bundled_models.h"
#include "support/file_bytes.h"
#include "support/temp_folder.h"

namespace facet::step {
namespace {

namespace fs = std::filesystem;

using testing_support::kModels;

struct Rendered {
    StageImage image;
    LinearImage pixels;
    ColorEncoding encoding;
};

std::vector<Rendered> renderAll(const PreparedScene& prepared, const StageImageOptions& options = {}) {
    std::vector<Rendered> images;
    renderStageImages(prepared, options,
                      [&](const StageImage& image, const LinearImage& pixels, ColorEncoding encoding) {
                          images.push_back({image, pixels, encoding});
                      });
    return images;
}

// A copy: the images are often a temporary.
Rendered find(const std::vector<Rendered>& images, const std::string& id) {
    for (const Rendered& r : images)
        if (r.image.id == id) return r;
    throw std::runtime_error("no stage image \"" + id + "\"");
}

std::vector<std::string> ids(const std::vector<Rendered>& images) {
    std::vector<std::string> result;
    for (const Rendered& r : images)
        result.push_back(r.image.id);
    return result;
}

vec3 rgbAt(const Rendered& r, ivec2 pixel) {
    return vec3(r.pixels.at(pixel.x, pixel.y));
}

using testing_support::fileBytes;

// Pixels of `image` exactly `colour`.
std::size_t pixelsOf(const LinearImage& image, vec3 colour) {
    std::size_t n = 0;
    for (const vec4& p : image.pixels)
        n += vec3(p) == colour;
    return n;
}

class StageImagesTest : public testing_support::TempFolderTest {
  protected:
    // A 40×30 scene of the OBJ text `obj` (one object), seen from (0, 0, 5) looking at the origin.
    Scene sceneOf(const std::string& obj) const {
        Scene scene;
        scene.source = folder_ / "scene.json";
        scene.width = 40;
        scene.height = 30;
        scene.camera.eye = vec3(0.0f, 0.0f, 5.0f);
        scene.camera.target = vec3(0.0f);
        scene.camera.near = 1.0f;
        scene.camera.far = 10.0f;
        ObjectSpec object;
        object.model = write("model" + std::to_string(models_++) + ".obj", obj);
        scene.objects.push_back(object);
        return scene;
    }
    void addObject(Scene& scene, const std::string& obj) const {
        ObjectSpec object;
        object.model = write("model" + std::to_string(models_++) + ".obj", obj);
        scene.objects.push_back(object);
    }

    mutable int models_ = 0;
};

// The pixel a world point lands on, through the prepared camera and the pipeline's viewport transform.
ivec2 pixelOf(const PreparedScene& prepared, vec3 world) {
    const vec4 clip = prepared.camera.clipFromView * prepared.camera.viewFromWorld * vec4(world, 1.0f);
    const vec2 window = toWindow(clip, prepared.state.viewport, 8).window;
    return ivec2(static_cast<int>(window.x), static_cast<int>(window.y));
}

// Two triangles side by side at z = 0, facing the camera, in one object: triangles 0 and 1 of draw 0.
const char* const kSideBySide = R"(
v -2 -1 0
v -0.2 -1 0
v -1.1 1 0
v 0.2 -1 0
v 2 -1 0
v 1.1 1 0
vn 0 0 1
f 1//1 2//1 3//1
f 4//1 5//1 6//1
)";
const vec3 kLeftCentre(-1.1f, -0.33f, 0.0f), kRightCentre(1.1f, -0.33f, 0.0f);

// A near triangle A at z = 1 (first), then a far one B at z = 0 overlapping part of it.
const char* const kNearTriangle = R"(
v -1.5 -1 1
v 0.5 -1 1
v -0.5 1 1
vn 0 0 1
f 1//1 2//1 3//1
)";
const char* const kFarTriangle = R"(
v -0.5 -1 0
v 1.5 -1 0
v 0.5 1 0
vn 0 0 1
f 1//1 2//1 3//1
)";
// Points of B behind A (the overlap), of B alone, and of A alone (at z = 1).
const vec3 kOverlap(0.0f, -0.6f, 0.0f), kFarOnly(1.0f, -0.6f, 0.0f), kNearOnly(-1.0f, -0.6f, 1.0f);

// Break: triangleIdColor(draw_, 0) in the recorder (a colour per draw, not per triangle), or painting
// the background in a triangle's colour.
TEST_F(StageImagesTest, TriangleIdsTellTwoTrianglesApartOnTheBackground) {
    const PreparedScene prepared = prepareScene(sceneOf(kSideBySide));
    const Rendered triangles = find(renderAll(prepared, {.buildFrames = 0}), "triangles");
    EXPECT_EQ(triangles.encoding, kLinearEncoding);
    const vec3 left = rgbAt(triangles, pixelOf(prepared, kLeftCentre));
    const vec3 right = rgbAt(triangles, pixelOf(prepared, kRightCentre));
    EXPECT_EQ(left, triangleIdColor(0, 0));
    EXPECT_EQ(right, triangleIdColor(0, 1));
    EXPECT_NE(left, right);
    EXPECT_EQ(rgbAt(triangles, {0, 0}), vec3(0.0f));
    EXPECT_EQ(rgbAt(triangles, {20, 1}), vec3(0.0f));  // above the gap between them
}

// Break: counting only the fragments that were written (the far triangle's fail the depth test).
TEST_F(StageImagesTest, OverdrawIsTwoWhereTwoTrianglesOverlap) {
    Scene scene = sceneOf(kNearTriangle);
    addObject(scene, kFarTriangle);
    const PreparedScene prepared = prepareScene(scene);
    const Rendered overdraw = find(renderAll(prepared, {.buildFrames = 0}), "overdraw");
    EXPECT_EQ(rgbAt(overdraw, pixelOf(prepared, kOverlap)), heatColor(2, 2));
    EXPECT_EQ(rgbAt(overdraw, pixelOf(prepared, kFarOnly)), heatColor(1, 2));
    EXPECT_EQ(rgbAt(overdraw, pixelOf(prepared, kNearOnly)), heatColor(1, 2));
    EXPECT_EQ(rgbAt(overdraw, {0, 0}), vec3(0.0f));
    EXPECT_NE(overdraw.image.title.find("at most 2"), std::string::npos) << overdraw.image.title;
}

// Break: brightness 0.2 + 0.8·t instead of 1 − 0.8·t (far white).
TEST_F(StageImagesTest, DepthIsBrighterForTheNearerTriangle) {
    Scene scene = sceneOf(kNearTriangle);
    addObject(scene, kFarTriangle);
    const PreparedScene prepared = prepareScene(scene);
    const Rendered depth = find(renderAll(prepared, {.buildFrames = 0}), "depth");
    const float nearer = rgbAt(depth, pixelOf(prepared, kNearOnly)).g;
    const float farther = rgbAt(depth, pixelOf(prepared, kFarOnly)).g;
    EXPECT_GT(nearer, farther);
    EXPECT_GT(farther, 0.0f);                                        // black is "no surface"
    EXPECT_EQ(rgbAt(depth, pixelOf(prepared, kOverlap)).g, nearer);  // the nearer one won
    EXPECT_NE(depth.image.title.find("white 4 "), std::string::npos) << depth.image.title;  // z = 1
}

// Break: observing the scene as it is (no per-pixel copy for Gouraud draws), or N instead of N·0.5 + 0.5.
TEST_F(StageImagesTest, NormalsOfAPlaneFacingTheCameraAreLightBlueEvenWhenShadedPerVertex) {
    Scene scene = sceneOf(kSideBySide);
    scene.objects[0].shading = ShadingFrequency::Gouraud;
    const PreparedScene prepared = prepareScene(scene);
    const vec3 normal =
        rgbAt(find(renderAll(prepared, {.buildFrames = 0}), "normals"), pixelOf(prepared, kLeftCentre));
    EXPECT_NEAR(normal.r, 0.5f, 1e-5f);
    EXPECT_NEAR(normal.g, 0.5f, 1e-5f);
    EXPECT_NEAR(normal.b, 1.0f, 1e-5f);
}

// A triangle whose bottom edge lies 0.4 from the eye, in front of the near plane (1): clipping removes
// that strip, which projects onto the screen below what is kept. Break: not drawing the assembled
// triangle in onClipped (or drawing it in the drawn colour).
TEST_F(StageImagesTest, WireframeMarksWhatTheNearPlaneCutsOff) {
    const std::string cut = "v -0.1 -0.05 4.6\nv 0.1 -0.05 4.6\nv 0 1 0\nf 1 2 3\n";
    Scene scene = sceneOf(cut);
    scene.pipeline.cull = CullMode::None;
    const LinearImage wireframe =
        find(renderAll(prepareScene(scene), {.buildFrames = 0}), "wireframe").pixels;
    EXPECT_GT(pixelsOf(wireframe, kRemovedEdgeColor), 10u);
    EXPECT_GT(pixelsOf(wireframe, kDrawnEdgeColor), 10u);

    // Moved 2 away from the eye it lies wholly beyond the near plane: nothing removed.
    Scene whole = sceneOf("v -0.1 -0.05 2.6\nv 0.1 -0.05 2.6\nv 0 1 -2\nf 1 2 3\n");
    whole.pipeline.cull = CullMode::None;
    const LinearImage kept = find(renderAll(prepareScene(whole), {.buildFrames = 0}), "wireframe").pixels;
    EXPECT_EQ(pixelsOf(kept, kRemovedEdgeColor), 0u);
    EXPECT_GT(pixelsOf(kept, kDrawnEdgeColor), 10u);
}

// Break: `if (fog)` dropped around the fog images, or the fog factor taken at the normal instead of
// the position. Linear fog from 3 to 7 on a plane 5 from the eye: f = (7 − 5)/(7 − 3) = 0.5.
TEST_F(StageImagesTest, FogImagesAppearOnlyWithFogAndShowTheFogFactor) {
    const std::vector<std::string> withoutFog = {"wireframe", "triangles", "overdraw",  "depth",
                                                 "normals",   "emission",  "ambient",   "diffuse",
                                                 "specular",  "final",     "build-001", "build-002"};
    Scene scene = sceneOf(kSideBySide);
    EXPECT_EQ(ids(renderAll(prepareScene(scene))), withoutFog);

    scene.fog.mode = FogMode::Linear;
    scene.fog.start = 3.0f;
    scene.fog.end = 7.0f;
    const PreparedScene prepared = prepareScene(scene);
    const std::vector<Rendered> images = renderAll(prepared);
    std::vector<std::string> withFog = withoutFog;
    withFog.insert(withFog.begin() + 9, {"before-fog", "fog-factor"});
    EXPECT_EQ(ids(images), withFog);
    const ivec2 pixel = pixelOf(prepared, kLeftCentre);
    EXPECT_NEAR(rgbAt(find(images, "fog-factor"), pixel).r, 0.5f, 1e-6f);
    EXPECT_NE(rgbAt(find(images, "before-fog"), pixel), rgbAt(find(images, "final"), pixel));
}

// The number printed right after `marker` in `text` (the captions print 4 significant digits); NaN
// when the marker is missing.
double valueAfter(const std::string& text, const std::string& marker) {
    const std::size_t at = text.find(marker);
    if (at == std::string::npos) return std::nan("");
    return std::strtod(text.c_str() + at + marker.size(), nullptr);
}

// A scene of 2^20 units (a plane 5·2^20 from the eye, linear fog from 3·2^20 to 7·2^20, exp and exp² fog
// of density 0.2/2^20) is drawn in an eye space rescaled by Camera::viewScale, but the captions speak the
// scene's own units: the fog's start, end and density as the scene gives them, the depth image's
// distances 5·2^20. Breaks: stage_images.cpp's fog start, end or density printed in eye-space units
// (its division or multiplication by viewScale dropped), or the depth image's distances not divided by
// viewScale.
TEST_F(StageImagesTest, CaptionsOfAScaledSceneSpeakTheScenesUnits) {
    const double s = 0x1p20;
    const auto vertex = [s](double x, double y) {
        return "v " + std::to_string(x * s) + " " + std::to_string(y * s) + " 0\n";
    };
    Scene scene = sceneOf(vertex(-2, -1) + vertex(2, -1) + vertex(2, 1) + vertex(-2, 1) + "f 1 2 3 4\n");
    scene.camera.eye = vec3(0.0f, 0.0f, float(5 * s));
    scene.camera.near = float(s);
    scene.camera.far = float(10 * s);
    scene.fog.mode = FogMode::Linear;
    scene.fog.start = float(3 * s);
    scene.fog.end = float(7 * s);
    const PreparedScene prepared = prepareScene(scene);
    ASSERT_NE(prepared.camera.viewScale, 1.0);
    const std::vector<Rendered> images = renderAll(prepared, {.buildFrames = 0});
    const Rendered fog = find(images, "fog-factor");
    EXPECT_NEAR(valueAfter(fog.image.description, "with start ") / (3 * s), 1.0, 1e-3)
        << fog.image.description;
    EXPECT_NEAR(valueAfter(fog.image.description, "and end ") / (7 * s), 1.0, 1e-3) << fog.image.description;
    EXPECT_NEAR(rgbAt(fog, pixelOf(prepared, vec3(0.0f))).r, 0.5f, 1e-5f);  // (7 − 5)/(7 − 3)
    const Rendered depth = find(images, "depth");
    EXPECT_NEAR(valueAfter(depth.image.title, "white ") / (5 * s), 1.0, 1e-3) << depth.image.title;
    EXPECT_NEAR(valueAfter(depth.image.title, "dark grey ") / (5 * s), 1.0, 1e-3) << depth.image.title;

    scene.fog.start.reset();
    scene.fog.end.reset();
    scene.fog.density = float(0.2 / s);
    for (const FogMode mode : {FogMode::Exponential, FogMode::ExponentialSquared}) {
        scene.fog.mode = mode;
        const std::string caption =
            find(renderAll(prepareScene(scene), {.buildFrames = 0}), "fog-factor").image.description;
        EXPECT_NEAR(valueAfter(caption, "with density ") / (0.2 / s), 1.0, 1e-3) << caption;
    }
}

// A transparent triangle (A, opacity 0.5) in front of an opaque one (B). Break: counting the fragments
// of opaque draws as layers too (B alone would show 1).
TEST_F(StageImagesTest, LayersCountTheTransparentFragmentsBlended) {
    Scene scene = sceneOf(kNearTriangle);
    scene.objects[0].material.opacity = 0.5f;
    addObject(scene, kFarTriangle);
    const PreparedScene prepared = prepareScene(scene);
    const Rendered layers = find(renderAll(prepared, {.buildFrames = 0}), "layers");
    EXPECT_EQ(rgbAt(layers, pixelOf(prepared, kOverlap)), heatColor(1, 1));
    EXPECT_EQ(rgbAt(layers, pixelOf(prepared, kNearOnly)), heatColor(1, 1));
    EXPECT_EQ(rgbAt(layers, pixelOf(prepared, kFarOnly)), vec3(0.0f));
}

// Break: the build-up ignoring its triangle count (every frame the whole scene).
TEST_F(StageImagesTest, BuildUpDrawsTheTrianglesInOrder) {
    const PreparedScene prepared = prepareScene(sceneOf(kSideBySide));
    const std::vector<Rendered> images = renderAll(prepared, {.buildFrames = 2});
    const Rendered first = find(images, "build-001");
    const Rendered final = find(images, "final");
    EXPECT_EQ(rgbAt(first, pixelOf(prepared, kLeftCentre)), rgbAt(final, pixelOf(prepared, kLeftCentre)));
    EXPECT_EQ(first.pixels.at(pixelOf(prepared, kRightCentre).x, pixelOf(prepared, kRightCentre).y),
              prepared.clearColor);
    EXPECT_NE(rgbAt(final, pixelOf(prepared, kRightCentre)), vec3(prepared.clearColor));
}

// The bundled intersecting quads: an opaque backdrop and three transparent panes, sorted back to front
// or in exact per-pixel lists. Break: the last frame's count one short (k·T/N − 1, or frames + 1 of them).
class LastBuildFrame : public ::testing::TestWithParam<TransparencyMode> {};

TEST_P(LastBuildFrame, EqualsTheFinalImage) {
    Scene scene = loadScene(kModels / "intersecting-quads.json");
    scene.width = 80;
    scene.height = 60;
    scene.transparency.mode = GetParam();
    const PreparedScene prepared = prepareScene(scene);
    const std::vector<Rendered> images = renderAll(prepared, {.buildFrames = 3});
    EXPECT_EQ(ids(images).back(), "build-003");
    EXPECT_EQ(find(images, "build-003").pixels.pixels, find(images, "final").pixels.pixels);
    EXPECT_EQ(find(images, "build-003").encoding, prepared.encoding);
}

INSTANTIATE_TEST_SUITE_P(StageImages, LastBuildFrame,
                         ::testing::Values(TransparencyMode::Sorted, TransparencyMode::Exact));

// The final image's PNG is facet render's, byte for byte: a scene with fog, a textured model and a
// glass cube, shaded per vertex. Break: the final image written linearly (as the data images are), or
// drawn from the per-pixel copy the observer watches.
TEST_F(StageImagesTest, FinalImageIsFacetRendersFileByteForByte) {
    const fs::path input = kModels / "fog-and-glass.json";
    const fs::path rendered = folder_ / "render.png";
    const std::string command = std::string(FACET_BINARY) +
                                " render -q --threads 2 --shading gouraud --width 64 --height 48 " +
                                input.string() + " -o " + rendered.string();
    ASSERT_EQ(std::system(command.c_str()), 0) << command;

    Scene scene = loadSceneOrModel(input);
    scene.width = 64;
    scene.height = 48;
    scene.lighting.shading = ShadingFrequency::Gouraud;
    for (ObjectSpec& object : scene.objects)
        object.shading = ShadingFrequency::Gouraud;
    const std::vector<StageImage> written =
        writeStageImages(prepareScene(scene), folder_ / "stages", {.buildFrames = 0, .threads = 1});
    ASSERT_FALSE(written.empty());
    EXPECT_EQ(written.back().id, "final");
    EXPECT_EQ(fileBytes(folder_ / "stages" / written.back().file), fileBytes(rendered));
    for (const StageImage& image : written)
        EXPECT_TRUE(fs::exists(folder_ / "stages" / image.file)) << image.file;
}

// The images for slides: at scale 3 every file holds the scale-1 file's pixels, each repeated as a 3×3
// block, in every stage image (colour and data). Catches: a magnification that blurs or shifts pixels
// (filtering, an off-by-one block), or one image left at the frame's size.
TEST_F(StageImagesTest, ScaleRepeatsEveryPixelOfEveryImageAsABlock) {
    const PreparedScene prepared = prepareScene(sceneOf(kSideBySide));
    const std::vector<StageImage> plain =
        writeStageImages(prepared, folder_ / "x1", {.buildFrames = 2, .threads = 1});
    const std::vector<StageImage> large =
        writeStageImages(prepared, folder_ / "x3", {.buildFrames = 2, .threads = 1, .scale = 3});
    ASSERT_EQ(plain.size(), large.size());
    for (std::size_t k = 0; k < plain.size(); ++k) {
        ASSERT_EQ(plain[k].file, large[k].file);
        const LinearImage one = readImage(folder_ / "x1" / plain[k].file);
        const LinearImage three = readImage(folder_ / "x3" / large[k].file);
        ASSERT_EQ(one.width, 40);
        ASSERT_EQ(three.width, 3 * one.width) << plain[k].file;
        ASSERT_EQ(three.height, 3 * one.height) << plain[k].file;
        std::size_t differing = 0;
        for (int y = 0; y < three.height; ++y)
            for (int x = 0; x < three.width; ++x)
                differing += three.at(x, y) != one.at(x / 3, y / 3);
        EXPECT_EQ(differing, 0u) << plain[k].file;
    }
}

}  // namespace
}  // namespace facet::step
