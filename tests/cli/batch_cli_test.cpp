// facet render of many inputs as a user runs it (docs/batch.md): what a log file gets, and the exit
// status. The plan and the run themselves are tested in tests/cli/batch_test.cpp.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "run_facet.h"

namespace facet {
namespace {

using testing_support::runFacet;
using testing_support::RunResult;
using testing_support::TempFolder;

// Standard error redirected to a file is no terminal: no progress line (no carriage return) in it,
// only the summary and the failure; a line per image on standard output; status 1 for the broken
// input. Breaks if renderBatch takes every standard error for a terminal, or returns 0 with a failure.
TEST(BatchCli, ALogGetsNoProgressLineAndAFailureExitsOne) {
    TempFolder dir;
    const std::filesystem::path models = std::filesystem::path(FACET_SOURCE_DIR) / "models";
    const std::filesystem::path broken = dir.write("broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n");
    const RunResult run =
        runFacet("render '" + (models / "cube/cube.obj").string() + "' '" + broken.string() + "' '" +
                     (models / "spot/spot_triangulated.obj").string() + "' -o '" +
                     (dir.path() / "out/{name}.png").string() + "' --width 64 --height 48",
                 dir);
    EXPECT_EQ(run.status, 1) << run.err;
    EXPECT_EQ(run.err.find('\r'), std::string::npos) << run.err;
    EXPECT_EQ(run.err.rfind("facet: rendered 2 of 3 inputs in ", 0), 0u) << run.err;
    EXPECT_NE(run.err.find("\nfacet: error: " + broken.string() + ":3: "), std::string::npos) << run.err;
    EXPECT_EQ(run.out.rfind("facet: wrote " + (dir.path() / "out/cube.png").string() + " (64x48, ", 0), 0u)
        << run.out;
    EXPECT_NE(run.out.find("\nfacet: wrote " + (dir.path() / "out/spot_triangulated.png").string()),
              std::string::npos)
        << run.out;
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "out/spot_triangulated.png"));
}

}  // namespace
}  // namespace facet
