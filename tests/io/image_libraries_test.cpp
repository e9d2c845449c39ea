// The two image libraries under image_io.h (io/image_file.h): the built-in PNG code and OpenImageIO
// read every kind of PNG to the same header and the same values, files written by either decode to the
// same pixels, the PNG compression level reaches the file, and OpenImageIO is loaded only for the
// formats that need it. Above each test, the one-line break it catches.
#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <png.h>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "base/errors.h"
#include "io/image_file.h"
#include "io/image_io.h"
#include "io/stored_bytes.h"
#include "pipeline/thread_pool.h"
#include "support/file_bytes.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using testing_support::TempFolderTest;

// One kind of PNG file: its colour type, bit depth, interlacing, and the extra chunks it carries.
struct PngKind {
    const char* name;
    int colorType;
    int bitDepth;
    bool interlaced = false;
    bool transparency = false;  // a tRNS chunk (a colour key, or palette alphas)
    bool gamma = false;         // a gAMA chunk of 1/1.8, which neither library applies
};

int channelsOf(int colorType) {
    switch (colorType) {
        case PNG_COLOR_TYPE_GRAY:
            return 1;
        case PNG_COLOR_TYPE_GRAY_ALPHA:
            return 2;
        case PNG_COLOR_TYPE_RGB:
            return 3;
        case PNG_COLOR_TYPE_RGB_ALPHA:
            return 4;
        default:
            return 1;  // palette indices
    }
}

// Writes a 13×7 file of that kind straight through libpng, its samples a pattern that reaches every
// value of small depths and both ends of large ones.
void writeKind(const fs::path& path, const PngKind& kind) {
    constexpr int kWidth = 13, kHeight = 7;
    std::FILE* file = std::fopen(path.c_str(), "wb");
    ASSERT_NE(file, nullptr);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    ASSERT_EQ(setjmp(png_jmpbuf(png)), 0);
    png_init_io(png, file);
    png_set_IHDR(png, info, kWidth, kHeight, kind.bitDepth, kind.colorType,
                 kind.interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    if (kind.colorType == PNG_COLOR_TYPE_PALETTE) {
        png_color palette[16];
        png_byte alphas[16];
        for (int k = 0; k < 16; ++k) {
            palette[k] = {png_byte(k * 17), png_byte(255 - k * 13), png_byte(k * 5)};
            alphas[k] = png_byte(k * 16);
        }
        png_set_PLTE(png, info, palette, 1 << std::min(kind.bitDepth, 4));
        if (kind.transparency) png_set_tRNS(png, info, alphas, 1 << std::min(kind.bitDepth, 4), nullptr);
    } else if (kind.transparency) {
        png_color_16 key{};
        key.gray = 1;
        key.red = 1, key.green = 2, key.blue = 3;
        png_set_tRNS(png, info, nullptr, 0, &key);
    }
    if (kind.gamma) png_set_gAMA(png, info, 1.0 / 1.8);
    png_write_info(png, info);
    // Palette indices stay within the 16 colours.
    const int maxValue =
        (1 << (kind.colorType == PNG_COLOR_TYPE_PALETTE ? std::min(kind.bitDepth, 4) : kind.bitDepth)) - 1;
    const int channels = channelsOf(kind.colorType);
    std::vector<std::uint16_t> samples;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x)
            for (int c = 0; c < channels; ++c)
                samples.push_back(static_cast<std::uint16_t>((x * 7 + y * 31 + c * 97) % (maxValue + 1)));
    samples[0] = 1;  // the colour key (1; 1, 2, 3 would need three channels: the grey key is hit)
    // Packed rows, as libpng takes them without transforms.
    const std::size_t rowBytes = png_get_rowbytes(png, info);
    std::vector<png_byte> rows(rowBytes * kHeight, 0);
    for (int y = 0; y < kHeight; ++y) {
        png_byte* row = &rows[y * rowBytes];
        for (int i = 0; i < kWidth * channels; ++i) {
            const std::uint16_t v = samples[static_cast<std::size_t>(y) * kWidth * channels + i];
            if (kind.bitDepth == 16) {
                row[2 * i] = png_byte(v >> 8);
                row[2 * i + 1] = png_byte(v & 255);
            } else if (kind.bitDepth == 8) {
                row[i] = png_byte(v);
            } else {
                const int perByte = 8 / kind.bitDepth;
                row[i / perByte] |= png_byte(v << (8 - kind.bitDepth * (i % perByte + 1)));
            }
        }
    }
    std::vector<png_bytep> pointers;
    for (int y = 0; y < kHeight; ++y)
        pointers.push_back(&rows[y * rowBytes]);
    png_write_image(png, pointers.data());
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    std::fclose(file);
}

