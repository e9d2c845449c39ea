// The pipeline, every stage in order on one screen:
//
//   vertex stage → primitive assembly → clipping → perspective divide + viewport → culling + setup
//   → rasterization (2×2 quads) → depth test → interpolation → fragment shader → blending
//
// Each stage is a plain function in its own file; draw() is the only place that knows their order, and
// it hands every stage's output to an Observer between stages (observer.h).
#pragma once

#include <algorithm>
#include <span>
#include <stdexcept>
#include <string>

#include "blend.h"
#include "clip.h"
#include "depth_test.h"
#include "fragment_stage.h"
#include "framebuffer.h"
#include "interpolate.h"
#include "observer.h"
#include "primitive_assembly.h"
#include "rasterize.h"
#include "shader.h"
#include "state.h"
#include "thread_pool.h"
#include "triangle_setup.h"
#include "vertex_stage.h"
#include "viewport.h"

namespace facet {

// The worker threads and buffers draws use, kept by the caller and reused, so that drawing allocates
// nothing per triangle or fragment (and, once warmed up, nothing per draw). The image a draw produces
// does not depend on the number of threads.
struct DrawContext {
    explicit DrawContext(int threads = 0) : pool(threads) {}
    ThreadPool pool;
    ShadedVertices shaded;
    std::vector<WindowVertex> window;  // viewport transform of each vertex that needs no clipping
    ClipPolygon polygon;
};

// Checks a draw's state and the mesh's indices; throws std::invalid_argument naming the problem.
void validateDraw(const DrawState& state, const Framebuffer& target, std::size_t vertexCount,
                  std::span<const std::uint32_t> indices);

namespace detail {

// Setup, rasterization and the per-fragment operations for one window triangle.
template <Shader S, class Observer>
void drawWindowTriangle(std::uint32_t triangleIndex, const WindowTriangle& window, const DrawState& state,
                        const typename S::Uniforms& uniforms, Framebuffer& target, DrawStats& stats,
                        Observer& observer) {
    TriangleSetup setup;
    const TriangleFate fate = setupTriangle(window, state, setup);
    if constexpr (Observer::enabled) observer.onSetup(triangleIndex, window, fate, setup);
    if (fate == TriangleFate::ZeroArea) ++stats.trianglesZeroArea;
    if (fate == TriangleFate::Culled) ++stats.trianglesCulled;
    if (fate != TriangleFate::Drawn) return;
    ++stats.trianglesRasterized;

    const DepthState depth = state.depth;
    const BlendMode blendMode = state.blend;
    float varyings[kMaxVaryingFloats];
    rasterizeTriangle(setup, [&](const Quad& quad) {
        for (int lane = 0; lane < 4; ++lane) {
            if (!(quad.mask & (1u << lane))) continue;
            const int x = quad.x + (lane & 1);
            const int y = quad.y + (lane >> 1);
            const float b1 = quad.b1[lane];
            const float b2 = quad.b2[lane];

            // Depth test before shading: the shader cannot change depth, so testing early gives the
            // same image and skips shading hidden fragments. The write waits for a possible discard.
            const float z = interpolateDepth(setup, b1, b2);
            float& storedDepth = target.depth(x, y);
            FragmentEvent event;
            if constexpr (Observer::enabled) {
                event = FragmentEvent{x, y, triangleIndex, z, storedDepth};
                event.colorBefore = event.colorAfter = target.color(x, y);
            }
            if (depth.testEnabled && !depthTestPasses(depth.compare, z, storedDepth)) {
                ++stats.fragmentsDepthFailed;
                if constexpr (Observer::enabled) {
                    event.fate = FragmentFate::DepthFailed;
                    observer.onFragment(event);
                }
                continue;
            }

            // Interpolation and the fragment shader.
            interpolateVaryings(setup, b1, b2, varyings);
            vec4 color;
            ++stats.fragmentsShaded;
            if (!shadeFragment<S>(varyings, uniforms, color)) {
                ++stats.fragmentsDiscarded;
                if constexpr (Observer::enabled) {
                    event.fate = FragmentFate::Discarded;
                    observer.onFragment(event);
                }
                continue;
            }

            // Depth write and blending.
            if (depth.testEnabled && depth.writeEnabled) storedDepth = z;
            vec4& destination = target.color(x, y);
            destination = blend(blendMode, color, destination);
            ++stats.fragmentsWritten;
            if constexpr (Observer::enabled) {
                event.fate = FragmentFate::Written;
                event.shaded = color;
                event.colorAfter = destination;
                observer.onFragment(event);
            }
        }
    });
}

}  // namespace detail

// Draws an indexed triangle list: indices[3t], indices[3t+1], indices[3t+2] make triangle t.
// The caller owns `scratch` (reuse it across draws). Returns counters for the draw.
template <Shader S, class Observer = NullObserver>
DrawStats draw(const DrawState& state, const typename S::Uniforms& uniforms,
               std::span<const typename S::Attributes> vertices, std::span<const std::uint32_t> indices,
               Framebuffer& target, DrawContext& scratch, Observer&& observer = Observer{}) {
    constexpr bool kObserving = std::remove_reference_t<Observer>::enabled;
    validateDraw(state, target, vertices.size(), indices);
    DrawStats stats;

    // Vertex stage: the vertex shader once per vertex, then the viewport transform for every vertex
    // inside the frustum (most of them), which the triangles sharing it then reuse.
    ShadedVertices& shaded = scratch.shaded;
    shadeVertices<S>(vertices, uniforms, shaded);
    stats.vertices = shaded.size();
    scratch.window.resize(shaded.size());
    for (std::size_t i = 0; i < shaded.size(); ++i) {
        if (shaded.outcodes[i] == 0)
            scratch.window[i] = toWindow(shaded.positions[i], state.viewport, state.raster.subpixelBits);
        if constexpr (kObserving)
            observer.onVertex(static_cast<std::uint32_t>(i), shaded.positions[i], shaded.varyingsOf(i),
                              shaded.varyingCount, shaded.outcodes[i]);
    }

    const std::size_t triangleCount = indices.size() / 3;
    stats.triangles = triangleCount;
    for (std::size_t t = 0; t < triangleCount; ++t) {
        const auto triangleIndex = static_cast<std::uint32_t>(t);
        const std::array<std::uint32_t, 3> i = {indices[3 * t], indices[3 * t + 1], indices[3 * t + 2]};

        // Primitive assembly and trivial reject.
        const std::uint8_t outcodeAnd = shaded.outcodes[i[0]] & shaded.outcodes[i[1]] & shaded.outcodes[i[2]];
        const std::uint8_t outcodeOr = shaded.outcodes[i[0]] | shaded.outcodes[i[1]] | shaded.outcodes[i[2]];
        const TriangleFate rejected = trivialReject(outcodeAnd, outcodeOr);
        if (rejected != TriangleFate::Drawn) {
            ++stats.trianglesRejected;
            if constexpr (kObserving) observer.onRejected(triangleIndex, rejected);
            continue;
        }
        ClipPolygon& polygon = scratch.polygon;
        if (kObserving || outcodeOr != 0) {
            assembleTriangle(shaded, i, polygon);
            if constexpr (kObserving) observer.onAssembled(triangleIndex, polygon);
        }

        WindowTriangle window;
        window.varyingCount = shaded.varyingCount;
        if (outcodeOr == 0) {
            // Trivially inside: no clipping, the vertices' window positions are ready.
            for (int k = 0; k < 3; ++k) {
                window.vertices[k] = scratch.window[i[k]];
                window.varyings[k] = shaded.varyingsOf(i[k]);
            }
            detail::drawWindowTriangle<S>(triangleIndex, window, state, uniforms, target, stats, observer);
            continue;
        }

        // Clipping: the triangle crosses at least one plane.
        ++stats.trianglesClipped;
        clipPolygon(polygon, outcodeOr);
        if constexpr (kObserving) observer.onClipped(triangleIndex, polygon);
        if (polygon.count == 0) {
            ++stats.trianglesRejected;
            if constexpr (kObserving) observer.onRejected(triangleIndex, TriangleFate::ClippedAway);
            continue;
        }

        // The clipped polygon is convex: draw it as a fan around its first vertex.
        const WindowVertex first =
            toWindow(polygon.vertices[0].position, state.viewport, state.raster.subpixelBits);
        WindowVertex previous =
            toWindow(polygon.vertices[1].position, state.viewport, state.raster.subpixelBits);
        for (int k = 2; k < polygon.count; ++k) {
            const WindowVertex current =
                toWindow(polygon.vertices[k].position, state.viewport, state.raster.subpixelBits);
            window.vertices = {first, previous, current};
            window.varyings = {polygon.vertices[0].varyings.data(), polygon.vertices[k - 1].varyings.data(),
                               polygon.vertices[k].varyings.data()};
            detail::drawWindowTriangle<S>(triangleIndex, window, state, uniforms, target, stats, observer);
            previous = current;
        }
    }
    return stats;
}

}  // namespace facet
