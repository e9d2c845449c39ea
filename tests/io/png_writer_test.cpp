// The built-in PNG writer's row filters and its per-thread buffers: rows built so that one filter
// predicts them exactly are written with that filter and decode to the codes written, and a thread's
// buffers carry nothing from one image to the next. Above each test, the one-line break it catches.
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <zlib.h>

#include <gtest/gtest.h>

#include "io/image_file.h"
#include "io/stored_bytes.h"
#include "pipeline/thread_pool.h"
#include "support/file_bytes.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using testing_support::TempFolderTest;

class PngWriter : public TempFolderTest {};

using testing_support::fileBytes;

std::uint32_t bigEndian(const std::string& bytes, std::size_t at) {
    std::uint32_t value = 0;
    for (int k = 0; k < 4; ++k)
        value = value << 8 | static_cast<std::uint8_t>(bytes[at + k]);
    return value;
}

// The filtered rows of a PNG file: its IDAT chunks joined and inflated (zlib checks the Adler-32).
std::vector<std::uint8_t> filteredRows(const fs::path& path, std::size_t expectedBytes) {
    const std::string file = fileBytes(path);
    std::string data;
    for (std::size_t at = 8; at + 12 <= file.size();) {
        const std::uint32_t length = bigEndian(file, at);
        if (file.compare(at + 4, 4, "IDAT") == 0) data += file.substr(at + 8, length);
        at += 12 + length;
    }
    std::vector<std::uint8_t> rows(expectedBytes);
    uLongf size = static_cast<uLongf>(rows.size());
    EXPECT_EQ(uncompress(rows.data(), &size, reinterpret_cast<const Bytef*>(data.data()),
                         static_cast<uLong>(data.size())),
              Z_OK);
    EXPECT_EQ(size, rows.size());
    return rows;
}

int paeth(int a, int b, int c) {  // PNG specification, 9.4
    const int p = a + b - c;
    const int pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}

// RGBA rows, every other one noise; the rows between are made so that one filter, (y / 2) mod 5,
// predicts each byte exactly from the noise above and to the left: zeros (None: Sub gives 0s as well,
// and None comes first), a constant row (Sub), the row above (Up), each byte the mean of its left and
// upper neighbours (Average), Paeth's prediction from its three after a first pixel of noise (Paeth;
// from the row above alone it would copy that row, which Up predicts as well). Bands of 64 rows start with
// an Up row (64) and a Paeth row (128).
struct FilterImage {
    static constexpr int kWidth = 37, kHeight = 150, kChannels = 4;
    std::vector<std::uint8_t> codes;
    std::vector<int> expectedFilter;  // per row; -1: noise, any filter

    FilterImage() : codes(static_cast<std::size_t>(kWidth) * kHeight * kChannels) {
        std::mt19937 random(44);
        const std::size_t rowBytes = static_cast<std::size_t>(kWidth) * kChannels;
        for (int y = 0; y < kHeight; ++y) {
            std::uint8_t* row = &codes[y * rowBytes];
            const std::uint8_t* above = y > 0 ? row - rowBytes : nullptr;
            const int filter = y % 2 == 1 ? -1 : y / 2 % 5;
            expectedFilter.push_back(filter);
            for (std::size_t i = 0; i < rowBytes; ++i) {
                const int a = i >= kChannels ? row[i - kChannels] : 0;
                const int b = above ? above[i] : 0;
                const int c = above && i >= kChannels ? above[i - kChannels] : 0;
                int value = static_cast<int>(random() % 256);
                if (filter == 0) value = 0;
                if (filter == 1 && i >= kChannels) value = a;
                if (filter == 2) value = b;
                if (filter == 3) value = (a + b) / 2;
                if (filter == 4 && i >= kChannels) value = paeth(a, b, c);
                row[i] = static_cast<std::uint8_t>(value);
            }
        }
    }
};

// Catches: a filter's formula wrong in the writer (Sub, Average or Paeth misread at the first pixel or
// the band's first row), or the choice among the five no longer libpng's least sum of |signed bytes|.
TEST_F(PngWriter, EachFilterIsChosenWhereItPredictsExactlyAndDecodes) {
    const FilterImage image;
    const ImagePixels pixels{
        FilterImage::kWidth, FilterImage::kHeight, FilterImage::kChannels, false, image.codes.data(), {}};
    const fs::path path = folder_ / "filters.png";
    ASSERT_EQ(builtInImageLibrary().write(path.string(), pixels, 9, nullptr), "");
    int channels = 0;
    EXPECT_EQ(testing_support::storedBytes(path, &channels), image.codes);
    const std::size_t rowBytes = static_cast<std::size_t>(FilterImage::kWidth) * FilterImage::kChannels;
    const std::vector<std::uint8_t> rows = filteredRows(path, (rowBytes + 1) * FilterImage::kHeight);
    int rowsChecked = 0;
    for (int y = 0; y < FilterImage::kHeight; ++y) {
        if (image.expectedFilter[y] < 0) continue;
        SCOPED_TRACE("row " + std::to_string(y));
        EXPECT_EQ(rows[y * (rowBytes + 1)], image.expectedFilter[y]);
        ++rowsChecked;
    }
    EXPECT_EQ(rowsChecked, FilterImage::kHeight / 2);
}

// Catches: a thread's reused buffers or deflate stream carrying something from one image into the
// next (a row of zeros or a stream left at another size or level), so that a file depends on what the
// thread wrote before.
TEST_F(PngWriter, AnImageGivesTheSameBytesAfterOthersOnTheSameThread) {
    const FilterImage wide;
    std::vector<std::uint8_t> narrowCodes(static_cast<std::size_t>(11) * 70 * 3);
    for (std::size_t i = 0; i < narrowCodes.size(); ++i)
        narrowCodes[i] = static_cast<std::uint8_t>(i * 7 % 251);
    const ImagePixels narrow{11, 70, 3, false, narrowCodes.data(), {}};
    const ImagePixels widePixels{
        FilterImage::kWidth, FilterImage::kHeight, FilterImage::kChannels, false, wide.codes.data(), {}};
    for (const int level : {0, 1, 6}) {
        SCOPED_TRACE("level " + std::to_string(level));
        const fs::path fresh = folder_ / ("fresh" + std::to_string(level) + ".png");
        const fs::path after = folder_ / ("after" + std::to_string(level) + ".png");
        std::string problem = "not run";
        // A thread of its own: its buffers start empty.
        std::thread([&] {
            problem = builtInImageLibrary().write(fresh.string(), narrow, level, nullptr);
        }).join();
        ASSERT_EQ(problem, "");
        ASSERT_EQ(builtInImageLibrary().write((folder_ / "before.png").string(), widePixels, 9, nullptr), "");
        ASSERT_EQ(builtInImageLibrary().write(after.string(), narrow, level, nullptr), "");
        EXPECT_EQ(fileBytes(fresh), fileBytes(after));
    }
}

}  // namespace
}  // namespace facet
