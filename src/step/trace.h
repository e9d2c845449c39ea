// The trace of the step-through mode: what the frame's draw calls did at some pixels and to some
// triangles, recorded by an observer (pipeline/observer.h) on the renderer's own renderFrame — the same
// draw() that `facet render` runs, so the trace shows exactly that render. Recording does not change the
// image: the framebuffer after a traced frame holds the same bytes as after an untraced one.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "pipeline/names.h"
#include "pipeline/types.h"
#include "render/renderer.h"
#include "step/screens.h"

namespace facet::step {

// What ended a triangle at one pixel, in the pixel history's words. The first ones are decided for the
// whole triangle before rasterization; the others at the pixel.
enum class PixelFate : std::uint8_t {
    NonFinite,       // a vertex position is NaN or infinite
    OutsideFrustum,  // all three vertices outside one clip plane (trivially rejected)
    ClippedAway,     // nothing was left of it after clipping
    ZeroArea,        // its snapped vertices lie on one line
    MissesSamples,   // its bounding box holds no pixel centre
    Culled,          // it faces away (or towards) the viewer and that side is culled
    OutsideEdge,     // the pixel centre lies outside one of its edges
    LostTie,         // the pixel centre lies exactly on an edge that is not top or left: a neighbour owns it
    DepthFailed,     // the depth test failed
    Discarded,       // the fragment shader discarded the fragment
    Dropped,         // exact transparency: its tile's fragment lists were full
    Written,         // its colour was written (replacing the colour before)
    Blended,         // its colour was blended with the colour before
    Stored,          // appended to the pixel's fragment list (exact transparency), composited after the frame
};
inline constexpr EnumName<PixelFate> kPixelFateNames[] = {{PixelFate::NonFinite, "non-finite"},
                                                          {PixelFate::OutsideFrustum, "outside-frustum"},
                                                          {PixelFate::ClippedAway, "clipped-away"},
                                                          {PixelFate::ZeroArea, "zero-area"},
                                                          {PixelFate::MissesSamples, "misses-samples"},
                                                          {PixelFate::Culled, "culled"},
                                                          {PixelFate::OutsideEdge, "outside-edge"},
                                                          {PixelFate::LostTie, "lost-tie"},
                                                          {PixelFate::DepthFailed, "depth-failed"},
                                                          {PixelFate::Discarded, "discarded"},
                                                          {PixelFate::Dropped, "dropped"},
                                                          {PixelFate::Written, "written"},
                                                          {PixelFate::Blended, "blended"},
                                                          {PixelFate::Stored, "stored"}};
constexpr std::span<const EnumName<PixelFate>> enumNames(PixelFate) {
    return kPixelFateNames;
}

// One triangle whose bounding box holds the pixel, and what became of it there.
struct TriangleAtPixel {
    TriangleRef ref;
    std::uint32_t call = 0;    // the frame's draw call that drew it (submission order)
    std::uint32_t inCall = 0;  // its place in that call (a transparent run has some of its draw's triangles)
    PixelFate fate = PixelFate::OutsideEdge;
    std::optional<CoverageEvent> coverage;  // the coverage test at the pixel's centre
    std::optional<FragmentEvent> fragment;  // the fragment, when the pixel was covered
    CompareOp depthCompare = CompareOp::Less;
    BlendMode blend = BlendMode::Replace;
    bool transparent = false;  // drawn in the transparent pass
    std::optional<std::uint32_t>
        sortPlace;  // transparent: its place in the back-to-front order (0: first drawn)
    std::optional<TriangleRef> tieOwner;       // LostTie: the triangle that covers the pixel instead
    std::optional<TriangleRef> overwrittenBy;  // Written or Blended: the next triangle that wrote the pixel
    // 1/w at the corners of the setup that covers the pixel, in its vertex order (the perspective
    // weights λ′ᵢ = λᵢ·(1/wᵢ) / (1/w) of the fragment's varyings).
    std::optional<vec3> cornerInvW;
    // Whether the setup that covers the pixel exchanged its last two corners to make its area positive:
    // the fragment's weights are then in the order v0, v2, v1 of the triangle (or piece) as drawn.
    bool setupExchanged = false;
};

// Exact transparency: the pixel's fragment list as stored (submission order) and as composited.
struct ResolveTrace {
    vec4 colorBefore{0.0f};
    std::vector<ResolvedFragment> fragments;  // compositing order, farthest first
    std::vector<TriangleRef> submitted;       // the list as stored: element k is submission k's triangle
};

// A pixel's history through the frame.
struct PixelTrace {
    int x = 0, y = 0;
    vec4 clearColor{0.0f};
    std::vector<TriangleAtPixel> triangles;  // submission order
    std::optional<ResolveTrace> resolve;
    vec4 finalColor{0.0f};                     // the colour buffer after the frame (linear)
    std::array<std::uint8_t, 4> finalBytes{};  // as the 8-bit image file stores it (RGBA)
    ColorEncoding encoding;
    // The triangle whose fragment gave the pixel its final colour: the last one written or blended,
    // or under exact transparency the nearest one composited. Index into `triangles`.
    std::optional<std::size_t> producer;
};

// One window triangle of the traced triangle: the triangle itself, or one fan piece of what clipping
// left of it, with its setup and fate.
struct WindowPiece {
    std::array<WindowVertex, 3> vertices;
    std::int64_t signedDoubleArea = 0;  // before setup made it positive
    TriangleFate fate = TriangleFate::Drawn;
    TriangleSetup setup;     // when Drawn, or Culled (the setup it would have had)
    std::vector<int> tiles;  // Drawn: the tiles it was binned to (row-major tile numbers)
};

// One clip plane's cut of the polygon: the polygon after it, and the vertices it made.
struct ClipStep {
    std::uint8_t plane = 0;  // one ClipPlaneBit
    struct NewVertex {
        int from = 0, to = 0;     // the edge it lies on: vertices of the polygon before this plane
        float t = 0.0f;           // P = P_from + t·(P_to − P_from), t = d_from / (d_from − d_to)
        vec4 position{0.0f};      // clip space
        bool depthFromW = false;  // its z set from its w by the projection (clip.h, clipEdgePoint)
    };
    std::vector<NewVertex> made;
    std::vector<vec4> polygon;  // clip positions after this plane
    // Where each vertex of `polygon` came from: k ≥ 0 is vertex k of the polygon before this plane,
    // kept; −1 − k is made[k].
    std::vector<int> origin;
    // The varyings of each vertex of `polygon`, as the clipper interpolated them (with t, in clip
    // space): what the fan pieces' corners carry to the rasterizer.
    std::vector<std::vector<float>> varyings;
};

// The traced triangle through the front end.
struct TriangleTrace {
    TriangleRef ref;
    std::uint32_t call = 0;
    std::array<std::uint32_t, 3> indices{};  // its vertices in its draw
    std::array<vec3, 3> objectPositions{};
    std::array<vec3, 3> objectNormals{};
    mat4 worldFromObject{1.0f}, viewFromWorld{1.0f}, clipFromView{1.0f};
    std::array<vec4, 3> clipPositions{};  // the vertex shader's gl_Position
    // The vertex shader's other outputs at the corners: its varyings, as the pipeline received them.
    std::array<std::vector<float>, 3> vertexVaryings{};
    std::array<std::uint8_t, 3> outcodes{};
    std::optional<TriangleFate> rejected;  // NonFinite, OutsideFrustum or ClippedAway
    std::vector<ClipStep> clipSteps;       // only for a triangle some plane cut
    std::vector<WindowPiece> pieces;
    DrawState state;  // the draw call's
    int tileSize = 0;
    int gridColumns = 0;
    // Coverage around the focus pixel: rasterWidth × rasterHeight pixels centred on (focusX, focusY),
    // row-major: ' ' outside the bounding box, '.' not covered, '#' covered, ':' on an edge and excluded
    // by the fill rule, '+' on a top-left edge and included.
    int focusX = 0, focusY = 0;
    int rasterWidth = 0, rasterHeight = 0;
    std::vector<char> raster;
    std::optional<CoverageEvent> focusCoverage;
    bool culled = false;
};

// What to record in one frame.
struct TraceRequest {
    std::vector<std::pair<int, int>> pixels;   // their histories
    std::vector<TriangleRef> triangles;        // their views
    std::pair<int, int> focus{0, 0};           // the triangle views' raster is centred here,
    std::vector<std::pair<int, int>> focuses;  // or, when given, triangle k's around focuses[k]
    int rasterWidth = 35, rasterHeight = 15;   // odd: the focus pixel in the middle
};

struct FrameTrace {
    std::vector<PixelTrace> pixels;             // as requested
    std::vector<TriangleTrace> triangles;       // as requested, those that exist
    std::vector<TriangleRef> transparentOrder;  // the frame's transparent triangles, in drawn order
};

// What the recorder needs to know of the frame: its size, background, file encoding, and where each
// draw's triangles start in the step mode's numbering (the triangles of all draws, in order).
struct FrameShape {
    int width = 0, height = 0;
    vec4 clearColor{0.0f};
    ColorEncoding encoding;
    std::vector<std::uint32_t> firstNumberOfDraw;
};
FrameShape frameShape(const PreparedScene& prepared);

// The observer that records a trace: the frame's hooks (pipeline/observer.h, and onPlannedDraw)
// arrive here in submission order, on the calling thread. traceFrame below runs it on a frame of a
// scene (renderFrameWatched); a caller of draw() (a test with its own shader) calls beginCall before
// each draw call.
class TraceRecorder final : public FrameWatcher {
  public:
    TraceRecorder(const TraceRequest& request, const FrameShape& frame, int tileSize);

