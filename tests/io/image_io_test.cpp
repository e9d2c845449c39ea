// Image files: round trips through each format (8-bit sRGB within half a code, float exact), the
// channel count each format gets, and the failure guarantees: nothing written for a bad name, no
// temporary file left behind, and an existing file untouched by a failed write.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include <unistd.h>

#include <OpenImageIO/imageio.h>

#include "base/errors.h"
#include "io/image_io.h"
#include "io/stored_bytes.h"
#include "pipeline/color.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

class ImageIoTest : public testing_support::TempFolderTest {
  protected:
    // Names of the entries in `folder` (hidden ones included, so a stray temporary file shows).
    static std::set<std::string> listing(const fs::path& folder) {
        std::set<std::string> names;
        for (const auto& entry : fs::directory_iterator(folder))
            names.insert(entry.path().filename().string());
        return names;
    }

    static std::string contents(const fs::path& path) {
        std::ifstream in(path, std::ios::binary);
        return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    }
};

// A gradient over the whole [0,1] range in each channel, with alpha varying too.
LinearImage gradient(int width = 64, int height = 4) {
    LinearImage image;
    image.width = width;
    image.height = height;
    image.pixels.resize(static_cast<std::size_t>(width) * height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float t = static_cast<float>(x) / (width - 1);
            image.at(x, y) = glm::vec4(t, 1.0f - t, t * t, 1.0f - 0.25f * y);
        }
    }
    return image;
}

LinearImage solid(glm::vec4 color, int width = 2, int height = 2) {
    LinearImage image;
    image.width = width;
    image.height = height;
    image.pixels.assign(static_cast<std::size_t>(width) * height, color);
    return image;
}

// The file's raw 8-bit values, as stored (no alpha association on read).
std::vector<std::uint8_t> rawBytes(const fs::path& path, int* channels = nullptr) {
    return testing_support::storedBytes(path, channels);
}

void writeGrayBytes(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
    auto output = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(output);
    const OIIO::ImageSpec spec(static_cast<int>(bytes.size()), 1, 1, OIIO::TypeDesc::UINT8);
    ASSERT_TRUE(output->open(path.string(), spec));
    ASSERT_TRUE(output->write_image(OIIO::TypeDesc::UINT8, bytes.data()));
    ASSERT_TRUE(output->close());
}

// ---- Round trips --------------------------------------------------------------------------------

// Rounding to the nearest code puts every encoded value within half a code of the original.
TEST_F(ImageIoTest, PngRoundTripWithinHalfACodeAfterEncoding) {
    const LinearImage image = gradient();
    const fs::path path = folder_ / "gradient.png";
    writeImage(path, image);
    const LinearImage back = readImage(path);

    ASSERT_EQ(back.width, image.width);
    ASSERT_EQ(back.height, image.height);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(linearToSrgb(back.pixels[i][c]), linearToSrgb(image.pixels[i][c]), 0.5f / 255 + 1e-6f)
                << "pixel " << i << " channel " << c;
        }
        // Alpha is stored linearly and as given (not premultiplied into the colour).
        EXPECT_NEAR(back.pixels[i].a, image.pixels[i].a, 0.5f / 255 + 1e-6f) << "pixel " << i;
    }
}

TEST_F(ImageIoTest, PngStoresSrgbCodes) {
    const fs::path path = folder_ / "half.png";
    writeImage(path, solid({0.5f, 0.0f, 1.0f, 0.5f}, 1, 1));
    int channels = 0;
    const std::vector<std::uint8_t> bytes = rawBytes(path, &channels);
    ASSERT_EQ(channels, 4);
    EXPECT_EQ(bytes[0], 188);  // sRGB(0.5) = 0.7354 → 187.5 → 188; a plain 0.5·255 would be 128
    EXPECT_EQ(bytes[1], 0);
    EXPECT_EQ(bytes[2], 255);
    EXPECT_EQ(bytes[3], 128);  // alpha is not sRGB-encoded
}

