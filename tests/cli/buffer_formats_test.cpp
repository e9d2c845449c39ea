// Plumbing of the buffer formats: --depth, --color-buffer and --infinite-far on the command line, and
// "pipeline": {"depth", "color_buffer"} and "camera": {"far": "infinite"} in a scene file, each reach
// the rendered image (or the projection it is drawn with), so that a driver ignoring one fails here.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/temp_folder.h"
#include "base/errors.h"
#include "cli/render_command.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace facet::cli {
namespace {

// Two parallel squares facing the camera, 5 and 5.002 away (a gap of 4e-4 relative): the 32-bit float
// buffer tells them apart there (its steps are about 1.5e-5 apart), a 16-bit one (3.8e-3) does not.
// The far one (green) is drawn first, the near one (red) second.
constexpr const char* kFarSquare = "v -2 -2 -0.002\nv 2 -2 -0.002\nv 2 2 -0.002\nv -2 2 -0.002\nf 1 2 3 4\n";
constexpr const char* kNearSquare = "v -2 -2 0\nv 2 -2 0\nv 2 2 0\nv -2 2 0\nf 1 2 3 4\n";

class BufferFormatPlumbing : public testing_support::TempFolderTest {
  protected:
    std::string sceneFile(const std::string& pipeline, const std::string& far = "100") {
        write("far.obj", kFarSquare);
        write("near.obj", kNearSquare);
        std::string text = R"({"width": 32, "height": 24, "background": [0.2, 0.2, 0.2],
            "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "near": 0.1, "far": )";
        text += far;
        text += R"(},
            "objects": [
              {"model": "far.obj", "material": {"diffuse": [0, 1, 0]}},
              {"model": "near.obj", "material": {"diffuse": [1, 0, 0]}}
            ],
            "pipeline": {)";
        text += pipeline;
        text += "}}";
        return write("scene.json", text).string();
    }

    // `facet render SCENE -o out.png ARGS...`, parsed and applied.
    static Scene sceneFromCommandLine(const std::string& scene, std::vector<std::string> args) {
        CLI::App app;
        RenderArgs parsed;
        addRenderCommand(app, parsed);
        args.insert(args.begin(), {"render", scene, "-o", "out.png"});
        std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
        app.parse(reversed);
        return sceneFromArgs(parsed);
    }

    static std::vector<vec4> render(const Scene& scene) {
        const PreparedScene prepared = prepareScene(scene);
        Framebuffer target(scene.width, scene.height);
        DrawContext context(1);
        renderFrame(prepared, target, context);
        return target.colorPixels();
    }

    // The share of pixels that show the far, green square.
    static double greenShare(const std::vector<vec4>& pixels) {
        const auto green = std::count_if(pixels.begin(), pixels.end(),
                                         [](const vec4& c) { return c.g > 0.1f && c.r < 0.05f; });
        return double(green) / double(pixels.size());
    }
};

// Float: the near (red) square hides the far one; unorm16, from the command line or the scene file:
// the green one shows through (the two squares store the same codes). Breaks if either way of
// choosing the format is dropped.
TEST_F(BufferFormatPlumbing, DepthFormatReachesTheImage) {
    const std::string plain = sceneFile("");
    EXPECT_EQ(greenShare(render(sceneFromCommandLine(plain, {}))), 0.0);
    EXPECT_GT(greenShare(render(sceneFromCommandLine(plain, {"--depth", "unorm16"}))), 0.3);
    EXPECT_EQ(greenShare(render(sceneFromCommandLine(plain, {"--depth", "unorm24"}))), 0.0);
    EXPECT_EQ(greenShare(render(sceneFromCommandLine(plain, {"--depth", "reversed-float"}))), 0.0);
    const std::string unorm16 = sceneFile(R"("depth": "unorm16")");
    EXPECT_GT(greenShare(render(sceneFromCommandLine(unorm16, {}))), 0.3);
    // The command line wins over the file.
    EXPECT_EQ(greenShare(render(sceneFromCommandLine(unorm16, {"--depth", "float"}))), 0.0);
    EXPECT_THROW(sceneFromCommandLine(plain, {"--depth", "unorm32"}), CLI::ParseError);
}

// Unorm8, from the command line or the scene file: every channel of every pixel is a multiple of 1/255
// and the image differs from the float buffer's. Breaks if either way of choosing is dropped.
TEST_F(BufferFormatPlumbing, ColorBufferReachesTheImage) {
    const auto allEightBit = [](const std::vector<vec4>& pixels) {
        for (const vec4& c : pixels)
            for (int k = 0; k < 4; ++k)
                if (std::round(c[k] * 255.0f) / 255.0f != c[k]) return false;
        return true;
    };
    const std::string plain = sceneFile("");
    const std::vector<vec4> floatImage = render(sceneFromCommandLine(plain, {}));
    EXPECT_FALSE(allEightBit(floatImage));
    const std::vector<vec4> fromCommandLine =
        render(sceneFromCommandLine(plain, {"--color-buffer", "unorm8"}));
    EXPECT_TRUE(allEightBit(fromCommandLine));
    const std::vector<vec4> fromFile =
        render(sceneFromCommandLine(sceneFile(R"("color_buffer": "unorm8")"), {}));
    EXPECT_TRUE(allEightBit(fromFile));
    EXPECT_EQ(fromFile, fromCommandLine);
    const std::vector<vec4> half = render(sceneFromCommandLine(plain, {"--color-buffer", "half"}));
    EXPECT_NE(half, floatImage);
    EXPECT_THROW(sceneFromCommandLine(plain, {"--color-buffer", "rgb565"}), CLI::ParseError);
}

// --infinite-far and "far": "infinite" give the camera no far plane (the scene file's finite "far" is
// overridden); any other text for "far" is refused with a one-line message. Breaks if either is dropped.
TEST_F(BufferFormatPlumbing, InfiniteFarReachesTheCamera) {
    const auto far = [](const Scene& scene) { return prepareScene(scene).camera.far; };
    const std::string plain = sceneFile("");
    EXPECT_EQ(far(sceneFromCommandLine(plain, {})), 100.0f);
    EXPECT_TRUE(std::isinf(far(sceneFromCommandLine(plain, {"--infinite-far"}))));
    EXPECT_TRUE(std::isinf(far(sceneFromCommandLine(sceneFile("", R"("infinite")"), {}))));
    // Reversed Z with no far plane still separates the two squares.
    EXPECT_EQ(
        greenShare(render(sceneFromCommandLine(plain, {"--infinite-far", "--depth", "reversed-float"}))),
        0.0);
    try {
        sceneFromCommandLine(sceneFile("", R"("endless")"), {});
        ADD_FAILURE() << "\"far\": \"endless\" was accepted";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("\"camera.far\" must be a number or \"infinite\" (got \"endless\")"),
                  std::string::npos)
            << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace facet::cli
