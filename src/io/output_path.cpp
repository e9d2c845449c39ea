#include "io/output_path.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <thread>

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/errors.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

// Symbolic links followed before giving up, as the kernel does (MAXSYMLINKS).
constexpr int kMostLinks = 40;

[[noreturn]] void cannotWrite(const fs::path& path, const std::string& why) {
    throw InputError(path.string() + ": cannot write: " + why);
}

std::string systemReason(int error) {
    return std::strerror(error);
}

// The wait, as messages say it: "30 s", "0.3 s".
std::string waitText() {
    const double seconds = std::chrono::duration<double>(pipeWait()).count();
    char text[32];
    std::snprintf(text, sizeof text, "%g s", seconds);
    return text;
}

// A link inside /proc (/dev/stdout -> /proc/self/fd/1, /dev/fd/N): the kernel's view of an open
// descriptor. Its text ("pipe:[123]", "/tmp/x (deleted)") is no path to follow: it is opened as it is,
// or, when it is one of this process's own descriptors, written through that descriptor (`descriptor`).
bool isDescriptorLink(const fs::path& link, int& descriptor) {
    descriptor = -1;
    std::error_code error;
    const fs::path folder = fs::canonical(link.has_parent_path() ? link.parent_path() : fs::path("."), error);
    if (error) return false;
    const std::string text = folder.string();
    if (text != "/proc" && text.rfind("/proc/", 0) != 0) return false;
    const std::string name = link.filename().string();
    if (folder == fs::path("/proc") / std::to_string(::getpid()) / "fd" && !name.empty() &&
        name.size() < 10 && name.find_first_not_of("0123456789") == std::string::npos)
        descriptor = std::stoi(name);
    return true;
}

// The kind of an existing node reached through `path` (links followed by the kernel): a stream to open,
// or refused.
OutputTarget classifyNode(const fs::path& shown, const fs::path& path, const struct stat& node) {
    if (S_ISDIR(node.st_mode)) cannotWrite(shown, "it is a folder");
    if (S_ISSOCK(node.st_mode)) cannotWrite(shown, "it is a socket, which Facet does not write to");
    if (S_ISCHR(node.st_mode) || S_ISBLK(node.st_mode) || S_ISFIFO(node.st_mode))
        return {OutputKind::Stream, path, false};
    cannotWrite(shown, "it is neither a file nor a device");
}

// Where a file is written: its folder ("." for a bare name).
fs::path folderOf(const fs::path& file) {
    return file.has_parent_path() ? file.parent_path() : fs::path(".");
}

// The nearest folder above `file` that exists must accept new files.
void checkNearestFolder(const fs::path& shown, const fs::path& file) {
    std::error_code error;
    fs::path existing = file.parent_path();
    while (!existing.empty() && !fs::exists(existing, error) && existing != existing.parent_path())
        existing = existing.parent_path();
    if (existing.empty()) existing = ".";
    if (!fs::is_directory(existing, error)) cannotWrite(shown, existing.string() + " is not a folder");
    if (::access(existing.c_str(), W_OK | X_OK) != 0) cannotWrite(shown, systemReason(errno));
}

void createFolders(const fs::path& shown, const fs::path& file) {
    const fs::path folder = file.parent_path();
    std::error_code error;
    if (folder.empty() || fs::is_directory(folder, error)) return;
    fs::create_directories(folder, error);
    if (error) cannotWrite(shown, "cannot create the folder " + folder.string() + ": " + error.message());
}

// Removes a temporary file unless released (unlink, not remove: never deletes a folder of that name).
class TemporaryFile {
  public:
    explicit TemporaryFile(fs::path path) : path_(std::move(path)) {}
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;
    ~TemporaryFile() {
        if (armed_) ::unlink(path_.c_str());
    }
    const fs::path& path() const { return path_; }
    void release() { armed_ = false; }

  private:
    fs::path path_;
    bool armed_ = true;
};

