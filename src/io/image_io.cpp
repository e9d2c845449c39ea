// Image files: LinearImage -> PNG/JPEG/PPM/TIFF/BMP/TGA (8-bit, sRGB-encoded) or EXR/HDR (32-bit
// float, linear), and any readable file back to linear RGBA. PNG and PPM go through the built-in
// library, the rest through OpenImageIO, loaded only then (image_file.h).
// A write goes where io/output_path.h decides: a file through a hidden temporary file beside it, renamed
// into place once complete (a failure never leaves a partial image nor destroys the previous one); a
// device, a FIFO or "-" (standard output, PNG unless the name says otherwise) directly.
#include "io/image_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>

#include <cstdio>

#include <fcntl.h>
#include <unistd.h>

#include "base/errors.h"
#include "base/memory_limit.h"
#include "base/quote.h"
#include "io/image_file.h"
#include "io/output_path.h"
#include "pipeline/color.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

// How each extension is written. Channel counts follow what the format (or its usual readers) can
// hold: PPM and JPEG have no alpha; BMP alpha is ignored by most viewers; Radiance HDR is RGB only.
struct FileFormat {
    std::string_view extension;  // lower case, with the dot
    int channels;                // 3 (RGB) or 4 (RGBA)
    bool isFloat;                // true: 32-bit float linear; false: 8-bit sRGB-encoded
    int maxSide;                 // pixels; checked first, as libjpeg exits the process beyond its limit
};

constexpr int kNoLimit = std::numeric_limits<int>::max();
constexpr int kJpegMaxSide = 65500;  // libjpeg's JPEG_MAX_DIMENSION
constexpr int kTgaMaxSide = 65535;   // 16-bit width and height fields

constexpr FileFormat kFormats[] = {
    {".png", 4, false, kNoLimit}, {".jpg", 3, false, kJpegMaxSide}, {".jpeg", 3, false, kJpegMaxSide},
    {".ppm", 3, false, kNoLimit}, {".tif", 4, false, kNoLimit},     {".tiff", 4, false, kNoLimit},
    {".bmp", 3, false, kNoLimit}, {".tga", 4, false, kTgaMaxSide},  {".exr", 4, true, kNoLimit},
    {".hdr", 3, true, kNoLimit},
};

constexpr std::string_view kFormatList = ".png, .jpg, .jpeg, .ppm, .tif, .tiff, .bmp, .tga, .exr, .hdr";

std::string lowerCase(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

const FileFormat* findFormat(const fs::path& path) {
    const std::string extension = lowerCase(path.extension().string());
    for (const FileFormat& format : kFormats) {
        if (format.extension == extension) return &format;
    }
    return nullptr;
}

// OpenImageIO messages may span several lines; ours are one line.
// A library's message on one line, bounded, with bytes a terminal would not show escaped (it may quote
// a file's metadata). "" when there is none.
std::string libraryMessage(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    while (!text.empty() && text.back() == ' ')
        text.pop_back();
    return printable(text, 300);
}

std::string oneLine(std::string text) {
    text = libraryMessage(std::move(text));
    return text.empty() ? "unknown error" : text;
}

[[noreturn]] void fail(const fs::path& path, const std::string& what) {
    throw InputError(path.string() + ": " + what);
}

// The library that reads this file: the built-in one for PNG (by its signature), else OpenImageIO.
// (A missing OpenImageIO module is an error about this file like any other.)
std::unique_ptr<ImageFileReader> openImageFile(const fs::path& path, std::string& error) {
    try {
        ImageLibrary& library = isPngFile(path.string()) ? builtInImageLibrary() : openImageIO();
        return library.open(path.string(), error);
    } catch (const InputError& e) {
        error = e.what();
        return nullptr;
    }
}

// The library that writes this format: the built-in one for 8-bit PNG and PPM, else OpenImageIO. By the
// format, not the path, which may have no extension ("-", a device written as PNG).
ImageLibrary& writerFor(const fs::path& path, const FileFormat& format) {
    if (!format.isFloat && builtInFormat("image" + std::string(format.extension)))
        return builtInImageLibrary();
    try {
        return openImageIO();
    } catch (const InputError& e) {
        fail(path, "cannot write image: " + std::string(e.what()));
    }
}

// Captures what libraries write straight to standard error (libpng's "libpng error: ..." lines) while
// it lives, so that their messages become part of ours instead of raw lines on the terminal.
class StderrCapture {
  public:
    StderrCapture() {
        std::fflush(stderr);
        file_ = std::tmpfile();
        if (file_ == nullptr) return;
        saved_ = ::dup(STDERR_FILENO);
        if (saved_ < 0 || ::dup2(::fileno(file_), STDERR_FILENO) < 0) restore();
    }
    StderrCapture(const StderrCapture&) = delete;
    StderrCapture& operator=(const StderrCapture&) = delete;
    ~StderrCapture() {
        restore();
        if (file_ != nullptr) std::fclose(file_);
    }

    // Ends the capture and returns what was written, on one line.
    std::string finish() {
        restore();
        std::string text;
        if (file_ == nullptr) return text;
        std::rewind(file_);
        char buffer[512];
        std::size_t count;
        while ((count = std::fread(buffer, 1, sizeof buffer, file_)) > 0 && text.size() < 4096)
            text.append(buffer, count);
        return libraryMessage(std::move(text));
    }

  private:
    void restore() {
        if (saved_ < 0) return;
        std::fflush(stderr);
        ::dup2(saved_, STDERR_FILENO);
        ::close(saved_);
        saved_ = -1;
    }

    std::FILE* file_ = nullptr;
    int saved_ = -1;
};

std::string gibibytes(std::size_t bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f GiB", static_cast<double>(bytes) / double(std::size_t{1} << 30));
    return text;
}

// What a texture's texels take in memory (Texture): 8-bit files as codes, others as float.
std::size_t texelBytes(const ImageHeader& spec) {
    return static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height) *
           (spec.eightBit ? sizeof(Texture::Codes) : sizeof(vec4));
}

