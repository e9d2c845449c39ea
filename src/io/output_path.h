// Where an output goes, decided in one place for every file Facet writes (images, JSON, CSV, web
// pages): what is already at the path is respected, never replaced by something of another kind.
//   a regular file, or nothing      written to a hidden temporary file beside it, renamed into place once
//                                   complete: a failure never leaves half a file nor destroys the old one
//   a device, a FIFO, "-"            written to directly, in order ("-" is standard output)
//   a symbolic link                 followed to its final target, which is then treated by these rules
//                                   (a dangling link: the file it names is created)
//   a folder, a socket, other        refused, one line naming the path
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace facet {

// How long opening a FIFO waits for the program at its other end (a reader for an output, a writer for
// a list of inputs) before giving up with a message. FACET_PIPE_WAIT_SECONDS overrides it.
constexpr std::chrono::seconds kPipeWaitDefault{30};
constexpr std::string_view kPipeWaitVariable = "FACET_PIPE_WAIT_SECONDS";
std::chrono::milliseconds pipeWait();

enum class OutputKind {
    AtomicFile,  // a regular file or a missing one: temporary file beside it, renamed into place
    Stream,      // a device, a FIFO, standard output: written directly
};

struct OutputTarget {
    OutputKind kind = OutputKind::AtomicFile;
    // AtomicFile: the file replaced (a link's final target); Stream: what is opened (empty for "-").
    std::filesystem::path path;
    bool standardOutput = false;  // "-"
    // A Stream that is one of this process's open descriptors ("-": 1; /dev/stdout, /dev/fd/N,
    // /proc/self/fd/N: N), written through it so that it shares its position with what else the program
    // prints there; -1 when the path is opened.
    int descriptor = -1;
};

// Decides how `path` is written, without writing anything. Throws InputError ("out: cannot write: it
// is a folder") for a path that must not be written.
OutputTarget classifyOutput(const std::filesystem::path& path);

// True for "-", the name of standard output: a command then prints its own reports to standard error.
bool isStandardOutput(const std::filesystem::path& path);

// Checks, without writing, that `path` can be written, so a command fails before long work: the kind
// (classifyOutput) and, for a file, that its folder exists, or with `createFolders` that the nearest
// existing folder above it may be written into (the writer then creates the rest).
void checkOutput(const std::filesystem::path& path, bool createFolders = false);

// Checks a folder that will receive several outputs (step --html DIR, trade -o DIR): a name is given,
// it is a folder or nothing yet, and the nearest existing folder above it may be written into.
// `option` names the option in the message ("--html").
void checkOutputFolder(const std::filesystem::path& folder, std::string_view option);

// Writes `bytes` to `path` by the rules above. Throws InputError naming `path` and the reason.
void writeOutput(const std::filesystem::path& path, std::string_view bytes);

// Writes `path` through `produce`, which writes a whole file at the path it is given (an image library):
// beside the destination, then renamed into place, for a file; in the temporary folder, then copied, for
// a stream. `extension` (".png") ends the temporary file's name, as libraries choose the format by it.
// Folders missing above a file are created when `createFolders`. What `produce` throws passes through,
// and its temporary file is removed.
void writeOutputThrough(const std::filesystem::path& path, std::string_view extension,
                        const std::function<void(const std::filesystem::path& file)>& produce,
                        bool createFolders = false);

// Opens a file, a device, a FIFO or "-" (standard input) for reading, as a list of inputs is read. A
// FIFO waits up to pipeWait() for a program to write into it (saying so on standard error after a
// second), then gives up. Throws InputError "path: cannot read `what` (reason)" ("is a folder", "no
// program wrote into the FIFO within 30 s; ..."). Returns a descriptor to close (except standard
// input's, 0).
int openInputStream(const std::filesystem::path& path, std::string_view what);

}  // namespace facet
