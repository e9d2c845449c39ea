// What OpenImageIO itself reads from an 8-bit image file: the stored values, alpha unassociated. The
// image tests check Facet's writers against it, an independent decoder.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

namespace facet::testing_support {

inline std::vector<std::uint8_t> storedBytes(const std::filesystem::path& path, int* channels = nullptr) {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto input = OIIO::ImageInput::open(path.string(), &config);
    EXPECT_TRUE(input) << OIIO::geterror();
    if (!input) return {};
    const OIIO::ImageSpec& spec = input->spec();
    if (channels) *channels = spec.nchannels;
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
    EXPECT_TRUE(input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, bytes.data()));
    return bytes;
}

}  // namespace facet::testing_support