// The texture's texels, read into `texture` (its size set): channels 0..3 of each pixel into the four
// slots of one texel of type T (vec4 or Codes) as `type`, then the alpha channel into slot 3 when it
// lies beyond them. Returns false on a read error.
template <class T>
bool readTexels(ImageFileReader& input, bool asFloat, std::vector<T>& texels) {
    const ImageHeader& spec = input.header();
    const std::size_t pixelCount = static_cast<std::size_t>(spec.width) * spec.height;
    texels.assign(pixelCount, T{});
    const int channels = std::min(spec.channels, 4);
    if (!input.read(0, channels, asFloat, texels.data(), sizeof(T))) return false;
    if (spec.alphaChannel >= 4 && spec.alphaChannel < spec.channels) {
        auto* alpha = reinterpret_cast<unsigned char*>(texels.data()) + 3 * (sizeof(T) / 4);
        if (!input.read(spec.alphaChannel, spec.alphaChannel + 1, asFloat, alpha, sizeof(T))) return false;
    }
    return true;
}

// Puts each texel's values where Texture expects them, in place: grey (one or two channels) copied to
// R, G and B, alpha to slot 3 (opaque when the file has none), each colour value through `color` and
// alpha through `alpha`, as readImage lays out its pixels.
template <class T, class Color, class Alpha, class Opaque>
void arrangeTexels(const ImageHeader& spec, std::vector<T>& texels, Color color, Alpha alpha, Opaque opaque) {
    const int alphaSlot =
        spec.alphaChannel < 0 || spec.alphaChannel >= spec.channels ? -1 : std::min(spec.alphaChannel, 3);
    const bool gray = spec.channels < 3;
    for (T& t : texels) {
        const T v = t;
        t[0] = color(v[0]);
        t[1] = gray ? t[0] : color(v[1]);
        t[2] = gray ? t[0] : color(v[2]);
        t[3] = alphaSlot >= 0 ? alpha(v[alphaSlot]) : opaque;
    }
}

// The format `path` is written in: by its extension, or PNG for a stream that has none ("-", /dev/null).
const FileFormat* outputFormat(const fs::path& path) {
    if (const FileFormat* format = findFormat(path)) return format;
    std::error_code error;
    if (fs::is_directory(path, error)) fail(path, "is a folder, not an image file");
    if (classifyOutput(path).kind == OutputKind::Stream) return &kFormats[0];
    return nullptr;
}

}  // namespace

