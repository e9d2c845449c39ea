// facet bench's modes: what they refuse before timing anything, and what a tiny run reports.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <sys/stat.h>

#include <gtest/gtest.h>

#include "bench/bench.h"
#include "bench/process_stats.h"
#include "render/frame_kernels.h"
#include "support/temp_folder.h"
#include "support/user_shader_files.h"

namespace facet {
namespace {

using BenchTest = testing_support::TempFolderTest;
using testing_support::errorWithoutOpening;

// A FIFO would block the benchmark until something writes to it; each mode refuses it unopened.
TEST_F(BenchTest, FifoIsRefusedWithoutOpeningIt) {
    const std::filesystem::path fifo = folder_ / "scene.json";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const std::string expected =
        fifo.string() + ": is not a regular file (a device, a pipe or a socket), not a scene file";
    BenchOptions options;
    options.model = fifo;
    options.frames = 1;
    std::ostringstream out;
    EXPECT_EQ(errorWithoutOpening(fifo, [&] { runBench(options, out); }), expected) << "bench";
    EXPECT_EQ(errorWithoutOpening(fifo, [&] { runSortBench(options, out); }), expected) << "bench --sort";
}

// The first five fields of each line of a CSV after its header: part, configuration, threads, lights,
// frames (the row's name); " +per-light" when its last three, the costs per shadowing light, are given.
std::vector<std::string> csvRowNames(const std::filesystem::path& path) {
    std::ifstream file(path);
    std::string line;
    std::getline(file, line);  // the header
    std::vector<std::string> names;
    while (std::getline(file, line)) {
        std::vector<std::string> fields(1);
        for (char c : line) {
            if (c == ',')
                fields.emplace_back();
            else
                fields.back().push_back(c);
        }
        std::string name;
        for (std::size_t k = 0; k < 5 && k < fields.size(); ++k) {
            if (k) name += ',';
            name += fields[k];
        }
        if (fields.size() == 14 && !fields[11].empty() && !fields[12].empty() && !fields[13].empty())
            name += " +per-light";
        if (fields.size() != 14) name += " (not 14 fields)";
        names.push_back(name);
    }
    return names;
}

// facet bench --reference, tiny (32×24, 1 frame each): every row of every table, named in the report and
// in the CSV, once, in order; the cost per shadowing light given exactly where lights cast shadows; the
// reference and the rays on 1, 2, 4, ... threads up to --threads and on --threads itself (3 here).
TEST_F(BenchTest, ReferenceModeNamesEveryRow) {
    BenchOptions options;
    options.model = std::filesystem::path(FACET_SOURCE_DIR) / "models/spot/spot_triangulated.obj";
    options.ground = std::filesystem::path(FACET_SOURCE_DIR) / "models/fog-and-glass/ground.obj";
    options.width = 32;
    options.height = 24;
    options.frames = 1;
    options.threads = 3;
    options.csv = folder_ / "out/bench-reference.csv";  // its folder is made
    std::ostringstream out;
    runReferenceBench(options, out);

    std::vector<std::string> expected;
    for (const char* samples : {"1 sample", "16 samples"})
        for (const char* threads : {"1", "2", "3"})
            expected.push_back(std::string("reference,") + samples + "," + threads + ",0,1");
    for (const char* rays : {"packets of 8", "single rays"})
        for (const char* culling : {" culling back", " culling none"})
            for (const char* threads : {"1", "2", "3"})
                expected.push_back(std::string("rays,") + rays + culling + "," + threads + ",0,1");
    expected.push_back("bvh,5856 triangles," + std::to_string(std::thread::hardware_concurrency()) + ",0,3");
    for (const char* lights : {"1", "2", "4"})
        for (const char* shadows : {"none", "ray", "map 1024", "map 2048", "map 4096"})
            expected.push_back(std::string("shadows,") + shadows + ",3," + lights + ",1" +
                               (std::string(shadows) == "none" ? "" : " +per-light"));
    EXPECT_EQ(csvRowNames(options.csv), expected);

    const std::string report = out.str();
    for (const char* name :
         {"Reference renderer", "16", "packets of 8 culling back", "single rays culling none", "BVH build",
          "5856 triangles", "Shadows in the rasterizer", "map 4096", "per shadowing light", "wrote"})
        EXPECT_NE(report.find(name), std::string::npos) << name << " missing from:\n" << report;
}

// A benchmark of the bundled cow at 64×48, one frame on one thread: quick enough for a test.
BenchOptions tinySpotOptions() {
    BenchOptions options;
    options.model = std::filesystem::path(FACET_SOURCE_DIR) / "models/spot/spot_triangulated.obj";
    options.width = 64;
    options.height = 48;
    options.frames = 1;
    options.threads = 1;
    return options;
}

// The number after "fragments  " in a report of runBench.
long long fragmentsShaded(const std::string& report) {
    const std::size_t at = report.find("fragments  ");
    return at == std::string::npos ? -1 : std::stoll(report.substr(at + 11));
}

// facet bench --aa: the timed frames are drawn with the anti-aliasing asked for (the report names it),
// and supersampling shades about four times the fragments of one sample per pixel. Fails if benchScene
// drops options.antialiasing.
TEST_F(BenchTest, TimesTheAntialiasingAskedFor) {
    BenchOptions options = tinySpotOptions();
    std::ostringstream none, ssaa4;
    runBench(options, none);
    options.antialiasing = Antialiasing::Ssaa4;
    runBench(options, ssaa4);
    EXPECT_NE(none.str().find("samples    1 per pixel (--aa none)"), std::string::npos) << none.str();
    EXPECT_NE(ssaa4.str().find("samples    4 per pixel (--aa ssaa4)"), std::string::npos) << ssaa4.str();
    const long long one = fragmentsShaded(none.str()), four = fragmentsShaded(ssaa4.str());
    ASSERT_GT(one, 100);
    EXPECT_GT(four, 3 * one);
    EXPECT_LT(four, 5 * one);
}

// facet bench --cut-for: one thread's frames cut as for 16 threads (the report says so, from the context the
// frames were drawn with) give the same fragments. Fails if runBench drops options.cutFor.
TEST_F(BenchTest, CutsTheWorkForTheThreadsAskedFor) {
    BenchOptions options = tinySpotOptions();
    std::ostringstream plain, cut;
    runBench(options, plain);
    options.cutFor = 16;
    runBench(options, cut);
    EXPECT_EQ(plain.str().find("work cut for"), std::string::npos) << plain.str();
    EXPECT_NE(cut.str().find("1 thread (work cut for 16)"), std::string::npos) << cut.str();
    EXPECT_EQ(fragmentsShaded(cut.str()), fragmentsShaded(plain.str()));
}

// With two threads the report says how long a cache line takes to reach the other core (what two-thread
// frames depend on), measured then; with one it says nothing of it. Fails if the line is dropped, printed
// for one thread, or its measurement returns nothing (0 on a machine of two hardware threads or more).
TEST_F(BenchTest, TwoThreadsReportTheCoresHandOffTime) {
    BenchOptions options = tinySpotOptions();
    std::ostringstream one, two;
    runBench(options, one);
    options.threads = 2;
    runBench(options, two);
    const std::string label = "cores      one core sees another's write after ";
    EXPECT_EQ(one.str().find("cores      "), std::string::npos) << one.str();
    if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one hardware thread: nothing to hand off";
    const std::size_t at = two.str().find(label);
    if (two.str().find("cores      two threads did not run at once") != std::string::npos)
        GTEST_SKIP() << "the machine is busy: the hand-off could not be timed";
    ASSERT_NE(at, std::string::npos) << two.str();
    EXPECT_GT(std::stol(two.str().substr(at + label.size())), 0) << two.str();
    EXPECT_GT(coreHandoffNanoseconds(5.0), 0.0);
}

// facet bench --instruction-sets: every copy of the hot path this CPU runs is timed, its image is
// identical to the widest copy's, and the copy chosen before is in use again afterwards. Fails if a
// copy is left out or its row does not report the comparison, if the restore is dropped (one frame per
// copy: the widest draws last), and, on a CPU without AVX-512, if the copies are taken from the built
// list without asking the CPU (a copy it cannot run throws). A comparison that always says "identical"
// is not caught: the copies do draw the same bytes (frame_kernels_test checks that on its own).
TEST_F(BenchTest, InstructionSetsAreEachTimedAndAgree) {
    const InstructionSet initial = frameKernels().instructionSet;
    useFrameKernels(InstructionSet::Baseline);
    std::ostringstream report;
    runInstructionSetBench(tinySpotOptions(), report);
    const InstructionSet after = frameKernels().instructionSet;
    useFrameKernels(initial);
    EXPECT_EQ(after, InstructionSet::Baseline);

    const std::string text = report.str();
    std::vector<InstructionSet> runnable;
    for (const FrameKernels& kernels : builtFrameKernels())
        if (cpuSupports(kernels.instructionSet)) runnable.push_back(kernels.instructionSet);
    ASSERT_FALSE(runnable.empty());
    const std::string widest(nameOf(runnable.back()));
    for (const InstructionSet set : runnable) {
        const std::string name(nameOf(set));
        const std::size_t line = text.find("\n" + name + " ");
        ASSERT_NE(line, std::string::npos) << name << " missing from:\n" << text;
        const std::string row = text.substr(line + 1, text.find('\n', line + 1) - line - 1);
        EXPECT_NE(row.find("median"), std::string::npos) << row;
        if (name != widest) {
            EXPECT_NE(row.find("image identical to " + widest + "'s"), std::string::npos) << row;
        }
    }
}

// facet bench --shader: the shader's frames and the built-in per-pixel Blinn-Phong's take turns, and
// the report gives both and their ratio. Breaks caught: the built-in side left drawing with the shader
// (or the shader side with the built-in: the written fragments of the two sides then agree where the
// discarding shader writes fewer of them), the ratio's line missing.
TEST_F(BenchTest, ShaderIsTimedAgainstTheBuiltInBlinnPhong) {
    const testing_support::SharedShaderCache cache;
    BenchOptions options;
    options.model = FACET_SOURCE_DIR "/models/spot/spot_triangulated.obj";
    options.width = 64;
    options.height = 48;
    options.frames = 2;
    options.threads = 1;
    options.shader = ShaderSpec{testing_support::kUserShaders / "displace_cutout.cpp", {}};
    options.uniforms = {{"cut", {0.3}, false, "test: cut"}};
    std::ostringstream out;
    runBench(options, out);
    const std::string report = out.str();
    EXPECT_NE(report.find("shader     displace_cutout.cpp: median "), std::string::npos) << report;
    EXPECT_NE(report.find("built-in   built-in per-pixel Blinn-Phong: median "), std::string::npos) << report;
    EXPECT_NE(report.find("x the built-in's frame (wall-clock medians)"), std::string::npos) << report;
    EXPECT_NE(report.find("frames     2 of each"), std::string::npos) << report;
    // The shader discards the fragments facing up, the built-in none: fewer written on its side.
    const auto written = [&](const std::string& line) {
        const std::size_t at = report.find(line);
        const std::size_t shaded = report.find(" shaded, ", at);
        return std::stoull(report.substr(shaded + 9));
    };
    EXPECT_LT(written("shader     "), written("built-in   ")) << report;
}

}  // namespace
}  // namespace facet