class ImageLibraries : public TempFolderTest {};

using testing_support::fileBytes;

// Every PNG kind reads to the same header and the same values, as float and (8-bit) as codes, through
// the built-in reader and OpenImageIO. Breaks caught: a palette not expanded, grey below 8 bits left
// packed, a tRNS chunk not turned into alpha, 16-bit samples read in file (big-endian) order, the
// interlaced passes not combined, a gAMA chunk applied, or 8-bit codes scaled by /255 instead of
// OpenImageIO's ·(1/255) (which differ in the last bit for some codes).
TEST_F(ImageLibraries, EveryKindOfPngReadsTheSameThroughBothLibraries) {
    const PngKind kinds[] = {
        {"grey1", PNG_COLOR_TYPE_GRAY, 1},
        {"grey2", PNG_COLOR_TYPE_GRAY, 2},
        {"grey4", PNG_COLOR_TYPE_GRAY, 4},
        {"grey8", PNG_COLOR_TYPE_GRAY, 8},
        {"grey16", PNG_COLOR_TYPE_GRAY, 16},
        {"grey8-key", PNG_COLOR_TYPE_GRAY, 8, false, true},
        {"grey-alpha8", PNG_COLOR_TYPE_GRAY_ALPHA, 8},
        {"grey-alpha16", PNG_COLOR_TYPE_GRAY_ALPHA, 16},
        {"rgb8", PNG_COLOR_TYPE_RGB, 8},
        {"rgb8-gamma", PNG_COLOR_TYPE_RGB, 8, false, false, true},
        {"rgb16", PNG_COLOR_TYPE_RGB, 16},
        {"rgba8", PNG_COLOR_TYPE_RGB_ALPHA, 8},
        {"rgba8-interlaced", PNG_COLOR_TYPE_RGB_ALPHA, 8, true},
        {"rgba16", PNG_COLOR_TYPE_RGB_ALPHA, 16},
        {"palette2", PNG_COLOR_TYPE_PALETTE, 2},
        {"palette8", PNG_COLOR_TYPE_PALETTE, 8},
        {"palette4-alpha", PNG_COLOR_TYPE_PALETTE, 4, false, true},
    };
    for (const PngKind& kind : kinds) {
        SCOPED_TRACE(kind.name);
        const fs::path path = folder_ / (std::string(kind.name) + ".png");
        writeKind(path, kind);
        ASSERT_TRUE(isPngFile(path.string()));
        std::string error;
        auto ours = builtInImageLibrary().open(path.string(), error);
        ASSERT_TRUE(ours) << error;
        auto theirs = openImageIO().open(path.string(), error);
        ASSERT_TRUE(theirs) << error;
        const ImageHeader& a = ours->header();
        const ImageHeader& b = theirs->header();
        ASSERT_EQ(a.width, b.width);
        ASSERT_EQ(a.height, b.height);
        ASSERT_EQ(a.channels, b.channels);
        EXPECT_EQ(a.alphaChannel, b.alphaChannel);
        EXPECT_EQ(a.eightBit, b.eightBit);
        EXPECT_EQ(a.floating, b.floating);
        const std::size_t values = static_cast<std::size_t>(a.width) * a.height * a.channels;
        std::vector<float> floatsA(values), floatsB(values);
        ASSERT_TRUE(ours->read(0, a.channels, true, floatsA.data(), a.channels * sizeof(float)))
            << ours->error();
        ASSERT_TRUE(theirs->read(0, b.channels, true, floatsB.data(), b.channels * sizeof(float)));
        for (std::size_t i = 0; i < values; ++i)
            ASSERT_EQ(std::bit_cast<std::uint32_t>(floatsA[i]), std::bit_cast<std::uint32_t>(floatsB[i]))
                << "value " << i << ": " << floatsA[i] << " vs " << floatsB[i];
        if (a.eightBit) {
            // One channel at a time into a wider stride, as readTexture reads alpha beyond slot 3.
            std::vector<std::uint8_t> codesA(values * 2), codesB(values * 2);
            for (int c = 0; c < a.channels; ++c) {
                ASSERT_TRUE(ours->read(c, c + 1, false, codesA.data() + c, a.channels * 2));
                ASSERT_TRUE(theirs->read(c, c + 1, false, codesB.data() + c, b.channels * 2));
            }
            EXPECT_EQ(codesA, codesB);
        }
    }
}

