// Lighting at every scale the framing accepts: the bundled cube scaled by 1e30, 1e23, 1e-18 and 1e-30
// (a scene's object "scale") draws the unit cube's image, lit, in the rasterizer under every depth
// format and shading frequency and in the exact reference. Eye space is world space times a power of two
// near 1/size (Camera::viewScale), so every light vector, normal and direction must be formed after
// that scale and normalised where its length is still representable.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "pipeline/thread_pool.h"
#include "reference/reference.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

constexpr int kWidth = 48, kHeight = 36;

// How the cube is made large or small: by the scene's object transform, or in the OBJ's coordinates
// themselves (then the view's scale alone brings it to unit size, and normals see that scale).
enum class ScaledBy { Transform, Coordinates };

class ScaleExtremesTest : public testing_support::TempFolderTest {
  protected:
    // The bundled cube with its vertex positions times `scale`, written beside its material and texture.
    fs::path scaledCube(double scale) {
        const fs::path source = FACET_SOURCE_DIR "/models/cube";
        for (const char* file : {"default.mtl", "default.png"})
            fs::copy_file(source / file, folder_ / file, fs::copy_options::overwrite_existing);
        std::ifstream in(source / "cube.obj");
        std::ostringstream out;
        out.precision(17);
        for (std::string line; std::getline(in, line);) {
            std::istringstream fields(line);
            std::string tag;
            double x, y, z;
            if (fields >> tag && tag == "v" && fields >> x >> y >> z)
                out << "v " << x * scale << " " << y * scale << " " << z * scale << "\n";
            else
                out << line << "\n";
        }
        return write("cube.obj", out.str());
    }
    // The cube at `scale` (1: the model as it is), with `extra` merged into the scene document.
    PreparedScene prepare(double scale, Json extra, ScaledBy by = ScaledBy::Transform) {
        Json document = std::move(extra);
        if (by == ScaledBy::Transform)
            document["objects"] = {{{"model", FACET_SOURCE_DIR "/models/cube/cube.obj"}, {"scale", scale}}};
        else
            document["objects"] = {{{"model", scaledCube(scale).string()}}};
        document["width"] = kWidth;
        document["height"] = kHeight;
        const fs::path path = folder_ / "scene.json";
        std::ofstream(path) << document.dump();
        return prepareScene(loadScene(path));
    }
    LinearImage render(double scale, const Json& extra, ScaledBy by = ScaledBy::Transform) {
        const PreparedScene prepared = prepare(scale, extra, by);
        Framebuffer framebuffer(kWidth, kHeight);
        DrawContext context(1);
        renderFrame(prepared, framebuffer, context);
        return toImage(framebuffer);
    }
    LinearImage reference(double scale, const Json& extra, ScaledBy by = ScaledBy::Transform) {
        const PreparedScene prepared = prepare(scale, extra, by);
        ThreadPool pool(1);
        ReferenceOptions options;
        options.samples = 1;
        return renderReference(prepared, options, pool);
    }
};

// Pixels whose colour differs from `unit`'s by more than 2/255 in some channel (or is not finite).
int pixelsDiffering(const LinearImage& scaled, const LinearImage& unit) {
    int differing = 0;
    for (std::size_t i = 0; i < unit.pixels.size(); ++i) {
        const glm::vec4 d = glm::abs(scaled.pixels[i] - unit.pixels[i]);
        const float largest = glm::max(glm::max(d.r, d.g), glm::max(d.b, d.a));
        differing += !(largest <= 2.0f / 255.0f);
    }
    return differing;
}

// Pixels lit brighter than the background: the image shows a lit cube, not only its silhouette.
int pixelsLit(const LinearImage& image) {
    int lit = 0;
    for (const glm::vec4& p : image.pixels)
        lit += p.r > image.pixels[0].r + 0.1f;
    return lit;
}

const double kScales[] = {1e30, 1e23, 1e-18, 1e-30};

// The lights tried: the default key light (directional, given relative to the camera), a directional
// and a spot light of the scene file (world space), and no scene file lighting at all but Gouraud
// and flat shading. Tolerance: 2/255, in at most 2 pixels (a silhouette pixel centre may fall on the
// other side of an edge once the corners are scaled and rounded).
const Json kLightings[] = {
    Json::object(),
    Json{{"lights", {{{"type", "directional"}, {"direction", {0.3, -1.0, -0.5}}}}}},
    Json{{"lighting", {{"shading", "gouraud"}}}},
    Json{{"lighting", {{"shading", "flat"}}}},
};

// Catches: a light direction normalised in float after the view's scale (1e-30 squared underflows to
// 0, 1e30 overflows): N·L = NaN, an unlit (dark) model at 1e30 and 1e-30 units.
TEST_F(ScaleExtremesTest, RasterizerLightsEveryScaleAsTheUnitModelInEveryDepthFormat) {
    for (const char* depth : {"float", "unorm16", "unorm24", "reversed-float"})
        for (const Json& lighting : kLightings) {
            Json extra = lighting;
            extra["pipeline"]["depth"] = depth;
            SCOPED_TRACE(extra.dump());
            const LinearImage unit = render(1.0, extra);
            ASSERT_GT(pixelsLit(unit), 100);
            for (const double scale : kScales)
                for (const ScaledBy by : {ScaledBy::Transform, ScaledBy::Coordinates}) {
                    SCOPED_TRACE(::testing::Message() << "scale " << scale << " in " << int(by));
                    EXPECT_LE(pixelsDiffering(render(scale, extra, by), unit), 2);
                }
        }
}

// A spot light's axis is a direction too; its position and cone are scaled with the scene.
// Catches: the spot direction normalised in float after the view's scale (NaN cone factor: unlit).
TEST_F(ScaleExtremesTest, SpotLightLightsEveryScaleAsTheUnitModel) {
    for (const double scale : kScales) {
        SCOPED_TRACE(::testing::Message() << "scale " << scale);
        const auto spot = [](double s) {
            return Json{{"lights",
                         {{{"type", "spot"},
                           {"position", {1.0 * s, 2.0 * s, 3.0 * s}},
                           {"direction", {-1.0, -2.0, -3.0}},
                           {"cutoff", 30}}}}};
        };
        const LinearImage unit = render(1.0, spot(1.0));
        ASSERT_GT(pixelsLit(unit), 50);
        EXPECT_LE(pixelsDiffering(render(scale, spot(scale)), unit), 2);
    }
}

// The reference renderer (rays in double) shades with the rasterizer's lighting code: its normals must
// be scaled as the rasterizer's are (normal matrix of determinant 1), not shrunk by the view's scale.
// Catches: the reference's normals of length 2^-60 (a model of 1e-18 in its OBJ coordinates) clamped by the
// lighting's smallest normalisable length, a dim model; or its key light NaN at 1e30 and 1e-30.
TEST_F(ScaleExtremesTest, ReferenceLightsEveryScaleAsTheUnitModel) {
    const LinearImage unit = reference(1.0, Json::object());
    ASSERT_GT(pixelsLit(unit), 100);
    for (const double scale : kScales)
        for (const ScaledBy by : {ScaledBy::Transform, ScaledBy::Coordinates}) {
            SCOPED_TRACE(::testing::Message() << "scale " << scale << " in " << int(by));
            EXPECT_LE(pixelsDiffering(reference(scale, Json::object(), by), unit), 2);
        }
}

}  // namespace
}  // namespace facet
