// The trace is of exactly the frame `facet render` draws: its final 8-bit value at every traced pixel
// equals the byte of the image file the renderer writes, over scenes and settings that take different
// paths (opaque; sorted, unsorted and exact transparency; each fog; each shading frequency; the GL
// preset; a shader of one's own, opaque and transparent). Catches: the observed frame drawing anything
// differently (an observer hook that changes state, a draw call left out or added when observed, a
// user shader's watched draw that differs from its draw), and the trace encoding the colour otherwise
// than the image file (a channel, the encoding or its rounding).
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/image_file.h"
#include "io/image_io.h"
#include "step/trace.h"
#include "support/temp_folder.h"
#include "support/user_shader_files.h"

namespace facet::step {
namespace {

namespace fs = std::filesystem;

struct Setting {
    std::string name;
    std::string input;  // relative to the source folder
    std::optional<ShadingFrequency> shading = std::nullopt;
    std::optional<TransparencyMode> transparency = std::nullopt;
    std::optional<LightingPreset> preset = std::nullopt;
    std::optional<std::string> shader = std::nullopt;  // a shader of one's own, relative to the source folder
};

void PrintTo(const Setting& s, std::ostream* os) {
    *os << s.name;
}

class TraceMatchesRender : public testing_support::TempFolderTest,
                           public ::testing::WithParamInterface<Setting> {};

// The 8-bit RGBA bytes of a PNG file, as stored.
std::vector<unsigned char> fileBytes(const fs::path& path, int& width, int& height, int& channels) {
    std::string error;
    auto input = builtInImageLibrary().open(path.string(), error);
    EXPECT_TRUE(input) << path << ": " << error;
    if (!input) return {};
    const ImageHeader& spec = input->header();
    width = spec.width;
    height = spec.height;
    channels = spec.channels;
    std::vector<unsigned char> bytes(static_cast<std::size_t>(width) * height * channels);
    EXPECT_TRUE(input->read(0, channels, false, bytes.data(), channels)) << input->error();
    return bytes;
}

TEST_P(TraceMatchesRender, FinalBytesOfEveryTracedPixelAreTheImageFilesBytes) {
    const Setting& setting = GetParam();
    Scene scene = loadSceneOrModel(fs::path(FACET_SOURCE_DIR) / setting.input);
    scene.width = 96;
    scene.height = 72;
    if (setting.shading) {
        scene.lighting.shading = *setting.shading;
        for (ObjectSpec& object : scene.objects)
            object.shading = *setting.shading;
    }
    if (setting.transparency) scene.transparency.mode = *setting.transparency;
    if (setting.preset) scene.lighting.preset = *setting.preset;
    if (setting.shader) {
        testing_support::useSharedShaderCache();
        compileForWatchedDraws();  // traced: the render's draws and the trace's watched ones, one compile
        scene.shader = ShaderSpec{fs::path(FACET_SOURCE_DIR) / *setting.shader, {}};
    }
    const PreparedScene prepared = prepareScene(scene);

    // As facet render does it: a frame on two threads, written as a PNG.
    Framebuffer rendered(scene.width, scene.height);
    DrawContext threads(2);
    FrameMemory memory;
    renderFrame(prepared, rendered, threads, memory);
    const fs::path png = folder_ / "render.png";
    writeImage(png, toImage(rendered), prepared.encoding);
    int width = 0, height = 0, channels = 0;
    const std::vector<unsigned char> file = fileBytes(png, width, height, channels);
    ASSERT_EQ(width, scene.width);

    // The trace of every third pixel of every third row.
    TraceRequest request;
    for (int y = 1; y < scene.height; y += 3)
        for (int x = 0; x < scene.width; x += 3)
            request.pixels.emplace_back(x, y);
    Framebuffer traced(scene.width, scene.height);
    DrawContext calling(1);
    const FrameTrace trace = traceFrame(prepared, traced, calling, request);
    ASSERT_EQ(trace.pixels.size(), request.pixels.size());
    std::size_t drawn = 0, differing = 0;
    for (const PixelTrace& p : trace.pixels) {
        const unsigned char* expected = &file[(static_cast<std::size_t>(p.y) * width + p.x) * channels];
        for (int c = 0; c < channels; ++c)
            if (p.finalBytes[c] != expected[c] && differing++ < 5)
                ADD_FAILURE() << "pixel (" << p.x << ", " << p.y << ") channel " << c << ": trace "
                              << int(p.finalBytes[c]) << ", file " << int(expected[c]);
        drawn += p.producer.has_value();
    }
    EXPECT_EQ(differing, 0u);
    EXPECT_GT(drawn, request.pixels.size() / 10) << "the scene should cover a good part of the image";
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, TraceMatchesRender,
    ::testing::Values(
        Setting{"spot_flat", "models/spot/spot_triangulated.obj", ShadingFrequency::Flat},
        Setting{"spot_gouraud", "models/spot/spot_triangulated.obj", ShadingFrequency::Gouraud},
        Setting{"spot_phong", "models/spot/spot_triangulated.obj", ShadingFrequency::Phong},
        Setting{"spot_gl_preset", "models/spot/spot_triangulated.obj", std::nullopt, std::nullopt,
                LightingPreset::GL},
        Setting{"fog_linear", "tests/conformance/scenes/facet-fog-linear-gouraud-spot.json"},
        Setting{"fog_exp2", "tests/conformance/scenes/gl-fog-exp2-suzanne.json"},
        Setting{"fog_exp_sorted", "tests/conformance/scenes/gl-fog-exp-transparent-teapots.json",
                std::nullopt, TransparencyMode::Sorted},
        Setting{"fog_exp_unsorted", "tests/conformance/scenes/gl-fog-exp-transparent-teapots.json",
                std::nullopt, TransparencyMode::Unsorted},
        Setting{"fog_exp_exact", "tests/conformance/scenes/gl-fog-exp-transparent-teapots.json", std::nullopt,
                TransparencyMode::Exact},
        Setting{"glass_exact", "models/fog-and-glass.json", std::nullopt, TransparencyMode::Exact},
        Setting{"blend_modes", "tests/conformance/scenes/facet-blend-modes-spheres.json"},
        Setting{"user_shader", "models/spot/spot_triangulated.obj", std::nullopt, std::nullopt, std::nullopt,
                "tests/step/shaders/toon_step.cpp"},
        Setting{"user_shader_transparent", "tests/conformance/scenes/gl-fog-exp-transparent-teapots.json",
                std::nullopt, TransparencyMode::Sorted, std::nullopt, "tests/step/shaders/toon_step.cpp"}),
    [](const ::testing::TestParamInfo<Setting>& info) { return info.param.name; });

}  // namespace
}  // namespace facet::step