// A PNG (RGBA) and a PPM (RGB) written by the built-in writer and by OpenImageIO from the same codes
// decode to the same pixels, and the built-in one marks the file sRGB as OpenImageIO does. Breaks
// caught: rows written bottom up, RGBA declared as RGB, the PPM header's width and height swapped, the
// sRGB chunk left out.
TEST_F(ImageLibraries, FilesWrittenByEitherLibraryDecodeToTheSamePixels) {
    constexpr int kWidth = 37, kHeight = 150;  // three bands of 64 rows in the built-in PNG writer
    for (const int channels : {3, 4}) {
        std::vector<std::uint8_t> codes(static_cast<std::size_t>(kWidth) * kHeight * channels);
        for (std::size_t i = 0; i < codes.size(); ++i)
            codes[i] = static_cast<std::uint8_t>(i * 37 % 251);
        const ImagePixels pixels{kWidth, kHeight, channels, false, codes.data(), {}};
        for (const char* extension : {".png", ".ppm"}) {
            if (channels == 4 && std::string(extension) == ".ppm") continue;
            SCOPED_TRACE(std::string(extension) + " " + std::to_string(channels));
            const fs::path ours = folder_ / ("ours" + std::to_string(channels) + extension);
            const fs::path theirs = folder_ / ("theirs" + std::to_string(channels) + extension);
            ASSERT_EQ(builtInImageLibrary().write(ours.string(), pixels, kFastPngCompression), "");
            ASSERT_EQ(openImageIO().write(theirs.string(), pixels, 6), "");
            int channelsA = 0, channelsB = 0;
            const std::vector<std::uint8_t> a = testing_support::storedBytes(ours, &channelsA);
            EXPECT_EQ(channelsA, channels);
            EXPECT_EQ(a, codes);
            EXPECT_EQ(a, testing_support::storedBytes(theirs, &channelsB));
            if (std::string(extension) == ".png") {
                auto input = OIIO::ImageInput::open(ours.string());
                ASSERT_TRUE(input);
                EXPECT_EQ(input->spec().get_string_attribute("oiio:ColorSpace"), "sRGB");
            }
        }
    }
}

// The built-in PNG writer deflates bands of 64 rows apart and joins them: at every level (0 stores,
// 1–3 the Up filter, 4–9 the filter chosen per row) OpenImageIO decodes the file to the codes written,
// and the bytes are the same written on one thread or four. Breaks caught: a band not ending on a byte
// boundary (Z_SYNC_FLUSH left out), the Adler-32 of the whole not combined from the bands', a filter's
// prediction wrong on a band's first row, or bands split by the thread count.
TEST_F(ImageLibraries, BandedPngDecodesAtEveryLevelAndIgnoresTheThreadCount) {
    constexpr int kWidth = 53, kHeight = 200;
    std::vector<std::uint8_t> codes(static_cast<std::size_t>(kWidth) * kHeight * 4);
    for (std::size_t i = 0; i < codes.size(); ++i)
        codes[i] = static_cast<std::uint8_t>((i / 4 % kWidth) * 3 + (i / 4 / kWidth) * 2 + (i % 4) * 40 +
                                             (i * 2654435761u >> 29));
    const ImagePixels pixels{kWidth, kHeight, 4, false, codes.data(), {}};
    ThreadPool four(4);
    for (int level = 0; level <= 9; ++level) {
        SCOPED_TRACE("level " + std::to_string(level));
        const fs::path one = folder_ / ("one" + std::to_string(level) + ".png");
        const fs::path many = folder_ / ("many" + std::to_string(level) + ".png");
        ASSERT_EQ(builtInImageLibrary().write(one.string(), pixels, level, nullptr), "");
        ASSERT_EQ(builtInImageLibrary().write(many.string(), pixels, level, &four), "");
        int channels = 0;
        EXPECT_EQ(testing_support::storedBytes(one, &channels), codes);
        std::string error;
        auto ours = builtInImageLibrary().open(one.string(), error);
        ASSERT_TRUE(ours) << error;
        std::vector<std::uint8_t> back(codes.size());
        ASSERT_TRUE(ours->read(0, 4, false, back.data(), 4)) << ours->error();
        EXPECT_EQ(back, codes);
        EXPECT_EQ(fileBytes(one), fileBytes(many));
    }
}

