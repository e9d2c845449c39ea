// The built-in image library: PNG through libpng (reading and writing) and binary PPM (writing), the
// formats a render writes by default, without loading OpenImageIO (image_file.h says why).
//
// libpng reports errors by longjmp out of its calls. Every function below that calls libpng after a
// setjmp holds only plain data (no object with a destructor is created between the setjmp and the
// calls), so that a jump never skips a destructor.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <png.h>

#include "io/image_file.h"

namespace facet {
namespace {

std::string lowerExtension(const std::string& path) {
    const std::size_t dot = path.find_last_of('.');
    const std::size_t slash = path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string extension = path.substr(dot);
    for (char& c : extension)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return extension;
}

// Where libpng's error handler leaves its message before it jumps back to the setjmp.
struct PngErrorSink {
    char message[256] = "";
};

[[noreturn]] void onPngError(png_structp png, png_const_charp text) {
    auto* sink = static_cast<PngErrorSink*>(png_get_error_ptr(png));
    std::snprintf(sink->message, sizeof sink->message, "%s", text);
    png_longjmp(png, 1);
}

// Warnings (an unknown chunk, a bad CRC in ancillary data) change nothing that is read; OpenImageIO
// does not report them either.
void onPngWarning(png_structp, png_const_charp) {}

// A PNG file being read: the header on opening, the pixels once, on the first read().
class PngReader final : public ImageFileReader {
  public:
    ~PngReader() override {
        if (png_ != nullptr) png_destroy_read_struct(&png_, &info_, nullptr);
        if (file_ != nullptr) std::fclose(file_);
    }

    // False with error() set when the file is not a PNG whose header libpng accepts.
    bool open(const std::string& path) {
        file_ = std::fopen(path.c_str(), "rb");
        if (file_ == nullptr) return fail(std::string("cannot open: ") + std::strerror(errno));
        png_ = png_create_read_struct(PNG_LIBPNG_VER_STRING, &sink_, onPngError, onPngWarning);
        if (png_ != nullptr) info_ = png_create_info_struct(png_);
        if (png_ == nullptr || info_ == nullptr) return fail("out of memory");
        if (!readHeader()) return fail(sink_.message);
        return true;
    }

    const ImageHeader& header() const override { return header_; }

    bool read(int firstChannel, int endChannel, bool asFloat, void* out, std::size_t pixelStride) override {
        if (firstChannel < 0 || endChannel > header_.channels || firstChannel >= endChannel)
            return fail("channels out of range");
        if (!asFloat && !header_.eightBit) return fail("16-bit data cannot be read as 8-bit codes");
        if (!decoded_ && !decode()) return false;
        const std::size_t pixels = static_cast<std::size_t>(header_.width) * header_.height;
        const int channels = header_.channels;
        auto* bytes = static_cast<unsigned char*>(out);
        if (header_.eightBit) {
            // OpenImageIO's conversion of a code to float: code · (1/255).
            constexpr float kScale = 1.0f / 255.0f;
            for (std::size_t i = 0; i < pixels; ++i, bytes += pixelStride) {
                const std::uint8_t* from = &pixels_[i * channels];
                for (int c = firstChannel; c < endChannel; ++c) {
                    if (asFloat) {
                        const float value = from[c] * kScale;
                        std::memcpy(bytes + (c - firstChannel) * sizeof(float), &value, sizeof value);
                    } else {
                        bytes[c - firstChannel] = from[c];
                    }
                }
            }
        } else {
            constexpr float kScale = 1.0f / 65535.0f;  // as OpenImageIO converts 16-bit samples
            for (std::size_t i = 0; i < pixels; ++i, bytes += pixelStride) {
                for (int c = firstChannel; c < endChannel; ++c) {
                    std::uint16_t code;
                    std::memcpy(&code, &pixels_[(i * channels + c) * 2], sizeof code);
                    const float value = code * kScale;
                    std::memcpy(bytes + (c - firstChannel) * sizeof(float), &value, sizeof value);
                }
            }
        }
        return true;
    }

    std::string error() override { return error_; }

  private:
    bool fail(std::string what) {
        error_ = std::move(what);
        return false;
    }

