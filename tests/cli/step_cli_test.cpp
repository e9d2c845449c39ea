// facet step as a user runs it: the screens printed without a terminal, the JSON trace, --versus, bad
// requests refused with one line. Each test names the one-line break it catches.
#include <algorithm>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "run_facet.h"

namespace facet {
namespace {

using testing_support::readText;
using testing_support::runFacet;
using testing_support::RunResult;
using testing_support::TempFolder;

const std::string kSpotArguments =
    std::string("'") + FACET_SOURCE_DIR + "/models/spot/spot_triangulated.obj' --width 96 --height 72";

// Columns a line takes: UTF-8 continuation bytes take none.
std::size_t columns(const std::string& line) {
    std::size_t n = 0;
    for (unsigned char c : line)
        n += (c & 0xC0) != 0x80;
    return n;
}

// Without a terminal, every screen is printed, each line within 80 columns. Catches: the command not
// falling back to --print without a terminal (it would wait for keys), a screen left out of the walk,
// a line of a screen over 80 columns.
TEST(StepCli, WithoutATerminalPrintsEveryScreenWithin80Columns) {
    TempFolder dir;
    for (const char* shading : {"flat", "gouraud", "phong"}) {
        SCOPED_TRACE(shading);
        const RunResult run = runFacet("step " + kSpotArguments + " --shading " + shading, dir);
        ASSERT_EQ(run.status, 0) << run.err;
        for (const char* title : {"Pixel history of", "Input: triangle", "Vertex shader: object",
                                  "Clipping:", "Divide and viewport", "Setup:", "Rasterization:",
                                  "Interpolation:", "Depth test:", "Encoding: the byte"})
            EXPECT_NE(run.out.find(title), std::string::npos) << title;
        std::istringstream lines(run.out);
        for (std::string line; std::getline(lines, line);)
            EXPECT_LE(columns(line), 80u) << line;
    }
}

// Anti-aliasing is refused, each kind for what it does: multisampling tests coverage at sample positions
// within one drawing, supersampling draws the frame once per sample. Catches the old message that said
// msaa4 draws the frame 4 times.
TEST(StepCli, AntialiasingIsRefusedSayingWhatItDoes) {
    TempFolder dir;
    const RunResult msaa = runFacet("step " + kSpotArguments + " --print --aa msaa4", dir);
    EXPECT_EQ(msaa.status, 1);
    EXPECT_NE(msaa.err.find("--aa msaa4"), std::string::npos) << msaa.err;
    EXPECT_NE(msaa.err.find("tests coverage and depth at 4 sample positions"), std::string::npos) << msaa.err;
    EXPECT_EQ(msaa.err.find("times"), std::string::npos) << msaa.err;
    const RunResult ssaa = runFacet("step " + kSpotArguments + " --print --aa ssaa4", dir);
    EXPECT_EQ(ssaa.status, 1);
    EXPECT_NE(ssaa.err.find("draws the frame 4 times"), std::string::npos) << ssaa.err;
}

// --json writes the trace as data, and its final bytes are the rendered image's. Catches: --json
// ignored, or a trace of another pixel than --pixel asks for.
TEST(StepCli, JsonHasThePixelAskedForAndItsHistory) {
    TempFolder dir;
    const auto json = dir.path() / "trace.json";
    const RunResult run =
        runFacet("step " + kSpotArguments + " --pixel 40,30 --print --json '" + json.string() + "'", dir);
    ASSERT_EQ(run.status, 0) << run.err;
    const nlohmann::json trace = nlohmann::json::parse(readText(json));
    EXPECT_EQ(trace["pixel"]["x"], 40);
    EXPECT_EQ(trace["pixel"]["y"], 30);
    EXPECT_FALSE(trace["pixel"]["triangles"].empty());
    EXPECT_EQ(trace["screens"].size(), 14u);
    EXPECT_TRUE(trace.contains("shading"));
    EXPECT_EQ(trace["screens"][0]["id"], "history");
    EXPECT_NE(run.out.find("Pixel (40, 30)"), std::string::npos);
}

// --versus traces the same pixel and triangle again under other options and marks the first line where
// they part: affine interpolation first changes the fragment's weights in the pixel history. Catches:
// --versus's options not applied to the second trace (no difference), or applied to both.
TEST(StepCli, VersusMarksWhereAffineInterpolationFirstDiffers) {
    TempFolder dir;
    const RunResult run =
        runFacet("step " + kSpotArguments + " --pixel 48,30 --versus '--interpolation affine'", dir);
    ASSERT_EQ(run.status, 0) << run.err;
    // The pixel history lists what interpolation gave each fragment: the weights part there first.
    EXPECT_NE(run.out.find("They first differ in \"Pixel history of (48, 30)\""), std::string::npos)
        << run.out.substr(0, 400);
    EXPECT_NE(run.out.find("right:   λ′ = λ: affine interpolation"), std::string::npos)
        << run.out.substr(0, 400);
    // And the interpolation screen says the same.
    EXPECT_NE(run.out.find(" > Affine interpolation (no perspective correction)"), std::string::npos);
    const RunResult same =
        runFacet("step " + kSpotArguments + " --pixel 48,30 --versus '--interpolation perspective'", dir);
    ASSERT_EQ(same.status, 0) << same.err;
    EXPECT_NE(same.out.find("The two traces are the same"), std::string::npos) << same.out.substr(0, 400);
}

// --lighting lecture reaches the step screens, and --versus '--lighting lecture' names where Facet's
// Cook-Torrance form and the notes' part: the denominator 4(N·L)(N·V) on the left, π(N·V)(N·L) on the
// right, F at V·H against F at N·L, and the output curve; every line within 80 columns. Catches: the
// preset not reaching the step mode, the versus view not showing both forms, or its lines too wide.
TEST(StepCli, VersusLecturePresetNamesTheDifferingForms) {
    TempFolder dir;
    const std::string cookTorrance = kSpotArguments + " --pixel 48,30 --reflection cook-torrance";
    const RunResult lecture = runFacet("step " + cookTorrance + " --lighting lecture --print", dir);
    ASSERT_EQ(lecture.status, 0) << lecture.err;
    EXPECT_NE(lecture.out.find("f_r = metalness·D·F·G/(π(N·V)(N·L))·c_base"), std::string::npos)
        << lecture.out.substr(0, 2000);
    const RunResult run = runFacet("step " + cookTorrance + " --versus '--lighting lecture'", dir);
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.out.find("They first differ in"), std::string::npos) << run.out.substr(0, 600);
    for (const char* shown :
         {"<   f_r = (1 − F)(1 − metalness)·c_base/π + D·F·G/(4(N·L)(N·V))",
          ">   f_r = metalness·D·F·G/(π(N·V)(N·L))·c_base", "<   F = F0 + (1 − F0)(1 − V·H)^5",
          ">   F = F0 + (1 − F0)(1 − N·L)^5", "c′ = c^(1/γ), γ = 2.2"})
        EXPECT_NE(run.out.find(shown), std::string::npos) << shown;
    std::istringstream lines(run.out);
    for (std::string line; std::getline(lines, line);)
        EXPECT_LE(columns(line), 80u) << line;
}

// Catches: a pixel outside the image, a triangle the scene lacks, a malformed --pixel or --versus
// option accepted (or a crash) instead of one line and exit status 1.
TEST(StepCli, BadRequestsAreRefusedWithOneLine) {
    TempFolder dir;
    for (const std::string& bad :
         {std::string(" --pixel 96,0"), std::string(" --pixel 3"), std::string(" --pixel -1,2"),
          std::string(" --triangle 99999"), std::string(" --versus '--shading wobbly'")}) {
        SCOPED_TRACE(bad);
        const RunResult run = runFacet("step " + kSpotArguments + bad, dir);
        EXPECT_EQ(run.status, 1);
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
        EXPECT_EQ(run.err.rfind("facet: error: ", 0), 0u) << run.err;
        EXPECT_TRUE(run.out.empty()) << run.out.substr(0, 200);
    }
}

// A web page of too many traced pixels is refused before anything is written. Catches: the bound
// checked only after the stage images are written (the folder appears), or not at all.
TEST(StepCli, HtmlStepTooFineIsRefusedBeforeAnythingIsWritten) {
    TempFolder dir;
    const auto page = dir.path() / "page";
    const RunResult run =
        runFacet(std::string("step '") + FACET_SOURCE_DIR +
                     "/models/spot/spot_triangulated.obj' --width 800 --height 600 --html-step 1 --html '" +
                     page.string() + "'",
                 dir);
    EXPECT_EQ(run.status, 1);
    EXPECT_NE(run.err.find("--html-step 1 would trace 480000 pixels"), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists(page));
}

// --screen prints one screen: in text the very block --print shows, in markdown under a heading, in
// latex a frame's body. Catches: --screen ignored (the whole walk printed), the text export drifting
// from --print, a format name not reaching its writer.
TEST(StepCli, ScreenPrintsOneScreenInTheFormatAsked) {
    TempFolder dir;
    const std::string all = runFacet("step " + kSpotArguments + " --print", dir).out;
    const RunResult text = runFacet("step " + kSpotArguments + " --screen clip", dir);
    ASSERT_EQ(text.status, 0) << text.err;
    EXPECT_NE(all.find("\n" + text.out), std::string::npos) << text.out;
    EXPECT_EQ(text.out.find("Pixel history"), std::string::npos);
    const RunResult markdown = runFacet("step " + kSpotArguments + " --screen clip --format markdown", dir);
    EXPECT_EQ(markdown.out.rfind("## Clipping", 0), 0u) << markdown.out;
    const RunResult latex = runFacet("step " + kSpotArguments + " --screen clip --format latex", dir);
    EXPECT_EQ(latex.out.rfind("\\frametitle{Clipping", 0), 0u) << latex.out;
    const RunResult walk = runFacet("step " + kSpotArguments + " --format latex", dir);
    EXPECT_NE(walk.out.find("\\begin{frame}\n\\frametitle{Pixel history"), std::string::npos);
    EXPECT_NE(walk.out.find("\\frametitle{Encoding"), std::string::npos);
}

// Catches: --stage-scale parsed but not handed to the stage images (written at the frame's size).
TEST(StepCli, StageScaleWritesTheImagesThatManyTimesLarger) {
    TempFolder dir;
    const auto stages = dir.path() / "stages";
    const RunResult run = runFacet(
        "step " + kSpotArguments + " --print --stages '" + stages.string() + "' --stage-scale 2", dir);
    ASSERT_EQ(run.status, 0) << run.err;
    // A PNG's size: the IHDR chunk's width and height, big-endian, at bytes 16 and 20.
    const std::string png = readText(stages / "final.png");
    ASSERT_GT(png.size(), 24u);
    auto at = [&](std::size_t k) {
        return (std::uint32_t(std::uint8_t(png[k])) << 24) | (std::uint32_t(std::uint8_t(png[k + 1])) << 16) |
               (std::uint32_t(std::uint8_t(png[k + 2])) << 8) | std::uint32_t(std::uint8_t(png[k + 3]));
    };
    EXPECT_EQ(at(16), 2u * 96u);
    EXPECT_EQ(at(20), 2u * 72u);
}

// Catches: an unknown screen name, a --format or --stage-scale out of range, or the two asks that
// cannot be met together accepted silently or with a crash instead of one line and a non-zero status.
TEST(StepCli, BadScreenOrScaleIsRefusedWithOneLine) {
    TempFolder dir;
    const std::string stages = " --stages '" + (dir.path() / "stages").string() + "'";
    struct Bad {
        std::string options;
        int status;
        std::string says;
    };
    for (const Bad& bad :
         {Bad{" --screen clipping", 1, "its screens are history, input, transform, clip"},
          Bad{" --format html", 2, "--format"}, Bad{" --stage-scale 0" + stages, 2, "--stage-scale"},
          Bad{" --stage-scale 2", 2, "--stages"},
          Bad{" --stage-scale 200" + stages, 1, "at most 16384 pixels a side (--stage-scale 170"},
          Bad{" --screen clip --versus '--shading flat'", 1, "--versus"}}) {
        SCOPED_TRACE(bad.options);
        const RunResult run = runFacet("step " + kSpotArguments + bad.options, dir);
        EXPECT_EQ(run.status, bad.status);
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
        EXPECT_NE(run.err.find(bad.says), std::string::npos) << run.err;
        EXPECT_TRUE(run.out.empty()) << run.out.substr(0, 200);
    }
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "stages"));
}

