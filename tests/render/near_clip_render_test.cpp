// A huge ground seen through a small near plane, drawn end to end in every depth format; and the
// relation z_c = slope·w + offset the renderer hands the clipper (scene/camera.h, clipDepthFromW).
#include <cmath>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "pipeline/names.h"
#include "render/renderer.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

using NearClipRenderTest = testing_support::TempFolderTest;

constexpr int kWidth = 64, kHeight = 48;

// A ground quad of ±1e6 units at y = 0, the eye 2 units above it looking level along −z, near 0.015
// (the unorm16 buffer still keeps depths out to n·2·65535 ≈ 1966 units, so no format refuses it), drawn
// in `depth`.
LinearImage renderGround(const fs::path& folder, const std::string& depth) {
    std::ofstream(folder / "ground.obj") << "v -1000000 0 -1000000\nv 1000000 0 -1000000\n"
                                            "v 1000000 0 1000000\nv -1000000 0 1000000\n"
                                            "vn 0 1 0\nf 1//1 4//1 3//1\nf 1//1 3//1 2//1\n";
    const fs::path scene = folder / ("ground-" + depth + ".json");
    std::ofstream(scene) << R"({"width": )" << kWidth << R"(, "height": )" << kHeight
                         << R"(, "background": [0, 0, 0], "ambient": [0.2, 0.2, 0.2],
        "camera": {"eye": [0, 2, 0], "target": [0, 2, -10], "fovy": 60, "near": 0.015},
        "lights": [{"type": "directional", "direction": [0, -1, -1]}],
        "objects": [{"model": "ground.obj"}],
        "pipeline": {"cull": "none", "depth": ")"
                         << depth << R"("}})";
    const PreparedScene prepared = prepareScene(loadScene(scene));
    Framebuffer framebuffer(kWidth, kHeight);
    DrawContext context(1);
    renderFrame(prepared, framebuffer, context);
    return toImage(framebuffer);
}

// The eye looks level, so the ground fills the image's lower half: rows 24..47, whose pixel centres
// lie at least half a row (0.625°) below the horizon, at most 2/tan(0.625°) ≈ 183 units away, well
// inside what every buffer keeps. Each format draws those pixels and only those, the same colours as
// reversed Z (one surface: the depth format changes nothing else).
// Catches: the ground vanishing under float, unorm16 and unorm24 depth (every vertex the clipper made
// got window depth 1 and failed "1 < 1" against the cleared buffer) while reversed Z drew it.
TEST_F(NearClipRenderTest, HugeGroundDrawsInEveryDepthFormat) {
    const LinearImage reversed = renderGround(folder_, "reversed-float");
    std::size_t ground = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const glm::vec4 p = reversed.pixels[std::size_t(y) * kWidth + x];
            const bool drawn = p.r > 0.0f || p.g > 0.0f || p.b > 0.0f;
            EXPECT_EQ(drawn, y >= kHeight / 2) << "reversed-float, pixel " << x << ", " << y;
            ground += drawn;
        }
    ASSERT_EQ(ground, std::size_t(kWidth * kHeight / 2));
    for (const char* depth : {"float", "unorm16", "unorm24"}) {
        SCOPED_TRACE(depth);
        const LinearImage image = renderGround(folder_, depth);
        ASSERT_EQ(image.pixels.size(), reversed.pixels.size());
        std::size_t differing = 0;
        for (std::size_t i = 0; i < image.pixels.size(); ++i)
            differing += image.pixels[i] != reversed.pixels[i];
        EXPECT_EQ(differing, 0u);
    }
}

// z_c − (slope·w_c + offset) for the eye-space point (x, y, z_e) under `p`, relative to |z_c|.
double relationError(const glm::dmat4& p, const DepthFromW& fromW, glm::dvec3 eye) {
    const glm::dvec4 clip = p * glm::dvec4(eye, 1.0);
    return std::abs(clip.z - (fromW.slope * clip.w + fromW.offset)) / std::max(std::abs(clip.z), 1e-300);
}

// The relation holds for any point under the projections the camera draws with: OpenGL's, reversed Z's
// and the infinite far plane's; an orthographic projection (w = 1 at every depth) has none.
// Catches: a relation read from the wrong matrix entries (the clipper would give new vertices depths
// off the projection), or one claimed for an orthographic projection.
TEST(ClipDepthFromW, HoldsForTheCamerasProjections) {
    CameraSpec spec;
    spec.eye = glm::vec3(0.0f, 2.0f, 5.0f);
    spec.target = glm::vec3(0.0f);
    spec.fovyDegrees = 60.0f;
    spec.near = 0.5f;
    spec.far = 50.0f;
    const Bounds bounds{glm::vec3(-1.0f), glm::vec3(1.0f)};
    const glm::dvec3 points[] = {{0.1, 0.2, -0.7}, {3.0, -1.0, -20.0}, {-4.0, 2.0, -49.0}, {1.0, 1.0, 3.0}};
    for (const DepthBufferFormat format : {DepthBufferFormat::Float, DepthBufferFormat::ReversedFloat}) {
        for (const bool infinite : {false, true}) {
            SCOPED_TRACE(std::string(nameOf(format)) + (infinite ? ", infinite far" : ""));
            CameraSpec s = spec;
            if (infinite) s.far.reset(), s.infiniteFar = true;
            const Camera camera = frameCamera(s, bounds, 4.0f / 3.0f, format);
            const glm::dmat4 p = drawnClipFromView(camera);
            const DepthFromW fromW = clipDepthFromW(p);
            ASSERT_TRUE(fromW.known);
            for (const glm::dvec3& point : points)
                EXPECT_LT(relationError(p, fromW, point), 1e-12);
        }
    }
    EXPECT_FALSE(clipDepthFromW(glm::ortho(-1.0, 1.0, -1.0, 1.0, 0.5, 50.0)).known);
}

}  // namespace
}  // namespace facet
