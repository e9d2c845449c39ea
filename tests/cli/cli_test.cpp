// The facet program as a user runs it: exit status, the one-line error, and no partial images.
#include <sys/wait.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "io/image_io.h"
#include "run_facet.h"
#include "support/mesa_fixture.h"
#include "support/sanitizers.h"
#include "support/user_shader_files.h"

namespace facet {
namespace {

using testing_support::readText;
using testing_support::runFacet;
using testing_support::RunResult;
using testing_support::TempFolder;

int lineCount(const std::string& text) {
    int n = 0;
    for (char c : text)
        n += c == '\n';
    return n;
}

using testing_support::shellQuoted;

TEST(Cli, RendersABundledModelToPng) {
    TempFolder dir;
    const auto png = dir.path() / "spot.png";
    const RunResult run = runFacet(
        "render " +
            shellQuoted(std::filesystem::path(FACET_SOURCE_DIR) / "models/spot/spot_triangulated.obj") +
            " -o " + shellQuoted(png) + " --width 96 --height 72",
        dir);
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.out.find("5856 triangles"), std::string::npos) << run.out;
    const LinearImage image = readImage(png);
    EXPECT_EQ(image.width, 96);
    EXPECT_EQ(image.height, 72);
    // No temporary file is left beside the image.
    int files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
        files += entry.path().extension() == ".png";
    EXPECT_EQ(files, 1);
}

// A render of a model with a PNG texture to a PNG file never loads OpenImageIO (its ~260 libraries
// cost a quarter of a second before anything is drawn) nor OpenCV (facet trade's SSIM: ~15 libraries,
// half of `facet --help`'s start-up); an EXR output does load OpenImageIO. The dynamic loader's own
// record (LD_DEBUG=files) says which libraries the process opened. Breaks caught: facet linking
// OpenImageIO or OpenCV again, or PNG textures or outputs sent through OpenImageIO.
TEST(Cli, OpenImageIOIsLoadedOnlyForFormatsThatNeedIt) {
    TempFolder dir;
    const std::string model =
        shellQuoted(std::filesystem::path(FACET_SOURCE_DIR) / "models/spot/spot_triangulated.obj");
    ::setenv("LD_DEBUG", "files", 1);
    const RunResult png = runFacet(
        "render " + model + " -o " + shellQuoted(dir.path() / "spot.png") + " --width 32 --height 24", dir);
    const RunResult exr = runFacet(
        "render " + model + " -o " + shellQuoted(dir.path() / "spot.exr") + " --width 32 --height 24", dir);
    ::unsetenv("LD_DEBUG");
    ASSERT_EQ(png.status, 0) << png.err.substr(png.err.size() > 2000 ? png.err.size() - 2000 : 0);
    ASSERT_EQ(exr.status, 0);
    EXPECT_NE(png.err.find("libpng16"), std::string::npos);  // the record is there
    EXPECT_EQ(png.err.find("libOpenImageIO"), std::string::npos);
    EXPECT_EQ(png.err.find("libfacet_openimageio"), std::string::npos);
    // Sanitized builds link OpenCV (src/trade/CMakeLists.txt says why).
#if !defined(FACET_TEST_ADDRESS_SANITIZER)
    EXPECT_EQ(png.err.find("libopencv"), std::string::npos);
    EXPECT_EQ(png.err.find("libfacet_opencv"), std::string::npos);
#endif
    EXPECT_NE(exr.err.find("libfacet_openimageio"), std::string::npos);
    EXPECT_NE(exr.err.find("libOpenImageIO"), std::string::npos);
}

// FACET_ISA forces the copy of the frame's code (render/frame_kernels.h), and --version names it; a
// name that is no instruction set is one line of error before anything is drawn, exit 1, no image.
// Breaks if the variable is ignored, or checked only when a frame is drawn (a batch would repeat the
// error per model).
TEST(Cli, FacetIsaForcesTheFrameCodeAndABadOneIsOneError) {
    TempFolder dir;
    ::setenv("FACET_ISA", "baseline", 1);
    const RunResult version = runFacet("--version", dir);
    ::setenv("FACET_ISA", "sse9", 1);
    const RunResult bad =
        runFacet("render " + shellQuoted(std::filesystem::path(FACET_SOURCE_DIR) / "models/cube/cube.obj") +
                     " -o " + shellQuoted(dir.path() / "cube.png") + " --width 32 --height 24",
                 dir);
    ::unsetenv("FACET_ISA");
    ASSERT_EQ(version.status, 0) << version.err;
    EXPECT_NE(version.out.find("frame code: baseline (widest this CPU runs: "), std::string::npos)
        << version.out;
    EXPECT_EQ(bad.status, 1);
    EXPECT_EQ(bad.err,
              "facet: error: FACET_ISA=\"sse9\" names no instruction set (one of: " FACET_FRAME_COPIES ")\n");
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "cube.png"));
}

