// The memory limit through the program (docs/bad-input.md, "Cost that grows with the input"): work whose
// buffers need more than --memory-limit (or FACET_MEMORY_LIMIT) is refused before it starts, with one
// line naming what needs the memory and how much, exit status 4; a bad SIZE is a command-line error.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "cli/run_facet.h"
#include "support/bundled_models.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

using testing_support::runFacet;
using testing_support::TempFolderTest;

using testing_support::shellQuoted;

using testing_support::kModels;

// One line on standard error, exit 4, and no image written.
void expectRefused(const testing_support::RunResult& run, const std::filesystem::path& image,
                   const std::string& naming) {
    EXPECT_EQ(run.status, 4) << run.err;
    EXPECT_NE(run.err.find("facet: error: "), std::string::npos) << run.err;
    EXPECT_NE(run.err.find(naming), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("more than the memory limit of"), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_FALSE(std::filesystem::exists(image));
}

class MemoryLimitCli : public TempFolderTest {};

// Catches: the samples of --aa msaa16 allocated without an estimate (8192² at 16 samples is ~21 GB),
// or --memory-limit not taken by render.
TEST_F(MemoryLimitCli, MultisamplingBeyondTheLimitIsRefusedBeforeLoading) {
    // 2048² × (16 + 1) samples × 20 bytes ≈ 1.3 GiB: more than 1G, refused before the model is read.
    const auto image = folder_ / "out.png";
    const auto run =
        runFacet("render " + shellQuoted(kModels / "cube/cube.obj") +
                     " --width 2048 --height 2048 --aa msaa16 --memory-limit 1G -o " + shellQuoted(image),
                 temp_);
    expectRefused(run, image, "rendering a 2048x2048 image with 16 samples per pixel (--aa msaa16) needs 1.");
    EXPECT_NE(run.err.find("1.0 GiB (--memory-limit)"), std::string::npos) << run.err;
}

// Catches: the limit read from FACET_MEMORY_LIMIT ignored, or --memory-limit not winning over it.
TEST_F(MemoryLimitCli, EnvironmentVariableSetsTheLimitAndTheOptionWins) {
    const auto image = folder_ / "out.png";
    // 512² × 5 samples × 20 bytes = 25 MiB of planes: more than 10M, less than 100M. (The command runs
    // under sh: "VAR=value facet ..." sets the variable for the second facet.)
    const std::string withVariable = "--version >/dev/null; FACET_MEMORY_LIMIT=10M '" FACET_BINARY
                                     "' render " +
                                     shellQuoted(kModels / "cube/cube.obj") +
                                     " --width 512 --height 512 --aa msaa4 -o " + shellQuoted(image);
    auto run = runFacet(withVariable, temp_);
    expectRefused(run, image, "(FACET_MEMORY_LIMIT; --memory-limit SIZE sets it)");
    run = runFacet(withVariable + " --memory-limit 100M", temp_);
    EXPECT_EQ(run.status, 0) << run.err;
}

// Catches: a SIZE that is no size accepted (or read as 0 and refusing everything), or its error given
// the exit status of resource errors instead of the command line's.
TEST_F(MemoryLimitCli, BadSizesAreCommandLineErrors) {
    for (const char* size : {"abc", "12X", "0", "1.2.3G", "-5G"}) {
        const auto run = runFacet("render " + shellQuoted(kModels / "cube/cube.obj") +
                                      " --memory-limit=" + size + " -o " + shellQuoted(folder_ / "out.png"),
                                  temp_);
        EXPECT_EQ(run.status, 2) << size << ": " << run.err;
        EXPECT_NE(run.err.find("--memory-limit"), std::string::npos) << run.err;
    }
    const auto run =
        runFacet("--version >/dev/null; FACET_MEMORY_LIMIT=lots '" FACET_BINARY "' render " +
                     shellQuoted(kModels / "cube/cube.obj") + " -o " + shellQuoted(folder_ / "out.png"),
                 temp_);
    EXPECT_EQ(run.status, 1) << run.err;
    EXPECT_NE(run.err.find("FACET_MEMORY_LIMIT expects a size like 512M"), std::string::npos) << run.err;
}

// Catches: shadow maps drawn without an estimate (8 point lights at 8192 took 13.6 GB and 47 s): the
// refusal must come before any map is drawn and name the maps, their count and size.
TEST_F(MemoryLimitCli, ShadowMapsBeyondTheLimitAreRefusedBeforeTheyAreDrawn) {
    const auto scene = folder_ / "lights.json";
    std::ofstream(scene) << R"({"width": 64, "height": 48, "lights": [)"
                         << R"({"type": "point", "position": [2, 2, 2], "shadows": "map"},)"
                         << R"({"type": "point", "position": [-2, 2, 2], "shadows": "map"}],)"
                         << R"("shadow_map": {"size": 4096}, "objects": [{"model": ")"
                         << (kModels / "cube/cube.obj").string() << R"("}]})";
    const auto image = folder_ / "out.png";
    // 2 lights × 6 faces × 4096² × 4 bytes = 768 MiB of depths, and 320 MiB for the one framebuffer.
    const auto run =
        runFacet("render " + shellQuoted(scene) + " --memory-limit 512M -o " + shellQuoted(image), temp_);
    expectRefused(run, image, "drawing the shadow maps of 2 lights (12 images of 4096x4096 texels");
    const auto fits = runFacet("render " + shellQuoted(scene) +
                                   " --shadow-map-size 256 --memory-limit 512M -o " + shellQuoted(image),
                               temp_);
    EXPECT_EQ(fits.status, 0) << fits.err;
}

