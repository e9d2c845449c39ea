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

}  // namespace facet
