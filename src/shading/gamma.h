// Gamma: how a linear colour becomes an 8-bit code in an image file (the output transfer curve).
// Shared by every renderer (rasterizer, ray caster) and by the image comparisons, which measure
// differences in the codes a viewer would see.
#pragma once

#include <algorithm>
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

// An 8-bit code for a value already in [0,1] (encoded colour, or alpha), rounded to nearest, ties as
// `rounding` says.
inline std::uint8_t toByte(float unit, Rounding rounding = Rounding::HalfAwayFromZero) {
    if (!(unit > 0.0f)) return 0;  // also NaN
    if (unit >= 1.0f) return 255;
    // lrint rounds in the current mode, round-to-nearest-even unless a program changed it (none does).
    return static_cast<std::uint8_t>(rounding == Rounding::HalfToEven ? std::lrint(unit * 255.0f)
                                                                      : std::lround(unit * 255.0f));
}

// The 8-bit code of one channel value: clamped to [0, 1], encoded, rounded to nearest.
inline std::uint8_t encodeChannel(float value, ColorEncoding encoding) {
    switch (encoding.curve) {
        case TransferCurve::Srgb:
            return toByte(linearToSrgb(value), encoding.rounding);
        case TransferCurve::Power:
            // c^(1/γ) on [0, 1]; below 0 (and NaN) toByte gives 0.
            return toByte(value > 0.0f ? std::pow(std::min(value, 1.0f), 1.0f / encoding.gamma) : 0.0f,
                          encoding.rounding);
        case TransferCurve::Linear:
            return toByte(value, encoding.rounding);
    }
    return 0;
}

}  // namespace facet
