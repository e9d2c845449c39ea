// Environment maps and height fog in whole frames: the background is the map along each pixel's view
// ray (checked against a ray and a lookup computed here), a mirror sphere's centre shows what is behind
// the camera, the rasterizer agrees with the exact reference, the same bytes at any thread count, the
// scene keys and flags reach the image, and bad input is one line naming the file and the key.
#include <cmath>
#include <fstream>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "io/image_io.h"
#include "reference/reference.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "support/bundled_models.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using testing_support::TempFolder;

constexpr double kPi = std::numbers::pi;

// A 256×128 map whose texel (i, j) holds codes (i, 2j, 0) read linearly: the bilinear lookup at (u, v)
// is then red = (256·u − ½)/255, green = 2·(128·(1 − v) − ½)/255, away from the seam and the poles.
fs::path gradientMap(const TempFolder& folder) {
    LinearImage image;
    image.width = 256;
    image.height = 128;
    image.pixels.resize(256 * 128);
    for (int j = 0; j < 128; ++j)
        for (int i = 0; i < 256; ++i)
            image.at(i, j) = glm::vec4(float(i) / 255.0f, float(2 * j) / 255.0f, 0.0f, 1.0f);
    const fs::path path = folder.path() / "gradient.png";
    writeImage(path, image, kLinearEncoding);
    return path;
}

// A map red where u < 1/8 or u > 7/8 (around +z, behind a default camera), blue elsewhere.
fs::path behindMap(const TempFolder& folder) {
    LinearImage image;
    image.width = 64;
    image.height = 32;
    image.pixels.resize(64 * 32);
    for (int j = 0; j < 32; ++j)
        for (int i = 0; i < 64; ++i)
            image.at(i, j) = (i < 8 || i >= 56) ? glm::vec4(1, 0, 0, 1) : glm::vec4(0, 0, 1, 1);
    const fs::path path = folder.path() / "behind.png";
    writeImage(path, image, kLinearEncoding);
    return path;
}

Scene sceneFrom(const TempFolder& folder, const std::string& json) {
    return loadScene(folder.write("scene.json", json));
}

LinearImage rasterize(const PreparedScene& prepared, int threads = 1) {
    Framebuffer framebuffer(prepared.scene.width, prepared.scene.height);
    DrawContext context(threads);
    renderFrame(prepared, framebuffer, context);
    return toImage(framebuffer);
}

using testing_support::kCube;
const std::string kSphere = FACET_SOURCE_DIR "/models/environment/sphere.obj";

TEST(EnvironmentFrame, BackgroundIsTheMapAlongEachViewRay) {
    const TempFolder folder;
    gradientMap(folder);
    // A small cube at the centre; the camera at +5 z looking down −z, 60° vertical field of view.
    const Scene scene = sceneFrom(folder, R"({"width": 64, "height": 48,
        "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0], "fovy": 60},
        "objects": [{"model": ")" + kCube + R"(", "scale": 0.2}],
        "environment": {"image": "gradient.png", "encoding": "linear"}})");
    const PreparedScene prepared = prepareScene(scene);
    const LinearImage image = rasterize(prepared);
    const double t = std::tan(kPi / 6.0), aspect = 64.0 / 48.0;
    int checked = 0;
    for (int y = 0; y < 48; y += 3)
        for (int x = 0; x < 64; x += 3) {
            if (std::abs(x - 32) < 8 && std::abs(y - 24) < 8) continue;  // the cube
            // The view ray through the pixel centre, in world space (the camera is not turned).
            const double dx = (2.0 * (x + 0.5) / 64 - 1.0) * t * aspect,
                         dy = (1.0 - 2.0 * (y + 0.5) / 48) * t;
            const double length = std::sqrt(dx * dx + dy * dy + 1.0);
            const double u = 0.5 + std::atan2(dx, 1.0) / (2 * kPi), v = 0.5 + std::asin(dy / length) / kPi;
            const glm::vec4 p = image.at(x, y);
            EXPECT_NEAR(p.r, (256.0 * u - 0.5) / 255.0, 2e-4) << x << "," << y;
            EXPECT_NEAR(p.g, 2.0 * (128.0 * (1.0 - v) - 0.5) / 255.0, 2e-4) << x << "," << y;
            ++checked;
        }
    EXPECT_GT(checked, 250);
    // Without "background": the clear colour, not the map.
    Scene plain = scene;
    plain.environment->background = false;
    EXPECT_EQ(rasterize(prepareScene(plain)).at(0, 0), prepareScene(plain).clearColor);
}

TEST(EnvironmentFrame, SameBytesAtAnyThreadCountAndUnderSupersampling) {
    const TempFolder folder;
    gradientMap(folder);
    Scene scene = sceneFrom(folder, R"({"width": 80, "height": 60,
        "objects": [{"model": ")" + kSphere +
                                        R"(", "material": {"specular": [0.6, 0.6, 0.6]}}],
        "environment": {"image": "gradient.png", "encoding": "linear", "rotation": 30}})");
    const PreparedScene prepared = prepareScene(scene);
    EXPECT_EQ(rasterize(prepared, 1).pixels, rasterize(prepared, 4).pixels);
    scene.pipeline.antialiasing = Antialiasing::Ssaa4;
    const PreparedScene ssaa = prepareScene(scene);
    const LinearImage a = rasterize(ssaa, 1), b = rasterize(ssaa, 3);
    EXPECT_EQ(a.pixels, b.pixels);
    // The passes average four directions around the pixel centre: close to the single-sample frame's.
    const glm::vec4 one = rasterize(prepared).at(0, 0), four = a.at(0, 0);
    EXPECT_NEAR(one.r, four.r, 0.01f);
    EXPECT_NEAR(one.g, four.g, 0.01f);
}

