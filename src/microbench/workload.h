// The inputs every micro-benchmark draws from: a UV sphere in front of a perspective camera on a
// 1920×1080 frame, run through the real front-end stages once, so each benchmark times one stage on the
// data that stage really sees. Everything is deterministic (fixed tessellation, fixed seeds).
#pragma once

#include <benchmark/benchmark.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "pipeline/names.h"
#include "pipeline/state.h"
#include "pipeline/types.h"
#include "scene/mesh.h"
#include "shaders/shaders.h"

namespace facet::microbench {

inline constexpr int kFrameWidth = 1920;
inline constexpr int kFrameHeight = 1080;
// Every random input comes from this seed: the same inputs, run to run.
inline constexpr std::uint32_t kSeed = 20261130;

// A UV sphere of unit radius around the origin: `rings` × `segments` quads, two triangles each.
struct SphereMesh {
    std::vector<MeshVertex> vertices;
    std::vector<std::uint32_t> indices;
    std::size_t triangles() const { return indices.size() / 3; }
};
SphereMesh makeSphere(int rings, int segments);

// The benchmarks' view: the sphere from `eyeDistance` on +z, 40° vertical field of view, near plane
// `near`, far 100, for the depth buffer `depth` (reversed Z draws with its remapped projection), two
// point lights with a white specular highlight, material shininess 32.
SurfaceUniforms makeUniforms(float eyeDistance, float near,
                             DepthBufferFormat depth = DepthBufferFormat::Float);
DrawState makeDrawState(DepthBufferFormat depth = DepthBufferFormat::Float);

// The sphere's triangles after the vertex stage (Phong shading's shader), viewport and setup: the
// triangles that survive culling, each with its varying planes, and every 8×8 block the rasterizer
// gives them on the whole frame. `interpolation` is the draw's (it decides how setup writes the planes).
struct RasterizedSphere {
    std::vector<TriangleSetup> setups;
    std::vector<float> planes;  // 3 · varyingCount floats per setup, at setup.varyingPlaneOffset
    struct Block {
        std::uint32_t setup;
        CoverageBlock coverage;
    };
    std::vector<Block> blocks;
    std::int64_t fragments = 0;  // covered samples over all blocks
};
const RasterizedSphere& rasterizedSphere(int rings, int segments, Interpolation interpolation);

// The label of a benchmark: each knob as its command-line flag and value ("--depth unorm16"), so the
// table reads as the settings `facet trade` applies.
template <class E>
std::string knob(std::string_view flag, E value) {
    std::string text(flag);
    text += ' ';
    text += nameOf(value);
    return text;
}
inline std::string knob(std::string_view flag, long value) {
    std::string text(flag);
    text += ' ';
    text += std::to_string(value);
    return text;
}
inline std::string joined(std::initializer_list<std::string> parts) {
    std::string text;
    for (const std::string& part : parts) {
        if (!text.empty()) text += ", ";
        text += part;
    }
    return text;
}

}  // namespace facet::microbench
