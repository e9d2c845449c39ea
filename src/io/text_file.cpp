#include "io/text_file.h"

#include "io/output_path.h"

namespace facet {

void checkTextDestination(const std::filesystem::path& path) {
    checkOutput(path);
}

void writeTextFile(const std::filesystem::path& path, std::string_view text) {
    writeOutput(path, text);
}

}  // namespace facet
