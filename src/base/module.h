// Optional parts of Facet that link a large library (OpenImageIO, OpenCV) live in modules: shared
// libraries the build writes beside the facet program, loaded with dlopen the first time a command needs
// them, so that every other run of the program starts without binding their hundreds of libraries.
#pragma once

#include <string>

namespace facet {

// Loads the module `fileName` (e.g. "libfacet_openimageio.so") and returns the address of its entry
// point `entry`. It looks beside the running program first (a copied or installed facet carries its
// modules along), then at `buildPath`, where the build wrote it (the test programs live in other folders
// of the build). The module stays loaded for the life of the process. Throws InputError, a one-line
// message beginning with `neededFor` ("this image format needs OpenImageIO"), when it cannot be found
// or loaded.
void* loadModuleEntry(const char* fileName, const char* buildPath, const char* entry,
                      const std::string& neededFor);

}  // namespace facet