void checkImageDestination(const fs::path& path, int width, int height) {
    // Choose the format before touching the disk, so a typo writes nothing.
    const FileFormat* format = outputFormat(path);
    if (format == nullptr) {
        const std::string extension = path.extension().string();
        // "out/.png": to the file system a hidden file named ".png" without an extension.
        // (Strings built with +=: GCC 12 warns falsely about chains of operator+.)
        std::string named = "image";
        named += path.filename().string();
        if (extension.empty() && findFormat(named)) {
            std::string message = "has no file name before the extension (like ";
            message += (path.parent_path() / named).string();
            fail(path, message + ")");
        }
        if (extension.empty()) {
            fail(path,
                 "no file extension to choose the image format from (use " + std::string(kFormatList) + ")");
        }
        fail(path, "unknown image format \"" + extension + "\" (use " + std::string(kFormatList) + ")");
    }
    if (width > format->maxSide || height > format->maxSide) {
        fail(path, "the " + std::string(format->extension.substr(1)) + " format cannot hold " +
                       std::to_string(width) + "x" + std::to_string(height) + " pixels (at most " +
                       std::to_string(format->maxSide) + " per side)");
    }
    std::error_code error;
    if (fs::is_directory(path, error)) fail(path, "is a folder, not an image file");
    // What is at the path (io/output_path.h), and the folder: the nearest part of it that exists must be
    // a folder we may write into (writeImage creates the rest), so an unwritable destination fails before
    // a long render.
    checkOutput(path, true);
}

void writeImage(const fs::path& path, const LinearImage& image, ColorEncoding encoding, int pngCompression) {
    writeImage(path, ImageView{image.width, image.height, image.pixels}, encoding, pngCompression, nullptr);
}

void writeImage(const fs::path& path, const ImageView& image, ColorEncoding encoding, int pngCompression,
                ThreadPool* pool) {
    checkImageDestination(path, image.width, image.height);
    const FileFormat* format = outputFormat(path);
    const std::size_t pixelCount = static_cast<std::size_t>(std::max(image.width, 0)) *
                                   static_cast<std::size_t>(std::max(image.height, 0));
    if (image.width <= 0 || image.height <= 0 || image.pixels.size() != pixelCount) {
        fail(path, "cannot write an image of " + std::to_string(image.width) + "x" +
                       std::to_string(image.height) + " pixels holding " +
                       std::to_string(image.pixels.size()) + " values");
    }

    // Convert to the file's pixel type: float values unchanged, or 8-bit codes (sRGB-encoded by
    // default). Alpha is coverage, not light, so it is stored linearly.
    const int channels = format->channels;
    std::vector<float> floats;
    std::function<void(int, int, std::uint8_t*)> encodeRows;
    if (format->isFloat) {
        // RGBE (.hdr) shares one exponent between positive mantissas: a negative value would come
        // back as garbage (-0.25 read as 3.75), so it is stored as 0. EXR keeps every value.
        const bool clampNegative = format->extension == ".hdr";
        floats.reserve(pixelCount * channels);
        for (std::size_t i = 0; i < pixelCount; ++i) {
            const glm::vec4& p = image.pixels[i];
            for (int c = 0; c < channels; ++c) {
                // An 8-bit file clamps; a float file would keep +Inf or NaN, which every reader of it
                // (compositors, image viewers, facet compare) would then have to survive.
                if (!std::isfinite(p[c])) {
                    fail(path, std::string("the image holds a value that is not finite (") +
                                   (std::isnan(p[c]) ? "NaN" : "infinity") + ") at pixel (" +
                                   std::to_string(i % static_cast<std::size_t>(image.width)) + ", " +
                                   std::to_string(i / static_cast<std::size_t>(image.width)) +
                                   "); nothing was written");
                }
                floats.push_back(clampNegative && !(p[c] > 0.0f) ? 0.0f : p[c]);
            }
        }
    } else {
        // The rows are encoded when the writer asks for them (the PNG writer band by band, on the
        // pool's threads), through the encoder's tables: encodeChannel's codes without a pow per channel.
        encodeRows = [&image, &encoding, channels, encode = ChannelEncoder(encoding)](int first, int count,
                                                                                      std::uint8_t* out) {
            const std::size_t width = static_cast<std::size_t>(image.width);
            const std::size_t begin = static_cast<std::size_t>(first) * width;
            const std::size_t end = begin + static_cast<std::size_t>(count) * width;
            // A render is mostly runs of equal pixels (the background): a pixel with the same bits as
            // the one before it takes its codes without walking the tables again.
            const glm::vec4* previous = nullptr;
            for (std::size_t i = begin; i < end; ++i, out += channels) {
                const glm::vec4& p = image.pixels[i];
                if (previous != nullptr && std::memcmp(&p, previous, sizeof p) == 0) {
                    std::memcpy(out, out - channels, static_cast<std::size_t>(channels));
                    continue;
                }
                previous = &p;
                out[0] = encode(p.r);
                out[1] = encode(p.g);
                out[2] = encode(p.b);
                if (channels == 4) out[3] = toByte(p.a, encoding.rounding);
            }
        };
    }

    const ImagePixels pixels{image.width,
                             image.height,
                             channels,
                             format->isFloat,
                             format->isFloat ? static_cast<const void*>(floats.data()) : nullptr,
                             std::move(encodeRows)};
    // Written where io/output_path.h decides: a file through a temporary one renamed into place (its
    // folder created when missing: "-o renders/spot.png" should just work), a stream directly.
    writeOutputThrough(
        path, format->extension,
        [&](const fs::path& file) {
            const std::string problem =
                writerFor(path, *format).write(file.string(), pixels, pngCompression, pool);
            if (problem.empty()) return;
            // The libraries' errors name the file they were given: the user knows the destination instead.
            std::string text = problem;
            for (std::size_t at; (at = text.find(file.string())) != std::string::npos;)
                text.replace(at, file.string().size(), path.string());
            fail(path, "cannot write image: " + oneLine(std::move(text)));
        },
        true);
}

