// Errors the facet program reports to its user: one line, naming the file (and line) at fault.
#pragma once

#include <stdexcept>
#include <string>

namespace facet {

// Bad input from the user: a missing or malformed file, an unknown scene key, an absurd size.
// what() is the whole one-line message, already prefixed with "file:line: " where one is known,
// e.g. "models/box.obj:12: face index 9 is out of range (the file has 8 vertices)".
class InputError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// The machine cannot give what sound input needs: threads it refuses to create, memory beyond the
// limit an estimate made before the work (or the system's own limit). The input may well work on a
// bigger machine, or with a smaller setting the message names; exit status 4 (kResourceExitStatus).
// what() is the whole one-line message, naming what needs the resource, e.g. "the shadow maps of 8
// point lights at 8192x8192 need 12.0 GiB, more than the memory limit of 4.0 GiB (--memory-limit)".
class ResourceError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Exit statuses, as docs/bad-input.md documents them.
constexpr int kInputErrorExitStatus = 1;
constexpr int kCommandLineExitStatus = 2;
constexpr int kResourceExitStatus = 4;

}  // namespace facet
