// Gamma: how a linear colour becomes an 8-bit code in an image file (the output transfer curve).
// Shared by every renderer (rasterizer, ray caster) and by the image comparisons, which measure
// differences in the codes a viewer would see.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "pipeline/color.h"
#include "pipeline/names.h"

namespace facet {

// How 8-bit files encode the colour buffer's values (its transfer function, "gamma").
enum class TransferCurve {
    Srgb,    // the exact sRGB curve (facet::linearToSrgb, pipeline/color.h), IEC 61966-2-1: the default
    Power,   // a plain power: code = round(255·c^(1/γ)), the "gamma 2.2" of older pipelines
    Linear,  // none: code = round(255·c), as OpenGL 1.x writes its colours to an 8-bit framebuffer
};
inline constexpr EnumName<TransferCurve> kTransferCurveNames[] = {
    {TransferCurve::Srgb, "srgb"}, {TransferCurve::Power, "power"}, {TransferCurve::Linear, "linear"}};
constexpr std::span<const EnumName<TransferCurve>> enumNames(TransferCurve) {
    return kTransferCurveNames;
}

// How 255·c becomes a whole code where it falls exactly halfway between two.
enum class Rounding : std::uint8_t {
    HalfAwayFromZero,  // std::lround: k + ½ → k + 1 (Facet's)
    HalfToEven,        // k + ½ → the even one of k, k + 1, as Mesa's float → unorm8 (_mesa_lroundevenf)
};

struct ColorEncoding {
    TransferCurve curve = TransferCurve::Srgb;
    float gamma = 2.2f;  // Power only
    Rounding rounding = Rounding::HalfAwayFromZero;
    bool operator==(const ColorEncoding&) const = default;
};
inline constexpr ColorEncoding kSrgbEncoding{TransferCurve::Srgb};
inline constexpr ColorEncoding kLinearEncoding{TransferCurve::Linear};
// The gl preset's: unencoded, rounded as Mesa rounds a float colour into an 8-bit framebuffer.
inline constexpr ColorEncoding kGlEncoding{TransferCurve::Linear, 2.2f, Rounding::HalfToEven};
// The lecture preset's: c^(1/2.2), the pure power of lighting-deck-C.txt's gamma correction.
inline constexpr ColorEncoding kLectureEncoding{TransferCurve::Power, 2.2f};

// An 8-bit code for a value already in [0,1] (encoded colour, or alpha), rounded to nearest, ties as
// `rounding` says.
inline std::uint8_t toByte(float unit, Rounding rounding = Rounding::HalfAwayFromZero) {
    if (!(unit > 0.0f)) return 0;  // also NaN
    if (unit >= 1.0f) return 255;
    // lrint rounds in the current mode, round-to-nearest-even unless a program changed it (none does).
    return static_cast<std::uint8_t>(rounding == Rounding::HalfToEven ? std::lrint(unit * 255.0f)
                                                                      : std::lround(unit * 255.0f));
}

// The encoded value c' of one channel, before toByte rounds 255·c' (the step mode's encoding screen
// shows it): sRGB's curve, c^(1/γ) of the value clamped to at most 1, or the value itself.
inline float encodedUnit(float value, ColorEncoding encoding) {
    switch (encoding.curve) {
        case TransferCurve::Srgb:
            return linearToSrgb(value);
        case TransferCurve::Power:
            // c^(1/γ) on [0, 1]; below 0 (and NaN) toByte gives 0.
            return value > 0.0f ? std::pow(std::min(value, 1.0f), 1.0f / encoding.gamma) : 0.0f;
        case TransferCurve::Linear:
            return value;
    }
    return 0.0f;
}

// The 8-bit code of one channel value: clamped to [0, 1], encoded, rounded to nearest.
inline std::uint8_t encodeChannel(float value, ColorEncoding encoding) {
    return toByte(encodedUnit(value, encoding), encoding.rounding);
}

// encodeChannel through tables, for whole images: the same code for every float, without a pow per
// channel. Built once per encoding from encodeChannel itself: firstValueOf[k] is the smallest float that
// encodes to k or above (found by bisection over the floats, as the code only rises with the value),
// and each of the 4064 buckets of floats in (0, 1) sharing their top 14 bits (the exponent and 5
// mantissa bits: 32 buckets an octave) starts from the code of its lowest float. A value's code is then
// its bucket's, stepped up past the thresholds inside the bucket — at most 4 steps for sRGB.
class ChannelEncoder {
  public:
    explicit ChannelEncoder(ColorEncoding encoding) {
        firstValueOf[0] = 0.0f;
        for (int code = 1; code < 256; ++code) {
            // Bisection over the bit patterns of positive floats, which order as the floats do.
            std::uint32_t below = 0, above = kOneBits;  // encode(below) < code <= encode(above)
            while (above - below > 1) {
                const std::uint32_t middle = below + (above - below) / 2;
                (encodeChannel(std::bit_cast<float>(middle), encoding) >= code ? above : below) = middle;
            }
            firstValueOf[code] = std::bit_cast<float>(above);
        }
        int code = 0;
        for (std::uint32_t bucket = 0; bucket < kBuckets; ++bucket) {
            const float lowest = std::bit_cast<float>(bucket << kBucketShift);
            while (code < 255 && lowest >= firstValueOf[code + 1])
                ++code;
            bucketCode[bucket] = static_cast<std::uint8_t>(code);
        }
    }

    std::uint8_t operator()(float value) const {
        if (!(value > 0.0f)) return 0;  // also NaN, as encodeChannel
        if (value >= 1.0f) return 255;
        int code = bucketCode[std::bit_cast<std::uint32_t>(value) >> kBucketShift];
        while (code < 255 && value >= firstValueOf[code + 1])
            ++code;
        return static_cast<std::uint8_t>(code);
    }

  private:
    static constexpr std::uint32_t kOneBits = 0x3F800000u;  // 1.0f
    static constexpr int kBucketShift = 18;
    static constexpr std::uint32_t kBuckets = kOneBits >> kBucketShift;
    std::array<float, 256> firstValueOf{};
    std::array<std::uint8_t, kBuckets> bucketCode{};
};

}  // namespace facet
