// Optional parts of Facet that link a large library (OpenImageIO, OpenCV) live in modules: shared
// libraries the build writes beside the facet program and `cmake --install` puts in <prefix>/lib/facet,
// loaded with dlopen the first time a command needs them, so that every other run of the program starts
// without binding their hundreds of libraries.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace facet {

// The folder of the running program (/proc/self/exe, symbolic links resolved), "" when unknown.
std::filesystem::path programFolder();

// Whether `folder` is `tree` or below it, both taken with their symbolic links resolved as far as they
// exist (the build folder may have been named through a link when it was configured).
bool inside(const std::filesystem::path& folder, const std::filesystem::path& tree);

// Whether the running program is inside the build folder it was built in (a test program, or facet run
// from the build): only such a program uses files of the build tree (modules, headers).
bool programInBuildTree();

// Loads the module `fileName` (e.g. "libfacet_openimageio.so") and returns the address of its entry
// point `entry`. It looks where moduleCandidates() says, for the running program: beside it, in the
// install layout's module folder relative to it, and at `buildPath` (where the build wrote it) only when
// the program itself is in the build tree (the test programs live in other folders of the build). The
// module stays loaded for the life of the process. Throws InputError, a one-line message beginning with
// `neededFor` ("this image format needs OpenImageIO"), when it cannot be found or loaded.
void* loadModuleEntry(const char* fileName, const char* buildPath, const char* entry,
                      const std::string& neededFor);

// The files loadModuleEntry() tries, in order, for a program in `programFolder` (empty when unknown):
// `programFolder/fileName` (a copied facet carries its modules along), `programFolder/moduleFolder/fileName`
// (the install layout: moduleFolder is relative to the program's folder, "../lib/facet", so that a moved
// prefix keeps working), and `buildPath` only when `programFolder` is inside `buildTree` (an installed
// facet never loads a module from a build tree, which may be stale or gone).
std::vector<std::filesystem::path> moduleCandidates(const std::filesystem::path& programFolder,
                                                    const std::filesystem::path& moduleFolder,
                                                    const std::filesystem::path& buildTree,
                                                    const char* fileName, const char* buildPath);

}  // namespace facet
