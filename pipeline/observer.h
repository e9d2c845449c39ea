// Observers watch the pipeline between its stages (the step-through mode, tests, pixel history).
// draw<Shader, Observer> calls these hooks; with NullObserver they are empty inline functions and the
// data they would receive is only assembled under `if constexpr (Observer::enabled)`, so observation
// costs nothing when it is off and there is only ever one copy of the pipeline.
#pragma once

#include <cstdint>

#include "types.h"

namespace facet {

struct NullObserver {
    static constexpr bool enabled = false;
    // Vertex stage output for vertex `index`.
    void onVertex(std::uint32_t /*index*/, const vec4& /*clipPosition*/, const float* /*varyings*/,
                  int /*varyingCount*/, std::uint8_t /*outcode*/) {}
    // Primitive assembly: triangle `triangle` as assembled from three shaded vertices.
    void onAssembled(std::uint32_t /*triangle*/, const ClipPolygon& /*assembled*/) {}
    // Clipping output, only for triangles that crossed a plane.
    void onClipped(std::uint32_t /*triangle*/, const ClipPolygon& /*clipped*/) {}
    // A window triangle (one per triangle, or one per fan piece of a clipped polygon) and its fate;
    // `setup` is meaningful only when fate == Drawn.
    void onSetup(std::uint32_t /*triangle*/, const WindowTriangle& /*window*/, TriangleFate /*fate*/,
                 const TriangleSetup& /*setup*/) {}
    // A triangle rejected before reaching the window (non-finite, outside, clipped away).
    void onRejected(std::uint32_t /*triangle*/, TriangleFate /*fate*/) {}
    // Every fragment and what became of it.
    void onFragment(const FragmentEvent& /*event*/) {}
};

}  // namespace facet
