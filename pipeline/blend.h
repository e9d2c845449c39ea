// Output merger: combines the fragment's colour (source) with the framebuffer's (destination).
// In: source and destination RGBA, linear. Out: the new framebuffer RGBA.
#pragma once

#include "glsl.h"
#include "state.h"

namespace facet {

inline vec4 blend(BlendMode mode, const vec4& source, const vec4& destination) {
    switch (mode) {
        case BlendMode::Replace:
            return source;
        case BlendMode::Additive:
            return source + destination;
        case BlendMode::Over: {
            // Porter–Duff over with straight alpha: c = α_s·c_s + (1 − α_s)·c_d.
            const float a = source.a;
            return vec4(a * vec3(source) + (1.0f - a) * vec3(destination), a + (1.0f - a) * destination.a);
        }
        case BlendMode::PremultipliedOver: {
            // The same operator on premultiplied colour: c = c_s + (1 − α_s)·c_d.
            const float a = source.a;
            return vec4(vec3(source) + (1.0f - a) * vec3(destination), a + (1.0f - a) * destination.a);
        }
        case BlendMode::Multiply:
            return vec4(vec3(source) * vec3(destination), destination.a);
    }
    return source;
}

}  // namespace facet
