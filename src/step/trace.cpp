#include "step/trace.h"

#include <algorithm>
#include <cmath>

#include "pipeline/bin.h"
#include "pipeline/clip.h"
#include "pipeline/depth_format.h"
#include "pipeline/rasterize.h"
#include "pipeline/triangle_setup.h"
#include "shading/gamma.h"

namespace facet::step {

TraceRecorder::TraceRecorder(const TraceRequest& request, const FrameShape& frame, int tileSize)
    : frame_(frame), tileSize_(tileSize) {
    pixelSlot_.assign(static_cast<std::size_t>(frame.width) * frame.height, -1);
    for (const auto& [x, y] : request.pixels) {
        trace_.pixels.push_back(PixelTrace{});
        PixelTrace& p = trace_.pixels.back();
        p.x = x;
        p.y = y;
        p.clearColor = frame.clearColor;
        p.encoding = frame.encoding;
        if (x >= 0 && y >= 0 && x < frame.width && y < frame.height)
            pixelSlot_[static_cast<std::size_t>(y) * frame.width + x] =
                static_cast<int>(trace_.pixels.size() - 1);
    }
    for (std::size_t k = 0; k < request.triangles.size(); ++k) {
        const TriangleRef& ref = request.triangles[k];
        const std::pair<int, int> focus = k < request.focuses.size() ? request.focuses[k] : request.focus;
        TriangleTrace t;
        t.ref = ref;
        t.focusX = focus.first;
        t.focusY = focus.second;
        t.rasterWidth = request.rasterWidth;
        t.rasterHeight = request.rasterHeight;
        t.raster.assign(static_cast<std::size_t>(t.rasterWidth) * t.rasterHeight, ' ');
        viewIndex_.emplace(viewKey(ref.draw, ref.triangle), views_.size());
        views_.push_back(std::move(t));
        viewSeen_.push_back(false);
    }
}

// ---- the frame's hooks ----

void TraceRecorder::onPlannedDraw(const PlannedDraw& call, const PreparedDraw& draw) {
    beginCall(call.draw, call.state, call.indices, call.vertices.size(), draw.transparent, call.triangles);
}

void TraceRecorder::beginCall(std::uint32_t draw, const DrawState& state,
                              std::span<const std::uint32_t> indices, std::size_t vertexCount,
                              bool transparent, std::span<const std::uint32_t> triangles) {
    ++callCount_;
    call_ = {draw, state, indices, triangles};
    transparent_ = transparent;
    const auto callTriangles = static_cast<std::uint32_t>(indices.size() / 3);
    // The call-local number of each of the draw's triangles (runs of transparent triangles).
    localOf_.clear();
    if (!triangles.empty()) {
        const std::uint32_t drawTriangles = *std::max_element(triangles.begin(), triangles.end()) + 1;
        localOf_.assign(drawTriangles, 0xffffffffu);
        for (std::uint32_t t = 0; t < callTriangles; ++t)
            localOf_[triangles[t]] = t;
    }
    transparentBase_ = static_cast<std::uint32_t>(trace_.transparentOrder.size());
    if (transparent_)
        for (std::uint32_t t = 0; t < callTriangles; ++t)
            trace_.transparentOrder.push_back(refOf(draw, triangles.empty() ? t : triangles[t]));
    clip_.assign(vertexCount, vec4(0.0f));
    outcodes_.assign(vertexCount, 0);
    keepVaryings_ = std::any_of(views_.begin(), views_.end(),
                                [&](const TriangleTrace& view) { return view.ref.draw == draw; });
    varyingCount_ = 0;
    varyings_.clear();
}

void TraceRecorder::onVertex(std::uint32_t index, const vec4& clip, const float* varyings, int varyingCount,
                             std::uint8_t outcode) {
    clip_[index] = clip;
    outcodes_[index] = outcode;
    if (!keepVaryings_ || varyingCount <= 0 || !varyings) return;
    if (varyings_.empty()) {
        varyingCount_ = varyingCount;
        varyings_.assign(clip_.size() * static_cast<std::size_t>(varyingCount), 0.0f);
    }
    if (varyingCount != varyingCount_) return;
    std::copy(varyings, varyings + varyingCount, varyings_.begin() + std::ptrdiff_t(index) * varyingCount);
}

void TraceRecorder::onRejected(std::uint32_t triangle, TriangleFate fate) {
    forEachView(triangle, [&](TriangleTrace& view) {
        fillVertices(view, triangle);
        view.rejected = fate;
    });
    // A pixel history lists a rejected triangle when its vertices, projected (all in front of the
    // eye), box the pixel.
    const std::uint32_t local = localOf(triangle);
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    const Viewport& vp = call_.state.viewport;
    for (int k = 0; k < 3; ++k) {
        const vec4 p = clip_[call_.indices[3 * local + k]];
        if (!(p.w > 0.0f) || !std::isfinite(p.x) || !std::isfinite(p.y)) return;
        const double x = vp.x + (double(p.x) / p.w + 1.0) * 0.5 * vp.width;
        const double y = vp.y + (1.0 - double(p.y) / p.w) * 0.5 * vp.height;
        lo[0] = std::min(lo[0], x), hi[0] = std::max(hi[0], x);
        lo[1] = std::min(lo[1], y), hi[1] = std::max(hi[1], y);
    }
    const PixelFate pixelFate = fate == TriangleFate::NonFinite        ? PixelFate::NonFinite
                                : fate == TriangleFate::OutsideFrustum ? PixelFate::OutsideFrustum
                                                                       : PixelFate::ClippedAway;
    forEachTracedPixelIn(lo, hi, [&](std::size_t slot) { entry(slot, triangle).fate = pixelFate; });
}

void TraceRecorder::onAssembled(std::uint32_t triangle, const ClipPolygon& assembled) {
    forEachView(triangle, [&](TriangleTrace& view) { recordClipping(view, triangle, assembled); });
}

void TraceRecorder::recordClipping(TriangleTrace& view, std::uint32_t triangle,
                                   const ClipPolygon& assembled) {
    fillVertices(view, triangle);
    // The clipper once more on the same polygon, plane by plane in its own order, to show each cut,
    // against the draw's depth planes (reversed Z: 0 ≤ z ≤ w).
    const ClipDepthRange range = clipDepthRange(call_.state.depth.format);
    std::uint8_t planes = 0;
    for (int k = 0; k < 3; ++k)
        planes |= computeOutcode(assembled.vertices[k].position, range);
    if (planes == 0) return;
    static constexpr std::uint8_t kOrder[] = {kClipLeft, kClipRight, kClipBottom, kClipTop,
                                              kClipNear, kClipFar,   kClipW};
    ClipPolygon polygon = assembled;
    for (std::uint8_t plane : kOrder) {
        if (!(planes & plane) || polygon.count == 0) continue;
        const ClipPolygon before = polygon;
        clipPolygon(polygon, plane, range, call_.state.depth.fromW);
        if (!(polygon.planesCut & plane)) continue;
        ClipStep step;
        step.plane = plane;
        for (int i = 0; i < before.count; ++i) {
            const int j = (i + 1) % before.count;
            const float di = planeDistance(before.vertices[i].position, plane, range);
            const float dj = planeDistance(before.vertices[j].position, plane, range);
            if ((di >= 0.0f) == (dj >= 0.0f)) continue;
            // As the clipper computes it: from the inside vertex towards the outside one.
            const int from = di >= 0.0f ? i : j, to = di >= 0.0f ? j : i;
            const float dFrom = di >= 0.0f ? di : dj, dTo = di >= 0.0f ? dj : di;
            ClipStep::NewVertex made;
            made.from = from;
            made.to = to;
            made.t = clipEdgeT(dFrom, dTo);
            made.position = clipEdgePoint(before.vertices[from].position, before.vertices[to].position,
                                          made.t, call_.state.depth.fromW, range, &made.depthFromW);
            step.made.push_back(made);
        }
        // The clipper's output order (clip.cpp's clipAgainstPlane): walking the edges i → i + 1, an
        // inside vertex is kept, then the vertex made where the edge crosses the plane.
        for (int i = 0, made = 0; i < before.count; ++i) {
            const int j = (i + 1) % before.count;
            const bool inside = planeDistance(before.vertices[i].position, plane, range) >= 0.0f;
            if (inside) step.origin.push_back(i);
            if (inside != (planeDistance(before.vertices[j].position, plane, range) >= 0.0f))
                step.origin.push_back(-1 - made++);
        }
        for (int i = 0; i < polygon.count; ++i) {
            step.polygon.push_back(polygon.vertices[i].position);
            step.varyings.emplace_back(polygon.vertices[i].varyings.begin(),
                                       polygon.vertices[i].varyings.begin() + polygon.varyingCount);
        }
        if (step.origin.size() != step.polygon.size()) step.origin.clear();  // emptied (non-finite)
        view.clipSteps.push_back(std::move(step));
    }
}

void TraceRecorder::onSetup(std::uint32_t triangle, const WindowTriangle& window, TriangleFate fate,
                            const TriangleSetup& setup) {
    if (fate == TriangleFate::Drawn) {
        // The corners' 1/w, for the pixels this setup covers (a clipped triangle has several setups),
        // when its varyings are interpolated perspective-correct.
        const double lo[2] = {setup.minX + 0.5, setup.minY + 0.5},
                     hi[2] = {setup.maxX + 0.5, setup.maxY + 0.5};
        const bool exchanged = signedDoubleArea(window) < 0;
        forEachTracedPixelIn(lo, hi, [&](std::size_t slot) {
            const PixelTrace& p = trace_.pixels[slot];
            if (!coverageAt(setup, p.x, p.y).covered) return;
            TriangleAtPixel& at = entry(slot, triangle);
            at.setupExchanged = exchanged;
            if (setup.perspective)
                at.cornerInvW = vec3(setup.invW0, setup.invW0 + setup.dInvW1, setup.invW0 + setup.dInvW2);
        });
    }
    forEachView(triangle, [&](TriangleTrace& view) {
        fillVertices(view, triangle);
        WindowPiece piece;
        piece.vertices = window.vertices;
        piece.signedDoubleArea = signedDoubleArea(window);
        piece.fate = fate;
        piece.setup = setup;
        if (fate == TriangleFate::Culled) view.culled = true;
        if (fate == TriangleFate::Drawn) {
            // The binning stage once more on this setup, to list its tiles.
            const TileGrid grid = makeTileGrid(call_.state.viewport, tileSize_);
            std::vector<std::vector<std::uint32_t>> bins(static_cast<std::size_t>(grid.count()));
            binTriangle(grid, setup, 0, bins);
            for (int t = 0; t < grid.count(); ++t)
                if (!bins[t].empty()) piece.tiles.push_back(t);
            view.gridColumns = grid.columns;
        }
        view.pieces.push_back(std::move(piece));
    });
    if (fate != TriangleFate::ZeroArea && fate != TriangleFate::MissesSamples) return;
    // These never reach the rasterizer: list them where their snapped box holds the pixel centre.
    double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
    for (const WindowVertex& v : window.vertices) {
        const double x = double(v.xFixed) / kFixedOne, y = double(v.yFixed) / kFixedOne;
        lo[0] = std::min(lo[0], x), hi[0] = std::max(hi[0], x);
        lo[1] = std::min(lo[1], y), hi[1] = std::max(hi[1], y);
    }
    const PixelFate pixelFate =
        fate == TriangleFate::ZeroArea ? PixelFate::ZeroArea : PixelFate::MissesSamples;
    forEachTracedPixelIn(lo, hi, [&](std::size_t slot) {
        TriangleAtPixel& e = entry(slot, triangle);
        if (!e.coverage) e.fate = pixelFate;  // another piece of a clipped triangle may cover it
    });
}

void TraceRecorder::onCoverage(const CoverageEvent& event) {
    forEachView(event.triangle, [&](TriangleTrace& view) {
        const int column = event.x - (view.focusX - view.rasterWidth / 2);
        const int row = event.y - (view.focusY - view.rasterHeight / 2);
        if (column >= 0 && row >= 0 && column < view.rasterWidth && row < view.rasterHeight) {
            char& c = view.raster[static_cast<std::size_t>(row) * view.rasterWidth + column];
            const char mark = event.covered ? (event.tiesIncluded() ? '+' : '#')
                              : (event.excludingEdges & ~event.tiesExcluded()) == 0 ? ':'
                                                                                    : '.';
            if (c == ' ' || c == '.' || (c == ':' && mark != '.')) c = mark;  // pieces of a clipped one
        }
        if (event.x == view.focusX && event.y == view.focusY && (!view.focusCoverage || event.covered))
            view.focusCoverage = event;
    });
    const int slot = slotOf(event.x, event.y);
    if (slot < 0) return;
    TriangleAtPixel& e = entry(static_cast<std::size_t>(slot), event.triangle);
    if (e.coverage && e.coverage->covered) return;  // a piece of a clipped triangle covered it already
    e.coverage = event;
    if (event.culled)
        e.fate = PixelFate::Culled;
    else if (event.covered)
        e.fate = PixelFate::Written;  // until its fragment says otherwise
    else if ((event.excludingEdges & ~event.tiesExcluded()) == 0)
        e.fate = PixelFate::LostTie;  // excluded only by ties on edges that are not top-left
    else
        e.fate = PixelFate::OutsideEdge;
}

void TraceRecorder::onFragment(const FragmentEvent& event) {
    const int slot = slotOf(event.x, event.y);
    if (slot < 0) return;
    TriangleAtPixel& e = entry(static_cast<std::size_t>(slot), event.triangle);
    e.fragment = event;
    switch (event.fate) {
        case FragmentFate::Written:
            e.fate = call_.state.blend == BlendMode::Replace ? PixelFate::Written : PixelFate::Blended;
            break;
        case FragmentFate::DepthFailed:
            e.fate = PixelFate::DepthFailed;
            break;
        case FragmentFate::Discarded:
            e.fate = PixelFate::Discarded;
            break;
        case FragmentFate::Stored:
            e.fate = PixelFate::Stored;
            break;
        case FragmentFate::Dropped:
            e.fate = PixelFate::Dropped;
            break;
    }
}

void TraceRecorder::onResolve(const ResolveEvent& event) {
    const int slot = slotOf(event.x, event.y);
    if (slot < 0) return;
    PixelTrace& p = trace_.pixels[static_cast<std::size_t>(slot)];
    ResolveTrace resolve;
    resolve.colorBefore = event.colorBefore;
    resolve.fragments.assign(event.fragments.begin(), event.fragments.end());
    for (const TriangleAtPixel& e : p.triangles)
        if (e.fate == PixelFate::Stored) resolve.submitted.push_back(e.ref);
    p.resolve = std::move(resolve);
}

// ---- after the frame ----

FrameTrace TraceRecorder::finish(const Framebuffer& target) {
    for (PixelTrace& p : trace_.pixels) {
        // Front-end verdicts come before the back end's: back into submission order.
        std::stable_sort(p.triangles.begin(), p.triangles.end(),
                         [](const TriangleAtPixel& a, const TriangleAtPixel& b) {
                             return std::pair(a.call, a.inCall) < std::pair(b.call, b.inCall);
                         });
        completeHistory(p, target);
    }
    for (std::size_t k = 0; k < views_.size(); ++k)
        if (viewSeen_[k]) trace_.triangles.push_back(std::move(views_[k]));
    return std::move(trace_);
}

int TraceRecorder::slotOf(int x, int y) const {
    if (x < 0 || y < 0 || x >= frame_.width ||
        static_cast<std::size_t>(y) * frame_.width + x >= pixelSlot_.size())
        return -1;
    return pixelSlot_[static_cast<std::size_t>(y) * frame_.width + x];
}

std::uint32_t TraceRecorder::localOf(std::uint32_t triangle) const {
    return localOf_.empty() ? triangle : localOf_[triangle];
}

// The history entry of this call's `triangle` at traced pixel `slot`, made when it has none.
TriangleAtPixel& TraceRecorder::entry(std::size_t slot, std::uint32_t triangle) {
    PixelTrace& p = trace_.pixels[slot];
    // Events of one triangle at one pixel arrive together (pieces, then its fragment): look from the
    // back.
    for (auto it = p.triangles.rbegin(); it != p.triangles.rend(); ++it)
        if (it->call == callCount_ - 1 && it->ref.triangle == triangle && it->ref.draw == call_.draw)
            return *it;
        else if (it->call != callCount_ - 1)
            break;
    TriangleAtPixel e;
    e.ref = refOf(call_.draw, triangle);
    e.call = callCount_ - 1;
    e.depthCompare = call_.state.depth.testEnabled ? call_.state.depth.compare : CompareOp::Always;
    e.blend = call_.state.blend;
    e.transparent = transparent_;
    if (transparent_) e.sortPlace = transparentBase_ + localOf(triangle);
    e.inCall = localOf(triangle);
    p.triangles.push_back(e);
    return p.triangles.back();
}

void TraceRecorder::fillVertices(TriangleTrace& view, std::uint32_t triangle) {
    view.call = callCount_ - 1;
    view.state = call_.state;
    view.tileSize = tileSize_;
    const std::uint32_t local = localOf(triangle);
    for (int k = 0; k < 3; ++k) {
        const std::uint32_t vertex = call_.indices[3 * local + k];
        view.clipPositions[k] = clip_[vertex];
        view.outcodes[k] = outcodes_[vertex];
        if (!varyings_.empty()) {
            const auto first = varyings_.begin() + std::ptrdiff_t(vertex) * varyingCount_;
            view.vertexVaryings[k].assign(first, first + varyingCount_);
        }
    }
}

void TraceRecorder::completeHistory(PixelTrace& p, const Framebuffer& target) {
    if (p.x < 0 || p.y < 0 || p.x >= target.width() || p.y >= target.height()) return;
    p.finalColor = target.color(p.x, p.y);
    for (int c = 0; c < 3; ++c)
        p.finalBytes[c] = encodeChannel(p.finalColor[c], p.encoding);
    p.finalBytes[3] = toByte(p.finalColor.a, p.encoding.rounding);
    // Who wrote last, and who overwrote whom.
    std::optional<std::size_t> lastWriter;
    for (std::size_t i = 0; i < p.triangles.size(); ++i) {
        TriangleAtPixel& e = p.triangles[i];
        if (e.fate != PixelFate::Written && e.fate != PixelFate::Blended) continue;
        if (lastWriter) p.triangles[*lastWriter].overwrittenBy = e.ref;
        lastWriter = i;
    }
    p.producer = lastWriter;
    if (p.resolve && !p.resolve->fragments.empty()) {
        const ResolvedFragment& nearest = p.resolve->fragments.back();
        if (nearest.submission < p.resolve->submitted.size()) {
            const TriangleRef ref = p.resolve->submitted[nearest.submission];
            for (std::size_t i = 0; i < p.triangles.size(); ++i)
                if (p.triangles[i].ref == ref && p.triangles[i].fate == PixelFate::Stored) p.producer = i;
        }
    }
    // A tie lost: the neighbour that covers the pixel instead (in the same draw call first).
    for (TriangleAtPixel& e : p.triangles) {
        if (e.fate != PixelFate::LostTie) continue;
        for (int sameCall = 1; sameCall >= 0 && !e.tieOwner; --sameCall)
            for (const TriangleAtPixel& other : p.triangles)
                if (other.coverage && other.coverage->covered && !other.coverage->culled &&
                    (other.call == e.call) == bool(sameCall)) {
                    e.tieOwner = other.ref;
                    break;
                }
    }
}

std::uint32_t triangleCount(const PreparedScene& prepared) {
    std::size_t count = 0;
    for (const PreparedDraw& draw : prepared.draws)
        count += draw.indices.size() / 3;
    return static_cast<std::uint32_t>(count);
}

std::optional<TriangleRef> triangleByNumber(const PreparedScene& prepared, std::uint32_t number) {
    std::uint32_t first = 0;
    for (std::uint32_t d = 0; d < prepared.draws.size(); ++d) {
        const auto count = static_cast<std::uint32_t>(prepared.draws[d].indices.size() / 3);
        if (number < first + count) return TriangleRef{number, d, number - first};
        first += count;
    }
    return std::nullopt;
}

TriangleRef triangleOf(const PreparedScene& prepared, std::uint32_t draw, std::uint32_t triangle) {
    std::uint32_t first = 0;
    for (std::uint32_t d = 0; d < draw; ++d)
        first += static_cast<std::uint32_t>(prepared.draws[d].indices.size() / 3);
    return TriangleRef{first + triangle, draw, triangle};
}

FrameShape frameShape(const PreparedScene& prepared) {
    FrameShape shape;
    shape.width = prepared.scene.width;
    shape.height = prepared.scene.height;
    shape.clearColor = prepared.clearColor;
    shape.encoding = prepared.encoding;
    std::uint32_t first = 0;
    for (const PreparedDraw& draw : prepared.draws) {
        shape.firstNumberOfDraw.push_back(first);
        first += static_cast<std::uint32_t>(draw.indices.size() / 3);
    }
    return shape;
}

FrameTrace traceFrame(const PreparedScene& prepared, Framebuffer& target, DrawContext& context,
                      const TraceRequest& request, std::uint8_t terms) {
    TraceRecorder recorder(request, frameShape(prepared), context.tileSize);
    FrameMemory memory;
    renderFrameWatched(prepared, target, context, memory, recorder, terms);
    FrameTrace trace = recorder.finish(target);
    // The traced triangles' corners as the model gives them, and the matrices that moved them.
    for (TriangleTrace& t : trace.triangles) {
        const PreparedDraw& draw = prepared.draws[t.ref.draw];
        for (int k = 0; k < 3; ++k) {
            t.indices[k] = draw.indices[3 * t.ref.triangle + k];
            t.objectPositions[k] = draw.vertices[t.indices[k]].position;
            t.objectNormals[k] = draw.vertices[t.indices[k]].normal;
        }
        t.worldFromObject = draw.worldFromObject;
        t.viewFromWorld = prepared.camera.viewFromWorld;
        t.clipFromView = prepared.camera.clipFromView;
    }
    return trace;
}

}  // namespace facet::step

