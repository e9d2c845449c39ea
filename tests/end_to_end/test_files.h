// Temporary folders and files for the end-to-end tests.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

namespace facet::testing {

// A fresh folder under the system temp directory, removed when the test ends.
class TempDir {
  public:
    TempDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ =
            std::filesystem::temp_directory_path() / ("facet-" + std::string(info->test_suite_name()) + "-" +
                                                      info->name() + "-" + std::to_string(::getpid()));
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() { std::filesystem::remove_all(path_); }
    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path write(const std::string& name, const std::string& text) const {
        const std::filesystem::path file = path_ / name;
        std::ofstream(file, std::ios::binary) << text;
        return file;
    }

  private:
    std::filesystem::path path_;
};

inline std::string readText(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

#ifdef FACET_BINARY
// The facet program run as a user runs it: its exit status and what it printed.
struct RunResult {
    int status = -1;
    std::string out;
    std::string err;
};

// Runs facet (FACET_BINARY) with `args`, its output captured in `dir`, standard input empty; in
// `workingFolder` when one is given.
inline RunResult runFacet(const std::string& args, const TempDir& dir,
                          const std::filesystem::path& workingFolder = {}) {
    const auto outFile = dir.path() / "stdout.txt", errFile = dir.path() / "stderr.txt";
    // Built with a stream: GCC 12 reports a false -Wrestrict on chains of std::string operator+.
    std::ostringstream command;
    if (!workingFolder.empty()) command << "cd '" << workingFolder.string() << "' && ";
    command << "'" << FACET_BINARY << "' " << args << " >'" << outFile.string() << "' 2>'" << errFile.string()
            << "' </dev/null";
    const int raw = std::system(command.str().c_str());
    RunResult run;
    run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    run.out = readText(outFile);
    run.err = readText(errFile);
    return run;
}
#endif  // FACET_BINARY

}  // namespace facet::testing
