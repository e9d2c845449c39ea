// Where the rasterizer samples a pixel: one sample, at the pixel's centre (x + ½, y + ½) in window
// coordinates, as OpenGL and Direct3D place the single sample of a pixel. Coverage (rasterize.h),
// the bounding box of setup (triangle_setup.cpp), binning (bin.cpp) and the barycentrics of the back
// end (interpolate.h) all take their sample points from here, so multisampling adds its sample
// positions in this one place.
#pragma once

#include <cstdint>
#include <span>

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

// ---- The standard sample positions of multisampling ----------------------------------------------

// A sample's offset from the pixel's centre in sixteenths of a pixel (x right, y down, as window
// coordinates run). Every offset is a multiple of 1/16 px, so it is exact in the rasterizer's fixed
// point at 4 or more sub-pixel bits (the default is 8).
struct SampleOffset {
    int x = 0;
    int y = 0;
};
inline constexpr int kSampleOffsetUnitsPerPixel = 16;

// The standard sample locations of Direct3D 11 (D3D11_STANDARD_MULTISAMPLE_PATTERN) and Vulkan (the
// specification's "Standard sample locations" table, used when standardSampleLocations is true),
// which are the same: there given as (x, y) in [0, 1)² from the pixel's top-left corner in units of
// 1/16, here minus the centre (8, 8). Checked against the WebGPU conformance tests' table
// (gpuweb/cts, its multisample test data). In sample order: sample i of Vulkan is entry i.
// The positions lie in [−8, 7]/16: the 16-sample pattern has samples on the pixel's left and top
// edges (−8, 0) and (−7, −8), which belong to the pixel as its half-open square [−½, ½)² does.
inline constexpr SampleOffset kStandardSamples1[] = {{0, 0}};
inline constexpr SampleOffset kStandardSamples2[] = {{4, 4}, {-4, -4}};
// The rotated grid: four samples on a grid turned so that no two share a row or a column.
inline constexpr SampleOffset kStandardSamples4[] = {{-2, -6}, {6, -2}, {-6, 2}, {2, 6}};
inline constexpr SampleOffset kStandardSamples8[] = {{1, -3}, {-1, 3},  {5, 1}, {-3, -5},
                                                     {-5, 5}, {-7, -1}, {3, 7}, {7, -7}};
inline constexpr SampleOffset kStandardSamples16[] = {{1, 1},  {-1, -3}, {-3, 2}, {4, -1}, {-5, -2}, {2, 5},
                                                      {5, 3},  {3, -5},  {-2, 6}, {0, -7}, {-4, -6}, {-6, 4},
                                                      {-8, 0}, {7, -4},  {6, 7},  {-7, -8}};

// The standard pattern of `count` samples (1, 2, 4, 8 or 16); empty for any other count.
constexpr std::span<const SampleOffset> standardSamplePositions(int count) {
    switch (count) {
        case 1:
            return kStandardSamples1;
        case 2:
            return kStandardSamples2;
        case 4:
            return kStandardSamples4;
        case 8:
            return kStandardSamples8;
        case 16:
            return kStandardSamples16;
        default:
            return {};
    }
}

// A sample's offset in fixed-point units (kFixedOne / 16 per unit: exact, kFixedFractionBits ≥ 4; the
// vertices' own sub-pixel precision, RasterState::subpixelBits, snaps only the vertices, so the
// samples stay at their standard positions at any setting).
static_assert(kFixedOne % kSampleOffsetUnitsPerPixel == 0, "sample offsets must be exact in fixed point");
inline constexpr std::int64_t sampleOffsetFixed(int units) {
    return std::int64_t{units} * (kFixedOne / kSampleOffsetUnitsPerPixel);
}

// How far from its pixel's centre a draw's sample may lie, in fixed-point units, along x or y: 0 for
// one sample (the centre), half a pixel for the multisample patterns (within [−8, 7]/16).
inline constexpr std::int64_t sampleReachFixed(int samples) {
    return samples > 1 ? kFixedOne / 2 : 0;
}

// The inverse of sampleCoordinate: the first pixel whose sample lies at or after the fixed-point
// coordinate c, ⌈(c − ½)/one⌉, and the last pixel whose sample lies at or before it, ⌊(c − ½)/one⌋.
// kFixedOne is 2^kFixedFractionBits, so the divisions are shifts: an arithmetic shift right rounds
// towards −∞ (C++20), ⌈a/2^k⌉ = −⌊−a/2^k⌋ (setup asks four times per triangle; a division and its
// rounding fix-up cost several times as many instructions).
static_assert(kFixedOne == std::int64_t{1} << kFixedFractionBits);
inline constexpr std::int64_t firstPixelSampledFrom(std::int64_t c) {
    return -((kSampleOffsetFixed - c) >> kFixedFractionBits);
}
inline constexpr std::int64_t lastPixelSampledUpTo(std::int64_t c) {
    return (c - kSampleOffsetFixed) >> kFixedFractionBits;
}

}  // namespace facet
