// What a scene may hold at the most, shared by the scene loader, the renderer and the command line:
// absurd sizes are refused before they cost memory or time.
#pragma once

#include <cstddef>
#include <cstdint>

namespace facet {

// Size limits shared by the scene loader and the command line (absurd sizes are rejected).
inline constexpr int kMaxImageSide = 16384;
// The largest image: 64 Mpixel (e.g. 8192 × 8192) keeps the buffers near 1.3 GB.
inline constexpr long long kMaxPixels = 1LL << 26;
// A scene file is a few kilobytes of hand-written JSON; a larger one than this is refused unread.
inline constexpr std::uintmax_t kMaxSceneFileBytes = std::uintmax_t{64} << 20;
// Objects in one scene. Each object is its own draw with its own copy of its model's vertices, so the
// memory a scene needs grows with objects × their models' size: the count is refused while reading
// (a 64 MiB file could otherwise list millions), and the triangles drawn are bounded once the
// distinct models are loaded, before any object's copy is made.
inline constexpr std::size_t kMaxObjects = 100'000;
inline constexpr std::size_t kMaxSceneTriangles = 50'000'000;  // ~3-5 GB of draws at the most

// The vertical field of view facet accepts, in degrees: below 0.01° the view is narrower than float
// coordinates can aim (a model a thousand times its size away would be placed to a fraction of a
// pixel); at 180° the projection is infinite.
inline constexpr double kMinFovyDegrees = 0.01;
inline constexpr double kMaxFovyDegrees = 179.0;
// Whether a field of view is within those bounds, as the float the camera keeps: the bounds are
// compared as floats too, since 0.01 typed by the user becomes the float 0.0099999998, below the
// double 0.01, and a documented bound must be accepted at the bound.
constexpr bool fovyAllowed(float degrees) {
    return degrees >= static_cast<float>(kMinFovyDegrees) && degrees <= static_cast<float>(kMaxFovyDegrees);
}
// An area light's shadow samples ("samples", --area-samples): at most 32×32 rays per point and light.
inline constexpr int kMaxAreaSamples = 1024;

}  // namespace facet