    // The signature and the header, with the transforms that give what OpenImageIO reads: palettes
    // expanded to RGB, grey below 8 bits widened to 8, a tRNS chunk turned into an alpha channel,
    // 16-bit samples kept (in the machine's byte order). No gamma is applied.
    bool readHeader() {
        if (setjmp(png_jmpbuf(png_))) return false;
        unsigned char signature[8];
        if (std::fread(signature, 1, 8, file_) != 8 || png_sig_cmp(signature, 0, 8) != 0) {
            std::snprintf(sink_.message, sizeof sink_.message, "not a PNG file");
            return false;
        }
        png_init_io(png_, file_);
        png_set_sig_bytes(png_, 8);
        png_read_info(png_, info_);
        const int colorType = png_get_color_type(png_, info_);
        const int bitDepth = png_get_bit_depth(png_, info_);
        if (colorType == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png_);
        if (colorType == PNG_COLOR_TYPE_GRAY && bitDepth < 8) png_set_expand_gray_1_2_4_to_8(png_);
        if (png_get_valid(png_, info_, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png_);
        if (bitDepth == 16) png_set_swap(png_);
        png_set_interlace_handling(png_);
        png_read_update_info(png_, info_);
        header_.width = static_cast<int>(png_get_image_width(png_, info_));
        header_.height = static_cast<int>(png_get_image_height(png_, info_));
        header_.channels = png_get_channels(png_, info_);
        header_.alphaChannel = header_.channels == 2 || header_.channels == 4 ? header_.channels - 1 : -1;
        header_.eightBit = png_get_bit_depth(png_, info_) == 8;
        rowBytes_ = png_get_rowbytes(png_, info_);
        return true;
    }

    bool decode() {
        pixels_.resize(rowBytes_ * static_cast<std::size_t>(header_.height));
        rows_.resize(static_cast<std::size_t>(header_.height));
        for (std::size_t y = 0; y < rows_.size(); ++y)
            rows_[y] = pixels_.data() + y * rowBytes_;
        if (!decodeRows()) return fail(sink_.message);
        decoded_ = true;
        return true;
    }

    bool decodeRows() {
        if (setjmp(png_jmpbuf(png_))) return false;
        png_read_image(png_, rows_.data());
        png_read_end(png_, nullptr);
        return true;
    }

    std::FILE* file_ = nullptr;
    png_structp png_ = nullptr;
    png_infop info_ = nullptr;
    PngErrorSink sink_;
    ImageHeader header_;
    std::size_t rowBytes_ = 0;
    std::vector<std::uint8_t> pixels_;
    std::vector<png_bytep> rows_;
    bool decoded_ = false;
    std::string error_;
};

// The chunks OpenImageIO writes for an sRGB image (sRGB, with gAMA and cHRM for older readers) and
// the Software text; no time, so that the same image gives the same bytes.
bool writePngRows(png_structp png, png_infop info, std::FILE* file, const ImagePixels& pixels,
                  png_bytep* rows, int compression) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_init_io(png, file);
    png_set_IHDR(png, info, static_cast<png_uint_32>(pixels.width), static_cast<png_uint_32>(pixels.height),
                 8, pixels.channels == 4 ? PNG_COLOR_TYPE_RGB_ALPHA : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_ABSOLUTE);
    png_text software{};
    software.compression = PNG_TEXT_COMPRESSION_NONE;
    software.key = const_cast<char*>("Software");
    software.text = const_cast<char*>("Facet");
    png_set_text(png, info, &software, 1);
    png_set_compression_level(png, compression);
    // Level 0 stores: filtering would only cost time. Up to level 3 only the Up filter: on renders it
    // compresses as well as libpng's adaptive choice among all five, in 40% of the time (the bunny at
    // 1920x1080, level 1: Up 21 ms, 230 KB; all five 54 ms, 236 KB; OpenImageIO's level 6 with all
    // five, 91 ms, 169 KB). From level 4, where size matters more, all five.
    png_set_filter(png, PNG_FILTER_TYPE_BASE,
                   compression == 0   ? PNG_FILTER_NONE
                   : compression <= 3 ? PNG_FILTER_UP
                                      : PNG_ALL_FILTERS);
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, info);
    return true;
}

std::string writePng(const std::string& path, const ImagePixels& pixels, int compression) {
    if (pixels.floating || (pixels.channels != 3 && pixels.channels != 4))
        return "PNG holds 8-bit RGB or RGBA here";
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (file == nullptr) return std::string("cannot open: ") + std::strerror(errno);
    PngErrorSink sink;
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, onPngError, onPngWarning);
    png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
    std::vector<png_bytep> rows(static_cast<std::size_t>(pixels.height));
    const std::size_t rowBytes = static_cast<std::size_t>(pixels.width) * pixels.channels;
    for (std::size_t y = 0; y < rows.size(); ++y)
        rows[y] = const_cast<png_bytep>(static_cast<const std::uint8_t*>(pixels.data) + y * rowBytes);
    std::string error;
    if (png == nullptr || info == nullptr)
        error = "out of memory";
    else if (!writePngRows(png, info, file, pixels, rows.data(), std::clamp(compression, 0, 9)))
        error = sink.message;
    if (png != nullptr) png_destroy_write_struct(&png, &info);
    // A full disk shows at the last write or at the close.
    if (std::fclose(file) != 0 && error.empty()) error = std::strerror(errno);
    return error;
}

// Binary PPM (P6): a text header, then RGB codes.
std::string writePpm(const std::string& path, const ImagePixels& pixels) {
    if (pixels.floating || pixels.channels != 3) return "PPM holds 8-bit RGB here";
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (file == nullptr) return std::string("cannot open: ") + std::strerror(errno);
    const std::size_t bytes = static_cast<std::size_t>(pixels.width) * pixels.height * 3;
    bool ok = std::fprintf(file, "P6\n%d %d\n255\n", pixels.width, pixels.height) > 0 &&
              std::fwrite(pixels.data, 1, bytes, file) == bytes;
    const int savedErrno = errno;
    ok = std::fclose(file) == 0 && ok;
    return ok ? "" : std::strerror(savedErrno ? savedErrno : errno);
}

class BuiltInLibrary final : public ImageLibrary {
  public:
    std::unique_ptr<ImageFileReader> open(const std::string& path, std::string& error) override {
        auto reader = std::make_unique<PngReader>();
        if (reader->open(path)) return reader;
        error = reader->error();
        return nullptr;
    }

    std::string write(const std::string& path, const ImagePixels& pixels, int pngCompression) override {
        const std::string extension = lowerExtension(path);
        if (extension == ".png") return writePng(path, pixels, pngCompression);
        if (extension == ".ppm") return writePpm(path, pixels);
        return "the built-in writer has no format for \"" + extension + "\"";
    }
};

}  // namespace

ImageLibrary& builtInImageLibrary() {
    static BuiltInLibrary library;
    return library;
}

bool builtInFormat(const std::string& path) {
    const std::string extension = lowerExtension(path);
    return extension == ".png" || extension == ".ppm";
}

bool isPngFile(const std::string& path) {
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (file == nullptr) return false;
    unsigned char signature[8];
    const bool png = std::fread(signature, 1, 8, file) == 8 && png_sig_cmp(signature, 0, 8) == 0;
    std::fclose(file);
    return png;
}

}  // namespace facet
