// Conformance with OpenGL: each scene in tests/conformance/scenes is rendered by Facet and by Mesa's
// softpipe (its reference rasterizer) through OSMesa, and the two 8-bit images are compared pixel by
// pixel. The scenes cover the gl preset with fixed-function Gouraud and flat shading, GLSL programs for
// per-pixel Phong and Blinn-Phong and per-vertex shading, and Cook-Torrance with every D, F and G, in
// both colour conventions, with several lights of each kind, emission and high shininess, on five
// models. The bar: at least 99.5% of the pixels within 2/255 on every channel. The pixels that differ
// more lie on edges, where the two rasterizers decide coverage differently (a silhouette against the
// background, or a seam where two surfaces meet); the test prints where they are. Agreement alone
// proves nothing when nothing is drawn (two empty images agree on every pixel), so each scene must also
// cover a twentieth of the image in Facet's image and in Mesa's. The tests need OSMesa and are skipped
// without it (support/mesa_fixture.h); tests/render/renderer_test.cpp guards, without Mesa, that a
// scene's draws are planned and drawn.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "oracle/compare.h"
#include "support/mesa_fixture.h"

namespace facet {
namespace {

const std::filesystem::path kScenes = std::filesystem::path(FACET_SOURCE_DIR) / "tests/conformance/scenes";

std::vector<std::string> sceneNames() {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(kScenes))
        if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

// The models a scene file names, resolved against its folder.
std::vector<std::filesystem::path> modelsOf(const std::filesystem::path& sceneFile) {
    std::ifstream in(sceneFile);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<std::filesystem::path> models;
    const std::regex model("\"model\":\\s*\"([^\"]+\\.obj)\"");  // not "lighting": {"model": ...}
    for (auto it = std::sregex_iterator(text.begin(), text.end(), model); it != std::sregex_iterator(); ++it)
        models.push_back(sceneFile.parent_path() / (*it)[1].str());
    return models;
}

// Skipped where OSMesa cannot give softpipe.
class OpenGlConformance : public MesaTest<MesaDriver::Softpipe, ::testing::TestWithParam<std::string>> {};

TEST_P(OpenGlConformance, AtLeast99Point5PercentOfPixelsWithin2Of255) {
    const std::filesystem::path file = kScenes / (GetParam() + ".json");
    for (const auto& model : modelsOf(file))
        if (!std::filesystem::exists(model)) GTEST_SKIP() << model << " is not here";

    const Scene scene = loadScene(file);
    const MesaComparison result = compareWithMesa(scene, MesaDriver::Softpipe);
    std::cout << GetParam() << "\n" << describe(result);
    const PixelDifference& d = result.difference;
    RecordProperty("within1", std::to_string(d.within1));
    RecordProperty("within2", std::to_string(d.within2));
    RecordProperty("maxDifference", d.maxDifference);
    // Covered pixels: those whose colour is not the clear colour, in each image (both are float
    // buffers, cleared to exactly that colour; comparePixels counts them). Counting agreeing pixels
    // instead let a frame that drew nothing on either side pass.
    RecordProperty("coveredByFacet", std::to_string(d.coveredA));
    RecordProperty("coveredByMesa", std::to_string(d.coveredB));
    EXPECT_GT(d.coveredA, d.pixels / 20) << "Facet's image must cover a twentieth of the pixels";
    EXPECT_GT(d.coveredB, d.pixels / 20) << "Mesa's image must cover a twentieth of the pixels";
    EXPECT_GE(d.within2, MesaComparison::kMinWithin2);
    // Most pixels are identical, not merely close: the formulas are the same, only rounding differs.
    EXPECT_GE(double(d.pixels - d.differing) / double(d.pixels), 0.99);
}

INSTANTIATE_TEST_SUITE_P(Scenes, OpenGlConformance, ::testing::ValuesIn(sceneNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                             std::string name = info.param;
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

}  // namespace
}  // namespace facet
