// The test shaders of one's own (tests/shaders/user) and a shader cache of one test's own.
#pragma once

#include <cstdlib>
#include <filesystem>

#include "support/temp_folder.h"

namespace facet::testing_support {

// displace_cutout.cpp: moves vertices along the normal (uniform displacement) and discards fragments
// whose eye-space normal's y is above `cut`. own_phong.cpp: the built-in per-pixel shading written with
// its formula functions (uniform specular=false leaves the specular term out).
inline const fs::path kUserShaders = fs::path(FACET_SOURCE_DIR) / "tests/shaders/user";

// FACET_SHADER_CACHE pointed at a fresh folder for as long as this lives: each test compiles its own
// modules, so that none finds another test's (or an earlier build's) in a shared cache.
class OwnShaderCache {
  public:
    OwnShaderCache() : folder_("shader-cache") { ::setenv("FACET_SHADER_CACHE", folder_.path().c_str(), 1); }
    ~OwnShaderCache() { ::unsetenv("FACET_SHADER_CACHE"); }
    OwnShaderCache(const OwnShaderCache&) = delete;
    OwnShaderCache& operator=(const OwnShaderCache&) = delete;

  private:
    TempFolder folder_;
};

}  // namespace facet::testing_support
