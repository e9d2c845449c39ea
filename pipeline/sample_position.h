// Where the rasterizer samples a pixel: one sample, at the pixel's centre (x + ½, y + ½) in window
// coordinates, as OpenGL and Direct3D place the single sample of a pixel. Coverage (rasterize.h),
// the bounding box of setup (triangle_setup.cpp), binning (bin.cpp) and the barycentrics of the back
// end (interpolate.h) all take their sample points from here, so multisampling adds its sample
// positions in this one place.
#pragma once

#include <cstdint>

#include "types.h"

namespace facet {

// The sample's offset from the pixel's top-left corner, in fixed-point units (kFixedOne is one pixel).
inline constexpr std::int64_t kSampleOffsetFixed = kFixedOne / 2;

// A sample point in fixed-point window coordinates (kFixedFractionBits fraction bits, y down).
struct SamplePoint {
    std::int64_t x = 0;
    std::int64_t y = 0;
};

// The fixed-point coordinate of the sample of pixel column (or row) `pixel`: pixel·one + ½.
inline constexpr std::int64_t sampleCoordinate(int pixel) {
    return std::int64_t{pixel} * kFixedOne + kSampleOffsetFixed;
}

inline constexpr SamplePoint samplePosition(int x, int y) {
    return {sampleCoordinate(x), sampleCoordinate(y)};
}

namespace detail {
// Integer division rounding towards −∞ and towards +∞ (C++ rounds towards zero).
inline constexpr std::int64_t floorDiv(std::int64_t a, std::int64_t b) {
    std::int64_t q = a / b;
    if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
    return q;
}
inline constexpr std::int64_t ceilDiv(std::int64_t a, std::int64_t b) {
    return -floorDiv(-a, b);
}
}  // namespace detail

// The inverse of sampleCoordinate: the first pixel whose sample lies at or after the fixed-point
// coordinate c, ⌈(c − ½)/one⌉, and the last pixel whose sample lies at or before it, ⌊(c − ½)/one⌋.
inline constexpr std::int64_t firstPixelSampledFrom(std::int64_t c) {
    return detail::ceilDiv(c - kSampleOffsetFixed, kFixedOne);
}
inline constexpr std::int64_t lastPixelSampledUpTo(std::int64_t c) {
    return detail::floorDiv(c - kSampleOffsetFixed, kFixedOne);
}

}  // namespace facet