TEST_F(ImageIoTest, OutOfRangeValuesClampInEightBitFiles) {
    const fs::path path = folder_ / "clamp.png";
    writeImage(path, solid({-1.0f, 7.5f, NAN, 2.0f}, 1, 1));
    const std::vector<std::uint8_t> bytes = rawBytes(path);
    EXPECT_EQ(bytes, (std::vector<std::uint8_t>{0, 255, 0, 255}));
}

TEST_F(ImageIoTest, ExrKeepsFloatValuesExactly) {
    LinearImage image = solid({0.5f, 0.5f, 0.5f, 1.0f}, 3, 2);
    image.at(0, 0) = {3.75f, -0.25f, 1e6f, 0.125f};
    image.at(2, 1) = {1.0f / 3.0f, 0.0f, 65504.5f, 1.0f};
    const fs::path path = folder_ / "values.exr";
    writeImage(path, image);

    auto input = OIIO::ImageInput::open(path.string());
    ASSERT_TRUE(input);
    EXPECT_EQ(input->spec().nchannels, 4);
    EXPECT_EQ(input->spec().format, OIIO::TypeDesc::FLOAT);
    input.reset();

    const LinearImage back = readImage(path);
    ASSERT_EQ(back.pixels.size(), image.pixels.size());
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
        EXPECT_EQ(back.pixels[i], image.pixels[i]) << i;
}

// The same image gives the same bytes: no file carries the time it was written (OpenEXR's writer
// and TIFF writers stamp the current time unless told a date; Facet gives an empty one).
TEST_F(ImageIoTest, FilesCarryNoTimeOfWriting) {
    for (const char* name : {"stamp.exr", "stamp.png", "stamp.tif", "stamp.jpg", "stamp.ppm"}) {
        const fs::path path = folder_ / name;
        writeImage(path, gradient());
        auto input = OIIO::ImageInput::open(path.string());
        ASSERT_TRUE(input) << name;
        EXPECT_EQ(input->spec().get_string_attribute("DateTime"), "") << name;
    }
}

TEST_F(ImageIoTest, PpmHasThreeChannelsAndReadsBackOpaque) {
    const fs::path path = folder_ / "image.ppm";
    writeImage(path, solid({0.5f, 0.25f, 1.0f, 0.3f}));
    int channels = 0;
    const std::vector<std::uint8_t> bytes = rawBytes(path, &channels);
    EXPECT_EQ(channels, 3);
    EXPECT_EQ(bytes[0], 188);
    const LinearImage back = readImage(path);
    EXPECT_EQ(back.pixels[0].a, 1.0f);
    EXPECT_NEAR(back.pixels[0].r, 0.5f, 0.003f);
}

TEST_F(ImageIoTest, JpegHasThreeChannels) {
    const fs::path path = folder_ / "image.JPG";  // extensions are case-insensitive
    writeImage(path, solid({0.5f, 0.5f, 0.5f, 1.0f}, 16, 16));
    int channels = 0;
    const std::vector<std::uint8_t> bytes = rawBytes(path, &channels);
    EXPECT_EQ(channels, 3);
    EXPECT_NEAR(bytes[0], 188, 2);  // lossy, but a flat grey survives closely
    EXPECT_EQ(readImage(path).pixels[0].a, 1.0f);
}

TEST_F(ImageIoTest, TiffIsEightBitRgba) {
    const fs::path path = folder_ / "image.tif";
    writeImage(path, solid({0.5f, 0.0f, 1.0f, 0.5f}));
    auto input = OIIO::ImageInput::open(path.string());
    ASSERT_TRUE(input);
    EXPECT_EQ(input->spec().nchannels, 4);
    EXPECT_EQ(input->spec().format, OIIO::TypeDesc::UINT8);
    input.reset();
    EXPECT_EQ(rawBytes(path)[0], 188);
}

