// How an output path is written (io/output_path.h), for each kind of thing that can be at the path:
// a regular file or nothing (atomically), a FIFO, a device and "-" (directly, never replaced), a
// symbolic link (followed), a folder, a socket or a link loop (refused). Every node is made by the test in
// its own folder; none of the system's is touched.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <future>
#include <string>
#include <thread>

#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <unistd.h>

#include "base/errors.h"
#include "io/output_path.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using testing_support::TempFolderTest;

std::string readAll(int fd) {
    std::string text;
    char buffer[4096];
    ssize_t count;
    while ((count = ::read(fd, buffer, sizeof buffer)) > 0)
        text.append(buffer, static_cast<std::size_t>(count));
    return text;
}

std::string readFile(const fs::path& file) {
    const int fd = ::open(file.c_str(), O_RDONLY);
    if (fd < 0) return "(cannot open)";
    std::string text = readAll(fd);
    ::close(fd);
    return text;
}

// What `write` throws, "" when it throws nothing.
template <class F>
std::string errorOf(F&& write) {
    try {
        write();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// Reads a FIFO on another thread; get() lets go a reader nothing was written to (a reader waiting to
// open a FIFO is released by a writer opening it), so a write that never comes fails the test instead of
// hanging it.
class FifoReader {
  public:
    explicit FifoReader(fs::path fifo) : fifo_(std::move(fifo)) {
        text_ = std::async(std::launch::async, [this] {
            const int fd = ::open(fifo_.c_str(), O_RDONLY);
            std::string text = readAll(fd);
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

// FACET_PIPE_WAIT_SECONDS set for one test, so a FIFO nobody opens is given up quickly.
class ShortPipeWait {
  public:
    ShortPipeWait() { ::setenv(std::string(kPipeWaitVariable).c_str(), "0.2", 1); }
    ~ShortPipeWait() { ::unsetenv(std::string(kPipeWaitVariable).c_str()); }
};

using OutputPathTest = TempFolderTest;

// Catches: a regular file written in place (a failure leaving half of it) or a temporary file left beside it.
TEST_F(OutputPathTest, RegularFileIsReplacedWholeAndNothingElseIsLeft) {
    const fs::path file = write("out.json", "old contents, longer than the new");
    writeOutput(file, "new");
    EXPECT_EQ(readFile(file), "new");
    int entries = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(folder_))
        ++entries;
    EXPECT_EQ(entries, 1) << "a temporary file was left in " << folder_;
}

// Catches: a write that fails part way destroying the file that was there (it must stay untouched).
TEST_F(OutputPathTest, FailedWriteLeavesTheOldFileUntouched) {
    const fs::path file = write("image.png", "the old image");
    const std::string message = errorOf([&] {
        writeOutputThrough(file, ".png", [&](const fs::path&) { throw InputError("the encoder failed"); });
    });
    EXPECT_EQ(message, "the encoder failed");
    EXPECT_EQ(readFile(file), "the old image");
    int entries = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(folder_))
        ++entries;
    EXPECT_EQ(entries, 1);
}

// Catches: a FIFO replaced by a regular file (the rename of a temporary file over it), or its reader
// getting nothing.
TEST_F(OutputPathTest, FifoIsWrittenToAndStaysAFifo) {
    const fs::path fifo = folder_ / "pipe";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    FifoReader read(fifo);
    writeOutput(fifo, "through the pipe");
    EXPECT_EQ(read.get(), "through the pipe");
    struct stat node;
    ASSERT_EQ(::lstat(fifo.c_str(), &node), 0);
    EXPECT_TRUE(S_ISFIFO(node.st_mode)) << "the FIFO was replaced";
}

// Catches: an image library's file (written through writeOutputThrough) not reaching a stream.
TEST_F(OutputPathTest, FileMadeByALibraryIsCopiedIntoAFifo) {
    const fs::path fifo = folder_ / "pipe.png";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    FifoReader read(fifo);
    fs::path made;
    writeOutputThrough(fifo, ".png", [&](const fs::path& file) {
        made = file;
        EXPECT_EQ(file.extension(), ".png") << "libraries choose the format by the extension";
        const int fd = ::open(file.c_str(), O_WRONLY | O_TRUNC);
        ASSERT_EQ(::write(fd, "PNG bytes", 9), 9);
        ::close(fd);
    });
    EXPECT_EQ(read.get(), "PNG bytes");
    EXPECT_FALSE(fs::exists(made)) << "the temporary copy was left behind";
    struct stat node;
    ASSERT_EQ(::lstat(fifo.c_str(), &node), 0);
    EXPECT_TRUE(S_ISFIFO(node.st_mode));
}

// Catches: a command hanging forever on a FIFO nobody reads, or replacing it after the wait.
TEST_F(OutputPathTest, FifoNobodyReadsIsGivenUpWithAMessage) {
    const ShortPipeWait shortWait;
    const fs::path fifo = folder_ / "pipe";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const std::string message = errorOf([&] { writeOutput(fifo, "nobody listens"); });
    EXPECT_NE(message.find(fifo.string() + ": cannot write: no program read the FIFO"), std::string::npos)
        << message;
    struct stat node;
    ASSERT_EQ(::lstat(fifo.c_str(), &node), 0);
    EXPECT_TRUE(S_ISFIFO(node.st_mode));
}

// Catches: a character device (like /dev/null, made here as a node of our own) replaced by a file.
TEST_F(OutputPathTest, CharacterDeviceIsWrittenToAndStaysADevice) {
    const fs::path device = folder_ / "null";
    if (::mknod(device.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0)
        GTEST_SKIP() << "cannot make a device node here (needs CAP_MKNOD)";
    writeOutput(device, "into the void");
    struct stat node;
    ASSERT_EQ(::lstat(device.c_str(), &node), 0);
    EXPECT_TRUE(S_ISCHR(node.st_mode)) << "the device was replaced by a file";
    EXPECT_EQ(classifyOutput(device).kind, OutputKind::Stream);
}

// Catches: "-" written as a file named "-" instead of to standard output.
TEST_F(OutputPathTest, DashIsStandardOutput) {
    const fs::path captured = folder_ / "stdout.txt";
    const int file = ::open(captured.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    ASSERT_GE(file, 0);
    std::fflush(stdout);
    const int saved = ::dup(STDOUT_FILENO);
    ::dup2(file, STDOUT_FILENO);
    const std::string message = errorOf([] { writeOutput("-", "to standard output\n"); });
    ::dup2(saved, STDOUT_FILENO);
    ::close(saved);
    ::close(file);
    EXPECT_EQ(message, "");
    EXPECT_EQ(readFile(captured), "to standard output\n");
    EXPECT_FALSE(fs::exists("-")) << "a file named - was made";
    EXPECT_TRUE(classifyOutput("-").standardOutput);
}

// Catches: a link replaced by a regular file instead of its target being written.
TEST_F(OutputPathTest, LinkToAFileWritesTheTargetAndKeepsTheLink) {
    const fs::path target = write("sub/real.json", "old");
    const fs::path link = folder_ / "link.json";
    fs::create_symlink("sub/real.json", link);  // relative: taken from the link's folder
    writeOutput(link, "new");
    EXPECT_TRUE(fs::is_symlink(link)) << "the link was replaced";
    EXPECT_EQ(readFile(target), "new");
    EXPECT_EQ(classifyOutput(link).path, folder_ / "sub/real.json");
}

// Catches: a dangling link replaced by a file (or refused) instead of the file it names being created.
TEST_F(OutputPathTest, DanglingLinkCreatesItsTarget) {
    const fs::path link = folder_ / "link.csv";
    fs::create_symlink(folder_ / "made.csv", link);
    writeOutput(link, "a,b\n");
    EXPECT_TRUE(fs::is_symlink(link));
    EXPECT_EQ(readFile(folder_ / "made.csv"), "a,b\n");
}

// Catches: a link chain leading to a FIFO followed as text but then written atomically over the FIFO.
TEST_F(OutputPathTest, LinkToAFifoStreamsIntoTheFifo) {
    const fs::path fifo = folder_ / "pipe";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    fs::create_symlink(fifo, folder_ / "one");
    fs::create_symlink(folder_ / "one", folder_ / "two");
    const OutputTarget target = classifyOutput(folder_ / "two");
    EXPECT_EQ(target.kind, OutputKind::Stream);
    EXPECT_EQ(target.path, fifo);
}

// Catches: a folder, a link to one, a socket or a link loop accepted (and replaced, or looped on forever).
TEST_F(OutputPathTest, FoldersSocketsAndLoopsAreRefusedInOneLine) {
    fs::create_directories(folder_ / "dir");
    fs::create_symlink(folder_ / "dir", folder_ / "to-dir");
    fs::create_symlink(folder_ / "b", folder_ / "a");
    fs::create_symlink(folder_ / "a", folder_ / "b");
    const fs::path socketPath = folder_ / "socket";
    const int sock = ::socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    ASSERT_LT(socketPath.string().size(), sizeof address.sun_path);
    std::strcpy(address.sun_path, socketPath.c_str());
    ASSERT_EQ(::bind(sock, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
    for (const auto& [name, reason] : {std::pair<std::string, std::string>{"dir", "it is a folder"},
                                       {"to-dir", "it is a folder"},
                                       {"socket", "it is a socket"},
                                       {"a", "Too many levels of symbolic links"}}) {
        const fs::path path = folder_ / name;  // clang before 16 cannot capture a structured binding
        const std::string message = errorOf([&] { writeOutput(path, "x"); });
        EXPECT_EQ(message.find(path.string() + ": cannot write: " + reason), 0u) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos);
    }
    ::close(sock);
    EXPECT_TRUE(fs::is_directory(folder_ / "dir"));
    EXPECT_TRUE(fs::is_symlink(folder_ / "a"));
}

// Catches: `--html ""` reaching create_directories ("cannot create the folder: Invalid argument"), or a
// file accepted as the folder of several outputs.
TEST_F(OutputPathTest, OutputFolderNeedsANameAndMustNotBeAFile) {
    EXPECT_EQ(errorOf([] { checkOutputFolder("", "--html"); }),
              "--html needs the name of a folder to write into (got an empty name)");
    const fs::path file = write("file", "");
    EXPECT_NE(errorOf([&] { checkOutputFolder(file, "--html"); }).find("it is not a folder"),
              std::string::npos);
    EXPECT_EQ(errorOf([&] { checkOutputFolder(folder_ / "new/deeper", "--html"); }), "");
    EXPECT_FALSE(fs::exists(folder_ / "new")) << "a check must not create anything";
}

// Catches: a list read from a FIFO no program writes into blocking forever.
TEST_F(OutputPathTest, InputFifoNobodyWritesIsGivenUp) {
    const ShortPipeWait shortWait;
    const fs::path fifo = folder_ / "list";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const std::string message = errorOf([&] { ::close(openInputStream(fifo, "the list")); });
    EXPECT_EQ(message, fifo.string() +
                           ": cannot read the list (no program wrote into the FIFO within 0.2 s; "
                           "FACET_PIPE_WAIT_SECONDS sets the wait)");
}

// Catches: a list from a FIFO whose writer comes later being refused instead of read.
TEST_F(OutputPathTest, InputFifoIsReadOnceAWriterComes) {
    const fs::path fifo = folder_ / "list";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::thread writer([&] {
        const int fd = ::open(fifo.c_str(), O_WRONLY);  // waits for the reader
        EXPECT_EQ(::write(fd, "a.obj\n", 6), 6);
        ::close(fd);
    });
    const int fd = openInputStream(fifo, "the list");
    EXPECT_EQ(readAll(fd), "a.obj\n");
    ::close(fd);
    writer.join();
}

}  // namespace
}  // namespace facet
