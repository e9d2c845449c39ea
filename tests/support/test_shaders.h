// Small shaders and helpers the pipeline tests share.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "pipeline/pipeline.h"
#include "pipeline/texture.h"

namespace facet::testing {

// Positions are given directly in clip space; one colour varying.
struct ClipSpaceColorShader {
    struct Attributes {
        vec4 position;
        vec4 color;
    };
    struct Varyings {
        vec4 color;
    };
    struct Uniforms {};
    static VertexOut<Varyings> vertex(const Attributes& in, const Uniforms&) {
        return {in.position, {in.color}};
    }
    static vec4 fragment(const Varyings& in, const Uniforms&) { return in.color; }
};

// A shader that discards where its colour's red is above ½: a third way for a fragment to end.
struct RedDiscardingShader {
    using Attributes = ClipSpaceColorShader::Attributes;
    using Varyings = ClipSpaceColorShader::Varyings;
    using Uniforms = ClipSpaceColorShader::Uniforms;
    static VertexOut<Varyings> vertex(const Attributes& in, const Uniforms&) {
        return {in.position, {in.color}};
    }
    static std::optional<vec4> fragment(const Varyings& in, const Uniforms&) {
        if (in.color.r > 0.5f) return std::nullopt;
        return in.color;
    }
};

// Like ClipSpaceColorShader, but the colour is flat (GLSL `flat`): the provoking vertex's, unblended,
// followed by an interpolated copy to show the two kinds side by side in one Varyings.
struct FlatColorShader {
    struct Attributes {
        vec4 position;
        vec4 color;
    };
    struct Varyings {
        vec4 flatColor;
        vec4 smoothColor;
    };
    static constexpr int kFlatVaryingFloats = 4;
    struct Uniforms {
        bool showSmooth = false;
    };
    static VertexOut<Varyings> vertex(const Attributes& in, const Uniforms&) {
        return {in.position, {in.color, in.color}};
    }
    static vec4 fragment(const Varyings& in, const Uniforms& u) {
        return u.showSmooth ? in.smoothColor : in.flatColor;
    }
};

// Every fragment adds exactly `value` to red: with additive blending a pixel's red counts its hits.
struct CountingShader {
    struct Attributes {
        vec4 position;
    };
    struct Varyings {};
    struct Uniforms {};
    static VertexOut<Varyings> vertex(const Attributes& in, const Uniforms&) { return {in.position, {}}; }
    static vec4 fragment(const Varyings&, const Uniforms&) { return vec4(1.0f, 0.0f, 0.0f, 0.0f); }
};

// A 64×64 texture whose mip level l ≥ 1 holds l everywhere (level 0 holds 0): a sample says which level
// it came from.
inline Texture levelNumberTexture() {
    Texture t;
    t.width = t.height = 64;
    t.texels.assign(64 * 64, vec4(0.0f));
    buildMipChain(t);
    for (std::size_t level = 0; level < t.mipLevels.size(); ++level)
        for (vec4& texel : t.mipLevels[level].texels)
            texel = vec4(static_cast<float>(level + 1));
    return t;
}

inline DrawState stateFor(const Framebuffer& fb) {
    DrawState state;
    state.viewport = {0, 0, fb.width(), fb.height()};
    state.raster.cull = CullMode::None;
    return state;
}

// Clip-space position of a window position (pixels, y down) at w = 1 and NDC depth z.
inline vec4 clipFromWindow(vec2 window, const Framebuffer& fb, float z = 0.0f) {
    return vec4(2.0f * window.x / fb.width() - 1.0f, 1.0f - 2.0f * window.y / fb.height(), z, 1.0f);
}

template <Shader S>
DrawStats drawTriangles(const DrawState& state, const std::vector<typename S::Attributes>& vertices,
                        Framebuffer& fb, const typename S::Uniforms& uniforms = {}) {
    std::vector<std::uint32_t> indices(vertices.size());
    for (std::size_t i = 0; i < indices.size(); ++i)
        indices[i] = static_cast<std::uint32_t>(i);
    DrawContext scratch;
    return draw<S>(state, uniforms, std::span<const typename S::Attributes>(vertices),
                   std::span<const std::uint32_t>(indices), fb, scratch);
}

// How many times each pixel was hit, read back from a CountingShader + additive draw.
inline int hits(const Framebuffer& fb, int x, int y) {
    return static_cast<int>(fb.color(x, y).r + 0.5f);
}

}  // namespace facet::testing