TEST_F(ImageIoTest, OtherEightBitFormatsRoundTrip) {
    const LinearImage image = gradient(16, 2);
    for (const char* name : {"image.bmp", "image.tga", "image.jpeg", "image.tiff"}) {
        SCOPED_TRACE(name);
        const fs::path path = folder_ / name;
        writeImage(path, image);
        const LinearImage back = readImage(path);
        ASSERT_EQ(back.width, 16);
        ASSERT_EQ(back.height, 2);
        const bool lossy = fs::path(name).extension() == ".jpeg";
        EXPECT_NEAR(linearToSrgb(back.at(8, 1).r), linearToSrgb(image.at(8, 1).r),
                    lossy ? 0.05f : 0.5f / 255 + 1e-6f);
    }
}

TEST_F(ImageIoTest, HdrKeepsBrightValuesAndDropsNegatives) {
    const fs::path path = folder_ / "image.hdr";
    writeImage(path, solid({3.75f, -0.25f, 0.5f, 1.0f}));
    const LinearImage back = readImage(path);
    EXPECT_NEAR(back.pixels[0].r, 3.75f, 0.02f);
    EXPECT_EQ(back.pixels[0].g, 0.0f);
    EXPECT_NEAR(back.pixels[0].b, 0.5f, 0.01f);
}

// Every 8-bit code decodes to a linear value that encodes back to the same code, so reading an
// 8-bit image and writing it again changes nothing.
TEST_F(ImageIoTest, AllByteValuesSurviveDecodeEncode) {
    for (int code = 0; code < 256; ++code) {
        const float linear = srgbToLinear(code / 255.0f);
        EXPECT_EQ(std::lround(linearToSrgb(linear) * 255.0f), code) << code;
    }

    std::vector<std::uint8_t> codes(256);
    for (int code = 0; code < 256; ++code)
        codes[code] = static_cast<std::uint8_t>(code);
    const fs::path source = folder_ / "codes.png";
    writeGrayBytes(source, codes);

    const LinearImage image = readImage(source);  // gray → rgb, no alpha → 1
    ASSERT_EQ(image.width, 256);
    for (int code = 0; code < 256; ++code) {
        const glm::vec4& p = image.at(code, 0);
        EXPECT_EQ(p.r, p.g);
        EXPECT_EQ(p.r, p.b);
        EXPECT_EQ(p.a, 1.0f);
    }
    const fs::path copy = folder_ / "copy.png";
    writeImage(copy, image);
    const std::vector<std::uint8_t> bytes = rawBytes(copy);
    ASSERT_EQ(bytes.size(), 256u * 4);
    for (int code = 0; code < 256; ++code) {
        EXPECT_EQ(bytes[code * 4 + 0], code);
        EXPECT_EQ(bytes[code * 4 + 1], code);
        EXPECT_EQ(bytes[code * 4 + 2], code);
        EXPECT_EQ(bytes[code * 4 + 3], 255);
    }
}

TEST_F(ImageIoTest, OverwritesAnExistingFile) {
    const fs::path path = folder_ / "image.png";
    writeImage(path, solid({1, 1, 1, 1}));
    writeImage(path, solid({0, 0, 0, 1}));
    EXPECT_EQ(readImage(path).pixels[0], glm::vec4(0, 0, 0, 1));
    EXPECT_EQ(listing(folder_), (std::set<std::string>{"image.png"}));
}

// Choice: a missing destination folder is created ("-o renders/x.png" should just work).
TEST_F(ImageIoTest, CreatesMissingFolders) {
    const fs::path path = folder_ / "renders/today/image.png";
    writeImage(path, solid({0.2f, 0.4f, 0.6f, 1}));
    EXPECT_TRUE(fs::exists(path));
    EXPECT_EQ(listing(path.parent_path()), (std::set<std::string>{"image.png"}));
}

// ---- Failures -----------------------------------------------------------------------------------

TEST_F(ImageIoTest, UnknownExtensionThrowsAndWritesNothing) {
    const fs::path path = folder_ / "new/x.bmpx";
    try {
        writeImage(path, solid({1, 0, 0, 1}));
        FAIL() << "no error";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(path.string() + ": unknown image format \".bmpx\" (use .png", 0), 0u)
            << message;
    }
    EXPECT_EQ(listing(folder_), std::set<std::string>{});  // not even the folder "new"
}