    // A draw call begins: which draw, its state, its index list (into `vertexCount` vertices), whether
    // it is of the transparent pass, and for a run of some of the draw's triangles their numbers.
    void beginCall(std::uint32_t draw, const DrawState& state, std::span<const std::uint32_t> indices,
                   std::size_t vertexCount, bool transparent = false,
                   std::span<const std::uint32_t> triangles = {});
    void onPlannedDraw(const PlannedDraw& call, const PreparedDraw& draw) override;

    void onVertex(std::uint32_t index, const vec4& clip, const float* varyings, int varyingCount,
                  std::uint8_t outcode) override;
    void onRejected(std::uint32_t triangle, TriangleFate fate) override;
    void onAssembled(std::uint32_t triangle, const ClipPolygon& assembled) override;
    void onSetup(std::uint32_t triangle, const WindowTriangle& window, TriangleFate fate,
                 const TriangleSetup& setup) override;
    void onCoverage(const CoverageEvent& event) override;
    void onFragment(const FragmentEvent& event) override;
    void onResolve(const ResolveEvent& event) override;

    // The frame is drawn: the histories completed from the colour buffer (the final colours and
    // bytes, who wrote last, who owns a lost tie). The triangle views' object-space corners and
    // matrices are left to the caller (traceFrame fills them from the scene).
    FrameTrace finish(const Framebuffer& target);

