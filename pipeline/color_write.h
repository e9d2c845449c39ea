// Output merger: how a draw's shaded fragments reach the colour buffer, with its blend mode and the
// colour buffer's format resolved once per draw (colorWriteFor) into one function of each shape, so that
// no fragment chooses either. Blending, then rounding to the colour buffer's format (blend.h).
#pragma once

#include <bit>

#include "blend.h"
#include "framebuffer.h"
#include "state.h"

namespace facet {

struct ColorWrite {
    // shaded[lane] into pixel (x[lane], y[lane]) for each lane set in `lanes` (a batch of the back end's
    // fragment queue: its pixels are distinct).
    using Lanes = void (*)(const FramebufferPlanes& target, const vec4* shaded, const int* x, const int* y,
                           unsigned lanes);
    // One multisampled fragment's colour into the samples of `colors` set in `samples`.
    using Samples = void (*)(vec4* colors, unsigned samples, const vec4& shaded);

    // Replace into the float buffer (every opaque draw's): the colour is stored as it is, which the back
    // end does in line (a call per batch cost that, the common draw, more than the stores).
    bool plainStores = true;
    Lanes lanes = nullptr;
    Samples samples = nullptr;
};

namespace detail {

template <BlendMode kMode, ColorBufferFormat kFormat>
vec4 mergeColor(const vec4& source, const vec4& destination) {
    return roundToColorBuffer<kFormat>(blend(kMode, source, destination));
}

template <BlendMode kMode, ColorBufferFormat kFormat>
void writeColorLanes(const FramebufferPlanes& target, const vec4* shaded, const int* x, const int* y,
                     unsigned lanes) {
    for (; lanes; lanes &= lanes - 1) {
        const int lane = std::countr_zero(lanes);
        vec4& destination = target.color(x[lane], y[lane]);
        destination = mergeColor<kMode, kFormat>(shaded[lane], destination);
    }
}

template <BlendMode kMode, ColorBufferFormat kFormat>
void writeColorSamples(vec4* colors, unsigned samples, const vec4& shaded) {
    for (; samples; samples &= samples - 1) {
        const int s = std::countr_zero(samples);
        colors[s] = mergeColor<kMode, kFormat>(shaded, colors[s]);
    }
}

template <BlendMode kMode>
ColorWrite colorWriteOf(ColorBufferFormat format) {
    const auto make = [&]<ColorBufferFormat kFormat>() {
        return ColorWrite{kMode == BlendMode::Replace && kFormat == ColorBufferFormat::Float,
                          &writeColorLanes<kMode, kFormat>, &writeColorSamples<kMode, kFormat>};
    };
    switch (format) {
        case ColorBufferFormat::Half:
            return make.template operator()<ColorBufferFormat::Half>();
        case ColorBufferFormat::Unorm8:
            return make.template operator()<ColorBufferFormat::Unorm8>();
        case ColorBufferFormat::Float:
            break;
    }
    return make.template operator()<ColorBufferFormat::Float>();
}

}  // namespace detail

// The output merger of a draw with blend mode `mode` into a colour buffer of `format`.
inline ColorWrite colorWriteFor(BlendMode mode, ColorBufferFormat format) {
    switch (mode) {
        case BlendMode::Additive:
            return detail::colorWriteOf<BlendMode::Additive>(format);
        case BlendMode::Over:
            return detail::colorWriteOf<BlendMode::Over>(format);
        case BlendMode::OverGL:
            return detail::colorWriteOf<BlendMode::OverGL>(format);
        case BlendMode::PremultipliedOver:
            return detail::colorWriteOf<BlendMode::PremultipliedOver>(format);
        case BlendMode::Multiply:
            return detail::colorWriteOf<BlendMode::Multiply>(format);
        case BlendMode::Replace:
            break;
    }
    return detail::colorWriteOf<BlendMode::Replace>(format);
}

}  // namespace facet