// The pixels the page's tiles hold walks for (trace-tiles/*.js, each calling facetStepTile).
std::set<std::pair<int, int>> tracedPixels(const std::filesystem::path& page) {
    std::set<std::pair<int, int>> pixels;
    for (const auto& entry : std::filesystem::directory_iterator(page / "trace-tiles")) {
        const std::string script = readText(entry.path());
        const std::size_t begin = script.find('{'), end = script.rfind(')');
        const nlohmann::json tile = nlohmann::json::parse(script.substr(begin, end - begin));
        for (const nlohmann::json& walk : tile["walks"])
            pixels.emplace(walk.at(0).get<int>(), walk.at(1).get<int>());
    }
    return pixels;
}

// A small image is traced in full by default; with a step and a region, the grid from step/2 and every
// pixel of the region. Catches: a default that still leaves pixels untraced (a click on the neighbour of
// a shared-edge tie saying "not traced"), or a region or grid pixel missing from the tiles.
TEST(StepCli, HtmlTracesEveryPixelOfASmallImageAndTheRegion) {
    TempFolder dir;
    const auto page = dir.path() / "page";
    const std::string spot = std::string("step '") + FACET_SOURCE_DIR + "/models/spot/spot_triangulated.obj'";
    RunResult run = runFacet(spot + " --width 21 --height 15 --html '" + page.string() + "'", dir);
    ASSERT_EQ(run.status, 0) << run.err;
    std::set<std::pair<int, int>> every;
    for (int y = 0; y < 15; ++y)
        for (int x = 0; x < 21; ++x)
            every.emplace(x, y);
    EXPECT_EQ(tracedPixels(page), every);

    std::filesystem::remove_all(page);
    run = runFacet(spot + " --width 21 --height 15 --html-step 4 --html-region 3,4,2,3 --pixel 2,2 --html '" +
                       page.string() + "'",
                   dir);
    ASSERT_EQ(run.status, 0) << run.err;
    std::set<std::pair<int, int>> expected;
    for (int y = 2; y < 15; y += 4)  // the grid: from 4/2 = 2, every 4th
        for (int x = 2; x < 21; x += 4)
            expected.emplace(x, y);
    for (int y = 4; y < 7; ++y)
        for (int x = 3; x < 5; ++x)
            expected.emplace(x, y);
    EXPECT_EQ(tracedPixels(page), expected);
}

