#include "base/module.h"

#include <dlfcn.h>
#include <unistd.h>

#include <climits>
#include <filesystem>

#include "base/errors.h"

namespace facet {
namespace {

// The folder of the running program (/proc/self/exe), "" when unknown.
std::filesystem::path programFolder() {
    char path[PATH_MAX];
    const ssize_t length = ::readlink("/proc/self/exe", path, sizeof path - 1);
    if (length <= 0) return {};
    path[length] = '\0';
    return std::filesystem::path(path).parent_path();
}

}  // namespace

void* loadModuleEntry(const char* fileName, const char* buildPath, const char* entry,
                      const std::string& neededFor) {
    std::string reasons;
    for (const std::filesystem::path& candidate :
         {programFolder() / fileName, std::filesystem::path(buildPath)}) {
        std::error_code error;
        if (candidate.empty() || !std::filesystem::exists(candidate, error)) continue;
        // Never closed: the libraries behind a module may keep threads and caches for the process's life.
        void* module = ::dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (module == nullptr) {
            reasons += reasons.empty() ? "" : "; ";
            reasons += ::dlerror();
            continue;
        }
        if (void* address = ::dlsym(module, entry)) return address;
        reasons += reasons.empty() ? "" : "; ";
        reasons += candidate.string() + " has no " + entry;
    }
    std::string message = neededFor + ", and " + fileName;
    message += reasons.empty() ? " was not found beside the facet program nor in the build folder "
                                 "(copy it next to facet)"
                               : " could not be loaded: " + reasons;
    throw InputError(message);
}

}  // namespace facet
