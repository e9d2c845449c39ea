// Output merger: combines the fragment's colour (source) with the framebuffer's (destination).
// In: source and destination RGBA, linear. Out: the new framebuffer RGBA.
#pragma once

#include <algorithm>
#include <cmath>

#include <immintrin.h>  // F16C's half conversion

#include "glsl.h"
#include "state.h"

namespace facet {

// Written once for float (the framebuffer's vec4) and double (the reference renderer's dvec4). Always
// inlined: it runs once per written fragment with the draw's mode, which the branch predictor learns;
// called out of line, it cost an opaque draw about 15 instructions per fragment.
template <class T, glm::qualifier Q>
[[gnu::always_inline]] inline glm::vec<4, T, Q> blend(BlendMode mode, const glm::vec<4, T, Q>& source,
                                                      const glm::vec<4, T, Q>& destination) {
    using Vec3 = glm::vec<3, T, Q>;
    using Vec4 = glm::vec<4, T, Q>;
    const T one(1);
    switch (mode) {
        case BlendMode::Replace:
            return source;
        case BlendMode::Additive:
            return source + destination;
        case BlendMode::Over: {
            // Porter–Duff over with straight alpha: c = α_s·c_s + (1 − α_s)·c_d.
            const T a = source.a;
            return Vec4(a * Vec3(source) + (one - a) * Vec3(destination), a + (one - a) * destination.a);
        }
        case BlendMode::OverGL: {
            // OpenGL's glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA): the same factors on alpha,
            // α = α_s·α_s + (1 − α_s)·α_d.
            const T a = source.a;
            return Vec4(a * Vec3(source) + (one - a) * Vec3(destination), a * a + (one - a) * destination.a);
        }
        case BlendMode::PremultipliedOver: {
            // The same operator on premultiplied colour: c = c_s + (1 − α_s)·c_d.
            const T a = source.a;
            return Vec4(Vec3(source) + (one - a) * Vec3(destination), a + (one - a) * destination.a);
        }
        case BlendMode::Multiply:
            return Vec4(Vec3(source) * Vec3(destination), destination.a);
    }
    return source;
}

// x as IEEE binary16 stores it: rounded to 11 significant bits, to nearest even (the step is
// 2^(e − 10) for 2^e ≤ |x| < 2^(e+1), and 2^-24 among the subnormals below 2^-14); beyond the largest
// half, 65504, clamped to ±65504 instead of overflowing to infinity, so no Inf reaches an image.
inline float roundToHalf(float x) {
    int exponent = 0;
    std::frexp(x, &exponent);  // |x| = m·2^exponent, m in [0.5, 1): the leading bit is 2^(exponent − 1)
    const int step = std::max(exponent - 1 - 10, -24);
    const float rounded = std::ldexp(std::nearbyint(std::ldexp(x, -step)), step);
    constexpr float kLargestHalf = 65504.0f;
    return std::clamp(rounded, -kLargestHalf, kLargestHalf);
}

// roundToHalf of each channel through F16C at once (round to nearest even; 16 times faster), clamped to
// ±65504 first so that none overflows to Inf — the value is the second operand of max and min, which
// return it when it is NaN, so NaN stays NaN. Compiled for F16C wherever it is included, so that a test
// can check it against roundToHalf on a CPU with F16C whatever the build's level; roundToColorBuffer
// calls it only in code compiled for F16C (the AVX2 and AVX-512 copies of the frame's code).
[[gnu::target("f16c")]] inline vec4 roundToHalfF16c(vec4 c) {
    const __m128 largest = _mm_set1_ps(65504.0f);
    __m128 v = _mm_setr_ps(c.r, c.g, c.b, c.a);
    v = _mm_min_ps(largest, _mm_max_ps(_mm_xor_ps(largest, _mm_set1_ps(-0.0f)), v));
    v = _mm_cvtph_ps(_mm_cvtps_ph(v, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC));
    alignas(16) float out[4];
    _mm_store_ps(out, v);
    return vec4(out[0], out[1], out[2], out[3]);
}

// c as an 8-bit unsigned normalised channel stores it: round(clamp(c, 0, 1)·255)/255 (OpenGL's float →
// unorm conversion, 4.6 §2.3.5.2). The value is linear light: 8-bit linear storage is what bands.
inline float roundToUnorm8(float c) {
    return std::round(std::clamp(c, 0.0f, 1.0f) * 255.0f) / 255.0f;
}

// A colour as the colour buffer of format kFormat keeps it, applied after every write (clear, blend,
// resolve): the buffer stays float, its values are those of the chosen format. Float: c itself.
template <ColorBufferFormat kFormat>
vec4 roundToColorBuffer(vec4 c) {
    if constexpr (kFormat == ColorBufferFormat::Half) {
#if defined(__F16C__)
        return roundToHalfF16c(c);
#else
        return vec4(roundToHalf(c.r), roundToHalf(c.g), roundToHalf(c.b), roundToHalf(c.a));
#endif
    } else if constexpr (kFormat == ColorBufferFormat::Unorm8)
        return vec4(roundToUnorm8(c.r), roundToUnorm8(c.g), roundToUnorm8(c.b), roundToUnorm8(c.a));
    else
        return c;
}

// The same with the format chosen at run time (a clear colour).
inline vec4 roundToColorBuffer(ColorBufferFormat format, vec4 c) {
    switch (format) {
        case ColorBufferFormat::Half:
            return roundToColorBuffer<ColorBufferFormat::Half>(c);
        case ColorBufferFormat::Unorm8:
            return roundToColorBuffer<ColorBufferFormat::Unorm8>(c);
        case ColorBufferFormat::Float:
            break;
    }
    return c;
}

}  // namespace facet