// A float file would keep an infinite or NaN value (an 8-bit one clamps it): the writer refuses it,
// names the output and the pixel, and leaves an existing file as it was.
TEST_F(ImageIoTest, NonFiniteValueIsNeverWrittenToAFloatFile) {
    const float infinity = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (const auto& [name, bad, what] :
         {std::tuple{"inf.exr", infinity, "infinity"}, std::tuple{"nan.exr", nan, "NaN"},
          std::tuple{"inf.hdr", infinity, "infinity"}, std::tuple{"alpha.exr", -infinity, "infinity"}}) {
        SCOPED_TRACE(name);
        const fs::path path = folder_ / name;
        writeImage(path, solid({0.5f, 0.5f, 0.5f, 1.0f}, 8, 2));
        const std::string before = contents(path);
        LinearImage image = solid({0.5f, 0.5f, 0.5f, 1.0f}, 8, 2);
        image.at(7, 1)[std::string_view(name) == "alpha.exr" ? 3 : 0] = bad;
        try {
            writeImage(path, image);
            FAIL() << "no error";
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()), path.string() +
                                                 ": the image holds a value that is not finite (" + what +
                                                 ") at pixel (7, 1); nothing was written");
        }
        EXPECT_EQ(contents(path), before);
    }
    EXPECT_EQ(listing(folder_), (std::set<std::string>{"inf.exr", "nan.exr", "inf.hdr", "alpha.exr"}));
}

TEST_F(ImageIoTest, MissingExtensionThrows) {
    const fs::path path = folder_ / "image";
    EXPECT_THROW(writeImage(path, solid({1, 0, 0, 1})), InputError);
    EXPECT_FALSE(fs::exists(path));
}

TEST_F(ImageIoTest, InconsistentImageThrows) {
    LinearImage image = solid({1, 0, 0, 1}, 4, 4);
    image.pixels.pop_back();
    EXPECT_THROW(writeImage(folder_ / "a.png", image), InputError);
    EXPECT_THROW(writeImage(folder_ / "b.png", LinearImage{}), InputError);
    EXPECT_EQ(listing(folder_), std::set<std::string>{});
}

// libjpeg would end the whole process on a side above 65500 pixels; the writer refuses first.
TEST_F(ImageIoTest, JpegTooWideIsAnErrorNotAnExit) {
    const fs::path path = folder_ / "wide.jpg";
    try {
        writeImage(path, solid({1, 1, 1, 1}, 65501, 1));
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("at most 65500 per side"), std::string::npos) << e.what();
    }
    EXPECT_EQ(listing(folder_), std::set<std::string>{});
}

// A write that fails inside OpenImageIO (here: the temporary file's name is taken by a folder) leaves
// the existing image byte for byte as it was and no temporary file.
TEST_F(ImageIoTest, FailedWriteKeepsExistingFileAndLeavesNoTemporary) {
    const fs::path path = folder_ / "keep.png";
    writeImage(path, solid({0.25f, 0.5f, 0.75f, 1}));
    const std::string before = contents(path);

    const fs::path blocker = folder_ / (".keep.tmp-" + std::to_string(::getpid()) + ".png");
    fs::create_directory(blocker);
    fs::create_directory(blocker / "child");  // not empty, so nothing can remove it by accident
    try {
        writeImage(path, solid({1, 0, 0, 1}));
        FAIL() << "no error";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(path.string() + ": cannot write", 0), 0u) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    EXPECT_EQ(contents(path), before);
    EXPECT_EQ(listing(folder_), (std::set<std::string>{"keep.png", blocker.filename().string()}));
    EXPECT_TRUE(fs::is_directory(blocker / "child"));
}

