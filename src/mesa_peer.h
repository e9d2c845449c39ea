// The benchmark's peer: Mesa's llvmpipe rasterizer through OSMesa, loaded at run time with dlopen
// (Facet never links Mesa). It draws a PreparedScene as renderFrame() does: the same vertices and
// indices, matrices, culling, depth test and a GLSL copy of the built-in Blinn-Phong shader, into a
// float RGBA + float depth framebuffer, so `facet bench --vs-mesa` times the same work on both sides.
#pragma once

#include <memory>
#include <string>

#include "image_io.h"
#include "renderer.h"

namespace facet {

class MesaPeer {
  public:
    // Loads libOSMesa.so.8 with GALLIUM_DRIVER=llvmpipe, set to run on `threads` threads (≥ 1), and
    // creates a GL context (each call below makes it current on the calling thread). Returns nullptr
    // and sets `whyNot` when OSMesa is missing, gives no usable context, or is not llvmpipe.
    // llvmpipe bins on the calling thread and rasterizes on LP_NUM_THREADS threads of its own, so one
    // thread is LP_NUM_THREADS=0 (everything on the calling thread) and n ≥ 2 is LP_NUM_THREADS=n (the
    // calling thread mostly waits for them). Mesa reads LP_NUM_THREADS once per process, so every peer
    // of a process runs on the thread count of the first one (opening with another count fails);
    // comparing thread counts means running the program once per count.
    static std::unique_ptr<MesaPeer> open(int threads, std::string& whyNot);
    static int lpNumThreads(int threads);  // the LP_NUM_THREADS open() sets for `threads`
    ~MesaPeer();
    MesaPeer(const MesaPeer&) = delete;
    MesaPeer& operator=(const MesaPeer&) = delete;

    const std::string& renderer() const;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    const std::string& version() const;   // GL_VERSION, e.g. "4.5 (Core Profile) Mesa 22.3.6"
    int threads() const;                  // as asked of open()
    bool floatColor() const;  // frames go to RGBA32F colour + float depth (else RGBA8 + 24-bit depth)

    // Uploads the scene's draws (vertex and index buffers), textures and a framebuffer of the scene's
    // size, and sets the pipeline state; not part of a frame. Replaces what a previous load() uploaded.
    // Throws std::runtime_error if GL reports an error, std::invalid_argument for state it cannot mirror.
    void load(const PreparedScene& prepared);

    // One frame, as renderFrame(): clear colour and depth, every draw with its uniforms, then glFinish()
    // so the frame is complete when this returns.
    void renderFrame();

    // The last frame's colour buffer, rows top to bottom like Facet's (GL's row 0 is the bottom).
    LinearImage readImage() const;

    // Frees what load() uploaded.
    void unload();

  private:
    struct Impl;
    explicit MesaPeer(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
};

// How closely two renderings of one scene agree: proof that two renderers did the same work.
struct ImageAgreement {
    double coverageAgreement = 0.0;     // fraction of all pixels that both call foreground or both background
    double colorWithinTolerance = 0.0;  // of the pixels both cover: fraction within kColorTolerance
    double meanColorDifference = 0.0;   // of the pixels both cover: mean of the largest |Δ| over R, G, B
    std::size_t foregroundA = 0, foregroundB = 0;  // pixels each image covers

    static constexpr double kMinCoverageAgreement = 0.98;  // silhouettes differ only along edges
    static constexpr double kMinColorWithin = 0.95;        // shading differs only by rounding and edges
    static constexpr float kColorTolerance = 0.02f;        // linear units, on one channel

    bool agrees() const {
        return foregroundA > 0 && foregroundB > 0 && coverageAgreement > kMinCoverageAgreement &&
               colorWithinTolerance > kMinColorWithin;
    }
};

// Compares two images of the same size, pixel by pixel. A pixel is foreground when some channel of
// RGB differs from `background` by more than `backgroundTolerance` (a little above the rounding of the
// buffer: 0 for float buffers, half a code step for 8-bit ones). Throws std::invalid_argument when the
// sizes differ.
ImageAgreement compareImages(const LinearImage& a, const LinearImage& b, vec4 background,
                             float backgroundTolerance = 1e-5f);

}  // namespace facet