  private:
    struct Call {
        std::uint32_t draw = 0;
        DrawState state;
        std::span<const std::uint32_t> indices;
        std::span<const std::uint32_t> triangles;
    };
    int slotOf(int x, int y) const;
    std::uint32_t localOf(std::uint32_t triangle) const;
    TriangleRef refOf(std::uint32_t draw, std::uint32_t triangle) const {
        return {frame_.firstNumberOfDraw[draw] + triangle, draw, triangle};
    }
    TriangleAtPixel& entry(std::size_t slot, std::uint32_t triangle);
    static std::uint64_t viewKey(std::uint32_t draw, std::uint32_t triangle) {
        return (std::uint64_t{draw} << 32) | triangle;
    }
    // Calls f(view) for every view of this call's `triangle` (one per focus asked for).
    template <class F>
    void forEachView(std::uint32_t triangle, F&& f) {
        if (viewIndex_.empty()) return;
        const auto [first, last] = viewIndex_.equal_range(viewKey(call_.draw, triangle));
        for (auto it = first; it != last; ++it) {
            viewSeen_[it->second] = true;
            f(views_[it->second]);
        }
    }
    // Calls f(slot) for every traced pixel whose centre (x + ½, y + ½) lies in the window-space box
    // [lo, hi]: a triangle the rasterizer never saw is listed where its box holds the pixel.
    template <class F>
    void forEachTracedPixelIn(const double lo[2], const double hi[2], F&& f) {
        const double x0 = std::max(std::ceil(lo[0] - 0.5), 0.0),
                     x1 = std::min(std::floor(hi[0] - 0.5), frame_.width - 1.0);
        const double y0 = std::max(std::ceil(lo[1] - 0.5), 0.0),
                     y1 = std::min(std::floor(hi[1] - 0.5), frame_.height - 1.0);
        if (!(x0 <= x1 && y0 <= y1)) return;
        if ((x1 - x0 + 1) * (y1 - y0 + 1) > double(trace_.pixels.size())) {
            for (std::size_t slot = 0; slot < trace_.pixels.size(); ++slot) {
                const PixelTrace& p = trace_.pixels[slot];
                if (p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1) f(slot);
            }
            return;
        }
        for (int y = int(y0); y <= int(y1); ++y)
            for (int x = int(x0); x <= int(x1); ++x)
                if (const int slot = slotOf(x, y); slot >= 0) f(static_cast<std::size_t>(slot));
    }
    void recordClipping(TriangleTrace& view, std::uint32_t triangle, const ClipPolygon& assembled);
    void fillVertices(TriangleTrace& view, std::uint32_t triangle);
    void completeHistory(PixelTrace& p, const Framebuffer& target);

