// facet bench's modes: what they refuse before timing anything.
#include <filesystem>
#include <sstream>
#include <string>

#include <sys/stat.h>

#include <gtest/gtest.h>

#include "bench/bench.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

using BenchTest = testing_support::TempFolderTest;
using testing_support::errorWithinASecond;

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
    EXPECT_EQ(errorWithinASecond(fifo, [&] { runBench(options, out); }), expected) << "bench";
    EXPECT_EQ(errorWithinASecond(fifo, [&] { runSortBench(options, out); }), expected) << "bench --sort";
}

}  // namespace
}  // namespace facet
