// A float's bits, for the shader tests that require the same bits, not merely a close value.
#pragma once

#include <bit>
#include <cstdint>

namespace facet::testing_shaders {

inline std::uint32_t bits(float v) {
    return std::bit_cast<std::uint32_t>(v);
}

}  // namespace facet::testing_shaders
