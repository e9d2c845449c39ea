// openImageIO(): the OpenImageIO module, loaded with dlopen at its first use (image_file.h says why).
#include <atomic>
#include <mutex>
#include <system_error>
#include <thread>

#include "base/errors.h"
#include "base/module.h"
#include "io/image_file.h"

#ifndef FACET_OPENIMAGEIO_MODULE
#error "FACET_OPENIMAGEIO_MODULE: the module's path in the build, set by src/io/CMakeLists.txt"
#endif

namespace facet {
namespace {

std::atomic<OpenImageIOLibrary*> loadedLibrary{nullptr};

OpenImageIOLibrary* load() {
    // The libraries OpenImageIO brings (log4cplus) start a thread as they load, and abort the process
    // when the system refuses it (ulimit -u): one is tried first, so that a refusal is one line.
    try {
        std::thread([] {}).join();
    } catch (const std::system_error& e) {
        throw ResourceError(
            "this image format needs OpenImageIO, whose libraries start a thread as they load, "
            "and the system refuses one (" +
            e.code().message() + ")");
    }
    using Entry = OpenImageIOLibrary* (*)();
    const auto entry =
        reinterpret_cast<Entry>(loadModuleEntry("libfacet_openimageio.so", FACET_OPENIMAGEIO_MODULE,
                                                "facetOpenImageIO", "this image format needs OpenImageIO"));
    return entry();
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
