#include "step/walk.h"

#include <functional>
#include <limits>
#include <memory>
#include <mutex>
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

// The scene's triangles for naming shadow-map blockers (shadow maps build no BVH of their own): built
// once for a frame's shadows, kept while they live.
const RayScene* blockerScene(const PreparedScene& prepared) {
    if (prepared.shadows && prepared.shadows->rays) return prepared.shadows->rays.get();
    static std::mutex mutex;
    static std::weak_ptr<const FrameShadows> builtFor;
    static std::unique_ptr<RayScene> scene;
    const std::lock_guard lock(mutex);
    if (!prepared.shadows) return nullptr;
    if (!scene || builtFor.lock() != prepared.shadows) {
        std::vector<std::vector<vec3>> positions;
        scene = std::make_unique<RayScene>(rayMeshes(prepared, positions));
        builtFor = prepared.shadows;
    }
    return scene.get();
}

// The object a draw belongs to, in words: "object 2 (teapot.obj)".
std::string objectName(const PreparedScene& prepared, std::uint32_t draw) {
    std::uint32_t k = 0, object = 0;
    if (prepared.assets)
        for (const ObjectSpec& spec : prepared.scene.objects) {
            for (const MeshPart& part : prepared.assets->model(spec.model).parts)
                if (part.indexCount != 0 && k++ == draw)
                    return "object " + std::to_string(object) + " (" + spec.model.filename().string() + ")";
            ++object;
        }
    return "draw " + std::to_string(draw);
}

// Names what blocks each light the shadow test found (partly) hidden at the point `s` shaded: the
// nearest opaque triangle on the ray the test casts, from P + ε·N (N as the lighting received it,
// turned towards the viewer) along L, up to ε short of the light (shaders/shadowing.h's rayVisibility).
ShadowBlockers blockersAt(const PreparedScene& prepared, const SurfaceUniforms& u,
                          const SurfaceTermsRecord& s) {
    ShadowBlockers blockers;
    if (!u.shadows) return blockers;
    const LightingRecord& lighting = s.lighting;
    const vec3 N = s.flipped ? -s.normal : s.normal;
    const vec3 origin = s.position + N * u.shadows->rayOffset;
    for (int k = 0; k < lighting.lightCount; ++k) {
        const LightRecord& r = lighting.lights[static_cast<std::size_t>(k)];
        const ShadowMethod method = u.shadows->lights[static_cast<std::size_t>(k)].method;
        if (!r.shadowTested || r.visibility == 1.0f || method == ShadowMethod::None ||
            isAreaLight(r.light.kind))
            continue;
        ShadowBlocker& b = blockers[static_cast<std::size_t>(k)];
        b.byMap = method == ShadowMethod::Map;
        const RayScene* rays = blockerScene(prepared);
        if (!rays) continue;
        const double reach = r.light.kind == LightKind::Directional
                                 ? double(std::numeric_limits<float>::infinity())
                                 : double(r.distance - 2.0f * u.shadows->rayOffset);
        const glm::dvec3 o(origin), d(r.L);
        const double tnear = 0.0;
        RayHit hit;
        rays->nearestOpaque8(&o, &d, &tnear, &reach, 1u, {}, &hit);
        if (!hit.hit() || hit.mesh >= prepared.draws.size()) continue;
        b.found = true;
        b.triangle = triangleOf(prepared, hit.mesh, hit.triangle).number;
        b.object = objectName(prepared, hit.mesh);
        b.distance = hit.t;
    }
    return blockers;
}

