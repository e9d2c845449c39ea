// The facet program run as a user runs it, for the tests of the command line (tests/cli): its exit
// status and what it printed, kept in the test's temporary folder (support/temp_folder.h).
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "support/temp_folder.h"

namespace facet::testing_support {

inline std::string readText(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// `path` in single quotes: one word of the shell command runFacet runs.
inline std::string shellQuoted(const std::filesystem::path& path) {
    std::string text = "'";  // appended piece by piece: GCC 12 warns falsely on "'" + s (-Wrestrict)
    text += path.string();
    text += '\'';
    return text;
}

#ifdef FACET_BINARY
struct RunResult {
    int status = -1;
    std::string out;
    std::string err;
};

// Runs facet (FACET_BINARY) with `args`, its output captured in `dir`, standard input empty; in
// `workingFolder` when one is given.
inline RunResult runFacet(const std::string& args, const TempFolder& dir,
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

}  // namespace facet::testing_support