TEST_F(ImageIoTest, FolderInTheWayIsAnError) {
    const fs::path file = folder_ / "file.txt";
    std::ofstream(file) << "not a folder";
    try {
        writeImage(file / "image.png", solid({1, 0, 0, 1}));
        FAIL() << "no error";
    } catch (const InputError& e) {
        // The user's path and the system's reason, found before anything is written.
        EXPECT_EQ(std::string(e.what()), (file / "image.png").string() + ": cannot write: Not a directory");
    }
    fs::create_directory(folder_ / "dir.png");
    EXPECT_THROW(writeImage(folder_ / "dir.png", solid({1, 0, 0, 1})), InputError);
    EXPECT_EQ(listing(folder_), (std::set<std::string>{"file.txt", "dir.png"}));
    EXPECT_EQ(contents(file), "not a folder");
}

// "out/.png" is, to the file system, a hidden file without an extension: say what is missing.
TEST_F(ImageIoTest, ExtensionWithoutANameIsAnError) {
    try {
        checkImageDestination(folder_ / ".png", 4, 4);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), (folder_ / ".png").string() +
                                             ": has no file name before the extension (like " +
                                             (folder_ / "image.png").string() + ")");
    }
}

TEST_F(ImageIoTest, ReadingAMissingFileNamesIt) {
    const fs::path path = folder_ / "missing.png";
    try {
        readImage(path);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), path.string() + ": image file not found");
    }
}