// Catches: a malformed or outside --html-region, or one without --html, accepted (or a crash) instead of
// one line and exit status 1; a page of too many pixels refused without naming the ways out.
TEST(StepCli, BadHtmlRegionsAreRefusedWithOneLine) {
    TempFolder dir;
    const std::string page = " --html '" + (dir.path() / "page").string() + "'";
    for (const std::string& bad :
         {" --html-region 1,2,3" + page, " --html-region 0,0,0,5" + page, " --html-region 90,0,10,10" + page,
          " --html-region a,b,c,d" + page, std::string(" --html-region 0,0,5,5")}) {
        SCOPED_TRACE(bad);
        const RunResult run = runFacet("step " + kSpotArguments + bad, dir);
        EXPECT_EQ(run.status, 1);
        EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
        EXPECT_NE(run.err.find("--html-region"), std::string::npos) << run.err;
        EXPECT_FALSE(std::filesystem::exists(dir.path() / "page"));
    }
    const RunResult big = runFacet(std::string("step '") + FACET_SOURCE_DIR +
                                       "/models/spot/spot_triangulated.obj' --width 800 --height 600 "
                                       "--html-region 0,0,400,300" +
                                       page,
                                   dir);
    EXPECT_EQ(big.status, 1);
    // The default grid of 800x600, every 16th pixel from 8 (ceil(sqrt(480000 / 2000)) = 16): 50 × 37
    // pixels, 25 × 19 of them in the region, which adds its 400 × 300: 1850 + 120000 − 475 = 121375.
    // Every 3rd pixel (ceil(sqrt(480000 / 100000)) = 3) would do.
    for (const char* named :
         {"would trace 121375 pixels", "at most 100000", "--html-region X,Y,W,H", "--html-step 3"})
        EXPECT_NE(big.err.find(named), std::string::npos) << named << " in " << big.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "page"));
}

}  // namespace
}  // namespace facet