// Catches: exact transparency's fragment lists growing without bound (1,000 layers at 640x480 took
// 5.4 GB): past the limit the frame is refused, naming the layers and the way out.
TEST_F(MemoryLimitCli, FragmentListsBeyondTheLimitAreRefused) {
    const auto scene = folder_ / "layers.json";
    {
        std::ofstream out(scene);
        out << R"({"width": 64, "height": 64, "pipeline": {"cull": "none"}, "objects": [)";
        // 40 see-through cubes in one place: 80 layers a pixel, 64² × 80 × 24 bytes ≈ 7.5 MiB of nodes.
        for (int k = 0; k < 40; ++k)
            out << (k ? "," : "") << R"({"model": ")" << (kModels / "cube/cube.obj").string()
                << R"(", "material": {"opacity": 0.5}})";
        out << "]}";
    }
    const auto image = folder_ / "out.png";
    const auto run = runFacet(
        "render " + shellQuoted(scene) + " --transparency exact --memory-limit 1M -o " + shellQuoted(image),
        temp_);
    expectRefused(run, image, "keeping every transparent layer of a 64x64 image (--transparency exact;");
    const auto sorted = runFacet(
        "render " + shellQuoted(scene) + " --transparency sorted --memory-limit 1M -o " + shellQuoted(image),
        temp_);
    EXPECT_EQ(sorted.status, 0) << sorted.err;
}

// Catches: facet step --html at a large size running for minutes before running out of memory (8192²
// reached 6.7 GB after 400 s): its stage images are estimated before the scene is loaded.
TEST_F(MemoryLimitCli, StepPageBeyondTheLimitIsRefusedBeforeTheWork) {
    const auto run = runFacet("step " + shellQuoted(kModels / "cube/cube.obj") +
                                  " --width 8192 --height 8192 --html-step 64 --memory-limit 2G --html " +
                                  shellQuoted(folder_ / "page"),
                              temp_);
    expectRefused(run, folder_ / "page", "drawing the stage images of --html for a 8192x8192 image");
}

// Catches: textures decoded one by one until their total is refused (five 8k textures were all read
// first): the headers are read first, so textures whose data is cut short (a decode would only warn)
// are refused by their total before any is decoded.
TEST_F(MemoryLimitCli, TexturesAreRefusedByTheirTotalFromTheirHeaders) {
    // Two 512² RGB PNGs cut short in their first IDAT chunk: 2 × 1 MiB once decoded.
    for (const char* name : {"a.png", "b.png"}) {
        const unsigned char header[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0,    0,    0,
                                        13,   'I', 'H', 'D', 'R',  0,    0,    2,    0,    0,    0,
                                        2,    0,   8,   2,   0,    0,    0,    0x7b, 0x1a, 0x43, 0xad,
                                        0,    0,   16,  0,   'I',  'D',  'A',  'T',  0x78, 0x9c};
        std::ofstream(folder_ / name, std::ios::binary)
            .write(reinterpret_cast<const char*>(header), sizeof header);
    }
    std::ofstream(folder_ / "m.mtl") << "newmtl a\nmap_Kd a.png\nnewmtl b\nmap_Kd b.png\n";
    std::ofstream(folder_ / "m.obj") << "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\n"
                                        "vt 0 1\nusemtl a\nf 1/1 2/2 3/3\nusemtl b\nf 2/2 4/1 3/3\n";
    const auto image = folder_ / "out.png";
    const auto run = runFacet("render " + shellQuoted(folder_ / "m.obj") +
                                  " --width 16 --height 16 --memory-limit 1536K -o " + shellQuoted(image),
                              temp_);
    expectRefused(run, image, "loading the 2 textures of this render needs 2.0 MiB");
}

}  // namespace
}  // namespace facet
