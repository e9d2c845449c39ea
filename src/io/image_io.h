// Image output and input, format by file extension: PNG and PPM built in, the rest through OpenImageIO
// (loaded only for them; image_file.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "io/image_file.h"
#include "pipeline/texture.h"
#include "pipeline/thread_pool.h"
#include "shading/gamma.h"

namespace facet {

// A linear, floating-point RGBA image, rows top to bottom.
struct LinearImage {
    int width = 0;
    int height = 0;
    std::vector<glm::vec4> pixels;  // width * height, row-major, row 0 at the top
    glm::vec4& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
    const glm::vec4& at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }
};

// Linear RGBA pixels held elsewhere (a LinearImage's, a framebuffer's), rows top to bottom.
struct ImageView {
    int width = 0;
    int height = 0;
    std::span<const glm::vec4> pixels;  // width * height
};

// Writes `image` to `path`, its format chosen by the extension (.png .exr .ppm .jpg/.jpeg .tif/.tiff ...).
// Float formats (EXR) keep the buffer's values unchanged; 8-bit formats get `encoding`, clamped to
// [0,1] (encodeChannel). PPM and JPEG have no alpha: RGB only. A file is written to a temporary file
// in the same folder and renamed into place, so a failure never leaves a partial file nor destroys an
// existing one; a device, a FIFO or "-" (standard output) is written directly, as PNG when its name has
// no image extension (io/output_path.h). `pngCompression`: zlib's level for PNG, 0 (store) to 9
// (smallest); the default favours speed. Throws InputError ("out/x.bmpx: unknown image format ...",
// "out/: cannot write ...").
void writeImage(const std::filesystem::path& path, const LinearImage& image,
                ColorEncoding encoding = kSrgbEncoding, int pngCompression = kFastPngCompression);
// The same from pixels held elsewhere (no copy), encoded to 8 bits on `pool`'s threads when given.
void writeImage(const std::filesystem::path& path, const ImageView& image, ColorEncoding encoding,
                int pngCompression, ThreadPool* pool);

// Checks, without writing anything, that `path` names an image format facet writes and that a
// width × height image fits it; throws InputError otherwise. Lets a command fail before a long render.
void checkImageDestination(const std::filesystem::path& path, int width, int height);

// Reads any image (PNG built in, any other format OpenImageIO knows) into linear RGBA (8-bit data is decoded
// from sRGB; float data as is). Throws InputError if the file is missing or unreadable.
LinearImage readImage(const std::filesystem::path& path);

// What the textures of one render may take, checked from each file's header before it is decoded:
// a 16384² 8-bit texture (1 GiB) fits, a file declaring 30000² does not.
struct TextureLimits {
    int maxSide = 16384;                               // pixels, either side
    std::size_t maxTotalBytes = std::size_t{1} << 30;  // all textures of a render together, in memory

    bool operator==(const TextureLimits&) const = default;
};

// How texture colour becomes linear: integer data (8- and 16-bit) holds sRGB-encoded codes and float
// data linear values, as readImage reads them. Without `decodeSrgb` colours are taken as written
// (codes/255, float values sRGB-encoded), as untouched inputs are elsewhere.
struct TextureRead {
    Texture texture;      // empty when the file could not be read
    std::string problem;  // why not, one line ("not a PNG file"), library messages included
};

// Reads a texture file: its header first, then the texels straight into the texture at the file's
// precision (8-bit files as codes, others as float; see Texture). A side above limits.maxSide, or
// texels needing more than `bytesLeft` of limits.maxTotalBytes, throws InputError naming the file and
// the limit, before anything is decoded. A missing, corrupt, truncated or non-image file is not an
// error: `problem` says why and the texture is empty. Nothing is printed (the messages libpng and
// others write to standard error are captured into `problem`).
TextureRead readTexture(const std::filesystem::path& path, bool decodeSrgb, const TextureLimits& limits,
                        std::size_t bytesLeft);

// The bytes readTexture will hold for the texels of `path`, from its header alone (nothing is decoded):
// width × height × 4 for 8-bit files, × 16 for others; 0 when the file is missing or not an image
// (readTexture then says why).
std::uint64_t textureBytesFromHeader(const std::filesystem::path& path);

// Refuses, from the files' headers and before any is decoded, textures that together exceed
// limits.maxTotalBytes (InputError, naming the count, the total and the largest file) or the memory
// limit (ResourceError, base/memory_limit.h): five 8192² textures are refused before the first is read.
void checkTextureTotal(const std::vector<std::filesystem::path>& files, const TextureLimits& limits);

}  // namespace facet