TEST_F(ImageIoTest, ReadingAFileThatIsNotAnImageFails) {
    const fs::path path = folder_ / "text.png";
    std::ofstream(path) << "this is not a PNG";
    try {
        readImage(path);
        FAIL() << "no error";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(path.string() + ": cannot read image: ", 0), 0u) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

// ---- Textures ------------------------------------------------------------------------------------

// PNG's chunk checksum (CRC-32, ISO 3309), to write a header by hand.
std::uint32_t pngCrc(const std::string& bytes) {
    std::uint32_t crc = 0xFFFFFFFFu;
    for (unsigned char byte : bytes) {
        crc ^= byte;
        for (int bit = 0; bit < 8; ++bit)
            crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

// A small valid PNG whose header then declares width × height: a file of a few hundred bytes that
// would decode to gigabytes.
void writePngDeclaring(const fs::path& path, std::uint32_t width, std::uint32_t height) {
    writeImage(path, solid(glm::vec4(0.5f, 0.5f, 0.5f, 1.0f), 4, 4));
    std::string bytes;
    {
        std::ifstream in(path, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    ASSERT_EQ(bytes.substr(12, 4), "IHDR");
    const auto put32 = [&](std::size_t at, std::uint32_t value) {
        for (int k = 0; k < 4; ++k)
            bytes[at + k] = static_cast<char>((value >> (24 - 8 * k)) & 0xFF);
    };
    put32(16, width);
    put32(20, height);
    put32(29, pngCrc(bytes.substr(12, 17)));  // over the chunk type and its 13 bytes of data
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

TEST_F(ImageIoTest, EightBitTextureKeepsFourBytesATexel) {
    const fs::path path = folder_ / "t.png";
    writeImage(path, gradient(64, 4));
    const TextureRead read = readTexture(path, true, TextureLimits{}, TextureLimits{}.maxTotalBytes);
    ASSERT_TRUE(read.problem.empty()) << read.problem;
    EXPECT_EQ(read.texture.width, 64);
    EXPECT_EQ(read.texture.height, 4);
    EXPECT_TRUE(read.texture.texels.empty());
    EXPECT_EQ(read.texture.codes.size(), 64u * 4u);
    EXPECT_EQ(read.texture.bytes(), 64u * 4u * 4u);
}

// The 8-bit texture's texels are exactly the values readImage gives (sRGB-decoded colour, alpha as
// stored); without decoding, the codes/255 that re-encoding readImage's values gives.
TEST_F(ImageIoTest, EightBitTextureTexelsEqualTheImageValues) {
    const fs::path path = folder_ / "t.png";
    writeImage(path, gradient(256, 4));
    const LinearImage image = readImage(path);
    for (bool decode : {true, false}) {
        const TextureRead read = readTexture(path, decode, TextureLimits{}, TextureLimits{}.maxTotalBytes);
        ASSERT_FALSE(read.texture.codes.empty()) << read.problem;
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) {
                glm::vec4 expected = image.at(x, y);
                if (!decode)
                    expected = glm::vec4(linearToSrgb(expected.r), linearToSrgb(expected.g),
                                         linearToSrgb(expected.b), expected.a);
                ASSERT_EQ(read.texture.texel(x, y), expected) << x << "," << y << " decode " << decode;
            }
    }
}

// Grey files fill R, G and B; a file without alpha is opaque, exactly 1.
TEST_F(ImageIoTest, GreyTextureWithoutAlphaIsOpaqueGrey) {
    const fs::path path = folder_ / "grey.png";
    writeGrayBytes(path, {0, 128, 255});
    const TextureRead read = readTexture(path, true, TextureLimits{}, TextureLimits{}.maxTotalBytes);
    ASSERT_EQ(read.texture.codes.size(), 3u) << read.problem;
    const glm::vec4 middle = read.texture.texel(1, 0);
    EXPECT_FLOAT_EQ(middle.r, srgbToLinear(128.0f / 255.0f));
    EXPECT_EQ(middle.g, middle.r);
    EXPECT_EQ(middle.b, middle.r);
    for (int x = 0; x < 3; ++x)
        EXPECT_EQ(read.texture.texel(x, 0).a, 1.0f);
}

// Float files stay float and linear, the values unchanged.
TEST_F(ImageIoTest, FloatTextureKeepsItsValues) {
    const fs::path path = folder_ / "t.exr";
    const LinearImage image = gradient(16, 3);
    writeImage(path, image);
    const TextureRead read = readTexture(path, true, TextureLimits{}, TextureLimits{}.maxTotalBytes);
    ASSERT_TRUE(read.texture.codes.empty()) << read.problem;
    ASSERT_EQ(read.texture.texels.size(), image.pixels.size());
    EXPECT_EQ(read.texture.texels, image.pixels);
}

// A few hundred bytes declaring 30000 × 30000 pixels are refused from the header, at once, with the
// file and the limit named.
TEST_F(ImageIoTest, TextureDeclaringAHugeSizeIsRefusedBeforeDecoding) {
    const fs::path path = folder_ / "huge.png";
    writePngDeclaring(path, 30000, 30000);
    try {
        readTexture(path, true, TextureLimits{}, TextureLimits{}.maxTotalBytes);
        FAIL() << "no error";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << message;
        EXPECT_NE(message.find("30000x30000"), std::string::npos) << message;
        EXPECT_NE(message.find("16384"), std::string::npos) << message;
    }
}

// Texels beyond the memory left for a render's textures are refused, naming the limit.
TEST_F(ImageIoTest, TextureBeyondTheMemoryLeftIsRefused) {
    const fs::path path = folder_ / "t.png";
    writeImage(path, gradient(64, 64));  // 16 KiB as 8-bit codes
    TextureLimits limits;
    limits.maxTotalBytes = 20000;
    EXPECT_FALSE(readTexture(path, true, limits, 20000).texture.empty());
    try {
        readTexture(path, true, limits, 20000 - 16384 + 1);
        FAIL() << "no error";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << message;
        EXPECT_NE(message.find("at most"), std::string::npos) << message;
    }
}

// Unreadable files are a problem to report, not an error, in one line; a truncated PNG included
// (libpng's own message is captured, not printed).
TEST_F(ImageIoTest, UnreadableTexturesReportAProblem) {
    const fs::path text = folder_ / "text.png";
    std::ofstream(text) << "this is not a PNG";
    const fs::path truncated = folder_ / "truncated.png";
    writeImage(truncated, gradient(256, 256));
    fs::resize_file(truncated, fs::file_size(truncated) / 2);
    for (const fs::path& path : {text, truncated, folder_ / "missing.png"}) {
        const TextureRead read = readTexture(path, true, TextureLimits{}, TextureLimits{}.maxTotalBytes);
        EXPECT_TRUE(read.texture.empty()) << path;
        EXPECT_FALSE(read.problem.empty()) << path;
        EXPECT_EQ(read.problem.find('\n'), std::string::npos) << read.problem;
    }
}

}  // namespace
}  // namespace facet