// The same render on 1, 2 and 7 threads gives the same image: every float of every pixel. (The EXR
// files' bytes may differ: OpenEXR's writer does not promise identical files, only identical pixels.)
TEST(Cli, ThreadCountDoesNotChangeTheImage) {
    TempFolder dir;
    const auto model = std::filesystem::path(FACET_SHARED_MODELS) / "stanford-bunny/stanford-bunny.obj";
    if (!std::filesystem::exists(model)) GTEST_SKIP() << model << " is not here";
    std::vector<glm::vec4> reference;
    for (int threads : {1, 2, 7}) {
        const auto exr = dir.path() / ("bunny-" + std::to_string(threads) + ".exr");
        const RunResult run = runFacet("render " + shellQuoted(model) + " -o " + shellQuoted(exr) +
                                           " --width 320 --height 240 --threads " + std::to_string(threads),
                                       dir);
        ASSERT_EQ(run.status, 0) << run.err;
        const LinearImage image = readImage(exr);
        ASSERT_EQ(image.pixels.size(), 320u * 240u);
        if (reference.empty()) reference = image.pixels;
        EXPECT_TRUE(image.pixels == reference) << threads << " threads";
    }
}

// --components writes the four terms next to the output; over a black background they add up to the
// image itself (EXR keeps the linear values). --only writes one of them as the output.
TEST(Cli, ComponentImagesAddUpToTheImage) {
    TempFolder dir;
    const auto model = std::filesystem::path(FACET_SOURCE_DIR) / "models/spot/spot_triangulated.obj";
    const auto scene = dir.write("scene.json", "{\"model\": \"" + model.string() +
                                                   "\", \"background\": [0, 0, 0, 1], \"width\": 80, "
                                                   "\"height\": 60, \"lights\": [{\"type\": \"point\", "
                                                   "\"position\": [1, 1, 3]}]}");
    const RunResult run =
        runFacet("render " + shellQuoted(scene) + " -o " + shellQuoted(dir.path() / "cow.exr") +
                     " --components --reflection phong",
                 dir);
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.out.find("cow-specular.exr (specular term alone)"), std::string::npos) << run.out;
    const LinearImage whole = readImage(dir.path() / "cow.exr");
    LinearImage sum = whole;
    for (glm::vec4& p : sum.pixels)
        p = glm::vec4(0.0f);
    float brightestSpecular = 0.0f;
    for (const char* term : {"emission", "ambient", "diffuse", "specular"}) {
        const LinearImage part = readImage(dir.path() / (std::string("cow-") + term + ".exr"));
        ASSERT_EQ(part.pixels.size(), whole.pixels.size());
        for (std::size_t i = 0; i < part.pixels.size(); ++i) {
            sum.pixels[i] += glm::vec4(glm::vec3(part.pixels[i]), 0.0f);
            if (std::string(term) == "specular")
                brightestSpecular = std::max(brightestSpecular, part.pixels[i].g);
        }
    }
    EXPECT_GT(brightestSpecular, 0.02f);  // the highlight is there to be summed
    for (std::size_t i = 0; i < whole.pixels.size(); ++i) {
        ASSERT_NEAR(sum.pixels[i].r, whole.pixels[i].r, 1e-3f * (1.0f + whole.pixels[i].r)) << i;
        ASSERT_NEAR(sum.pixels[i].b, whole.pixels[i].b, 1e-3f * (1.0f + whole.pixels[i].b)) << i;
    }

    const RunResult only =
        runFacet("render " + shellQuoted(scene) + " -o " + shellQuoted(dir.path() / "only.exr") +
                     " --only specular --reflection phong",
                 dir);
    ASSERT_EQ(only.status, 0) << only.err;
    EXPECT_TRUE(readImage(dir.path() / "only.exr").pixels ==
                readImage(dir.path() / "cow-specular.exr").pixels);
}

// facet compare renders a scene with Facet and with OpenGL (Mesa) and says whether they agree; the
// bundled example scene does (exit status 0), and the three images it was asked for are written.
// Skipped where this process cannot open softpipe (support/mesa_fixture.h); where it can, so can facet.
class CliWithMesa : public SoftpipeTest {};

