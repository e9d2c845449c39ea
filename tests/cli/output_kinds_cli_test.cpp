// The facet program's outputs against what is already at the path (docs/bad-input.md, "Files and
// paths"): a FIFO read while facet writes, "-" as standard output, links followed, folders refused, and
// every output checked before long work; lists of inputs from FIFOs and endless pipes bounded. Every
// node is made by the test in its own folder.
#include <cstdlib>
#include <filesystem>
#include <future>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "run_facet.h"
#include "support/bundled_models.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using testing_support::readText;
using testing_support::runFacet;
using testing_support::RunResult;
using testing_support::TempFolder;

using testing_support::kCube;
const std::string kPngSignature = "\x89PNG\r\n\x1a\n";

using testing_support::shellQuoted;

// Reads a FIFO on another thread while facet runs; get() lets a reader go that facet never wrote to
// (a reader waiting to open a FIFO is let go by a writer opening it), so a failing test cannot hang.
class FifoReader {
  public:
    explicit FifoReader(fs::path fifo) : fifo_(std::move(fifo)) {
        text_ = std::async(std::launch::async, [this] {
            const int fd = ::open(fifo_.c_str(), O_RDONLY);
            std::string text;
            char buffer[4096];
            ssize_t count;
            while ((count = ::read(fd, buffer, sizeof buffer)) > 0)
                text.append(buffer, static_cast<std::size_t>(count));
            ::close(fd);
            return text;
        });
    }
    std::string get() {
        while (text_.wait_for(std::chrono::milliseconds(20)) != std::future_status::ready) {
            const int writer = ::open(fifo_.c_str(), O_WRONLY | O_NONBLOCK);
            if (writer >= 0) ::close(writer);
        }
        return text_.get();
    }

  private:
    fs::path fifo_;
    std::future<std::string> text_;
};

bool isFifo(const fs::path& path) {
    struct stat node;
    return ::lstat(path.c_str(), &node) == 0 && S_ISFIFO(node.st_mode);
}

// Catches: -o FIFO replaced by a regular PNG file (the temporary file renamed over it), exit 0.
TEST(OutputKindsCli, RenderIntoAFifoStreamsTheImage) {
    TempFolder dir;
    const fs::path fifo = dir.path() / "view.png";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    FifoReader reader(fifo);
    const RunResult run =
        runFacet("render " + shellQuoted(kCube) + " --width 32 --height 24 -o " + shellQuoted(fifo), dir);
    const std::string image = reader.get();
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(image.rfind(kPngSignature, 0), 0u) << "the reader got " << image.size() << " bytes";
    EXPECT_TRUE(isFifo(fifo)) << "the FIFO was replaced";
}

// Catches: -o - writing a file named "-", or the "facet: wrote" report mixed into the image's bytes.
TEST(OutputKindsCli, RenderToDashWritesThePngToStandardOutput) {
    TempFolder dir;
    const RunResult run =
        runFacet("render " + shellQuoted(kCube) + " --width 32 --height 24 -o -", dir, dir.path());
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.out.rfind(kPngSignature, 0), 0u);
    EXPECT_EQ(run.out.find("facet: wrote"), std::string::npos) << "a report went into the image";
    EXPECT_NE(run.err.find("facet: wrote -"), std::string::npos) << run.err;
    EXPECT_FALSE(fs::exists(dir.path() / "-"));
}

// Catches: a link given to -o replaced by a file instead of its target written; a dangling link not
// creating the file it names.
TEST(OutputKindsCli, RenderThroughLinksWritesTheirTargets) {
    TempFolder dir;
    const fs::path target = dir.write("real/image.png", "old");
    fs::create_symlink("real/image.png", dir.path() / "link.png");
    fs::create_symlink(dir.path() / "made.png", dir.path() / "dangling.png");
    for (const char* link : {"link.png", "dangling.png"}) {
        const RunResult run = runFacet(
            "render " + shellQuoted(kCube) + " --width 32 --height 24 -o " + shellQuoted(dir.path() / link),
            dir);
        EXPECT_EQ(run.status, 0) << link << ": " << run.err;
        EXPECT_TRUE(fs::is_symlink(dir.path() / link)) << link << " was replaced";
    }
    EXPECT_EQ(readText(target).rfind(kPngSignature, 0), 0u);
    EXPECT_EQ(readText(dir.path() / "made.png").rfind(kPngSignature, 0), 0u);
}

