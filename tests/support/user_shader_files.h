// The test shaders of one's own (tests/shaders/user) and the shader cache the build's tests share.
#pragma once

#include <cstdlib>
#include <filesystem>

#include "support/temp_folder.h"

namespace facet::testing_support {

// displace_cutout.cpp: moves vertices along the normal (uniform displacement) and discards fragments
// whose eye-space normal's y is above `cut`. own_phong.cpp: the built-in per-pixel shading written with
// its formula functions (uniform specular=false leaves the specular term out).
inline const fs::path kUserShaders = fs::path(FACET_SOURCE_DIR) / "tests/shaders/user";

// FACET_SHADER_CACHE pointed (for as long as a SharedShaderCache lives) at the shader cache the build's
// tests share (FACET_TEST_SHADER_CACHE, a folder of the build's own): a test never writes to the user's
// cache, and a shader one test compiled (most of such a test's time) is loaded by the next, in this test
// program or another, or by a facet it runs (which inherits the variable). Sharing is as safe
// as the cache is for its users (render/user_shaders.cpp): a module is found only under the key of its
// source text, compiler, flags and header folders, with every file it included unchanged; one process
// compiles a key at a time while the others wait on its lock, and a module appears whole, renamed into
// place. The tests of the cache itself (user_shader_cli_test.cpp) keep a fresh folder each.
inline void useSharedShaderCache() {
    std::filesystem::create_directories(FACET_TEST_SHADER_CACHE);
    ::setenv("FACET_SHADER_CACHE", FACET_TEST_SHADER_CACHE, 1);
}
class SharedShaderCache {
  public:
    SharedShaderCache() { useSharedShaderCache(); }
    ~SharedShaderCache() { ::unsetenv("FACET_SHADER_CACHE"); }
    SharedShaderCache(const SharedShaderCache&) = delete;
    SharedShaderCache& operator=(const SharedShaderCache&) = delete;
};

}  // namespace facet::testing_support