TEST_F(CliWithMesa, CompareWithOpenGlAgreesOnTheBundledScene) {
    TempFolder dir;
    const auto scene = std::filesystem::path(FACET_SOURCE_DIR) / "models/example-scene.json";
    const RunResult run =
        runFacet("compare " + shellQuoted(scene) + " --width 160 --height 120 --lighting gl --diff " +
                     shellQuoted(dir.path() / "diff.png") + " --mesa " + shellQuoted(dir.path() / "gl.png"),
                 dir);
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    EXPECT_NE(run.out.find("verdict    agrees"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("softpipe"), std::string::npos) << run.out;
    EXPECT_EQ(readImage(dir.path() / "diff.png").width, 160);
    EXPECT_EQ(readImage(dir.path() / "gl.png").height, 120);
}

// A turntable writes numbered images; --stats shows the first frame sorted from scratch and the next
// ones by insertion from the previous order, with their comparisons and moves, and the transparent
// pass's calls drawn in runs.
TEST(Cli, TurntableFramesWithSortStatistics) {
    TempFolder dir;
    const auto scene = std::filesystem::path(FACET_SOURCE_DIR) / "models/intersecting-quads.json";
    const RunResult run =
        runFacet("render " + shellQuoted(scene) + " -o " + shellQuoted(dir.path() / "spin.png") +
                     " --width 64 --height 48 --frames 3-5 --turntable 30 --stats",
                 dir);
    ASSERT_EQ(run.status, 0) << run.err;
    for (const char* name : {"spin-0003.png", "spin-0004.png", "spin-0005.png"})
        EXPECT_TRUE(std::filesystem::exists(dir.path() / name)) << name;
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "spin.png"));
    EXPECT_NE(run.out.find("frame 3: "), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("sorted from scratch"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("frame 5: "), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("by insertion from the last frame's order"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find(" moves"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("small draws drawn together in "), std::string::npos) << run.out;
    // Frames differ: the objects turned.
    EXPECT_FALSE(readImage(dir.path() / "spin-0003.png").pixels ==
                 readImage(dir.path() / "spin-0005.png").pixels);
}

// Each bad input: exit status 1, exactly one line on stderr naming what is wrong, and an existing
// output file left as it was.
struct BadInput {
    const char* name;
    const char* objText;    // written as bad.obj when not null
    const char* sceneText;  // written as bad.json when not null
    const char* extraArgs;
    const char* expected;  // must appear in the error line
    int status = 1;        // 1: bad input; 2: the command line itself is malformed
};

// Printed by gtest in test listings.
void PrintTo(const BadInput& c, std::ostream* os) {
    *os << c.name;
}

class CliBadInput : public ::testing::TestWithParam<BadInput> {};

TEST_P(CliBadInput, FailsWithOneLineAndKeepsTheOldImage) {
    const BadInput& c = GetParam();
    TempFolder dir;
    std::string input = shellQuoted(dir.path() / "missing.obj");
    if (c.objText) input = shellQuoted(dir.write("bad.obj", c.objText));
    if (c.sceneText) input = shellQuoted(dir.write("bad.json", c.sceneText));
    if (!c.objText && !c.sceneText && std::string(c.extraArgs).empty() == false)
        input = shellQuoted(dir.write("ok.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    const auto out = dir.write("old.png", "previous contents");
    const RunResult run = runFacet("render " + input + " -o " + shellQuoted(out) + " " + c.extraArgs, dir);
    EXPECT_EQ(run.status, c.status) << run.err;
    EXPECT_EQ(lineCount(run.err), 1) << run.err;
    EXPECT_EQ(run.err.rfind("facet: error: ", 0), 0u) << run.err;
    EXPECT_NE(run.err.find(c.expected), std::string::npos)
        << "expected \"" << c.expected << "\" in: " << run.err;
    EXPECT_EQ(readText(out), "previous contents");
}

INSTANTIATE_TEST_SUITE_P(
    Cases, CliBadInput,
    ::testing::Values(
        BadInput{"MissingFile", nullptr, nullptr, "", "missing.obj"},
        BadInput{"IndexOutOfRange", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", nullptr, "", "bad.obj:4"},
        BadInput{"NanCoordinate", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", nullptr, "", "bad.obj:2"},
        BadInput{"NoTriangles", "v 0 0 0\nv 1 0 0\n", nullptr, "", "bad.obj"},
        BadInput{"UnknownSceneKey", nullptr, "{\"model\": \"x.obj\", \"camera\": {\"fvoy\": 30}}", "",
                 "camera.fvoy"},
        BadInput{"SceneSyntax", nullptr, "{\n  \"width\": 10,\n  oops\n}", "", "bad.json"},
        BadInput{"WidthZero", nullptr, nullptr, "--width 0", "--width"},
        BadInput{"WidthHuge", nullptr, nullptr, "--width 1000000", "--width"},
        BadInput{"TooManyPixels", nullptr, nullptr, "--width 16384 --height 16384", "limit"},
        BadInput{"TooManyPixelsWithTheSceneHeight", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
                 "{\"model\": \"bad.obj\", \"height\": 16384}", "--width 8192",
                 "larger than the limit of 67108864 pixels (\"height\" from "},
        BadInput{"BadEye", nullptr, nullptr, "--eye 1,2", "--eye"},
        BadInput{"FovyOutOfRange", nullptr, nullptr, "--fovy 200", "--fovy"},
        BadInput{"UnknownTerm", nullptr, nullptr, "--only glare", "--only: glare not in", 2},
        BadInput{"UnknownShading", nullptr, nullptr, "--shading smooth", "--shading", 2},
        BadInput{"OnlyAndComponents", nullptr, nullptr, "--only diffuse --components", "do not go together"},
        BadInput{"CreaseAngleOutOfRange", nullptr, nullptr, "--crease-angle 200", "--crease-angle"},
        BadInput{"BackwardFrames", nullptr, nullptr, "--frames 9-3", "--frames"},
        // Frame numbers near the largest int used to overflow the frame counter and never stop.
        BadInput{"FramesAtTheLargestInt", nullptr, nullptr, "--frames 2147483646-2147483647", "0 to 9999999"},
        BadInput{"FrameNumberBeyondSevenDigits", nullptr, nullptr, "--frames 10000000", "0 to 9999999"},
        BadInput{"ThreadsNotANumber", nullptr, nullptr, "--threads abc",
                 "--threads: expects a whole number from 0 to 1024 (got \"abc\")", 2},
        BadInput{"WidthNotANumber", nullptr, nullptr, "--width 12px", "--width: expects a whole number", 2},
        BadInput{"FovyNotANumber", nullptr, nullptr, "--fovy nan", "--fovy: expects a finite number", 2},
        BadInput{"TurntableInfinite", nullptr, nullptr, "--frames 0-1 --turntable inf",
                 "--turntable: expects a finite number", 2},
        BadInput{"GammaBeyondFloat", nullptr, nullptr, "--gamma 1e39", "--gamma: expects a finite number", 2},
        BadInput{"TurntableWithoutFrames", nullptr, nullptr, "--turntable 90", "--turntable needs --frames"},
        BadInput{"GammaWithLinear", nullptr, nullptr, "--encode linear --gamma 2.2", "--gamma goes with"},
        BadInput{"GammaWithGlPreset", nullptr, nullptr, "--lighting gl --gamma 2.2", "gl preset"}),
    [](const ::testing::TestParamInfo<BadInput>& info) { return std::string(info.param.name); });

TEST(Cli, UnknownImageFormatWritesNothing) {
    TempFolder dir;
    const auto obj = dir.write("ok.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const RunResult run =
        runFacet("render " + shellQuoted(obj) + " -o " + shellQuoted(dir.path() / "x.notaformat"), dir);
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(lineCount(run.err), 1) << run.err;
    EXPECT_NE(run.err.find("x.notaformat"), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "x.notaformat"));
}

// Counts are checked before the model is loaded: with a model that is not even there, the error is
// about the images --frames and --components would write, and it comes at once.
TEST(Cli, ImageCountIsCheckedBeforeTheModelIsLoaded) {
    TempFolder dir;
    const RunResult run = runFacet("render " + shellQuoted(dir.path() / "missing.obj") + " -o " +
                                       shellQuoted(dir.path() / "x.png") + " --frames 0-20000 --components",
                                   dir);
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(lineCount(run.err), 1) << run.err;
    EXPECT_NE(run.err.find("would write 100005 images"), std::string::npos) << run.err;
    EXPECT_EQ(run.err.find("missing.obj"), std::string::npos) << run.err;
}

TEST(Cli, OutputPathsGetPlainMessages) {
    TempFolder dir;
    const auto obj = shellQuoted(dir.write("ok.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    const auto file = dir.write("file.png", "a file, not a folder");
    const struct {
        std::string output;
        std::string expected;  // the whole error line
    } cases[] = {
        {"", "facet: error: no output file given: name one with -o, like -o out/image.png\n"},
        {(dir.path() / ".png").string(), "facet: error: " + (dir.path() / ".png").string() +
                                             ": has no file name before the extension (like " +
                                             (dir.path() / "image.png").string() + ")\n"},
        {(file / "x.png").string(),
         "facet: error: " + (file / "x.png").string() + ": cannot write: Not a directory\n"},
    };
    for (const auto& c : cases) {
        const RunResult run = runFacet(
            "render " + obj + " -o " + shellQuoted(std::filesystem::path(c.output)) + " --width 8 --height 8",
            dir);
        EXPECT_EQ(run.status, 1) << c.output;
        EXPECT_EQ(run.err, c.expected);
    }
    EXPECT_EQ(readText(file), "a file, not a folder");
}

// A folder that refuses new files: the error names the user's path and the system's reason, never the
// hidden temporary file the image is first written to. (/sys refuses files even to root.)
TEST(Cli, UnwritableFolderNamesThePathAndTheReason) {
    if (!std::filesystem::is_directory("/sys")) GTEST_SKIP() << "no /sys here";
    TempFolder dir;
    const auto obj = shellQuoted(dir.write("ok.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    const RunResult run = runFacet("render " + obj + " -o /sys/facet-test.png --width 8 --height 8", dir);
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(lineCount(run.err), 1) << run.err;
    EXPECT_EQ(run.err.rfind("facet: error: /sys/facet-test.png: cannot write: ", 0), 0u) << run.err;
    EXPECT_EQ(run.err.find(".tmp"), std::string::npos) << run.err;
}

// facet bench finds its default model beside the repository it was built in, from any folder.
TEST(Cli, BenchFindsItsDefaultModelFromAnyFolder) {
    const auto bunny = std::filesystem::path(FACET_SHARED_MODELS) / "stanford-bunny/stanford-bunny.obj";
    if (!std::filesystem::exists(bunny)) GTEST_SKIP() << bunny << " is not here";
    TempFolder dir;
    const RunResult run = runFacet("bench --frames 1 --width 16 --height 16 --threads 1", dir, dir.path());
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.out.find("stanford-bunny.obj"), std::string::npos) << run.out;
}

// facet bench --instruction-sets reaches its benchmark (each copy's row, the baseline's always), and
// refuses the other modes' options.
TEST(Cli, BenchTimesEachInstructionSet) {
    TempFolder dir;
    const auto obj = shellQuoted(dir.write("triangle.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    const RunResult run =
        runFacet("bench --instruction-sets --frames 1 --width 16 --height 16 --threads 1 " + obj, dir);
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.out.find("the copies taking turns"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find("\nbaseline "), std::string::npos) << run.out;
    const RunResult refused = runFacet("bench --instruction-sets --vs-mesa " + obj, dir);
    EXPECT_EQ(refused.status, 1);
    EXPECT_NE(refused.err.find("--vs-mesa does not go with --instruction-sets"), std::string::npos)
        << refused.err;
}

// facet bench --cut-for reaches the plain frames' report and is refused by the modes that draw their own
// configurations (and out of range).
TEST(Cli, BenchCutsPlainFramesForTheThreadsAskedFor) {
    TempFolder dir;
    const auto obj = shellQuoted(dir.write("triangle.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    const RunResult run =
        runFacet("bench --cut-for 8 --frames 1 --width 16 --height 16 --threads 1 " + obj, dir);
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.out.find("1 thread (work cut for 8)"), std::string::npos) << run.out;
    const RunResult refused = runFacet("bench --cut-for 8 --scaling " + obj, dir);
    EXPECT_EQ(refused.status, 1);
    EXPECT_NE(refused.err.find("--cut-for does not go with --scaling"), std::string::npos) << refused.err;
    EXPECT_EQ(runFacet("bench --cut-for 0 " + obj, dir).status, 2);
}

TEST(Cli, BenchRefusesNonFiniteSteps) {
    TempFolder dir;
    for (const char* value : {"nan", "inf", "-inf"}) {
        const RunResult run = runFacet(std::string("bench --transparency --degrees-per-frame ") + value +
                                           " " + shellQuoted(dir.path() / "missing.obj"),
                                       dir);
        EXPECT_EQ(run.status, 2) << value;
        EXPECT_NE(run.err.find("--degrees-per-frame: expects a finite number"), std::string::npos) << run.err;
    }
}

constexpr const char* kCubeObj =
    "v -1 -1 -1\nv 1 -1 -1\nv -1 1 -1\nv 1 1 -1\nv -1 -1 1\nv 1 -1 1\nv -1 1 1\nv 1 1 1\n"
    "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";

// Inside the cube (corners ±1), looking at its far wall 1.5 away under a 16-bit depth buffer: with a
// near plane of 1e-6 every depth past about 0.12 rounds to the far plane (scene/camera.cpp), so the wall
// fails the depth test and nothing is drawn; the camera warns first, and the empty frame names the depth
// buffer, not the camera's direction. A near plane of 0.1 draws the wall without a word.
// Catches: an interior view with a tiny near plane blamed on "the camera may look away", or unwarned.
TEST(Cli, InteriorViewLostToDepthPrecisionSaysSo) {
    TempFolder dir;
    dir.write("cube.obj", kCubeObj);
    const auto scene = [&](const std::string& near) {
        return shellQuoted(
            dir.write("inside-" + near + ".json",
                      "{\"camera\": {\"eye\": [0, 0, 0.5], \"target\": [0, 0, -1], \"near\": " + near +
                          "}, \"objects\": [{\"model\": \"cube.obj\"}]}"));
    };
    const std::string options = " --width 32 --height 24 --cull none --depth unorm16 -o ";
    const RunResult lost =
        runFacet("render " + scene("1e-6") + options + shellQuoted(dir.path() / "lost.png"), dir);
    EXPECT_EQ(lost.status, 0) << lost.err;
    EXPECT_NE(lost.err.find("every depth farther than 0.12"), std::string::npos) << lost.err;
    EXPECT_NE(lost.err.find("nothing was drawn"), std::string::npos) << lost.err;
    EXPECT_NE(lost.err.find("their depths all rounded to the far plane"), std::string::npos) << lost.err;
    EXPECT_EQ(lost.err.find("look away"), std::string::npos) << lost.err;
    const RunResult seen =
        runFacet("render " + scene("0.1") + options + shellQuoted(dir.path() / "seen.png"), dir);
    EXPECT_EQ(seen.status, 0) << seen.err;
    EXPECT_EQ(seen.err, "");
}

// The last line of defence: a frame that draws nothing says so, and what became of its triangles.
TEST(Cli, FrameThatDrawsNothingIsWarnedAbout) {
    TempFolder dir;
    const auto obj = shellQuoted(dir.write("cube.obj", kCubeObj));
    const RunResult away = runFacet("render " + obj + " -o " + shellQuoted(dir.path() / "away.png") +
                                        " --width 32 --height 24 --eye 0,0,5 --target 0,0,10",
                                    dir);
    EXPECT_EQ(away.status, 0) << away.err;
    EXPECT_EQ(lineCount(away.err), 1) << away.err;
    EXPECT_NE(
        away.err.find("facet: warning: " + (dir.path() / "away.png").string() +
                      ": nothing was drawn, only the background: of 12 triangles, 12 lay outside the view"),
        std::string::npos)
        << away.err;
    const RunResult seen = runFacet("render " + obj + " -o " + shellQuoted(dir.path() / "seen.png") +
                                        " --width 32 --height 24 --eye 0,0,5",
                                    dir);
    EXPECT_EQ(seen.status, 0) << seen.err;
    EXPECT_EQ(seen.err, "");
}

// Straight above the target with the default up vector: drawn, with the up vector chosen and named.
TEST(Cli, EyeStraightAboveTheTargetRendersWithAWarning) {
    TempFolder dir;
    const auto obj = shellQuoted(dir.write("cube.obj", kCubeObj));
    const auto scene = dir.write("above.json", "{\"model\": \"cube.obj\", \"camera\": {\"eye\": [0, 5, 0]}}");
    for (const std::string& input :
         {"render " + obj + " --eye 0,5,0 --target 0,0,0", "render " + shellQuoted(scene)}) {
        const RunResult run =
            runFacet(input + " -o " + shellQuoted(dir.path() / "above.png") + " --width 32 --height 24", dir);
        EXPECT_EQ(run.status, 0) << run.err;
        EXPECT_EQ(lineCount(run.err), 1) << run.err;
        EXPECT_NE(run.err.find("facet: warning: "), std::string::npos) << run.err;
        EXPECT_NE(run.err.find("looks straight down"), std::string::npos) << run.err;
        EXPECT_EQ(run.out.find(" 0 fragments shaded"), std::string::npos) << run.out;
    }
}

// Camera numbers that leave nothing to see are refused with the scene file's name; extreme ones that
// still work render.
TEST(Cli, ImpossibleNearPlaneIsRefusedAndExtremeFarPlaneRenders) {
    TempFolder dir;
    dir.write("cube.obj", kCubeObj);
    const auto tiny = dir.write("tiny-near.json", "{\"model\": \"cube.obj\", \"camera\": {\"near\": 1e-10}}");
    const RunResult refused =
        runFacet("render " + shellQuoted(tiny) + " -o " + shellQuoted(dir.path() / "x.png"), dir);
    EXPECT_EQ(refused.status, 1);
    EXPECT_EQ(lineCount(refused.err), 1) << refused.err;
    EXPECT_NE(refused.err.find("tiny-near.json: the camera's near plane (1e-10) is too small"),
              std::string::npos)
        << refused.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "x.png"));

    const auto huge = dir.write("huge-far.json", "{\"model\": \"cube.obj\", \"camera\": {\"far\": 3e38}}");
    const RunResult drawn = runFacet("render " + shellQuoted(huge) + " -o " +
                                         shellQuoted(dir.path() / "y.png") + " --width 32 --height 24",
                                     dir);
    EXPECT_EQ(drawn.status, 0) << drawn.err;
    EXPECT_EQ(drawn.out.find(" 0 fragments shaded"), std::string::npos) << drawn.out;
}

// A model of size 2 at 1e7 from the origin, where floats are 1 apart: drawn, with a warning.
TEST(Cli, ModelFarFromTheOriginForItsSizeIsWarnedAbout) {
    TempFolder dir;
    const auto obj = dir.write("far.obj", "v 10000000 0 0\nv 10000002 0 0\nv 10000000 2 0\nf 1 2 3\n");
    const RunResult run = runFacet("render " + shellQuoted(obj) + " -o " +
                                       shellQuoted(dir.path() / "far.png") + " --width 32 --height 24",
                                   dir);
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(lineCount(run.err), 1) << run.err;
    EXPECT_NE(run.err.find("far.obj: coordinates reach 1e+07 while the model is only 2.82843 across"),
              std::string::npos)
        << run.err;
}

TEST(Cli, MissingMaterialFileWarnsAndRenders) {
    TempFolder dir;
    const auto obj =
        dir.write("m.obj", "mtllib nowhere.mtl\nusemtl red\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const RunResult run = runFacet(
        "render " + shellQuoted(obj) + " -o " + shellQuoted(dir.path() / "m.png") + " --width 32 --height 32",
        dir);
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.err.find("warning"), std::string::npos);
    EXPECT_NE(run.err.find("nowhere.mtl"), std::string::npos) << run.err;
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "m.png"));
}

TEST(Cli, NoArgumentsPrintsUsageAndFails) {
    TempFolder dir;
    const RunResult run = runFacet("", dir);
    EXPECT_NE(run.status, 0);
    EXPECT_NE((run.out + run.err).find("render"), std::string::npos);
}

// ---- Textures ------------------------------------------------------------------------------------

// A square facing the camera, its material's MTL statements given (e.g. "map_Kd t.png\n").
std::filesystem::path writeTexturedSquare(const TempFolder& dir, const std::string& mtlStatements) {
    dir.write("square.mtl", "newmtl square\nKd 1 1 1\n" + mtlStatements);
    return dir.write("square.obj",
                     "mtllib square.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                     "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl square\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
}

// Every line of standard error is Facet's own ("facet: ..."): no raw library output.
bool onlyFacetLines(const std::string& err) {
    std::istringstream lines(err);
    for (std::string line; std::getline(lines, line);)
        if (line.rfind("facet: ", 0) != 0) return false;
    return true;
}

// A PNG header declaring 30000 × 30000 pixels (about 29 GB as float RGBA) in a file of a few hundred
// bytes: refused from the header at once, naming the texture and the limit.
TEST(Cli, TextureDeclaringAHugeSizeFailsNamingIt) {
    TempFolder dir;
    const auto texture = dir.path() / "huge.png";
    LinearImage small;
    small.width = small.height = 4;
    small.pixels.assign(16, glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
    writeImage(texture, small);
    std::string bytes = readText(texture);
    ASSERT_EQ(bytes.substr(12, 4), "IHDR");
    for (int k = 0; k < 8; ++k)  // width and height: 30000 = 0x7530
        bytes[16 + k] = "\0\0\x75\x30\0\0\x75\x30"[k];
    std::uint32_t crc = 0xFFFFFFFFu;  // the chunk's CRC-32 over its type and 13 bytes of data
    for (int k = 12; k < 29; ++k) {
        crc ^= static_cast<unsigned char>(bytes[k]);
        for (int bit = 0; bit < 8; ++bit)
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    crc = ~crc;
    for (int k = 0; k < 4; ++k)
        bytes[29 + k] = static_cast<char>((crc >> (24 - 8 * k)) & 0xFF);
    dir.write("huge.png", bytes);
    const auto obj = writeTexturedSquare(dir, "map_Kd huge.png\n");
    const RunResult run =
        runFacet("render " + shellQuoted(obj) + " -o " + shellQuoted(dir.path() / "x.png"), dir);
    EXPECT_EQ(run.status, 1) << run.err;
    EXPECT_EQ(lineCount(run.err), 1) << run.err;
    EXPECT_EQ(run.err.rfind("facet: error: " + texture.string() + ": ", 0), 0u) << run.err;
    EXPECT_NE(run.err.find("16384"), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "x.png"));
}

// A texture that is not an image, or a truncated one, is a warning like a missing one: one line
// naming the file and the reason, no library output, and the square drawn untextured.
TEST(Cli, UnreadableTextureWarnsAndDrawsWithoutIt) {
    TempFolder dir;
    LinearImage checker;
    checker.width = checker.height = 256;
    for (int i = 0; i < 256 * 256; ++i)
        checker.pixels.push_back(glm::vec4(float((i / 256 + i) % 7) / 6.0f, 0.2f, 0.7f, 1.0f));
    writeImage(dir.path() / "whole.png", checker);
    const std::string whole = readText(dir.path() / "whole.png");
    dir.write("truncated.png", whole.substr(0, whole.size() / 2));
    dir.write("text.png", "this is not a PNG");
    for (const char* name : {"truncated.png", "text.png"}) {
        const auto obj = writeTexturedSquare(dir, std::string("map_Kd ") + name + "\n");
        const auto png = dir.path() / "x.png";
        const RunResult run = runFacet(
            "render " + shellQuoted(obj) + " -o " + shellQuoted(png) + " --width 32 --height 32", dir);
        EXPECT_EQ(run.status, 0) << run.err;
        EXPECT_EQ(lineCount(run.err), 1) << run.err;
        EXPECT_EQ(run.err.rfind("facet: warning: " + (dir.path() / name).string() + ": ", 0), 0u) << run.err;
        EXPECT_TRUE(onlyFacetLines(run.err)) << run.err;
        // The square is there, lit white-ish (Kd 1): the centre is far from the black background.
        const LinearImage image = readImage(png);
        const glm::vec4 centre = image.at(16, 16);
        EXPECT_GT(centre.r + centre.g + centre.b, 0.5f) << name;
        EXPECT_NEAR(centre.r, centre.b, 1e-3f) << name;  // untextured: grey, not the texture's blue
    }
}

// facet compare --shader FILE --against MODEL: exit 0 and "identical" for a shader computing the built-in
// formula; exit 1 (as diff) for one without the specular term, with the count, the first pixel's two
// colours, the facet step command and both traces side by side. Breaks caught: --against falling
// through to the Mesa comparison (exit 3 or a Mesa message), the exit statuses swapped or 3, the trace
// of the first pixel left out.
TEST(CompareAgainst, AShaderIsComparedWithTheBuiltInModel) {
    const testing_support::SharedShaderCache cache;
    const TempFolder dir;
    const std::string shader = (testing_support::kUserShaders / "own_phong.cpp").string();
    const std::string common = "compare '" FACET_SOURCE_DIR
                               "/models/spot/spot_triangulated.obj' --width 64 "
                               "--height 48 --against phong --shader '" +
                               shader + "'";
    const RunResult same = runFacet(common, dir);
    EXPECT_EQ(same.status, 0) << same.out << same.err;
    EXPECT_NE(same.out.find("identical: every pixel has the same 8-bit codes"), std::string::npos)
        << same.out;
    const RunResult differ = runFacet(common + " --uniform specular=false", dir);
    EXPECT_EQ(differ.status, 1) << differ.out << differ.err;
    EXPECT_NE(differ.out.find("differ: "), std::string::npos) << differ.out;
    EXPECT_NE(differ.out.find("first differing pixel (reading order): "), std::string::npos) << differ.out;
    EXPECT_NE(differ.out.find("trace it: facet step "), std::string::npos) << differ.out;
    EXPECT_NE(
        differ.out.find("under two settings:\n  left (<):  own_phong.cpp\n  right (>): built-in phong\n"),
        std::string::npos)
        << differ.out;
}

// --environment reaches the image (the background becomes the map) and the step mode's lighting
// screen (the reflection's numbers); a file that cannot be read is one line naming it and the flag.
TEST(Cli, EnvironmentFlagReachesTheImageAndTheStepScreen) {
    TempFolder dir;
    const std::filesystem::path root(FACET_SOURCE_DIR);
    const std::string model = shellQuoted(root / "models/spot/spot_triangulated.obj");
    const std::string sky = shellQuoted(root / "models/environment/sky.png");
    const auto plain = dir.path() / "plain.png", mapped = dir.path() / "mapped.png";
    ASSERT_EQ(
        runFacet("render " + model + " -o " + shellQuoted(plain) + " --width 48 --height 36", dir).status, 0);
    const RunResult run = runFacet(
        "render " + model + " -o " + shellQuoted(mapped) + " --width 48 --height 36 --environment " + sky,
        dir);
    ASSERT_EQ(run.status, 0) << run.err;
    // The top-left corner looks up-left into the sky: blue above red, not the dark clear colour.
    const glm::vec4 before = readImage(plain).at(0, 0), after = readImage(mapped).at(0, 0);
    EXPECT_LT(before.b, 0.05f);
    EXPECT_GT(after.b, 0.3f);
    EXPECT_GT(after.b, after.r);

    const RunResult step =
        runFacet("step " + model + " --width 48 --height 36 --pixel 24,18 --environment " + sky, dir);
    ASSERT_EQ(step.status, 0) << step.err;
    EXPECT_NE(step.out.find("R = 2(N·V)N − V"), std::string::npos) << step.out;
    EXPECT_NE(step.out.find("reflection = w ⊗ E(R) = RGB("), std::string::npos) << step.out;

    const RunResult missing = runFacet("render " + model + " -o " + shellQuoted(mapped) +
                                           " --width 48 --height 36 --environment nowhere/sky.png",
                                       dir);
    EXPECT_NE(missing.status, 0);
    EXPECT_NE(missing.err.find("nowhere/sky.png"), std::string::npos) << missing.err;
    EXPECT_NE(missing.err.find("--environment"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace facet
