// Mesa as Facet's peer, through OSMesa loaded at run time with dlopen (Facet never links Mesa). It draws
// a GlScene (gl_scene.h) the way an OpenGL program would: fixed-function lighting (glLight, glMaterial,
// glShadeModel) or GLSL programs evaluating lighting.h's formulas per vertex or per pixel, into a float
// RGBA + float depth framebuffer. Two uses: `facet bench --vs-mesa` times llvmpipe drawing the scene
// Facet draws, and the conformance tests take softpipe, Mesa's reference rasterizer, as the oracle of
// Facet's lighting.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "io/image_io.h"
#include "oracle/gl_scene.h"
#include "oracle/image_compare.h"
#include "pipeline/names.h"

namespace facet {

// Mesa's Gallium software drivers.
enum class MesaDriver {
    Llvmpipe,  // LLVM-compiled shaders, multithreaded rasterization: the benchmark's peer
    Softpipe,  // Mesa's reference rasterizer, one thread, interpreted shaders: the conformance oracle
};
inline constexpr EnumName<MesaDriver> kMesaDriverNames[] = {{MesaDriver::Softpipe, "softpipe"},
                                                            {MesaDriver::Llvmpipe, "llvmpipe"}};
constexpr std::span<const EnumName<MesaDriver>> enumNames(MesaDriver) {
    return kMesaDriverNames;
}
inline const char* driverName(MesaDriver driver) {
    return nameOf(driver).data();
}  // "llvmpipe", "softpipe"

struct MesaOptions {
    MesaDriver driver = MesaDriver::Llvmpipe;
    // llvmpipe only (softpipe runs on the calling thread; asking it for more throws). llvmpipe bins on
    // the calling thread and rasterizes on LP_NUM_THREADS threads of its own, so one thread is
    // LP_NUM_THREADS=0 (everything on the calling thread) and n ≥ 2 is LP_NUM_THREADS=n (the calling
    // thread mostly waits for them).
    int threads = 1;
};

class MesaPeer {
  public:
    // Loads libOSMesa.so.8 with GALLIUM_DRIVER set to the options' driver (and LP_NUM_THREADS for
    // llvmpipe) and creates a compatibility-profile GL context (fixed-function lighting needs it; each
    // call below makes it current on the calling thread). Returns nullptr and sets `whyNot` (one line)
    // when OSMesa is missing, gives no usable context, or renders with another driver. Mesa reads
    // GALLIUM_DRIVER and LP_NUM_THREADS once per process, so every peer of a process has the driver and
    // thread count of the first one (opening with others fails); comparing drivers or thread counts
    // means running the program once for each. Throws std::invalid_argument for threads < 1, or > 1
    // with softpipe.
    static std::unique_ptr<MesaPeer> open(const MesaOptions& options, std::string& whyNot);
    static int lpNumThreads(int threads);  // the LP_NUM_THREADS open() sets for `threads`
    ~MesaPeer();
    MesaPeer(const MesaPeer&) = delete;
    MesaPeer& operator=(const MesaPeer&) = delete;

    MesaDriver driver() const;
    const std::string& renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    const std::string& version() const;   // GL_VERSION, e.g. "4.5 (Compatibility Profile) Mesa 22.3.6"
    const std::string& shadingLanguageVersion() const;  // GL_SHADING_LANGUAGE_VERSION, e.g. "4.50"
    int threads() const;                                // as asked of open()
    bool floatColor() const;  // frames go to RGBA32F colour + float depth (else RGBA8 + 24-bit depth)

    // Uploads the scene's draws (vertex and index buffers), textures and a framebuffer of the scene's
    // size, builds the GLSL programs the draws need and sets the pipeline state; not part of a frame.
    // Keeps nothing of `scene` (textures are copied). Replaces what a previous load() uploaded.
    // Blending, depth writes and fog are as gl_scene.h describes; the blend's alpha factors give
    // pipeline/state.h's alphas (glBlendFuncSeparate: Over and PremultipliedOver α_s + (1 − α_s)·α_d,
    // Additive α_s + α_d, Multiply α_d).
    // Throws std::invalid_argument for what OpenGL cannot draw as asked: more than 8 lights; a
    // program and frequency that do not go together (PerPixel needs ShadingFrequency::Phong,
    // FixedFunction and PerVertex need Flat or Gouraud); fixed function with another reflection model
    // than Blinn-Phong, a Smooth-profile spot light, a spot cutoff outside [0, 90] (other than ≥ 180:
    // no cone), a spot exponent or shininess outside [0, 128], a negative attenuation coefficient, a
    // blend other than Replace and Over (the others need a shader's output: use PerVertex), linear fog
    // with end = start, a negative fog density, or radial fog without GL_NV_fog_distance.
    // Throws std::runtime_error if GL reports an error.
    void load(const GlScene& scene);

    // One frame: clear colour and depth, every draw in order, then glFinish() so that the frame is
    // complete when this returns.
    void renderFrame();

    // The last frame's colour buffer, rows top to bottom like Facet's (GL's row 0 is the bottom).
    LinearImage readImage() const;

    // Frees what load() uploaded (the compiled programs stay, for the next load()).
    void unload();

  private:
    struct Impl;
    explicit MesaPeer(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

}  // namespace facet
