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
#include <string>

#include "gl_scene.h"
#include "image_io.h"

namespace facet {

// Mesa's Gallium software drivers.
enum class MesaDriver {
    Llvmpipe,  // LLVM-compiled shaders, multithreaded rasterization: the benchmark's peer
    Softpipe,  // Mesa's reference rasterizer, one thread, interpreted shaders: the conformance oracle
};
const char* driverName(MesaDriver driver);  // "llvmpipe", "softpipe"

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
    // Throws std::invalid_argument for what OpenGL cannot draw as asked: more than 8 lights; a
    // program and frequency that do not go together (PerPixel needs ShadingFrequency::Phong,
    // FixedFunction and PerVertex need Flat or Gouraud); fixed function with another reflection model
    // than Blinn-Phong, a Smooth-profile spot light, a spot cutoff outside [0, 90] (other than ≥ 180:
    // no cone), a spot exponent or shininess outside [0, 128] or a negative attenuation coefficient.
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

// ---- 8-bit comparison, for the conformance tests ------------------------------------------------------

// How a linear value becomes an 8-bit code.
enum class ByteEncoding {
    Srgb,    // the sRGB transfer curve, as Facet's 8-bit image files (PNG, JPEG, ...) store colour
    Linear,  // the value itself: clamp to [0, 1], × 255
};

// The 8-bit code of a linear value: clamped to [0, 1] (NaN → 0), encoded, × 255, rounded to nearest.
// The same conversion as writeImage()'s for 8-bit files (image_io.cpp) with ByteEncoding::Srgb.
std::uint8_t quantize8(float linear, ByteEncoding encoding);

// Two images compared after both are quantised to 8 bits the same way; differences in code steps,
// over R, G and B (alpha is not compared).
struct PixelDifference {
    std::size_t pixels = 0;     // width × height
    std::size_t differing = 0;  // pixels with some channel's codes unequal
    int maxDifference = 0;      // the largest |Δcode| of any channel of any pixel
    double within1 = 0.0;       // fraction of pixels whose every channel is within 1 code
    double within2 = 0.0;       // ... within 2 codes
    // With a background colour only (else 0): silhouette pixels are those that are background, or have
    // a 4-neighbour that is background, in either image; interior ones are the rest.
    std::size_t differingAtEdges = 0;  // differing pixels on the silhouette
    int maxInteriorDifference = 0;     // maxDifference over interior pixels
};

// Throws std::invalid_argument when the sizes differ. A pixel is background when each of its four
// channels (alpha included) is within `backgroundTolerance` of `background`'s: clearing to an alpha no
// drawn pixel has (0, say) tells coverage apart even where a lit pixel is as dark as the background.
PixelDifference comparePixels(const LinearImage& a, const LinearImage& b, ByteEncoding encoding,
                              std::optional<vec4> background = std::nullopt,
                              float backgroundTolerance = 1e-6f);

}  // namespace facet