LinearImage readImage(const fs::path& path) {
    std::error_code error;
    if (!fs::exists(path, error)) fail(path, "image file not found");
    if (fs::is_directory(path, error)) fail(path, "is a folder, not an image file");

    std::string problem;
    std::unique_ptr<ImageFileReader> input = openImageFile(path, problem);
    if (!input) fail(path, "cannot read image: " + oneLine(problem));

    const ImageHeader& spec = input->header();
    if (spec.deep) fail(path, "deep images are not supported");
    if (spec.width <= 0 || spec.height <= 0 || spec.depth > 1 || spec.channels <= 0) {
        fail(path, "cannot read an image of " + std::to_string(spec.width) + "x" +
                       std::to_string(spec.height) + " pixels");
    }

    const int channels = spec.channels;
    const std::size_t pixelCount = static_cast<std::size_t>(spec.width) * spec.height;
    std::vector<float> values(pixelCount * channels);
    if (!input->read(0, channels, true, values.data(), channels * sizeof(float)))
        fail(path, "cannot read image: " + oneLine(input->error()));

    // Integer data holds display-encoded (sRGB) colour; float data is linear already.
    const bool encoded = !spec.floating;
    const auto decode = [encoded](float value) { return encoded ? srgbToLinear(value) : value; };
    const int alphaChannel = spec.alphaChannel >= 0 && spec.alphaChannel < channels ? spec.alphaChannel : -1;
    const bool gray = channels < 3;

    LinearImage image;
    image.width = spec.width;
    image.height = spec.height;
    image.pixels.resize(pixelCount);
    for (std::size_t i = 0; i < pixelCount; ++i) {
        const float* v = &values[i * channels];
        glm::vec4& p = image.pixels[i];
        p.r = decode(v[0]);
        p.g = gray ? p.r : decode(v[1]);
        p.b = gray ? p.r : decode(v[2]);
        p.a = alphaChannel >= 0 ? v[alphaChannel] : 1.0f;
    }
    return image;
}

