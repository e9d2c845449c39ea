// Fragment stage: runs the user's fragment shader on one fragment's interpolated varyings.
// In: the varyings as a flat float array, the uniforms. Out: the colour, or false when discarded.
#pragma once

#include <cstring>

#include "shader.h"
#include "wide.h"

namespace facet {

// A shader that can also shade eight fragments at once: static Vec4x8 fragmentBatch(const FragmentBatch&,
// const Uniforms&), computing what fragment() computes. The pipeline then shades a block row at a time.
template <class S>
concept BatchShader = Shader<S> && !kMayDiscard<S> &&
                      requires(const FragmentBatch& batch, const typename S::Uniforms& uniforms) {
    { S::fragmentBatch(batch, uniforms) } -> std::same_as<Vec4x8>;
};

// A shader that may discard and shades eight fragments at once: static Vec4x8 fragmentBatch(const
// FragmentBatch&, const Uniforms&, unsigned& kept), which clears in `kept` (on entry the batch's mask)
// the bit of every lane it discards, as fragment() returning nullopt would.
template <class S>
concept DiscardingBatchShader = Shader<S> && kMayDiscard<S> &&
    requires(const FragmentBatch& batch, const typename S::Uniforms& uniforms, unsigned& kept) {
    { S::fragmentBatch(batch, uniforms, kept) } -> std::same_as<Vec4x8>;
};

#if FACET_SIXTEEN_LANES
// A batch shader that also shades two batches in one call, sixteen lanes (wide.h): static Vec4x16
// fragmentBatchPair(const FragmentBatch& a, const FragmentBatch& b, const Uniforms&), a's lanes then
// b's, each what fragmentBatch gives it.
template <class S>
concept PairBatchShader = BatchShader<S> &&
    requires(const FragmentBatch& batch, const typename S::Uniforms& uniforms) {
    { S::fragmentBatchPair(batch, batch, uniforms) } -> std::same_as<Vec4x16>;
};
#endif

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
