// A step-through of one pixel and one triangle: the frame traced (trace.h), its screens (views.h) in
// pipeline order, and the data behind them (for --json).
#pragma once

#include <cstdint>
#include <optional>
#include <utility>

#include <nlohmann/json.hpp>

#include "render/renderer.h"
#include "step/screens.h"
#include "step/shading_view.h"
#include "step/trace.h"
#include "step/user_shader_view.h"

namespace facet::step {

struct StepRequest {
    std::optional<std::pair<int, int>> pixel;  // none: the covered pixel nearest the image centre
    std::optional<std::uint32_t> triangle;     // none: the triangle that gave the pixel its final colour
    std::uint8_t terms = kAllTerms;            // --only
};

struct StepTrace {
    Walk walk;
    PixelTrace pixel;
    std::optional<TriangleTrace> triangle;
    std::optional<ShadingTrace> shading;        // when the triangle's built-in shader ran at the pixel
    std::optional<UserShaderTrace> userShader;  // when its draw has a shader of one's own and a fragment here
};

// Traces the frame of `prepared` for the request. Throws InputError for a pixel outside the image or a
// triangle number the scene does not have.
StepTrace traceStep(const PreparedScene& prepared, DrawContext& context, const StepRequest& request);

// The walks of many pixels at once (the web page's): two traced frames for all of them, each pixel
// following the triangle that gave it its colour. In the order of `pixels`.
std::vector<Walk> traceWalks(const PreparedScene& prepared, DrawContext& context,
                             const std::vector<std::pair<int, int>>& pixels, std::uint8_t terms = kAllTerms);

// The shading of the traced triangle's fragment at the pixel, recomputed by the shaders' own formulas
// with their records on; none when the shader did not run there.
std::optional<ShadingTrace> shadingOf(const PreparedScene& prepared, const PixelTrace& pixel,
                                      const TriangleTrace& triangle, std::uint8_t terms);

// The fragment part of a shader of one's own at the traced triangle's fragment at the pixel, run again
// with its record on; none when the triangle's draw has no such shader or made no fragment there.
std::optional<UserShaderTrace> userShaderOf(const PreparedScene& prepared, const PixelTrace& pixel,
                                            const TriangleTrace& triangle, std::uint8_t terms);

// The walk's screens in pipeline order for a traced pixel and triangle.
Walk walkOf(const PreparedScene& prepared, const PixelTrace& pixel, const TriangleTrace* triangle,
            const ShadingTrace* shading, const UserShaderTrace* userShader = nullptr);

// facet step --stats: a few lines on the trace (the pixel's history in numbers; a shader of one's own:
// its recorded values and how many values were NaN or infinite).
std::string stepStats(const StepTrace& trace);

// The whole trace as data: the pixel's history, the triangle's stages and the screens.
nlohmann::json toJson(const StepTrace& trace);

}  // namespace facet::step
