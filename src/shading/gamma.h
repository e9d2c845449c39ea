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

struct ColorEncoding {
    TransferCurve curve = TransferCurve::Srgb;
    float gamma = 2.2f;  // Power only
    bool operator==(const ColorEncoding&) const = default;
};
inline constexpr ColorEncoding kSrgbEncoding{TransferCurve::Srgb};
inline constexpr ColorEncoding kLinearEncoding{TransferCurve::Linear};

// An 8-bit code for a value already in [0,1] (encoded colour, or alpha), rounded to nearest.
inline std::uint8_t toByte(float unit) {
    if (!(unit > 0.0f)) return 0;  // also NaN
    if (unit >= 1.0f) return 255;
    return static_cast<std::uint8_t>(std::lround(unit * 255.0f));
}

// The 8-bit code of one channel value: clamped to [0, 1], encoded, rounded to nearest.
inline std::uint8_t encodeChannel(float value, ColorEncoding encoding) {
    switch (encoding.curve) {
        case TransferCurve::Srgb:
            return toByte(linearToSrgb(value));
        case TransferCurve::Power:
            // c^(1/γ) on [0, 1]; below 0 (and NaN) toByte gives 0.
            return toByte(value > 0.0f ? std::pow(std::min(value, 1.0f), 1.0f / encoding.gamma) : 0.0f);
        case TransferCurve::Linear:
            return toByte(value);
    }
    return 0;
}

}  // namespace facet