    FrameShape frame_;
    int tileSize_;
    FrameTrace trace_;
    std::vector<TriangleTrace> views_;
    std::vector<bool> viewSeen_;
    std::unordered_multimap<std::uint64_t, std::size_t> viewIndex_;  // viewKey(draw, triangle) → views_
    std::vector<int> pixelSlot_;  // per pixel of the frame: its index in trace_.pixels, or −1
    std::uint32_t callCount_ = 0;
    Call call_;
    bool transparent_ = false;
    std::uint32_t transparentBase_ = 0;
    std::vector<std::uint32_t> localOf_;  // a run's call-local number of each of its draw's triangles
    std::vector<vec4> clip_;              // the call's vertices in clip space (onVertex)
    bool keepVaryings_ = false;           // a traced triangle is of this call's draw: keep its varyings
    int varyingCount_ = 0;
    std::vector<float> varyings_;  // the call's vertices' varyings (onVertex), when kept
    std::vector<std::uint8_t> outcodes_;
};

// Draws one frame of `prepared` into `target` through renderFrame with the recorder, and returns what
// was asked for. `terms` as for renderFrame.
FrameTrace traceFrame(const PreparedScene& prepared, Framebuffer& target, DrawContext& context,
                      const TraceRequest& request, std::uint8_t terms = kAllTerms);

// The triangle numbering of the step mode: --triangle N counts the triangles of all draws, in order.
std::uint32_t triangleCount(const PreparedScene& prepared);
std::optional<TriangleRef> triangleByNumber(const PreparedScene& prepared, std::uint32_t number);
TriangleRef triangleOf(const PreparedScene& prepared, std::uint32_t draw, std::uint32_t triangle);

// Which pixels some fragment reached (written, blended or stored), row-major: one frame, recorded.
std::vector<bool> coveredPixels(const PreparedScene& prepared, DrawContext& context, std::uint8_t terms);

// The covered pixel nearest the image centre (the first in row order among equals); none when the
// frame is empty.
std::optional<std::pair<int, int>> pixelNearestCentre(const std::vector<bool>& covered, int width,
                                                      int height);

}  // namespace facet::step