// --png-compression's level reaches the file: 0 stores (at least 4 bytes a pixel), 9 is smaller than
// the default, and every level decodes to the same pixels. Breaks caught: the level not passed to
// libpng, or clamped to the default.
TEST_F(ImageLibraries, PngCompressionLevelChangesTheSizeNotThePixels) {
    LinearImage image;
    image.width = 64;
    image.height = 48;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            image.pixels.push_back({float(x) / 63.0f, float(y) / 47.0f, float((x * y) % 7) / 6.0f, 1.0f});
    std::vector<std::uintmax_t> sizes;
    for (const int level : {0, kFastPngCompression, 9}) {
        const fs::path path = folder_ / ("level" + std::to_string(level) + ".png");
        writeImage(path, image, kSrgbEncoding, level);
        sizes.push_back(fs::file_size(path));
        const LinearImage back = readImage(path);
        const LinearImage first = readImage(folder_ / "level0.png");
        EXPECT_EQ(back.pixels, first.pixels);
    }
    EXPECT_GE(sizes[0], 64u * 48u * 4u);
    EXPECT_LT(sizes[1], sizes[0]);
    EXPECT_LT(sizes[2], sizes[1]);
}

// Writing and reading PNG never loads OpenImageIO; writing EXR does. (Each test runs in a process of
// its own.) Breaks caught: the writer or the reader sending PNG to OpenImageIO, or openImageIOLoaded
// reporting the attempt rather than the load.
TEST_F(ImageLibraries, OpenImageIOIsLoadedOnlyForTheFormatsThatNeedIt) {
    if (openImageIOLoaded())
        GTEST_SKIP() << "an earlier test of this process loaded it (ctest runs each alone)";
    LinearImage image;
    image.width = 4;
    image.height = 2;
    image.pixels.assign(8, glm::vec4(0.25f, 0.5f, 0.75f, 1.0f));
    writeImage(folder_ / "a.png", image);
    writeImage(folder_ / "a.ppm", image);
    readImage(folder_ / "a.png");
    Texture texture = readTexture(folder_ / "a.png", true, TextureLimits{}, std::size_t{1} << 20).texture;
    EXPECT_EQ(texture.width, 4);
    EXPECT_FALSE(openImageIOLoaded());
    writeImage(folder_ / "a.exr", image);
    EXPECT_TRUE(openImageIOLoaded());
    EXPECT_EQ(readImage(folder_ / "a.exr").pixels, image.pixels);
}

// A file named .png that is not one (here a PPM) is read by its content, through OpenImageIO, not
// refused by the PNG reader. Break caught: choosing the reader by the extension.
TEST_F(ImageLibraries, AFileIsReadByItsContentNotItsName) {
    LinearImage image;
    image.width = 3;
    image.height = 2;
    image.pixels.assign(6, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
    writeImage(folder_ / "red.ppm", image);
    fs::rename(folder_ / "red.ppm", folder_ / "red.png");
    EXPECT_FALSE(isPngFile((folder_ / "red.png").string()));
    EXPECT_EQ(readImage(folder_ / "red.png").pixels, image.pixels);
}

}  // namespace
}  // namespace facet
