// Vertex stage: runs the user's vertex shader once for every vertex of an indexed mesh.
// In: the mesh's vertex attributes and the uniforms. Out: ShadedVertices (clip position, flattened
// varyings and the clip outcode of every vertex), reused from draw to draw without reallocating.
#pragma once

#include <cstring>
#include <span>

#include "clip.h"
#include "shader.h"

namespace facet {

// Sizes `out` for `count` vertices of shader S.
template <Shader S>
void prepareShadedVertices(std::size_t count, ShadedVertices& out) {
    constexpr int kFloats = kVaryingFloatCount<typename S::Varyings>;
    out.varyingCount = kFloats;
    out.positions.resize(count);
    out.varyings.resize(count * kFloats);
    out.outcodes.resize(count);
}

// Shades vertices [begin, end) into `out` (already sized by prepareShadedVertices). Disjoint ranges
// may run on different threads.
template <Shader S>
void shadeVertices(std::span<const typename S::Attributes> attributes, const typename S::Uniforms& uniforms,
                   std::size_t begin, std::size_t end, ShadedVertices& out) {
    constexpr int kFloats = kVaryingFloatCount<typename S::Varyings>;
    for (std::size_t i = begin; i < end; ++i) {
        const VertexOut<typename S::Varyings> shaded = S::vertex(attributes[i], uniforms);
        out.positions[i] = shaded.position;
        if constexpr (kFloats > 0)
            std::memcpy(out.varyings.data() + i * kFloats, &shaded.varyings, kFloats * sizeof(float));
        out.outcodes[i] = computeOutcode(shaded.position);
    }
}

// All vertices, on the calling thread.
template <Shader S>
void shadeVertices(std::span<const typename S::Attributes> attributes, const typename S::Uniforms& uniforms,
                   ShadedVertices& out) {
    prepareShadedVertices<S>(attributes.size(), out);
    shadeVertices<S>(attributes, uniforms, 0, attributes.size(), out);
}

}  // namespace facet
