// The built-in image library: PNG read through libpng and written through zlib, and binary PPM
// (writing), the
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
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <libdeflate.h>
#include <png.h>
#include <zlib.h>

#include "io/image_file.h"
#include "pipeline/thread_pool.h"

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
        path_ = path;
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
        auto* bytes = static_cast<unsigned char*>(out);
        const std::size_t rowStride = static_cast<std::size_t>(header_.width) * pixelStride;
        // A file without interlacing is decoded row by row straight into `out`: a 16384² RGB texture
        // needs its 1 GiB of texels and one row more, not another 768 MiB for the whole decoded file.
        // A second read (another channel range) decodes the file again from its start: libpng cannot
        // rewind, and keeping the first pass's rows would cost the memory streaming saves.
        if (!decoded_ && passes_ == 1) {
            if (streamed_ && !reopen()) return false;
            streamed_ = true;
            std::vector<std::uint8_t> row(rowBytes_);
            for (int y = 0; y < header_.height; ++y) {
                if (!decodeRow(row.data())) return fail(sink_.message);
                convertRow(row.data(), firstChannel, endChannel, asFloat, bytes + y * rowStride, pixelStride);
            }
            return finishRows() || fail(sink_.message);
        }
        if (!decoded_ && !decode()) return false;
        for (int y = 0; y < header_.height; ++y)
            convertRow(pixels_.data() + y * rowBytes_, firstChannel, endChannel, asFloat,
                       bytes + y * rowStride, pixelStride);
        return true;
    }

    std::string error() override { return error_; }

  private:
    bool fail(std::string what) {
        error_ = std::move(what);
        return false;
    }

    bool reopen() {
        png_destroy_read_struct(&png_, &info_, nullptr);
        std::fclose(file_);
        png_ = nullptr;
        info_ = nullptr;
        file_ = nullptr;
        streamed_ = false;
        return open(std::string(path_));
    }

    // One decoded row's channels [firstChannel, endChannel) into `bytes`, pixels `pixelStride` apart.
    void convertRow(const std::uint8_t* row, int firstChannel, int endChannel, bool asFloat,
                    unsigned char* bytes, std::size_t pixelStride) const {
        const int channels = header_.channels;
        if (header_.eightBit) {
            // OpenImageIO's conversion of a code to float: code · (1/255).
            constexpr float kScale = 1.0f / 255.0f;
            for (int i = 0; i < header_.width; ++i, bytes += pixelStride) {
                const std::uint8_t* from = &row[static_cast<std::size_t>(i) * channels];
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
            for (int i = 0; i < header_.width; ++i, bytes += pixelStride) {
                for (int c = firstChannel; c < endChannel; ++c) {
                    std::uint16_t code;
                    std::memcpy(&code, &row[(static_cast<std::size_t>(i) * channels + c) * 2], sizeof code);
                    const float value = code * kScale;
                    std::memcpy(bytes + (c - firstChannel) * sizeof(float), &value, sizeof value);
                }
            }
        }
    }

    bool decodeRow(std::uint8_t* row) {
        if (setjmp(png_jmpbuf(png_))) return false;
        png_read_row(png_, row, nullptr);
        return true;
    }

    bool finishRows() {
        if (setjmp(png_jmpbuf(png_))) return false;
        png_read_end(png_, nullptr);
        return true;
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
        passes_ = png_set_interlace_handling(png_);
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

    std::string path_;
    std::FILE* file_ = nullptr;
    png_structp png_ = nullptr;
    png_infop info_ = nullptr;
    PngErrorSink sink_;
    ImageHeader header_;
    std::size_t rowBytes_ = 0;
    std::vector<std::uint8_t> pixels_;
    std::vector<png_bytep> rows_;
    int passes_ = 1;         // 7 for an interlaced (Adam7) file: decoded whole, then converted
    bool decoded_ = false;   // the whole image is in pixels_
    bool streamed_ = false;  // its rows were decoded straight into a read's `out`
    std::string error_;
};

// ---- PNG writing: bands of rows filtered and deflated independently, on the pool's threads --------
//
// A PNG's pixel data is one zlib stream (RFC 1950) over the filtered rows, split across IDAT chunks as
// the writer likes. Deflate streams concatenate when every part but the last ends on a byte boundary
// (Z_SYNC_FLUSH), so each band of kPngBandRows rows is deflated on its own (raw, no header) and the
// parts are written in order behind one zlib header, with the Adler-32 of the whole combined from the
// bands'. Bands are fixed by the image, not by the threads: the same image gives the same bytes for
// any thread count. Each band starts without the previous band's history, which costs a few hundred
// bytes a band.
constexpr int kPngBandRows = 64;

// PNG's row filters (PNG specification, section 9): each byte minus a prediction from the bytes to its
// left (a), above (b) and above-left (c); a and c are 0 in the first pixel, b and c in the first row.
enum PngFilter : std::uint8_t { kFilterNone = 0, kFilterSub, kFilterUp, kFilterAverage, kFilterPaeth };

// Paeth's predictor (section 9.4): of a, b and c, the one nearest to a + b − c, ties to a then b.
inline int paethPredictor(int a, int b, int c) {
    const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
    return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

// Filters `row` (bytes, `stride` bytes a pixel) with `filter` into `out` (its filter byte first);
// `above` is the previous row, all zeros for the first. One loop per filter, without a branch on the
// filter or on the first pixel inside it, so that each vectorises.
void filterRow(PngFilter filter, const std::uint8_t* row, const std::uint8_t* above, std::size_t bytes,
               std::size_t stride, std::uint8_t* out) {
    out[0] = filter;
    ++out;
    const std::size_t first = std::min(stride, bytes);  // the first pixel: a = c = 0
    switch (filter) {
        case kFilterNone:
            std::memcpy(out, row, bytes);
            return;
        case kFilterSub:
            std::memcpy(out, row, first);
            for (std::size_t i = first; i < bytes; ++i)
                out[i] = static_cast<std::uint8_t>(row[i] - row[i - stride]);
            return;
        case kFilterUp:
            for (std::size_t i = 0; i < bytes; ++i)
                out[i] = static_cast<std::uint8_t>(row[i] - above[i]);
            return;
        case kFilterAverage:
            for (std::size_t i = 0; i < first; ++i)
                out[i] = static_cast<std::uint8_t>(row[i] - above[i] / 2);
            for (std::size_t i = first; i < bytes; ++i)
                out[i] = static_cast<std::uint8_t>(row[i] - (row[i - stride] + above[i]) / 2);
            return;
        case kFilterPaeth:
            for (std::size_t i = 0; i < first; ++i)  // Paeth(0, b, 0) = b
                out[i] = static_cast<std::uint8_t>(row[i] - above[i]);
            for (std::size_t i = first; i < bytes; ++i)
                out[i] = static_cast<std::uint8_t>(
                    row[i] - paethPredictor(row[i - stride], above[i], above[i - stride]));
            return;
    }
}

// libpng's measure of how well a filtered row will compress: the sum of its bytes read as signed,
// made positive.
std::uint64_t sumOfMagnitudes(const std::uint8_t* filtered, std::size_t bytes) {
    std::uint64_t sum = 0;
    constexpr std::size_t kChunk = std::size_t{1} << 20;  // 128 · 2^20 fits the 32-bit partial sums
    for (std::size_t from = 0; from < bytes; from += kChunk) {
        std::uint32_t partial = 0;
        const std::size_t to = std::min(bytes, from + kChunk);
        for (std::size_t i = from; i < to; ++i) {
            const int value = static_cast<std::int8_t>(filtered[i]);
            partial += static_cast<std::uint32_t>(value < 0 ? -value : value);
        }
        sum += partial;
    }
    return sum;
}

// What a thread keeps from band to band (and image to image): two rows of codes (a row and the one
// above it), the filtered row, the filter trials, a row of zeros, the deflate output and the deflate
// stream. A band is filtered and deflated row by row, so that these stay a few rows in size (in
// cache) and a render pays their page faults once per thread, not per band (a 1920×1080 band is 0.5 MB
// of codes and as much filtered).
struct PngBandScratch {
    std::vector<std::uint8_t> codes[2], filtered, trial, zeros;
    std::unique_ptr<std::uint8_t[]> deflated;  // not value-initialised: only what deflate writes is touched
    std::size_t deflatedCapacity = 0;
    z_stream stream{};
    int streamLevel = -1;  // the level `stream` was started at; -1: not started

    PngBandScratch() = default;
    PngBandScratch(const PngBandScratch&) = delete;
    PngBandScratch& operator=(const PngBandScratch&) = delete;
    ~PngBandScratch() {
        if (streamLevel >= 0) deflateEnd(&stream);
    }

    // A raw deflate stream (no zlib header) at `level`, reset: the same output as a fresh one.
    z_stream* deflateAt(int level) {
        if (streamLevel == level) return deflateReset(&stream) == Z_OK ? &stream : nullptr;
        if (streamLevel >= 0) deflateEnd(&stream);
        stream = z_stream{};
        streamLevel =
            deflateInit2(&stream, level, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) == Z_OK ? level : -1;
        return streamLevel >= 0 ? &stream : nullptr;
    }

    std::uint8_t* deflatedOfAtLeast(std::size_t bytes) {
        if (deflatedCapacity < bytes) {
            deflated = std::make_unique_for_overwrite<std::uint8_t[]>(bytes);
            deflatedCapacity = bytes;
        }
        return deflated.get();
    }
};

// Filters a row into `out` (1 + bytes): none at level 0 (storing), Up at the fast levels 1–3 (on
// renders as small as trying all five, at a fraction of the time: the bunny at 1920×1080, level 1,
// 230 KB against 236 KB), and from level 4 libpng's heuristic: the filter whose output has the least
// sum of |signed bytes|, the first of equals.
void filterChosen(int level, const std::uint8_t* row, const std::uint8_t* above, std::size_t bytes,
                  std::size_t stride, PngBandScratch& scratch, std::uint8_t* out) {
    if (level <= 3) {
        filterRow(level == 0 ? kFilterNone : kFilterUp, row, above, bytes, stride, out);
        return;
    }
    std::uint64_t bestSum = ~std::uint64_t{0};
    scratch.trial.resize(bytes + 1);
    for (const PngFilter filter : {kFilterNone, kFilterSub, kFilterUp, kFilterAverage, kFilterPaeth}) {
        filterRow(filter, row, above, bytes, stride, scratch.trial.data());
        const std::uint64_t sum = sumOfMagnitudes(scratch.trial.data() + 1, bytes);
        if (sum < bestSum) {
            bestSum = sum;
            std::memcpy(out, scratch.trial.data(), bytes + 1);
        }
    }
}

struct PngBand {
    std::vector<std::uint8_t> deflated;  // raw deflate data, ending on a byte boundary
    std::uint32_t adler = 1;             // Adler-32 of the band's filtered bytes
    std::size_t filteredBytes = 0;
    std::string error;
};

// A band's rows filtered and deflated one at a time. zlib's output at levels 1–9 does not depend on
// how its input is handed over; at level 0 (stored blocks) it does, but the rows are always handed
// over one by one, so the bytes still depend on the image alone.
void deflateBand(const ImagePixels& pixels, int level, std::size_t band, bool last, PngBand& out) {
    thread_local PngBandScratch scratch;
    const std::size_t rowBytes = static_cast<std::size_t>(pixels.width) * pixels.channels;
    const std::size_t stride = static_cast<std::size_t>(pixels.channels);
    const int firstRow = static_cast<int>(band) * kPngBandRows;
    const int endRow = std::min(pixels.height, firstRow + kPngBandRows);
    z_stream* stream = scratch.deflateAt(level);
    if (stream == nullptr) {
        out.error = "zlib cannot start";
        return;
    }
    const std::size_t filteredBytes = static_cast<std::size_t>(endRow - firstRow) * (rowBytes + 1);
    const std::size_t bound = deflateBound(stream, static_cast<uLong>(filteredBytes)) + 16;
    stream->next_out = scratch.deflatedOfAtLeast(bound);
    stream->avail_out = static_cast<uInt>(bound);
    scratch.filtered.resize(rowBytes + 1);
    // The row above the band's first (the filters predict from it): the previous band's last, or zeros.
    if (firstRow == 0) scratch.zeros.assign(rowBytes, 0);
    const std::uint8_t* above = firstRow == 0
                                    ? scratch.zeros.data()
                                    : pixels.codes(firstRow - 1, 1, scratch.codes[(firstRow - 1) & 1]);
    std::uint32_t adler = 1;
    for (int y = firstRow; y < endRow; ++y) {
        const std::uint8_t* row = pixels.codes(y, 1, scratch.codes[y & 1]);
        filterChosen(level, row, above, rowBytes, stride, scratch, scratch.filtered.data());
        adler = libdeflate_adler32(adler, scratch.filtered.data(), rowBytes + 1);
        stream->next_in = scratch.filtered.data();
        stream->avail_in = static_cast<uInt>(rowBytes + 1);
        const bool lastRow = y + 1 == endRow;
        const int flush = !lastRow ? Z_NO_FLUSH : last ? Z_FINISH : Z_SYNC_FLUSH;
        const int result = deflate(stream, flush);
        if (result != (flush == Z_FINISH ? Z_STREAM_END : Z_OK) || stream->avail_in != 0) {
            out.error = "zlib cannot compress";
            return;
        }
        above = row;
    }
    out.adler = adler;
    out.filteredBytes = filteredBytes;
    out.deflated.assign(scratch.deflated.get(), scratch.deflated.get() + (bound - stream->avail_out));
}

void putBigEndian(std::vector<std::uint8_t>& out, std::uint32_t value) {
    for (int shift = 24; shift >= 0; shift -= 8)
        out.push_back(static_cast<std::uint8_t>(value >> shift));
}

// One chunk: length, type, data, CRC-32 of type and data.
bool writeChunk(std::FILE* file, const char type[4], const std::uint8_t* data, std::size_t size) {
    std::vector<std::uint8_t> head;
    putBigEndian(head, static_cast<std::uint32_t>(size));
    head.insert(head.end(), type, type + 4);
    std::uint32_t crc = libdeflate_crc32(0, type, 4);
    if (size > 0) crc = libdeflate_crc32(crc, data, size);
    std::vector<std::uint8_t> tail;
    putBigEndian(tail, crc);
    return std::fwrite(head.data(), 1, head.size(), file) == head.size() &&
           (size == 0 || std::fwrite(data, 1, size, file) == size) &&
           std::fwrite(tail.data(), 1, tail.size(), file) == tail.size();
}

// The chunks OpenImageIO writes for an 8-bit sRGB image: sRGB (absolute colorimetric), with gAMA and
// cHRM for older readers (the values the PNG specification gives for sRGB), and the Software text; no
// time, so that the same image gives the same bytes.
std::string writePng(const std::string& path, const ImagePixels& pixels, int compression, ThreadPool* pool) {
    if (pixels.floating || (pixels.channels != 3 && pixels.channels != 4))
        return "PNG holds 8-bit RGB or RGBA here";
    const int level = std::clamp(compression, 0, 9);
    const std::size_t bandCount = (static_cast<std::size_t>(pixels.height) + kPngBandRows - 1) / kPngBandRows;
    std::vector<PngBand> bands(bandCount);
    const auto deflateOne = [&](std::size_t band, int) {
        deflateBand(pixels, level, band, band + 1 == bandCount, bands[band]);
    };
    if (pool != nullptr)
        pool->parallelFor(bandCount, deflateOne);
    else
        for (std::size_t band = 0; band < bandCount; ++band)
            deflateOne(band, 0);
    for (const PngBand& band : bands)
        if (!band.error.empty()) return band.error;

    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (file == nullptr) return std::string("cannot open: ") + std::strerror(errno);
    static constexpr std::uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    std::vector<std::uint8_t> header;
    putBigEndian(header, static_cast<std::uint32_t>(pixels.width));
    putBigEndian(header, static_cast<std::uint32_t>(pixels.height));
    // 8 bits, RGB (2) or RGBA (6), deflate, adaptive filtering, not interlaced.
    header.insert(header.end(), {8, static_cast<std::uint8_t>(pixels.channels == 4 ? 6 : 2), 0, 0, 0});
    const std::uint8_t srgbIntent[1] = {3};
    std::vector<std::uint8_t> gamma, chromaticities;
    putBigEndian(gamma, 45455);  // 1/2.2 × 100000
    for (const std::uint32_t value : {31270u, 32900u, 64000u, 33000u, 30000u, 60000u, 15000u, 6000u})
        putBigEndian(chromaticities, value);
    static constexpr char kSoftware[] = "Software\0Facet";
    // The zlib header (deflate, 32 KiB window, the level's hint; a multiple of 31) and the Adler-32.
    const std::uint8_t zlibHeader[2] = {0x78, static_cast<std::uint8_t>(level <= 1   ? 0x01
                                                                        : level <= 5 ? 0x5E
                                                                        : level == 6 ? 0x9C
                                                                                     : 0xDA)};
    uLong adler = 1;
    for (const PngBand& band : bands)
        adler = adler32_combine(adler, band.adler, static_cast<z_off_t>(band.filteredBytes));
    std::vector<std::uint8_t> trailer;
    putBigEndian(trailer, static_cast<std::uint32_t>(adler));

    bool ok =
        std::fwrite(kSignature, 1, 8, file) == 8 && writeChunk(file, "IHDR", header.data(), header.size()) &&
        writeChunk(file, "sRGB", srgbIntent, 1) && writeChunk(file, "gAMA", gamma.data(), gamma.size()) &&
        writeChunk(file, "cHRM", chromaticities.data(), chromaticities.size()) &&
        writeChunk(file, "tEXt", reinterpret_cast<const std::uint8_t*>(kSoftware), sizeof kSoftware - 1) &&
        writeChunk(file, "IDAT", zlibHeader, 2);
    for (const PngBand& band : bands)
        ok = ok && writeChunk(file, "IDAT", band.deflated.data(), band.deflated.size());
    ok = ok && writeChunk(file, "IDAT", trailer.data(), trailer.size()) &&
         writeChunk(file, "IEND", nullptr, 0);
    const int savedErrno = errno;
    // A full disk shows at the last write or at the close.
    ok = std::fclose(file) == 0 && ok;
    return ok ? "" : std::strerror(savedErrno ? savedErrno : errno);
}

// Binary PPM (P6): a text header, then RGB codes.
std::string writePpm(const std::string& path, const ImagePixels& pixels) {
    if (pixels.floating || pixels.channels != 3) return "PPM holds 8-bit RGB here";
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (file == nullptr) return std::string("cannot open: ") + std::strerror(errno);
    const std::size_t rowBytes = static_cast<std::size_t>(pixels.width) * 3;
    bool ok = std::fprintf(file, "P6\n%d %d\n255\n", pixels.width, pixels.height) > 0;
    std::vector<std::uint8_t> scratch;
    constexpr int kRowsPerWrite = 64;  // rows encoded (when `pixels.rows` makes them) and written at once
    for (int y = 0; ok && y < pixels.height; y += kRowsPerWrite) {
        const int count = std::min(kRowsPerWrite, pixels.height - y);
        ok = std::fwrite(pixels.codes(y, count, scratch), 1, rowBytes * count, file) == rowBytes * count;
    }
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

    std::string write(const std::string& path, const ImagePixels& pixels, int pngCompression,
                      ThreadPool* pool) override {
        const std::string extension = lowerExtension(path);
        if (extension == ".png") return writePng(path, pixels, pngCompression, pool);
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