// Gouraud after clipping: the corners of `piece` (the fan piece k of the clipped polygon: p0, p(k+1),
// p(k+2)), each followed back through the planes to a corner of the triangle or to the plane that made
// it, and the new vertices behind them with their colours (Gouraud's varyings: c_mod, then c_add), as
// the clip record holds them.
ShadingTrace::PieceCorners pieceCornersOf(const TriangleTrace& t, const WindowPiece& piece,
                                          const FragmentEvent& f) {
    ShadingTrace::PieceCorners p;
    const std::vector<ClipStep>& steps = t.clipSteps;
    for (const ClipStep& step : steps)
        if (step.origin.size() != step.polygon.size() || step.varyings.size() != step.polygon.size())
            return p;
    const int last = static_cast<int>(steps.size()) - 1;
    // A vertex of the polygon after step s (s = −1: the triangle): followed back while it was kept.
    const auto resolve = [&](int s, int i) {
        while (s >= 0 && steps[static_cast<std::size_t>(s)].origin[static_cast<std::size_t>(i)] >= 0)
            i = steps[static_cast<std::size_t>(s--)].origin[static_cast<std::size_t>(i)];
        return std::pair(s, i);
    };
    const auto name = [&](std::pair<int, int> v) {
        // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "v" + std::string.
        std::string text(1, v.first < 0 ? 'v' : 'p');
        text += std::to_string(v.second);
        if (v.first >= 0 && v.first != last) {
            text += " after ";
            text += clipPlaneNames(steps[static_cast<std::size_t>(v.first)].plane);
        }
        return text;
    };
    const auto colours = [&](std::pair<int, int> v, vec3& modulated, vec3& added) {
        const std::vector<float>& a =
            v.first < 0
                ? t.vertexVaryings[static_cast<std::size_t>(v.second)]
                : steps[static_cast<std::size_t>(v.first)].varyings[static_cast<std::size_t>(v.second)];
        if (a.size() < 6) return false;
        modulated = vec3(a[0], a[1], a[2]);
        added = vec3(a[3], a[4], a[5]);
        return true;
    };
    std::vector<std::pair<int, int>> listed;
    bool ok = true;
    std::function<void(std::pair<int, int>)> collect = [&](std::pair<int, int> v) {
        if (v.first < 0 || std::find(listed.begin(), listed.end(), v) != listed.end()) return;
        listed.push_back(v);
        const ClipStep& step = steps[static_cast<std::size_t>(v.first)];
        const int m = -1 - step.origin[static_cast<std::size_t>(v.second)];
        const ClipStep::NewVertex& made = step.made[static_cast<std::size_t>(m)];
        const std::pair<int, int> from = resolve(v.first - 1, made.from), to = resolve(v.first - 1, made.to);
        collect(from);
        collect(to);
        ShadingTrace::ClipMix mix;
        mix.made = name(v);
        mix.plane = clipPlaneNames(step.plane);
        mix.from = name(from);
        mix.to = name(to);
        mix.t = made.t;
        ok = ok && colours(from, mix.modulated[0], mix.added[0]) &&
             colours(to, mix.modulated[1], mix.added[1]) && colours(v, mix.modulated[2], mix.added[2]);
        p.mixes.push_back(mix);
    };
    const auto k = static_cast<int>(&piece - t.pieces.data());
    const int polygon[3] = {0, k + 1, k + 2};
    for (int i = 0; i < 3; ++i) {
        if (polygon[i] >= static_cast<int>(steps.back().polygon.size())) return p;
        const std::pair<int, int> v = resolve(last, polygon[i]);
        p.names[i] = name({last, polygon[i]});
        p.sources[i] = name(v);
        collect(v);
        ok = ok && colours({last, polygon[i]}, p.modulated[i], p.added[i]);
    }
    if (!ok) return p;
    // λ in the piece's setup order (v1 and v2 exchanged when its area was negative), weighted by the
    // corners' 1/w: λ′_i = (λ_i/w_i)/(1/w), in the order p0, p(k+1), p(k+2).
    const TriangleSetup& s = piece.setup;
    const float invW[3] = {s.invW0, s.invW0 + s.dInvW1, s.invW0 + s.dInvW2};
    const bool exchanged = piece.signedDoubleArea < 0;
    const int setupOf[3] = {0, exchanged ? 2 : 1, exchanged ? 1 : 2};
    for (int i = 0; i < 3; ++i) {
        const int c = setupOf[i];
        p.weights[i] = s.perspective ? f.barycentrics[c] * invW[c] / f.invW : f.barycentrics[c];
        p.mixedModulated += p.weights[i] * p.modulated[static_cast<std::size_t>(i)];
        p.mixedAdded += p.weights[i] * p.added[static_cast<std::size_t>(i)];
    }
    p.piece = k;
    p.present = true;
    return p;
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
    const WindowPiece* covering = nullptr;
    for (const WindowPiece& piece : triangle.pieces)
        if (piece.fate == TriangleFate::Drawn && coverageAt(piece.setup, pixel.x, pixel.y).covered) {
            exchanged = piece.signedDoubleArea < 0;
            covering = &piece;
        }
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
    if (draw.frequency == ShadingFrequency::Gouraud && !triangle.clipSteps.empty() && covering)
        trace.piece = pieceCornersOf(triangle, *covering, *entry->fragment);
    if (trace.fragment.perPixel) trace.blockers = blockersAt(prepared, uniforms, trace.fragment.lighting);
    for (CornerShading& c : trace.corners)
        c.blockers = blockersAt(prepared, uniforms, c.lighting.lighting);
    trace.faceNormal = prepared.scene.lighting.preset != LightingPreset::GL;
    if (draw.frequency == ShadingFrequency::Flat && trace.faceNormal) {
        // The face normal as renderer.h's flatFaceNormal made it from v0, v1, v2 as drawn (the draw's
        // corners already carry it, so it is turned the same way again).
        std::array<MeshVertex, 3> drawn;
        for (int k = 0; k < 3; ++k) {
            drawn[k] = draw.vertices[triangle.indices[k]];
            trace.facePositions[k] = drawn[k].position;
        }
        flatFaceNormal(drawn[0], drawn[1], drawn[2], &trace.faceNormalRecord);
    }
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
