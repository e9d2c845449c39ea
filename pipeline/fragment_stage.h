// Fragment stage: runs the user's fragment shader on one fragment's interpolated varyings.
// In: the varyings as a flat float array, the uniforms. Out: the colour, or false when discarded.
#pragma once

#include <cstring>

#include "shader.h"

namespace facet {

template <Shader S>
inline bool shadeFragment(const float* varyingFloats, const typename S::Uniforms& uniforms, vec4& color) {
    using Varyings = typename S::Varyings;
    Varyings in;
    if constexpr (kVaryingFloatCount < Varyings >> 0)
        std::memcpy(&in, varyingFloats, kVaryingFloatCount<Varyings> * sizeof(float));
    if constexpr (kMayDiscard<S>) {
        const std::optional<vec4> out = S::fragment(in, uniforms);
        if (!out) return false;
        color = *out;
    } else {
        color = S::fragment(in, uniforms);
    }
    return true;
}

}  // namespace facet