namespace facet::step {

namespace {

// Marks the pixels some fragment reached.
class CoverageMarker final : public FrameWatcher {
  public:
    CoverageMarker(std::vector<bool>& covered, int width) : covered(covered), width(width) {}
    std::vector<bool>& covered;
    int width;
    void onFragment(const FragmentEvent& e) override {
        if (e.fate == FragmentFate::Written || e.fate == FragmentFate::Stored)
            covered[static_cast<std::size_t>(e.y) * width + e.x] = true;
    }
};

}  // namespace

std::vector<bool> coveredPixels(const PreparedScene& prepared, DrawContext& context, std::uint8_t terms) {
    const int width = prepared.scene.width, height = prepared.scene.height;
    std::vector<bool> covered(static_cast<std::size_t>(width) * height, false);
    Framebuffer target(width, height);
    FrameMemory memory;
    CoverageMarker marker(covered, width);
    renderFrameWatched(prepared, target, context, memory, marker, terms);
    return covered;
}

std::optional<std::pair<int, int>> pixelNearestCentre(const std::vector<bool>& covered, int width,
                                                      int height) {
    std::optional<std::pair<int, int>> best;
    double bestDistance = 0;
    // Distances between pixel centres and the image centre, in pixels (twice, to stay in integers).
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            if (!covered[static_cast<std::size_t>(y) * width + x]) continue;
            const double dx = 2.0 * x + 1 - width, dy = 2.0 * y + 1 - height;
            const double d = dx * dx + dy * dy;
            if (!best || d < bestDistance) best = std::pair(x, y), bestDistance = d;
        }
    return best;
}

}  // namespace facet::step
