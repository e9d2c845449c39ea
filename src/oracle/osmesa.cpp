#include "oracle/osmesa.h"

#include <cstdlib>
#include <string>

#include <dlfcn.h>

namespace facet {

namespace {

template <class Function>
void resolveSymbol(void* handle, const char* name, Function& function) {
    function = reinterpret_cast<Function>(::dlsym(handle, name));
}

}  // namespace

OsMesaLibrary& library() {
    static OsMesaLibrary instance;
    return instance;
}

OsMesaLibrary& loadOsMesa(const MesaOptions& options) {
    OsMesaLibrary& lib = library();
    const int threads = options.threads;
    const char* const driver = driverName(options.driver);
    if (!lib.tried) {
        lib.tried = true;
        lib.driver = options.driver;
        lib.threads = threads;
        ::setenv("GALLIUM_DRIVER", driver, 1);
        if (options.driver == MesaDriver::Llvmpipe)
            ::setenv("LP_NUM_THREADS", std::to_string(MesaPeer::lpNumThreads(threads)).c_str(), 1);
        lib.handle = ::dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
        if (!lib.handle) {
            const char* error = ::dlerror();
            lib.loadError = error ? error : "libOSMesa.so.8 cannot be loaded";
        } else {
            resolveSymbol(lib.handle, "OSMesaCreateContextAttribs", lib.createContextAttribs);
            resolveSymbol(lib.handle, "OSMesaCreateContextExt", lib.createContextExt);
            resolveSymbol(lib.handle, "OSMesaMakeCurrent", lib.makeCurrent);
            resolveSymbol(lib.handle, "OSMesaGetCurrentContext", lib.getCurrentContext);
            resolveSymbol(lib.handle, "OSMesaDestroyContext", lib.destroyContext);
            resolveSymbol(lib.handle, "OSMesaGetProcAddress", lib.getProcAddress);
            if (!lib.createContextExt || !lib.makeCurrent || !lib.getCurrentContext || !lib.destroyContext ||
                !lib.getProcAddress)
                lib.loadError = "libOSMesa.so.8 lacks the OSMesa entry points";
        }
    }
    return lib;
}

std::string resolveGlFunctions(const OsMesaLibrary& lib, Gl& gl) {
    std::string missing;
#define FACET_GL_RESOLVE(name)                                                \
    gl.name = reinterpret_cast<decltype(gl.name)>(lib.getProcAddress(#name)); \
    if (!gl.name) missing += std::string(missing.empty() ? "" : ", ") + #name;
    FACET_GL_FUNCTIONS(FACET_GL_RESOLVE)
#undef FACET_GL_RESOLVE
    return missing;
}

}  // namespace facet
