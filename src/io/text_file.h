// Text files (JSON traces, web pages, CSV tables), written as images are (io/output_path.h): a file
// through a hidden temporary file beside it, renamed into place once complete, so a failure never leaves
// half a file; a device, a FIFO or "-" (standard output) directly.
#pragma once

#include <filesystem>
#include <string_view>

namespace facet {

// Checks, without writing, that `path` could be written: a kind of path Facet writes, its folder exists.
void checkTextDestination(const std::filesystem::path& path);

// Writes `text` to `path`; throws InputError naming the file and the reason when it cannot.
void writeTextFile(const std::filesystem::path& path, std::string_view text);

}  // namespace facet