TEST(EnvironmentFrame, MirrorSphereCentreReflectsWhatIsBehindTheCamera) {
    const TempFolder folder;
    behindMap(folder);
    // A black sphere whose only light is the map's reflection, weighted by m_specular = 1: at its centre
    // N = V = +z, so R = +z, the direction behind the camera (red in the map).
    const Scene scene = sceneFrom(folder, R"({"width": 41, "height": 41, "ambient": [0, 0, 0],
        "camera": {"eye": [0, 0, 4], "target": [0, 0, 0], "fovy": 40},
        "lights": [{"type": "directional", "direction": [0, 0, 1]}],
        "objects": [{"model": ")" + kSphere + R"(",
                     "material": {"ambient": [0, 0, 0], "diffuse": [0, 0, 0], "specular": [1, 1, 1]}}],
        "environment": {"image": "behind.png", "encoding": "linear", "background": false}})");
    const LinearImage image = rasterize(prepareScene(scene));
    const glm::vec4 centre = image.at(20, 20);
    EXPECT_GT(centre.r, 0.95f);
    EXPECT_LT(centre.b, 0.05f);
    // Turned by 180°, the map puts blue behind the camera.
    Scene turned = scene;
    turned.environment->rotationDegrees = 180.0f;
    const glm::vec4 turnedCentre = rasterize(prepareScene(turned)).at(20, 20);
    EXPECT_LT(turnedCentre.r, 0.05f);
    EXPECT_GT(turnedCentre.b, 0.95f);
}

// 8-bit sRGB code of a linear value.
int code(float linear) {
    return int(encodeChannel(linear, kSrgbEncoding));
}

TEST(EnvironmentFrame, RasterizerAgreesWithTheReference) {
    Scene scene = loadScene(FACET_SOURCE_DIR "/models/environment.json");
    scene.width = 160;
    scene.height = 120;
    const PreparedScene prepared = prepareScene(scene);
    const LinearImage raster = rasterize(prepared, 2);
    ThreadPool pool(2);
    const LinearImage reference = renderReference(prepared, {.samples = 1}, pool);
    std::size_t close = 0, background = 0, backgroundExact = 0;
    int worst = 0;
    for (std::size_t i = 0; i < raster.pixels.size(); ++i) {
        int d = 0;
        for (int c = 0; c < 3; ++c)
            d = std::max(d, std::abs(code(raster.pixels[i][c]) - code(reference.pixels[i][c])));
        close += d <= 3;
        worst = std::max(worst, d);
    }
    // The background: the reference's ray and the rasterizer's agree to a code or less everywhere.
    for (int x = 0; x < 160; x += 7) {
        const std::size_t i = static_cast<std::size_t>(x);  // the top row: sky, no surface
        ++background;
        int d = 0;
        for (int c = 0; c < 3; ++c)
            d = std::max(d, std::abs(code(raster.pixels[i][c]) - code(reference.pixels[i][c])));
        backgroundExact += d <= 1;
    }
    EXPECT_EQ(backgroundExact, background);
    EXPECT_GE(double(close) / double(raster.pixels.size()), 0.97) << "worst " << worst;
}

TEST(EnvironmentFrame, HeightFogReachesTheImage) {
    const TempFolder folder;
    const std::string objects = R"("objects": [{"model": ")" + kCube + R"("}], "width": 40, "height": 30)";
    const LinearImage clear = rasterize(prepareScene(sceneFrom(folder, "{" + objects + "}")));
    const LinearImage fogged = rasterize(prepareScene(sceneFrom(
        folder,
        "{" + objects +
            R"(, "fog": {"mode": "height", "color": [1, 1, 1], "density": 0.3, "falloff": 2, "base_height": 0}})")));
    const LinearImage thinner = rasterize(prepareScene(sceneFrom(
        folder,
        "{" + objects +
            R"(, "fog": {"mode": "height", "color": [1, 1, 1], "density": 0.3, "falloff": 2, "base_height": -3}})")));
    // The cube's centre pixel: whiter with fog, less so with the fog's base lowered.
    const glm::vec4 a = clear.at(20, 15), b = fogged.at(20, 15), c = thinner.at(20, 15);
    EXPECT_GT(b.g, a.g + 0.02f);
    EXPECT_GT(b.g, c.g + 0.01f);
    EXPECT_GT(c.g, a.g);
}

TEST(EnvironmentFrame, BadInputIsOneLineNamingFileAndKey) {
    const TempFolder folder;
    try {
        sceneFrom(folder, R"({"model": ")" + kCube + R"(", "environment": {"image": "missing.png"}})");
        FAIL() << "no error";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("environment.image"), std::string::npos) << message;
        EXPECT_NE(message.find("missing.png"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    gradientMap(folder);
    try {
        sceneFrom(folder, R"({"model": ")" + kCube +
                              R"(", "environment": {"image": "gradient.png", "encoding": "gamma"}})");
        FAIL() << "no error";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("environment.encoding"), std::string::npos) << message;
        EXPECT_NE(message.find("\"srgb\""), std::string::npos) << message;
    }
    // A file that is not an image: the load names the file and where it came from.
    folder.write("not-an-image.png", "hello");
    Scene scene =
        sceneFrom(folder, R"({"model": ")" + kCube + R"(", "environment": {"image": "not-an-image.png"}})");
    try {
        prepareScene(scene);
        FAIL() << "no error";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("not-an-image.png"), std::string::npos) << message;
        EXPECT_NE(message.find("environment.image"), std::string::npos) << message;
    }
    // Height-fog keys with another mode are refused.
    EXPECT_THROW(sceneFrom(folder, R"({"model": ")" + kCube + R"(", "fog": {"mode": "exp", "falloff": 1}})"),
                 InputError);
}

}  // namespace
}  // namespace facet
