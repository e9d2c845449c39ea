// Vertex stage: runs the user's vertex shader once for every vertex of an indexed mesh.
// In: the mesh's vertex attributes and the uniforms. Out: ShadedVertices (clip position, flattened
// varyings and the clip outcode of every vertex), reused from draw to draw without reallocating.
#pragma once

#include <algorithm>
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
// may run on different threads. Outcodes are those of the depth buffer's clip-depth range.
template <Shader S>
void shadeVertices(std::span<const typename S::Attributes> attributes, const typename S::Uniforms& uniforms,
                   std::size_t begin, std::size_t end, ShadedVertices& out,
                   ClipDepthRange clipDepth = ClipDepthRange::MinusWToW) {
    constexpr int kFloats = kVaryingFloatCount<typename S::Varyings>;
    const auto storeShaded = [&](std::size_t i, const VertexOut<typename S::Varyings>& shaded) {
        out.positions[i] = shaded.position;
        if constexpr (kFloats > 0)
            std::memcpy(out.varyings.data() + i * kFloats, &shaded.varyings, kFloats * sizeof(float));
    };
    const auto store = [&](std::size_t i, const VertexOut<typename S::Varyings>& shaded) {
        storeShaded(i, shaded);
        out.outcodes[i] = computeOutcode(shaded.position, clipDepth);
    };
    if constexpr (BatchVertexShader<S>) {
        // Eight at a time; a vertex's result does not depend on which group or lane it lands in.
        VertexOut<typename S::Varyings> shaded[kVertexBatch];
        std::size_t i = begin;
        for (; i + kVertexBatch <= end; i += kVertexBatch) {
            S::vertexBatch(&attributes[i], uniforms, shaded);
            for (int lane = 0; lane < kVertexBatch; ++lane)
                storeShaded(i + lane, shaded[lane]);
        }
        // The groups' outcodes eight at a time, in a pass of their own: loaded right after the group's
        // positions were stored, a 32-byte load spanning two 16-byte stores would wait for them.
        for (std::size_t group = begin; group < i; group += kVertexBatch)
            computeOutcodes(&out.positions[group], &out.outcodes[group], clipDepth);
        if (i < end) {
            typename S::Attributes group[kVertexBatch];
            for (int lane = 0; lane < kVertexBatch; ++lane)
                group[lane] = attributes[std::min(i + lane, end - 1)];
            S::vertexBatch(group, uniforms, shaded);
            for (std::size_t lane = 0; i + lane < end; ++lane)
                store(i + lane, shaded[lane]);
        }
    } else {
        for (std::size_t i = begin; i < end; ++i)
            store(i, S::vertex(attributes[i], uniforms));
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