TextureRead readTexture(const fs::path& path, bool decodeSrgb, const TextureLimits& limits,
                        std::size_t bytesLeft) {
    TextureRead result;
    std::error_code error;
    if (!fs::exists(path, error)) {
        result.problem = "file not found";
        return result;
    }
    if (fs::is_directory(path, error)) {
        result.problem = "is a folder, not an image file";
        return result;
    }
    StderrCapture libraryOutput;
    const auto problem = [&](std::string what) {
        // libpng prints "libpng error: X" and OpenImageIO usually repeats X: add only what is new.
        std::string printed = libraryOutput.finish();
        for (const std::string_view prefix : {"libpng error: ", "libpng warning: "})
            for (std::size_t at; (at = printed.find(prefix)) != std::string::npos;)
                printed.erase(at, prefix.size());
        if (!printed.empty() && what.find(printed) == std::string::npos) what += " (" + printed + ")";
        result.texture = Texture{};
        result.problem = std::move(what);
        return std::move(result);
    };

    std::string openProblem;
    std::unique_ptr<ImageFileReader> input = openImageFile(path, openProblem);
    if (!input) return problem("cannot read it as an image: " + oneLine(openProblem));

    // The header alone decides whether the texels may be decoded at all.
    const ImageHeader& spec = input->header();
    if (spec.deep) return problem("deep images are not supported as textures");
    if (spec.width <= 0 || spec.height <= 0 || spec.depth > 1 || spec.channels <= 0)
        return problem("cannot use an image of " + std::to_string(spec.width) + "x" +
                       std::to_string(spec.height) + " pixels with " + std::to_string(spec.channels) +
                       " channels as a texture");
    const std::string size = std::to_string(spec.width) + "x" + std::to_string(spec.height);
    if (spec.width > limits.maxSide || spec.height > limits.maxSide) {
        libraryOutput.finish();
        fail(path, "the texture is " + size + " pixels; textures may be at most " +
                       std::to_string(limits.maxSide) + " pixels on a side (scale it down)");
    }
    const bool eightBit = spec.eightBit;
    const std::size_t bytes = texelBytes(spec);
    if (bytes > bytesLeft) {
        libraryOutput.finish();
        const std::size_t used = limits.maxTotalBytes - std::min(bytesLeft, limits.maxTotalBytes);
        fail(path, "the texture (" + size + " pixels, " + (eightBit ? "8-bit" : "float") + ") needs " +
                       gibibytes(bytes) + "; the textures of one render may take at most " +
                       gibibytes(limits.maxTotalBytes) + " together" +
                       (used > 0 ? " (" + gibibytes(used) + " taken by the ones before it)" : "") +
                       " (scale it down)");
    }

    // A colour value read as float: integer data is display-encoded (sRGB), float data linear already.
    const bool encoded = !spec.floating;
    const auto finish = [encoded, decodeSrgb](float value) {
        const float linear = encoded ? srgbToLinear(value) : value;
        return decodeSrgb ? linear : linearToSrgb(linear);
    };
    Texture& texture = result.texture;
    texture.width = spec.width;
    texture.height = spec.height;
    if (eightBit) {
        // Each code's value as both libraries read it as float (code · (1/255), image_file.h), so that
        // sampling gives the values a float read would; alpha's is alphaFromCode, the same product.
        for (int c = 0; c < 256; ++c)
            texture.colorFromCode[c] = finish(static_cast<float>(c) * (1.0f / 255.0f));
        if (!readTexels(*input, false, texture.codes))
            return problem("cannot read it: " + oneLine(input->error()));
        const auto same = [](std::uint8_t code) { return code; };
        arrangeTexels(spec, texture.codes, same, same, std::uint8_t{255});
    } else {
        if (!readTexels(*input, true, texture.texels))
            return problem("cannot read it: " + oneLine(input->error()));
        arrangeTexels(
            spec, texture.texels, finish, [](float a) { return a; }, 1.0f);
    }
    input.reset();
    const std::string printed = libraryOutput.finish();
    (void)printed;  // a successful read may have printed warnings; a texture that reads is used as it is
    return result;
}

std::uint64_t textureBytesFromHeader(const fs::path& path) {
    std::error_code error;
    if (!fs::is_regular_file(path, error)) return 0;
    StderrCapture libraryOutput;  // a file that is no image: readTexture warns of it later
    std::string problem;
    const std::unique_ptr<ImageFileReader> input = openImageFile(path, problem);
    libraryOutput.finish();
    if (!input) return 0;
    const ImageHeader& spec = input->header();
    if (spec.deep || spec.width <= 0 || spec.height <= 0 || spec.depth > 1 || spec.channels <= 0) return 0;
    return texelBytes(spec);
}

void checkTextureTotal(const std::vector<fs::path>& files, const TextureLimits& limits) {
    std::uint64_t total = 0, largest = 0;
    fs::path largestFile;
    for (const fs::path& file : files) {
        const std::uint64_t bytes = textureBytesFromHeader(file);
        total += bytes;
        if (bytes > largest) {
            largest = bytes;
            largestFile = file;
        }
    }
    const std::string count = std::to_string(files.size());
    // (One texture too large: readTexture names it and its size.)
    if (files.size() > 1 && total > limits.maxTotalBytes)
        throw InputError("the " + count + " textures of this render need " + describeBytes(total) +
                         " together (the largest, " + largestFile.string() + ", " + describeBytes(largest) +
                         "); the textures of one render may take at most " +
                         describeBytes(limits.maxTotalBytes) + " together (scale them down)");
    requireMemory(files.size() == 1 ? "loading the texture " + files.front().string()
                                    : "loading the " + count + " textures of this render",
                  total);
}

}  // namespace facet
