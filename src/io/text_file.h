// Text files (JSON traces, web pages) written as images are: to a hidden temporary file beside the
// destination, renamed into place once complete, so a failure never leaves half a file.
#pragma once

#include <filesystem>
#include <string_view>

namespace facet {

// Checks, without writing, that `path` could be written: its folder exists and it is not a folder.
void checkTextDestination(const std::filesystem::path& path);

// Writes `text` to `path`; throws InputError naming the file and the reason when it cannot.
void writeTextFile(const std::filesystem::path& path, std::string_view text);

}  // namespace facet
