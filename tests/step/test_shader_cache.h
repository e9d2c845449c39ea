// The shader cache of the step tests that compile a shader of one's own (tests/step/shaders/): a folder
// of their own under the system's temporary folder, so that a test never writes to the user's cache,
// and a shader compiled by one test process (about 15 s) is found by the next and by the facet program
// the CLI tests run (which inherits the variable).
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace facet::step {

inline void useTestShaderCache() {
    const std::filesystem::path cache =
        std::filesystem::temp_directory_path() / ("facet-step-shader-cache-" + std::to_string(::getuid()));
    std::filesystem::create_directories(cache);
    ::setenv("FACET_SHADER_CACHE", cache.c_str(), 1);
}

}  // namespace facet::step
