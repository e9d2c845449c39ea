// libOSMesa, loaded at run time with dlopen (Facet never links Mesa), and the table of the GL functions
// the Mesa peer calls, each resolved through OSMesaGetProcAddress; the GL headers supply only types and
// constants. Internal to the oracle (mesa_peer.h is its interface).
#pragma once

#include <string>

#define GL_GLEXT_PROTOTYPES  // declares the prototypes used below with decltype; nothing is linked
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

#include "oracle/mesa_peer.h"

namespace facet {

// The GL functions the peer calls, each resolved through OSMesaGetProcAddress.
#define FACET_GL_FUNCTIONS(X)    \
    X(glActiveTexture)           \
    X(glAttachShader)            \
    X(glBindAttribLocation)      \
    X(glBindBuffer)              \
    X(glBindFragDataLocation)    \
    X(glBindFramebuffer)         \
    X(glBindRenderbuffer)        \
    X(glBindTexture)             \
    X(glBindVertexArray)         \
    X(glBlendEquation)           \
    X(glBlendFuncSeparate)       \
    X(glBufferData)              \
    X(glCheckFramebufferStatus)  \
    X(glClampColor)              \
    X(glClear)                   \
    X(glClearColor)              \
    X(glClearDepth)              \
    X(glClipControl)             \
    X(glCompileShader)           \
    X(glCreateProgram)           \
    X(glCreateShader)            \
    X(glCullFace)                \
    X(glDeleteBuffers)           \
    X(glDeleteFramebuffers)      \
    X(glDeleteProgram)           \
    X(glDeleteRenderbuffers)     \
    X(glDeleteShader)            \
    X(glDeleteTextures)          \
    X(glDeleteVertexArrays)      \
    X(glDepthFunc)               \
    X(glDepthMask)               \
    X(glDepthRange)              \
    X(glDisable)                 \
    X(glDrawElements)            \
    X(glEnable)                  \
    X(glEnableClientState)       \
    X(glEnableVertexAttribArray) \
    X(glFinish)                  \
    X(glFogf)                    \
    X(glFogfv)                   \
    X(glFogi)                    \
    X(glFramebufferRenderbuffer) \
    X(glFrontFace)               \
    X(glGenBuffers)              \
    X(glGenFramebuffers)         \
    X(glGenRenderbuffers)        \
    X(glGenTextures)             \
    X(glGenVertexArrays)         \
    X(glGetError)                \
    X(glGetProgramInfoLog)       \
    X(glGetProgramiv)            \
    X(glGetShaderInfoLog)        \
    X(glGetShaderiv)             \
    X(glGetString)               \
    X(glGetUniformLocation)      \
    X(glHint)                    \
    X(glLightModelfv)            \
    X(glLightModeli)             \
    X(glLightf)                  \
    X(glLightfv)                 \
    X(glLinkProgram)             \
    X(glLoadIdentity)            \
    X(glLoadMatrixf)             \
    X(glMaterialf)               \
    X(glMaterialfv)              \
    X(glMatrixMode)              \
    X(glNormalPointer)           \
    X(glPixelStorei)             \
    X(glProvokingVertex)         \
    X(glReadPixels)              \
    X(glRenderbufferStorage)     \
    X(glShadeModel)              \
    X(glShaderSource)            \
    X(glTexCoordPointer)         \
    X(glTexEnvi)                 \
    X(glTexImage2D)              \
    X(glTexParameteri)           \
    X(glUniform1f)               \
    X(glUniform1i)               \
    X(glUniform3fv)              \
    X(glUniform4fv)              \
    X(glUniformMatrix3fv)        \
    X(glUniformMatrix4fv)        \
    X(glUseProgram)              \
    X(glVertexAttribPointer)     \
    X(glVertexPointer)           \
    X(glViewport)

struct Gl {
#define FACET_GL_MEMBER(name) decltype(&::name) name = nullptr;
    FACET_GL_FUNCTIONS(FACET_GL_MEMBER)
#undef FACET_GL_MEMBER
};

// libOSMesa, loaded once per process and never unloaded (Mesa's LLVM keeps global state that
// dlclose would leave dangling).
struct OsMesaLibrary {
    bool tried = false;
    void* handle = nullptr;
    std::string loadError;
    MesaDriver driver = MesaDriver::Llvmpipe;  // as asked of the first open()
    int threads = 0;                           // as asked of the first open()
    decltype(&::OSMesaCreateContextAttribs) createContextAttribs = nullptr;
    decltype(&::OSMesaCreateContextExt) createContextExt = nullptr;
    decltype(&::OSMesaMakeCurrent) makeCurrent = nullptr;
    decltype(&::OSMesaGetCurrentContext) getCurrentContext = nullptr;
    decltype(&::OSMesaDestroyContext) destroyContext = nullptr;
    decltype(&::OSMesaGetProcAddress) getProcAddress = nullptr;
};

// The process's one library, as loadOsMesa left it.
OsMesaLibrary& library();

// Loads the library once per process: Mesa reads GALLIUM_DRIVER (and llvmpipe LP_NUM_THREADS) when it
// starts, so they are set from the first caller's options (later callers get the library as it is and
// compare its driver and threads with theirs). OsMesaLibrary::loadError says why it is unusable.
OsMesaLibrary& loadOsMesa(const MesaOptions& options);

// Fills `gl` through OSMesaGetProcAddress (a context must be current): the names it lacks,
// comma-separated, or "" when it has them all.
std::string resolveGlFunctions(const OsMesaLibrary& library, Gl& gl);

}  // namespace facet