// Catches: a folder (or a link to one) given to -o or --json accepted, or refused with more than one line.
TEST(OutputKindsCli, FoldersAreRefusedInOneLine) {
    TempFolder dir;
    fs::create_directories(dir.path() / "folder.png");
    fs::create_symlink(dir.path() / "folder.png", dir.path() / "to-folder.json");
    const RunResult image =
        runFacet("render " + shellQuoted(kCube) + " -o " + shellQuoted(dir.path() / "folder.png"), dir);
    EXPECT_EQ(image.status, 1);
    EXPECT_EQ(image.err,
              "facet: error: " + (dir.path() / "folder.png").string() + ": is a folder, not an image file\n");
    const RunResult json = runFacet("step " + shellQuoted(kCube) + " --width 32 --height 24 --json " +
                                        shellQuoted(dir.path() / "to-folder.json"),
                                    dir);
    EXPECT_EQ(json.status, 1);
    EXPECT_EQ(json.err, "facet: error: " + (dir.path() / "to-folder.json").string() +
                            ": cannot write: it is a folder\n");
    EXPECT_TRUE(fs::is_symlink(dir.path() / "to-folder.json"));
}

// Catches: step --json into a FIFO replacing it (the /dev/full case of the battery, on a node of our own).
TEST(OutputKindsCli, StepJsonIntoAFifo) {
    TempFolder dir;
    const fs::path fifo = dir.path() / "trace.json";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    FifoReader reader(fifo);
    const RunResult run =
        runFacet("step " + shellQuoted(kCube) + " --width 32 --height 24 --json " + shellQuoted(fifo), dir);
    const std::string json = reader.get();
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(json.rfind("{", 0), 0u) << json.substr(0, 80);
    EXPECT_TRUE(isFifo(fifo));
}

// Catches: `--html ""` reported as ": cannot create the folder: Invalid argument".
TEST(OutputKindsCli, EmptyHtmlFolderNameIsNamed) {
    TempFolder dir;
    const RunResult run = runFacet("step " + shellQuoted(kCube) + " --width 32 --height 24 --html ''", dir);
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(run.err, "facet: error: --html needs the name of a folder to write into (got an empty name)\n");
}

// Catches: bench --vs-mesa running its whole benchmark (a minute) before finding the CSV cannot be
// written: refused before the first line of the benchmark is printed.
TEST(OutputKindsCli, BenchCsvFolderIsRefusedBeforeTheBenchmark) {
    TempFolder dir;
    fs::create_directories(dir.path() / "tables");
    const RunResult run =
        runFacet("bench --vs-mesa --quick --csv " + shellQuoted(dir.path() / "tables"), dir);
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(run.out, "") << "the benchmark began";
    EXPECT_EQ(run.err,
              "facet: error: " + (dir.path() / "tables").string() + ": cannot write: it is a folder\n");
}

// Catches: --list FIFO with no program writing into it blocking forever (FACET_PIPE_WAIT_SECONDS shortens
// the wait for the test).
TEST(OutputKindsCli, ListFifoNobodyWritesIsGivenUp) {
    TempFolder dir;
    const fs::path fifo = dir.path() / "list";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    ::setenv("FACET_PIPE_WAIT_SECONDS", "0.3", 1);
    const RunResult run = runFacet(
        "render --list " + shellQuoted(fifo) + " -o " + shellQuoted(dir.path() / "{index}.png"), dir);
    ::unsetenv("FACET_PIPE_WAIT_SECONDS");
    EXPECT_EQ(run.status, 1);
    EXPECT_NE(run.err.find("facet: error: " + fifo.string() +
                           ": cannot read the list of inputs (no program wrote into the FIFO within 0.3 s"),
              std::string::npos)
        << run.err;
}

// Catches: an endless list from a pipe (yes model | facet render --list -) read until the memory runs out.
TEST(OutputKindsCli, EndlessListFromAPipeIsBounded) {
    TempFolder dir;
    const fs::path err = dir.path() / "stderr.txt", out = dir.path() / "stdout.txt";
    const std::string command = "yes " + shellQuoted(kCube) + " | '" + FACET_BINARY +
                                "' render --list - -o " + shellQuoted(dir.path() / "{index}.png") + " >" +
                                shellQuoted(out) + " 2>" + shellQuoted(err);
    const int raw = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(raw));
    EXPECT_EQ(WEXITSTATUS(raw), 1);
    EXPECT_NE(readText(err).find("the list names more than 1000000 inputs"), std::string::npos)
        << readText(err);
    EXPECT_FALSE(fs::exists(dir.path() / "0.png")) << "rendering began";
}

}  // namespace
}  // namespace facet
