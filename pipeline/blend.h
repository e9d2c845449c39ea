// Output merger: combines the fragment's colour (source) with the framebuffer's (destination).
// In: source and destination RGBA, linear. Out: the new framebuffer RGBA.
#pragma once

#include "glsl.h"
#include "state.h"

namespace facet {

// Written once for float (the framebuffer's vec4) and double (the reference renderer's dvec4).
template <class T, glm::qualifier Q>
glm::vec<4, T, Q> blend(BlendMode mode, const glm::vec<4, T, Q>& source,
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

}  // namespace facet
