// openImageIO(): the OpenImageIO module, loaded with dlopen at its first use (image_file.h says why).
#include <dlfcn.h>
#include <unistd.h>

#include <atomic>
#include <climits>
#include <filesystem>
#include <mutex>
#include <string>

#include "base/errors.h"
#include "io/image_file.h"

#ifndef FACET_OPENIMAGEIO_MODULE
#error "FACET_OPENIMAGEIO_MODULE: the module's path in the build, set by src/io/CMakeLists.txt"
#endif

namespace facet {
namespace {

constexpr const char* kModuleName = "libfacet_openimageio.so";

std::atomic<OpenImageIOLibrary*> loadedLibrary{nullptr};

// The folder of the running program (/proc/self/exe), "" when unknown.
std::filesystem::path programFolder() {
    char path[PATH_MAX];
    const ssize_t length = ::readlink("/proc/self/exe", path, sizeof path - 1);
    if (length <= 0) return {};
    path[length] = '\0';
    return std::filesystem::path(path).parent_path();
}

OpenImageIOLibrary* load() {
    // Beside the program first (a copied or installed facet carries its module along), then where the
    // build wrote it (the test programs live in another folder of the build).
    std::string reasons;
    for (const std::filesystem::path& candidate :
         {programFolder() / kModuleName, std::filesystem::path(FACET_OPENIMAGEIO_MODULE)}) {
        std::error_code error;
        if (candidate.empty() || !std::filesystem::exists(candidate, error)) continue;
        void* module = ::dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (module == nullptr) {
            reasons += reasons.empty() ? "" : "; ";
            reasons += ::dlerror();
            continue;
        }
        // Never closed: OpenImageIO keeps threads and caches for the life of the process.
        using Entry = OpenImageIOLibrary* (*)();
        auto entry = reinterpret_cast<Entry>(::dlsym(module, "facetOpenImageIO"));
        if (entry != nullptr) return entry();
        reasons += reasons.empty() ? "" : "; ";
        reasons += candidate.string() + " has no facetOpenImageIO";
    }
    std::string message = "this image format needs OpenImageIO, and ";
    message += kModuleName;
    message += reasons.empty() ? " was not found beside the facet program nor in the build folder "
                                 "(copy it next to facet)"
                               : " could not be loaded: " + reasons;
    throw InputError(message);
}

}  // namespace

OpenImageIOLibrary& openImageIO() {
    static std::mutex mutex;
    std::lock_guard lock(mutex);
    if (loadedLibrary.load() == nullptr) loadedLibrary = load();  // a failure is tried again next time
    return *loadedLibrary.load();
}

bool openImageIOLoaded() {
    return loadedLibrary.load() != nullptr;
}

}  // namespace facet
