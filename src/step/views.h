// The screens of a trace (trace.h) in the lectures' notation: the triangle view (one screen per front-end
// stage), the pixel history, and the traced fragment's interpolation, depth test, blend and encoding.
#pragma once

#include <string>
#include <vector>

#include "render/renderer.h"
#include "step/screens.h"
#include "step/trace.h"

namespace facet::step {

// Numbers as the screens print them: 6 significant digits, "-0" printed as "0", any NaN as "NaN".
std::string number(double value);
std::string vectorText(const vec2& v);
std::string vectorText(const vec3& v);
std::string vectorText(const vec4& v);

// The triangle through the front end: "input", "transform", "clip", "window", "setup", "raster".
std::vector<Screen> triangleScreens(const PreparedScene& prepared, const TriangleTrace& triangle);

// The one-line verdict of a pixel's history.
std::string verdictOf(const PixelTrace& pixel);

// Every triangle whose box holds the pixel, in submission order, and what ended it there: "history".
// `prepared` (when the trace is of a scene's frame) names the draws' varyings.
Screen historyScreen(const PixelTrace& pixel, const PreparedScene* prepared = nullptr);

// The traced triangle's fragment at the pixel: "interpolate" and "depth" (when it was covered), then
// "blend" and "encode" for the pixel. `entry` is the triangle's line of the history, or null when the
// triangle's box does not hold the pixel; `triangle` its view (for the vertices' 1/w).
std::vector<Screen> fragmentScreens(const PreparedScene* prepared, const PixelTrace& pixel,
                                    const TriangleAtPixel* entry, const TriangleTrace* triangle);
std::vector<Screen> outputScreens(const PreparedScene& prepared, const PixelTrace& pixel,
                                  const TriangleAtPixel* entry);

}  // namespace facet::step
