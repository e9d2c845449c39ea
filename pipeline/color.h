// Colour encoding: the framebuffer holds linear light; images store it encoded for display.
// The sRGB transfer curve is IEC 61966-2-1's piecewise function, not a plain power 2.2.
#pragma once

#include <cmath>

namespace facet {

// sRGB-encoded value in [0,1] -> linear: c/12.92 below 0.04045, ((c + 0.055)/1.055)^2.4 above.
inline float srgbToLinear(float encoded) {
    if (encoded <= 0.04045f) return encoded / 12.92f;
    return std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

// Linear value -> sRGB-encoded: 12.92·c below 0.0031308, 1.055·c^(1/2.4) − 0.055 above.
// Out-of-range input is clamped to [0,1] first, as an 8-bit image cannot hold it.
inline float linearToSrgb(float linear) {
    if (!(linear > 0.0f)) return 0.0f;  // also maps NaN to 0
    if (linear >= 1.0f) return 1.0f;
    if (linear <= 0.0031308f) return 12.92f * linear;
    return 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

}  // namespace facet
