// Vertex stage: runs the user's vertex shader once for every vertex of an indexed mesh.
// In: the mesh's vertex attributes and the uniforms. Out: ShadedVertices (clip position, flattened
// varyings and the clip outcode of every vertex), reused from draw to draw without reallocating.
#pragma once

#include <cstring>
#include <span>

#include "clip.h"
#include "shader.h"

namespace facet {

template <Shader S>
void shadeVertices(std::span<const typename S::Attributes> attributes, const typename S::Uniforms& uniforms,
                   ShadedVertices& out) {
    constexpr int kFloats = kVaryingFloatCount<typename S::Varyings>;
    out.varyingCount = kFloats;
    out.positions.resize(attributes.size());
    out.varyings.resize(attributes.size() * kFloats);
    out.outcodes.resize(attributes.size());
    for (std::size_t i = 0; i < attributes.size(); ++i) {
        const VertexOut<typename S::Varyings> shaded = S::vertex(attributes[i], uniforms);
        out.positions[i] = shaded.position;
        if constexpr (kFloats > 0)
            std::memcpy(out.varyings.data() + i * kFloats, &shaded.varyings, kFloats * sizeof(float));
        out.outcodes[i] = computeOutcode(shaded.position);
    }
}

}  // namespace facet