// The temporary name's end: the process's id, so two programs writing one file never share one
// (".tmp-1234"); `count` tells apart files of one process in the shared temporary folder.
std::string uniqueSuffix(bool count = false) {
    static std::atomic<unsigned> counter{0};
    std::string suffix = ".tmp-";
    suffix += std::to_string(::getpid());
    if (count) {  // appended piece by piece: GCC 12 warns falsely on "-" + string (-Wrestrict)
        suffix += '-';
        suffix += std::to_string(counter++);
    }
    return suffix;
}

// The hidden temporary file beside `target` ("out/.spot.tmp-1234.png"), the extension kept last.
fs::path besideTarget(const fs::path& target, std::string_view extension) {
    std::string name = ".";
    name += target.filename().string();
    if (!extension.empty() && target.extension() == fs::path(std::string(extension)))
        name.resize(name.size() - extension.size());
    name += uniqueSuffix();
    name += extension;
    return folderOf(target) / name;
}

// Opens a stream for writing. A FIFO is opened without blocking, and retried until a program reads it
// or pipeWait() has passed, so that a FIFO nobody reads cannot hang the command.
int openStream(const fs::path& shown, const OutputTarget& target) {
    if (target.descriptor >= 0) {
        std::cout.flush();  // what the command printed before, in order
        std::cerr.flush();
        std::fflush(nullptr);
        return target.descriptor;
    }
    const auto start = std::chrono::steady_clock::now();
    const auto deadline = start + pipeWait();
    bool announced = false;
    for (;;) {
        const int fd = ::open(target.path.c_str(), O_WRONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
        if (fd >= 0) {
            // Writes then wait for a slow reader instead of failing.
            ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
            return fd;
        }
        if (errno == EINTR) continue;
        if (errno != ENXIO) cannotWrite(shown, systemReason(errno));  // ENXIO: a FIFO with no reader yet
        if (std::chrono::steady_clock::now() >= deadline)
            cannotWrite(shown, "no program read the FIFO within " + waitText() + "; " +
                                   std::string(kPipeWaitVariable) + " sets the wait");
        if (!announced && std::chrono::steady_clock::now() - start >= std::chrono::seconds(1)) {
            std::cerr << "facet: waiting for a program to read " << shown.string() << " (a FIFO; up to "
                      << waitText() << ")\n";
            announced = true;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
}

void writeAll(const fs::path& shown, int fd, const char* data, std::size_t size) {
    while (size > 0) {
        const ssize_t written = ::write(fd, data, std::min<std::size_t>(size, std::size_t{1} << 20));
        if (written < 0 && errno == EINTR) continue;
        if (written <= 0) cannotWrite(shown, systemReason(written < 0 ? errno : EIO));
        data += written;
        size -= static_cast<std::size_t>(written);
    }
}

// Writes to a stream target, closing what it opened.
void writeStream(const fs::path& shown, const OutputTarget& target,
                 const std::function<void(int fd)>& write) {
    const int fd = openStream(shown, target);
    const bool opened = target.descriptor < 0;  // else the program's own descriptor, kept open
    try {
        write(fd);
    } catch (...) {
        if (opened) ::close(fd);
        throw;
    }
    if (opened && ::close(fd) != 0) cannotWrite(shown, systemReason(errno));
}

// Writes a regular file's bytes: to the temporary file, then renamed over `target.path`.
void writeAtomically(const fs::path& shown, const fs::path& target, std::string_view extension,
                     const std::function<void(const fs::path& file)>& produce) {
    TemporaryFile temp(besideTarget(target, extension));
    // Created here first, so that a folder that refuses files is reported with the user's path and the
    // system's reason ("Permission denied"), not a library's words about the hidden temporary name.
    const int created = ::open(temp.path().c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (created < 0) cannotWrite(shown, systemReason(errno));
    ::close(created);
    produce(temp.path());
    if (std::rename(temp.path().c_str(), target.c_str()) != 0) cannotWrite(shown, systemReason(errno));
    temp.release();
}

}  // namespace

std::chrono::milliseconds pipeWait() {
    const char* text = std::getenv(std::string(kPipeWaitVariable).c_str());
    if (text != nullptr && *text != '\0') {
        char* end = nullptr;
        const double seconds = std::strtod(text, &end);
        if (end != text && *end == '\0' && seconds >= 0.0 && seconds <= 86400.0)
            return std::chrono::milliseconds(static_cast<long long>(seconds * 1000.0));
    }
    return kPipeWaitDefault;
}

bool isStandardOutput(const fs::path& path) {
    return path == "-";
}

OutputTarget classifyOutput(const fs::path& path) {
    if (path.empty()) throw InputError("no output file name given");
    if (isStandardOutput(path)) return {OutputKind::Stream, {}, true, STDOUT_FILENO};
    fs::path current = path;
    for (int links = 0;; ++links) {
        struct stat node;
        if (::lstat(current.c_str(), &node) != 0) {
            if (errno == ENOENT) {
                // Nothing there (a dangling link's target): a new file. "out/" names a folder, not a file.
                if (!current.has_filename()) cannotWrite(path, "the name ends with /, which names a folder");
                return {OutputKind::AtomicFile, current, false};
            }
            cannotWrite(path, systemReason(errno));
        }
        if (S_ISREG(node.st_mode)) return {OutputKind::AtomicFile, current, false};
        if (!S_ISLNK(node.st_mode)) return classifyNode(path, current, node);
        if (int descriptor; isDescriptorLink(current, descriptor)) {
            // Standard output through /dev/stdout, whatever the shell made it (a file, a pipe, a terminal):
            // written where it points, never replaced.
            if (::stat(current.c_str(), &node) != 0) cannotWrite(path, systemReason(errno));
            OutputTarget target = S_ISREG(node.st_mode) ? OutputTarget{OutputKind::Stream, current, false}
                                                        : classifyNode(path, current, node);
            target.descriptor = descriptor;
            return target;
        }
        if (links == kMostLinks) cannotWrite(path, systemReason(ELOOP));
        std::error_code error;
        const fs::path next = fs::read_symlink(current, error);
        if (error) cannotWrite(path, error.message());
        current = next.is_absolute() ? next : folderOf(current) / next;
    }
}

void checkOutput(const fs::path& path, bool createFoldersToo) {
    const OutputTarget target = classifyOutput(path);
    if (target.kind == OutputKind::Stream) {
        if (target.descriptor < 0 && ::access(target.path.c_str(), W_OK) != 0)
            cannotWrite(path, systemReason(errno));
        return;
    }
    std::error_code error;
    if (createFoldersToo) {
        checkNearestFolder(path, target.path);
        return;
    }
    const fs::path folder = folderOf(target.path);
    if (!fs::is_directory(folder, error))
        cannotWrite(path, "the folder " + folder.string() + " does not exist");
    if (::access(folder.c_str(), W_OK | X_OK) != 0) cannotWrite(path, systemReason(errno));
}

void checkOutputFolder(const fs::path& folder, std::string_view option) {
    if (folder.empty())
        throw InputError(std::string(option) +
                         " needs the name of a folder to write into (got an empty name)");
    if (isStandardOutput(folder))
        throw InputError(std::string(option) +
                         " needs a folder, not - (standard output): it writes several files");
    std::error_code error;
    const fs::file_status status = fs::status(folder, error);
    if (fs::is_directory(status)) {
        if (::access(folder.c_str(), W_OK | X_OK) != 0) cannotWrite(folder, systemReason(errno));
        return;
    }
    if (fs::exists(status)) cannotWrite(folder, "it is not a folder (" + std::string(option) + " needs one)");
    checkNearestFolder(folder, folder / "file");
}

void writeOutput(const fs::path& path, std::string_view bytes) {
    const OutputTarget target = classifyOutput(path);
    if (target.kind == OutputKind::Stream) {
        writeStream(path, target, [&](int fd) { writeAll(path, fd, bytes.data(), bytes.size()); });
        return;
    }
    const fs::path folder = folderOf(target.path);
    std::error_code error;
    if (!fs::is_directory(folder, error))
        cannotWrite(path, "the folder " + folder.string() + " does not exist");
    writeAtomically(path, target.path, {}, [&](const fs::path& file) {
        const int fd = ::open(file.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
        if (fd < 0) cannotWrite(path, systemReason(errno));
        try {
            writeAll(path, fd, bytes.data(), bytes.size());
        } catch (...) {
            ::close(fd);
            throw;
        }
        if (::close(fd) != 0) cannotWrite(path, systemReason(errno));
    });
}

void writeOutputThrough(const fs::path& path, std::string_view extension,
                        const std::function<void(const fs::path& file)>& produce, bool createFoldersToo) {
    const OutputTarget target = classifyOutput(path);
    if (target.kind == OutputKind::AtomicFile) {
        if (createFoldersToo) createFolders(path, target.path);
        writeAtomically(path, target.path, extension, produce);
        return;
    }
    // A stream: the whole file made in the temporary folder, then copied, so a library that seeks (TIFF,
    // EXR) works on a pipe too, and a failure sends nothing.
    std::error_code error;
    fs::path scratch = fs::temp_directory_path(error);
    if (error) scratch = "/tmp";
    std::string name = "facet-output";
    name += uniqueSuffix(true);
    name += extension;
    TemporaryFile temp(scratch / name);
    const int created = ::open(temp.path().c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (created < 0)
        cannotWrite(path, "cannot make a temporary file in " + scratch.string() + ": " + systemReason(errno));
    ::close(created);
    produce(temp.path());
    const int in = ::open(temp.path().c_str(), O_RDONLY | O_CLOEXEC);
    if (in < 0) cannotWrite(path, systemReason(errno));
    try {
        writeStream(path, target, [&](int fd) {
            char buffer[1 << 16];
            for (;;) {
                const ssize_t count = ::read(in, buffer, sizeof buffer);
                if (count < 0 && errno == EINTR) continue;
                if (count < 0) cannotWrite(path, systemReason(errno));
                if (count == 0) break;
                writeAll(path, fd, buffer, static_cast<std::size_t>(count));
            }
        });
    } catch (...) {
        ::close(in);
        throw;
    }
    ::close(in);
}

int openInputStream(const fs::path& path, std::string_view what) {
    if (path == "-") return STDIN_FILENO;
    const auto fail = [&](const std::string& why) -> int {
        throw InputError(path.string() + ": cannot read " + std::string(what) + " (" + why + ")");
    };
    // Without blocking: a FIFO opens at once, writer or not, and is then waited on with poll().
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) return fail(systemReason(errno));
    struct stat node;
    if (::fstat(fd, &node) != 0 || S_ISDIR(node.st_mode)) {
        const int error = S_ISDIR(node.st_mode) ? EISDIR : errno;
        ::close(fd);
        return fail(error == EISDIR ? "is a folder" : systemReason(error));
    }
    if (S_ISFIFO(node.st_mode)) {
        // Linux reports nothing on a FIFO no writer has opened yet (no POLLHUP before a first writer):
        // poll() returns when one writes or comes and goes, or times out.
        const auto start = std::chrono::steady_clock::now();
        const auto deadline = start + pipeWait();
        bool announced = false;
        for (;;) {
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                deadline - std::chrono::steady_clock::now());
            const int wait =
                static_cast<int>(std::clamp<long long>(left.count(), 0, 1000));  // a second at most
            pollfd request{fd, POLLIN, 0};
            const int ready = ::poll(&request, 1, wait);
            if (ready < 0 && errno == EINTR) continue;
            if (ready > 0) break;
            if (ready < 0) {
                const int error = errno;
                ::close(fd);
                return fail(systemReason(error));
            }
            if (left.count() <= 0) {
                ::close(fd);
                return fail("no program wrote into the FIFO within " + waitText() + "; " +
                            std::string(kPipeWaitVariable) + " sets the wait");
            }
            if (!announced && std::chrono::steady_clock::now() - start >= std::chrono::seconds(1)) {
                std::cerr << "facet: waiting for a program to write into " << path.string()
                          << " (a FIFO; up to " << waitText() << ")\n";
                announced = true;
            }
        }
    }
    ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);  // then read as any file: waits for more
    return fd;
}

}  // namespace facet
