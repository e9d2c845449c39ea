// The texture knobs reach the image: --texture-filter and --textures on the command line, and the scene
// file's "textures": {"filter", "maps"}, each change the rendered image of a textured scene (the
// checkerboard floor of support/checker_scene.h) in the way asked, and a bad value is refused.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "cli/render_command.h"
#include "render/renderer.h"
#include "support/checker_scene.h"
#include "support/temp_folder.h"

namespace facet::cli {
namespace {

using testing_support::TempFolderTest;
using testing_support::writeCheckerScene;

class TextureOptionsTest : public TempFolderTest {
  protected:
    // `facet render SCENE -o out.png ARGS...`: the scene as the command line makes it, rendered.
    static std::vector<glm::vec4> render(const std::filesystem::path& scenePath,
                                         std::vector<std::string> args) {
        CLI::App app;
        RenderArgs parsed;
        addRenderCommand(app, parsed);
        args.insert(args.begin(), {"render", scenePath.string(), "-o", "out.png"});
        std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
        app.parse(reversed);
        const PreparedScene prepared = prepareScene(sceneFromArgs(parsed));
        Framebuffer framebuffer(prepared.scene.width, prepared.scene.height);
        DrawContext context(1);
        renderFrame(prepared, framebuffer, context);
        return framebuffer.colorPixels();
    }
};

// Breaks caught: --texture-filter parsed but not applied to the scene, the scene's filter not copied
// into the draws' uniforms, or "textures.filter" not read from the file.
TEST_F(TextureOptionsTest, FilterFromCommandLineAndSceneFileReachesTheImage) {
    const std::filesystem::path scene = writeCheckerScene(folder_);
    const std::vector<glm::vec4> bilinear = render(scene, {});
    EXPECT_EQ(render(scene, {"--texture-filter", "bilinear"}), bilinear);
    const std::vector<glm::vec4> nearest = render(scene, {"--texture-filter", "nearest"});
    const std::vector<glm::vec4> trilinear = render(scene, {"--texture-filter", "trilinear"});
    EXPECT_NE(nearest, bilinear);
    EXPECT_NE(trilinear, bilinear);
    EXPECT_NE(trilinear, nearest);
    std::filesystem::create_directories(folder_ / "file");
    EXPECT_EQ(render(writeCheckerScene(folder_ / "file", R"({"filter": "trilinear"})"), {}), trilinear);
    EXPECT_EQ(render(writeCheckerScene(folder_ / "file", R"({"filter": "nearest"})"), {}), nearest);
    // The command line wins over the file.
    EXPECT_EQ(render(writeCheckerScene(folder_ / "file", R"({"filter": "nearest"})"),
                     {"--texture-filter", "trilinear"}),
              trilinear);
}

// Off draws the floor in its material's colour alone: the image of the same scene whose MTL has no
// map_Kd. Breaks caught: --textures or "textures.maps" not applied, or only the emission map ignored.
TEST_F(TextureOptionsTest, TexturesOffDrawsTheMaterialsColours) {
    const std::filesystem::path scene = writeCheckerScene(folder_);
    const std::vector<glm::vec4> textured = render(scene, {});
    const std::vector<glm::vec4> off = render(scene, {"--textures", "off"});
    EXPECT_NE(off, textured);
    EXPECT_EQ(render(scene, {"--textures", "on"}), textured);
    std::filesystem::create_directories(folder_ / "file");
    EXPECT_EQ(render(writeCheckerScene(folder_ / "file", R"({"maps": "off"})"), {}), off);
    std::filesystem::create_directories(folder_ / "plain");
    const std::filesystem::path plain = writeCheckerScene(folder_ / "plain");
    std::ofstream(folder_ / "plain" / "plane.mtl") << "newmtl checker\nKa 0 0 0\nKd 1 1 1\nKs 0 0 0\n";
    EXPECT_EQ(render(plain, {}), off);
}

// Values outside the tables are refused, naming what is allowed.
TEST_F(TextureOptionsTest, BadValuesAreRefused) {
    const std::filesystem::path scene = writeCheckerScene(folder_);
    EXPECT_THROW(render(scene, {"--texture-filter", "cubic"}), CLI::ParseError);
    EXPECT_THROW(render(scene, {"--textures", "yes"}), CLI::ParseError);
    try {
        render(writeCheckerScene(folder_, R"({"filter": "anisotropic"})"), {});
        ADD_FAILURE() << "not refused";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("textures.filter"), std::string::npos) << message;
        EXPECT_NE(message.find("trilinear"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace facet::cli
