// Scenes read from files and drawn: what the scene reader's values do to the image.
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "render/renderer.h"
#include "scene/scene.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

using SceneRenderTest = testing_support::TempFolderTest;

// ---- Directions of any length ---------------------------------------------------------------------

// The scene `text` (with "model" the bundled cube) drawn at 48×36 on one thread.
LinearImage renderCube(const fs::path& path, const std::string& text) {
    nlohmann::json document = nlohmann::json::parse(text);
    document["model"] = FACET_SOURCE_DIR "/models/cube/cube.obj";
    document["width"] = 48;
    document["height"] = 36;
    std::ofstream(path) << document.dump();
    const PreparedScene prepared = prepareScene(loadScene(path));
    Framebuffer framebuffer(48, 36);
    DrawContext context(1);
    renderFrame(prepared, framebuffer, context);
    return toImage(framebuffer);
}

// Only an exactly zero vector is refused; any other length lights the model exactly as the same
// direction at unit length (normalising in float turned 1e-30, 1e20 and -3e38 into NaN: black).
TEST_F(SceneRenderTest, DirectionsOfAnyLengthLightLikeUnitOnes) {
    const std::pair<std::string, std::string> cases[] = {
        {R"({"lights": [{"direction": [0, -1e-30, 0]}]})", R"({"lights": [{"direction": [0, -1, 0]}]})"},
        {R"({"lights": [{"direction": [0, -1e20, 0]}]})", R"({"lights": [{"direction": [0, -1, 0]}]})"},
        {R"({"lights": [{"direction": [-3e38, 0, 0]}]})", R"({"lights": [{"direction": [-1, 0, 0]}]})"},
        // 2^-100 · [1, -2, -2]: scaled by a power of two, the same unit vector to the last bit.
        {R"({"lights": [{"direction": [7.888609052210118e-31, -1.5777218104420236e-30, -1.5777218104420236e-30]}]})",
         R"({"lights": [{"direction": [1, -2, -2]}]})"},
        {R"({"lights": [{"type": "spot", "position": [0, 3, 0], "direction": [0, -1e-30, 0], "cutoff": 40}]})",
         R"({"lights": [{"type": "spot", "position": [0, 3, 0], "direction": [0, -1, 0], "cutoff": 40}]})"},
        {R"({"camera": {"eye": [2, 1, 3], "target": [0, 0, 0], "up": [0, 1e-30, 0]}})",
         R"({"camera": {"eye": [2, 1, 3], "target": [0, 0, 0], "up": [0, 1, 0]}})"},
        {R"({"camera": {"eye": [2, 1, 3], "target": [0, 0, 0], "up": [0, 3e38, 0]}})",
         R"({"camera": {"eye": [2, 1, 3], "target": [0, 0, 0], "up": [0, 1, 0]}})"},
    };
    for (const auto& [extreme, unit] : cases) {
        SCOPED_TRACE(extreme);
        const LinearImage expected = renderCube(folder_ / "unit.json", unit);
        const LinearImage actual = renderCube(folder_ / "extreme.json", extreme);
        // The cube is drawn and lit: some pixel is brighter than the background in the corner.
        bool lit = false;
        for (const glm::vec4& p : expected.pixels)
            lit = lit || p.r > expected.pixels[0].r + 0.05f;
        EXPECT_TRUE(lit);
        ASSERT_EQ(actual.pixels.size(), expected.pixels.size());
        std::size_t differing = 0;
        for (std::size_t i = 0; i < expected.pixels.size(); ++i)
            differing += actual.pixels[i] != expected.pixels[i];
        EXPECT_EQ(differing, 0u);
    }
}

}  // namespace
}  // namespace facet
