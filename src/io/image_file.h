// The image files underneath image_io.h: one reader interface over the two libraries that decode them.
// PNG is read here through libpng and written through zlib, PPM written by hand (image_formats.cpp):
// the formats a render writes by default; every other format goes through OpenImageIO, which lives
// in a module of its own (libfacet_openimageio.so, oiio_module.cpp) loaded on first use. Linking
// OpenImageIO binds ~260 shared libraries before main() (a quarter of a second), which a render that
// reads and writes PNG never needs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace facet {

class ThreadPool;

// What a file says about its pixels before any is decoded.
struct ImageHeader {
    int width = 0;
    int height = 0;
    int depth = 1;          // > 1: a volume (refused)
    int channels = 0;       // after palette expansion: grey 1, grey+alpha 2, RGB 3, RGBA 4, or more
    int alphaChannel = -1;  // which channel is alpha, -1 when none
    bool eightBit = false;  // 8-bit unsigned samples: they can be read as codes
    bool floating = false;  // float samples hold linear values; integer samples display-encoded ones
    bool deep = false;      // several samples per pixel (refused)
};

// An open image file. Integer samples read as float are code / (2^bits − 1), computed as OpenImageIO
// computes it (code · (1/255.0f) for 8-bit), so both libraries give the same values.
class ImageFileReader {
  public:
    virtual ~ImageFileReader() = default;
    virtual const ImageHeader& header() const = 0;
    // Channels [firstChannel, endChannel) of every pixel, rows top to bottom, into `out`: 8-bit codes
    // (`asFloat` false, 8-bit files only) or floats, consecutive within a pixel, pixels `pixelStride`
    // bytes apart. False on a read error (error() says what).
    virtual bool read(int firstChannel, int endChannel, bool asFloat, void* out, std::size_t pixelStride) = 0;
    // The last error, as the library worded it (may span lines).
    virtual std::string error() = 0;
};

// The pixels of an image to write: `channels` values per pixel, rows top to bottom, 8-bit codes
// (sRGB-encoded colour, linear alpha) or 32-bit linear floats.
struct ImagePixels {
    int width = 0;
    int height = 0;
    int channels = 0;
    bool floating = false;
    const void* data = nullptr;
    // Or, for 8-bit pixels without `data`: writes the codes of rows [first, first + count) to `out`,
    // so that a writer can encode band by band without the whole image in memory (any thread may call
    // it, for different rows). Both libraries take either.
    std::function<void(int first, int count, std::uint8_t* out)> rows;

    // The codes of rows [first, first + count), from `data` or through `rows`, into `scratch`.
    const std::uint8_t* codes(int first, int count, std::vector<std::uint8_t>& scratch) const {
        const std::size_t rowBytes = static_cast<std::size_t>(width) * channels;
        if (data != nullptr) return static_cast<const std::uint8_t*>(data) + first * rowBytes;
        scratch.resize(rowBytes * count);
        rows(first, count, scratch.data());
        return scratch.data();
    }
};

// How hard a PNG writer compresses: zlib's level, 0 (store) to 9 (smallest). The default favours time:
// level 1 writes a render four times faster than OpenImageIO's 6, for files about 40% larger (README
// "End to end").
inline constexpr int kFastPngCompression = 1;

// One library's way to read and write files; both are complete for the formats they serve.
class ImageLibrary {
  public:
    virtual ~ImageLibrary() = default;
    // nullptr with `error` set when the file cannot be opened as an image.
    virtual std::unique_ptr<ImageFileReader> open(const std::string& path, std::string& error) = 0;
    // Writes `pixels` to `path` in the format its extension names; "" on success, else the library's
    // message. `pngCompression` applies to PNG only; `pool`, when given, may share the work (the bytes
    // written never depend on it).
    virtual std::string write(const std::string& path, const ImagePixels& pixels, int pngCompression,
                              ThreadPool* pool = nullptr) = 0;
};

// OpenImageIO's comparison of two float images (ImageBufAlgo::compare): over every channel value, the
// mean and largest absolute difference and the root of the mean squared one; and how many pixels have
// some channel off by more than the threshold.
struct PixelComparison {
    double meanError = 0;
    double maxError = 0;
    double rmsError = 0;
    std::size_t pixelsOver = 0;
};

// OpenImageIO: every format it knows, and its image comparison.
class OpenImageIOLibrary : public ImageLibrary {
  public:
    // `a` and `b`: width × height pixels of `channels` floats each.
    virtual PixelComparison compare(const float* a, const float* b, int width, int height, int channels,
                                    float threshold) = 0;
};

// OpenImageIO, loaded at the first call (every later call returns the same library): the module
// libfacet_openimageio.so is looked for beside the running program, then where the build put it.
// Throws InputError when it or OpenImageIO cannot be loaded, with the loader's reason.
OpenImageIOLibrary& openImageIO();

// Whether openImageIO() has loaded the module in this process (for tests of what a command loads).
bool openImageIOLoaded();

// The built-in library: PNG read (libpng) and written (zlib, in bands), binary PPM (P6) written.
ImageLibrary& builtInImageLibrary();

// Whether builtInImageLibrary() writes the format of `path` (by its extension, any case: .png, .ppm).
bool builtInFormat(const std::string& path);

// Whether the file starts with PNG's signature: builtInImageLibrary() reads it. Readers choose by the
// content, not the name, so a JPEG named .png still reads (through OpenImageIO).
bool isPngFile(const std::string& path);

}  // namespace facet
