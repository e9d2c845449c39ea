// Observers watch the pipeline between its stages (the step-through mode, tests, pixel history).
// draw<Shader, Observer> calls these hooks; with NullObserver they are empty inline functions and the
// data they would receive is only assembled under `if constexpr (Observer::enabled)`, so observation
// costs nothing when it is off and there is only ever one copy of the pipeline.
#pragma once

#include <concepts>
#include <cstdint>

#include "state.h"
#include "types.h"

namespace facet {

struct NullObserver {
    static constexpr bool enabled = false;
    // A draw begins: its id (DrawContext::drawsStarted, counting the context's draws from 0) and state.
    void onDrawBegin(std::uint64_t /*drawId*/, const DrawState& /*state*/) {}
    // The draw has ended, with its counters.
    void onDrawEnd(std::uint64_t /*drawId*/, const DrawStats& /*stats*/) {}
    // Vertex stage output for vertex `index`.
    void onVertex(std::uint32_t /*index*/, const vec4& /*clipPosition*/, const float* /*varyings*/,
                  int /*varyingCount*/, std::uint8_t /*outcode*/) {}
    // Primitive assembly: triangle `triangle` as assembled from three shaded vertices.
    void onAssembled(std::uint32_t /*triangle*/, const ClipPolygon& /*assembled*/) {}
    // Clipping output, only for triangles that crossed a plane.
    void onClipped(std::uint32_t /*triangle*/, const ClipPolygon& /*clipped*/) {}
    // A window triangle (one per triangle, or one per fan piece of a clipped polygon) and its fate;
    // `setup` is meaningful when fate == Drawn, and when fate == Culled, where it is the setup the
    // triangle would have had (its coverage follows as onCoverage events with `culled` set).
    void onSetup(std::uint32_t /*triangle*/, const WindowTriangle& /*window*/, TriangleFate /*fate*/,
                 const TriangleSetup& /*setup*/) {}
    // The coverage decision at one pixel's sample, edge by edge with the fill rule's ties: for every
    // pixel of a drawn triangle's bounding box (tile by tile, before the triangle's fragments there),
    // and of a culled triangle's (right after its onSetup).
    void onCoverage(const CoverageEvent& /*event*/) {}
    // A triangle rejected before reaching the window (non-finite, outside, clipped away).
    void onRejected(std::uint32_t /*triangle*/, TriangleFate /*fate*/) {}
    // Every fragment and what became of it, with its barycentrics, 1/w and interpolated varyings.
    void onFragment(const FragmentEvent& /*event*/) {}
    // resolveFragmentLists(target, pool, observer): each pixel with fragments, its list in compositing
    // order and the colour after each blend.
    void onResolve(const ResolveEvent& /*event*/) {}
};

// What draw() and the renderer's renderFrame accept as an observer: NullObserver, or a type derived
// from it with `enabled` set and the hooks it wants overridden.
template <class O>
concept PipelineObserver = requires {
    { O::enabled } -> std::convertible_to<bool>;
};

}  // namespace facet
