#include "step/walk.h"

#include <sstream>

#include "base/errors.h"
#include "pipeline/rasterize.h"
#include "step/views.h"

namespace facet::step {

namespace {

const TriangleAtPixel* entryOf(const PixelTrace& pixel, const std::optional<TriangleRef>& ref) {
    if (!ref) return nullptr;
    for (const TriangleAtPixel& e : pixel.triangles)
        if (e.ref == *ref) return &e;
    return nullptr;
}

// The triangle a pixel's walk follows when none is asked for: the one that gave the pixel its final
// colour; else the last one that made a fragment here, else the last one that came near.
std::optional<TriangleRef> defaultTriangle(const PixelTrace& pixel) {
    if (pixel.producer) return pixel.triangles[*pixel.producer].ref;
    for (auto it = pixel.triangles.rbegin(); it != pixel.triangles.rend(); ++it)
        if (it->fragment) return it->ref;
    if (!pixel.triangles.empty()) return pixel.triangles.back().ref;
    return std::nullopt;
}

}  // namespace

std::optional<ShadingTrace> shadingOf(const PreparedScene& prepared, const PixelTrace& pixel,
                                      const TriangleTrace& triangle, std::uint8_t terms) {
    const TriangleAtPixel* entry = entryOf(pixel, triangle.ref);
    if (!entry || !entry->fragment || entry->fragment->fate == FragmentFate::DepthFailed) return std::nullopt;
    const PreparedDraw& draw = prepared.draws[triangle.ref.draw];
    if (draw.userShader.module) return std::nullopt;  // its own shader: userShaderOf
    // The corners in the order of the setup that rasterized the pixel: the triangle's, v1 and v2
    // exchanged when setup made its area positive; the provoking vertex among them.
    bool exchanged = false;
    for (const WindowPiece& piece : triangle.pieces)
        if (piece.fate == TriangleFate::Drawn && coverageAt(piece.setup, pixel.x, pixel.y).covered)
            exchanged = piece.signedDoubleArea < 0;
    std::array<MeshVertex, 3> corners;
    for (int k = 0; k < 3; ++k)
        corners[k] = draw.vertices[triangle.indices[k]];
    int provoking = triangle.state.raster.provokingVertex == ProvokingVertex::Last ? 2 : 0;
    if (exchanged) {
        std::swap(corners[1], corners[2]);
        if (provoking != 0) provoking = 1;
    }
    SurfaceUniforms uniforms = draw.uniforms;
    uniforms.terms = terms;  // as renderFrame draws it
    ShadingTrace trace = traceShading(uniforms, draw.frequency, *entry->fragment, corners, provoking);
    if (exchanged) trace.vertexOfCorner = {0, 2, 1};
    trace.faceNormal = prepared.scene.lighting.preset != LightingPreset::GL;
    return trace;
}

std::optional<UserShaderTrace> userShaderOf(const PreparedScene& prepared, const PixelTrace& pixel,
                                            const TriangleTrace& triangle, std::uint8_t terms) {
    const TriangleAtPixel* entry = entryOf(pixel, triangle.ref);
    if (!entry || !entry->fragment || triangle.ref.draw >= prepared.draws.size()) return std::nullopt;
    const PreparedDraw& draw = prepared.draws[triangle.ref.draw];
    if (!draw.userShader.module) return std::nullopt;
    SurfaceUniforms scratch;
    const SurfaceUniforms& uniforms =
        detail::callUniforms(draw, terms, nullptr, scratch);  // as renderFrame draws it
    return traceUserShader(draw, uniforms, triangle.state, *entry->fragment, &prepared.scene);
}

std::string stepStats(const StepTrace& trace) {
    std::ostringstream out;
    const PixelTrace& p = trace.pixel;
    int fragments = 0;
    for (const TriangleAtPixel& e : p.triangles)
        fragments += e.fragment.has_value();
    out << "pixel " << p.x << "," << p.y << ": " << p.triangles.size() << " triangles near it, " << fragments
        << " fragments\n";
    if (trace.triangle) out << "triangle " << trace.triangle->ref.number << " traced\n";
    if (const auto& u = trace.userShader) {
        out << "shader " << u->file << " (" << u->name << "): " << u->uniforms.size() << " uniforms, "
            << u->recorded.size() << " values recorded, output "
            << (!u->shaderRan  ? "none (not run)"
                : u->discarded ? "discarded"
                               : "a colour")
            << "\n";
        out << "non-finite shader values (NaN or infinite): " << nonFiniteCount(*u) << "\n";
    }
    return out.str();
}

Walk walkOf(const PreparedScene& prepared, const PixelTrace& pixel, const TriangleTrace* triangle,
            const ShadingTrace* shading, const UserShaderTrace* userShader) {
    Walk walk;
    walk.x = pixel.x;
    walk.y = pixel.y;
    if (triangle) {
        walk.triangle = triangle->ref;
        for (const WindowPiece& piece : triangle->pieces) {
            std::array<std::array<double, 2>, 3>& corners = walk.windowPieces.emplace_back();
            for (int k = 0; k < 3; ++k)  // the fixed-point grid of pipeline/types.h, as pixels
                corners[k] = {double(piece.vertices[k].xFixed) / (1 << kFixedFractionBits),
                              double(piece.vertices[k].yFixed) / (1 << kFixedFractionBits)};
        }
    }
    walk.verdict = verdictOf(pixel);
    walk.screens.push_back(historyScreen(pixel, &prepared));
    if (triangle)
        for (Screen& screen : triangleScreens(prepared, *triangle))
            walk.screens.push_back(std::move(screen));
    const TriangleAtPixel* entry = entryOf(pixel, walk.triangle);
    if (triangle)
        for (Screen& screen : fragmentScreens(&prepared, pixel, entry, triangle))
            walk.screens.push_back(std::move(screen));
    if (shading)
        for (Screen& screen : shadingScreens(*shading))
            walk.screens.push_back(std::move(screen));
    if (userShader)
        for (Screen& screen : userShaderScreens(*userShader))
            walk.screens.push_back(std::move(screen));
    for (Screen& screen : outputScreens(prepared, pixel, entry))
        walk.screens.push_back(std::move(screen));
    fitToColumns(walk);  // the safety net: a line a screen made too wide is wrapped, and recorded
    return walk;
}

StepTrace traceStep(const PreparedScene& prepared, DrawContext& context, const StepRequest& request) {
    const int width = prepared.scene.width, height = prepared.scene.height;
    std::pair<int, int> pixel{width / 2, height / 2};
    if (request.pixel) {
        pixel = *request.pixel;
        if (pixel.first < 0 || pixel.second < 0 || pixel.first >= width || pixel.second >= height)
            throw InputError("pixel " + std::to_string(pixel.first) + "," + std::to_string(pixel.second) +
                             " is outside the image, which is " + std::to_string(width) + "x" +
                             std::to_string(height) + " (x from 0 to " + std::to_string(width - 1) +
                             ", y from 0 to " + std::to_string(height - 1) + ", y down)");
    } else if (const auto nearest =
                   pixelNearestCentre(coveredPixels(prepared, context, request.terms), width, height)) {
        pixel = *nearest;
    }
    std::optional<TriangleRef> triangle;
    if (request.triangle) {
        triangle = triangleByNumber(prepared, *request.triangle);
        if (!triangle)
            throw InputError("there is no triangle " + std::to_string(*request.triangle) +
                             ": the scene has " + std::to_string(triangleCount(prepared)) +
                             " (numbered from 0)");
    }
    Framebuffer target(width, height);
    TraceRequest first;
    first.pixels = {pixel};
    first.focus = pixel;
    if (triangle) first.triangles = {*triangle};
    FrameTrace frame = traceFrame(prepared, target, context, first, request.terms);
    StepTrace trace;
    trace.pixel = std::move(frame.pixels.front());
    if (!triangle) {
        triangle = defaultTriangle(trace.pixel);
        if (triangle) {
            TraceRequest second = first;
            second.triangles = {*triangle};
            second.pixels.clear();
            frame = traceFrame(prepared, target, context, second, request.terms);
        }
    }
    if (triangle && !frame.triangles.empty()) trace.triangle = std::move(frame.triangles.front());
    if (trace.triangle) {
        trace.shading = shadingOf(prepared, trace.pixel, *trace.triangle, request.terms);
        trace.userShader = userShaderOf(prepared, trace.pixel, *trace.triangle, request.terms);
    }
    trace.walk =
        walkOf(prepared, trace.pixel, trace.triangle ? &*trace.triangle : nullptr,
               trace.shading ? &*trace.shading : nullptr, trace.userShader ? &*trace.userShader : nullptr);
    return trace;
}

std::vector<Walk> traceWalks(const PreparedScene& prepared, DrawContext& context,
                             const std::vector<std::pair<int, int>>& pixels, std::uint8_t terms) {
    Framebuffer target(prepared.scene.width, prepared.scene.height);
    TraceRequest histories;
    histories.pixels = pixels;
    FrameTrace first = traceFrame(prepared, target, context, histories, terms);
    // Each pixel's triangle, its view centred on the pixel.
    TraceRequest views;
    std::vector<std::optional<std::size_t>> viewOfPixel(pixels.size());
    for (std::size_t k = 0; k < first.pixels.size(); ++k)
        if (const std::optional<TriangleRef> triangle = defaultTriangle(first.pixels[k])) {
            viewOfPixel[k] = views.triangles.size();
            views.triangles.push_back(*triangle);
            views.focuses.push_back(pixels[k]);
        }
    const FrameTrace second = traceFrame(prepared, target, context, views, terms);
    // finish() keeps the views in request order, dropping any never seen: find each by its focus.
    std::vector<Walk> walks;
    std::size_t next = 0;
    for (std::size_t k = 0; k < first.pixels.size(); ++k) {
        const TriangleTrace* view = nullptr;
        if (viewOfPixel[k] && next < second.triangles.size() &&
            second.triangles[next].ref == views.triangles[*viewOfPixel[k]] &&
            second.triangles[next].focusX == pixels[k].first &&
            second.triangles[next].focusY == pixels[k].second)
            view = &second.triangles[next++];
        const std::optional<ShadingTrace> shading =
            view ? shadingOf(prepared, first.pixels[k], *view, terms) : std::nullopt;
        const std::optional<UserShaderTrace> user =
            view ? userShaderOf(prepared, first.pixels[k], *view, terms) : std::nullopt;
        walks.push_back(
            walkOf(prepared, first.pixels[k], view, shading ? &*shading : nullptr, user ? &*user : nullptr));
    }
    return walks;
}

}  // namespace facet::step
