// The wire format: the plain structs that flow from one pipeline stage to the next, named for where
// they are in the pipeline. Each is printable (operator<<), so tests and the step mode show the same text.
//
//   vertex stage → ShadedVertices → primitive assembly → ClipPolygon (3 vertices) → clip → ClipPolygon
//   → viewport → WindowTriangle → cull + setup → TriangleSetup → bin (tiles) → rasterize → CoverageBlock
//   → depth test, interpolate, fragment shader, blend → Framebuffer
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <span>
#include <string>
#include <vector>

#include "glsl.h"
#include "names.h"
#include "state.h"

namespace facet {

// Varyings cross the middle of the pipeline as a flat float array (as in Mesa and SwiftShader), so the
// stages between the two shaders are ordinary functions, not templates on the user's Varyings struct.
inline constexpr int kMaxVaryingFloats = 32;

// ---- Vertex stage → primitive assembly -------------------------------------------------------------

// Outcode bits: which clip planes a clip-space position lies outside of (Cohen–Sutherland in
// homogeneous space). A triangle whose three outcodes share a bit is wholly outside that plane.
enum ClipPlaneBit : std::uint8_t {
    kClipLeft = 1 << 0,    // x < −w
    kClipRight = 1 << 1,   // x > w
    kClipBottom = 1 << 2,  // y < −w
    kClipTop = 1 << 3,     // y > w
    kClipNear = 1 << 4,    // z < −w
    kClipFar = 1 << 5,     // z > w
    kClipW = 1 << 6,       // w < kMinClipW: at or behind the eye, where dividing by w is meaningless
    kNonFinite = 1 << 7,   // a coordinate is NaN or ±Inf: the triangle is dropped, never clipped
};
inline constexpr std::uint8_t kAllClipPlanes = 0x7f;

// The smallest w a vertex may keep after clipping. Points with w ≤ 0 satisfy −w ≤ x ≤ w only at the
// origin, so the six frustum planes alone would still let w = 0 through to the divide.
inline constexpr float kMinClipW = 1e-9f;

// The vertex shader's output for every vertex of a draw, structure of arrays, reused between draws.
struct ShadedVertices {
    int varyingCount = 0;                // floats per vertex
    std::vector<vec4> positions;         // clip space (gl_Position)
    std::vector<float> varyings;         // varyingCount floats per vertex
    std::vector<std::uint8_t> outcodes;  // ClipPlaneBit mask per vertex

    std::size_t size() const { return positions.size(); }
    const float* varyingsOf(std::size_t vertex) const { return varyings.data() + vertex * varyingCount; }
};

// ---- Primitive assembly → clip → viewport -----------------------------------------------------------

struct ClipVertex {
    vec4 position;                                  // clip space
    std::array<float, kMaxVaryingFloats> varyings;  // the first varyingCount are used
};

// A convex polygon in clip space: a triangle as assembled, or what is left of it after clipping.
// Each plane adds at most one vertex, so 3 + 7 planes bound the count.
struct ClipPolygon {
    static constexpr int kCapacity = 3 + 7;
    int count = 0;
    int varyingCount = 0;
    std::uint8_t planesCut = 0;  // ClipPlaneBit mask of the planes that actually cut the polygon
    std::array<ClipVertex, kCapacity> vertices;
};

// ---- Viewport → cull / setup ------------------------------------------------------------------------

// A vertex after the perspective divide and the viewport transform.
struct WindowVertex {
    std::int64_t xFixed = 0;  // window x in pixels, fixed point with kFixedFractionBits fraction bits
    std::int64_t yFixed = 0;  // window y, same units, growing downwards
    float z = 0.0f;           // window depth in the viewport's depth range
    float invW = 0.0f;        // 1/w_clip, for perspective-correct interpolation
    vec2 window;              // unsnapped window position in pixels (for display and tests)
};

// Every window position is held with 8 fraction bits; RasterState::subpixelBits ≤ 8 chooses how finely
// vertices are snapped inside that grid. Budget: the viewport is at most kMaxViewportSide = 2^14 pixels,
// so a coordinate needs 14 + 8 = 22 bits and an edge function value (a product of two coordinate
// differences, plus a constant) stays below 2^46: int64 holds it with room to spare.
inline constexpr int kFixedFractionBits = 8;
inline constexpr std::int64_t kFixedOne = std::int64_t{1} << kFixedFractionBits;
inline constexpr int kMaxViewportSide = 1 << 14;

struct WindowTriangle {
    std::array<WindowVertex, 3> vertices;
    std::array<const float*, 3> varyings{};  // each points to varyingCount floats (not owned)
    int varyingCount = 0;
    // The first flatVaryingCount varyings are flat (GLSL `flat`): not interpolated, but taken from the
    // provoking vertex of the triangle as submitted, which clipping does not move (OpenGL's rule).
    int flatVaryingCount = 0;
    const float* provokingVaryings = nullptr;  // varyingCount floats; needed when flatVaryingCount > 0
};

// ---- Setup → rasterize → interpolate ----------------------------------------------------------------

// A top edge is horizontal with the triangle below it; a left edge has the triangle to its right.
// For an edge a → b of a triangle with positive orientation in y-down window space, that is
// dy < 0 (left), or dy = 0 and dx > 0 (top).
inline bool isTopLeft(std::int64_t dx, std::int64_t dy) {
    return dy < 0 || (dy == 0 && dx > 0);
}

// E(x, y) = a·x + b·y + c in fixed-point window coordinates, ≥ 0 on the inner side of the edge, for the
// edge from vertex p to vertex q: a = p.y − q.y, b = q.x − p.x, c = p.x·q.y − p.y·q.x. Window
// coordinates are clamped to ±2·kMaxViewportSide pixels (viewport.h), 24 bits in fixed point, so a and b
// fit in 32 bits (products with them are taken in 64); c, a product, needs 64. Small, so that a
// triangle's setup fits in two cache lines.
struct EdgeFunction {
    std::int32_t a = 0;
    std::int32_t b = 0;
    std::int64_t c = 0;
    std::int64_t at(std::int64_t xFixed, std::int64_t yFixed) const {
        return std::int64_t{a} * xFixed + std::int64_t{b} * yFixed + c;
    }
    // 0 for a top or left edge and −1 otherwise: testing E + bias ≥ 0 then includes samples exactly on
    // the edge only for top-left edges, so two triangles sharing an edge never both cover them. Read off
    // the edge's direction q − p, which is (b, −a).
    std::int64_t bias() const { return isTopLeft(b, -std::int64_t{a}) ? 0 : -1; }
};

// Everything the rasterizer and the interpolator need for one triangle, computed once. Two cache lines,
// aligned: the back end reads the setups of a tile's triangles one after another, often on another core
// than the one that wrote them.
struct alignas(64) TriangleSetup {
    // edges[i] is the edge opposite vertex i; its value at a sample, divided by doubleArea,
    // is vertex i's barycentric weight λᵢ.
    std::array<EdgeFunction, 3> edges;
    std::int64_t doubleArea = 0;  // twice the signed area in fixed units², made positive by setup
    bool frontFacing = true;
    bool perspective = true;
    int minX = 0, minY = 0, maxX = -1, maxY = -1;  // pixel bounds, inclusive, clamped to the viewport
    std::uint32_t triangle = 0;                    // index of the triangle in its draw

    // Attribute planes in barycentric form: value = v0 + λ1·d1 + λ2·d2.
    float z0 = 0, dz1 = 0, dz2 = 0;           // window depth (affine in screen space)
    float invW0 = 0, dInvW1 = 0, dInvW2 = 0;  // 1/w
    int varyingCount = 0;
    int flatVaryingCount = 0;  // the first ones: constant, their differences 0
    // Where this setup's varying planes start in the array of planes that holds them (the front end's
    // SetupChunk::varyingPlanes; 0 for planes setupTriangle wrote to a caller's buffer). With n =
    // varyingCount, three rows of n floats: [k] varying k's value at v0, [n + k] and [2n + k] its
    // differences to v1 and v2 (rows, not triples, so that setup computes each row eight varyings at a
    // time); premultiplied by 1/w when interpolation is perspective-correct. An offset, not a pointer,
    // so a setup stays small whatever the shader and a copy of it never dangles when the array grows.
    std::uint32_t varyingPlaneOffset = 0;

    // The pixel bounds hold no pixel whose sample the triangle could cover (set-up's MissesSamples).
    bool boxEmpty() const { return minX > maxX || minY > maxY; }
};
static_assert(sizeof(TriangleSetup) == 128, "a triangle's setup is two cache lines");

// The rasterizer's unit of work: an 8×8 block of pixels with one coverage bit per pixel.
// Bit (8·row + column) is pixel (x + column, y + row). Blocks sit on multiples of 8 in the framebuffer,
// so how the screen is cut into tiles never changes what a block computes.
inline constexpr int kBlockSize = 8;

struct CoverageBlock {
    int x = 0;                  // first column: a multiple of kBlockSize, or placed (rasterize.h)
    int y = 0;                  // first row: likewise
    std::uint64_t mask = 0;     // covered samples inside the triangle, the viewport and the tile
    bool fullyCovered = false;  // every sample of the block is inside the triangle (no edge test ran)
};

// An inclusive rectangle of pixels.
struct PixelRect {
    int minX = 0, minY = 0, maxX = -1, maxY = -1;
    bool empty() const { return minX > maxX || minY > maxY; }
};

inline bool overlaps(const PixelRect& a, const PixelRect& b) {
    return !a.empty() && !b.empty() && a.minX <= b.maxX && b.minX <= a.maxX && a.minY <= b.maxY &&
           b.minY <= a.maxY;
}

// ---- Fragment → output -------------------------------------------------------------------------------

// The rasterizer's decision at one pixel's sample for one triangle, edge by edge: a pixel history's view
// of coverage. Edge i is opposite vertex i (TriangleSetup::edges). A sample exactly on an edge (Eᵢ = 0,
// a tie) is inside only when that edge is a top or left edge (the top-left fill rule), so two
// triangles sharing the edge never both cover it.
struct CoverageEvent {
    int x = 0, y = 0;
    std::uint32_t triangle = 0;                // index of the triangle in the draw
    std::array<std::int64_t, 3> edgeValues{};  // Eᵢ at the sample, unbiased: > 0 inside, 0 on the edge
    std::uint8_t tiedEdges = 0;                // bit i: the sample lies exactly on edge i
    std::uint8_t topLeftEdges = 0;             // bit i: edge i is a top or left edge
    std::uint8_t excludingEdges = 0;           // bit i: edge i puts the sample outside (Eᵢ + biasᵢ < 0)
    bool covered = false;                      // no edge excludes the sample
    bool culled = false;  // the triangle was culled for its facing: what it would have covered

    // Ties the fill rule settled: included (on a top-left edge) and excluded (on another edge).
    std::uint8_t tiesIncluded() const { return tiedEdges & topLeftEdges; }
    std::uint8_t tiesExcluded() const { return tiedEdges & static_cast<std::uint8_t>(~topLeftEdges); }
};

// What happened to one fragment (a pixel history verdict, in the step mode's vocabulary).
// Stored: appended to the pixel's fragment list (FragmentOutput::AppendToLists), the colour buffer
// untouched until the lists are resolved; Dropped: not stored, its tile's node pool being full.
enum class FragmentFate : std::uint8_t { Written, DepthFailed, Discarded, Stored, Dropped };
inline constexpr EnumName<FragmentFate> kFragmentFateNames[] = {{FragmentFate::Written, "written"},
                                                                {FragmentFate::DepthFailed, "depth-failed"},
                                                                {FragmentFate::Discarded, "discarded"},
                                                                {FragmentFate::Stored, "stored"},
                                                                {FragmentFate::Dropped, "dropped"}};
constexpr std::span<const EnumName<FragmentFate>> enumNames(FragmentFate) {
    return kFragmentFateNames;
}

struct FragmentEvent {
    int x = 0, y = 0;
    std::uint32_t triangle = 0;  // index of the triangle in the draw (index / 3)
    float depth = 0.0f;          // the fragment's window depth
    float depthBefore = 0.0f;    // the depth buffer before this fragment
    FragmentFate fate = FragmentFate::Written;
    vec4 shaded{0.0f};  // the fragment shader's output (when it ran and did not discard)
    vec4 colorBefore{0.0f};
    vec4 colorAfter{0.0f};
    // The interpolation stage's inputs and outputs at the pixel's sample (for every fate).
    // λ0, λ1, λ2 (λ0 = 1 − λ1 − λ2), from the exact edge values, for the setup's vertex order: the
    // window triangle's, with v1 and v2 exchanged when its signed area was negative (triangle_setup).
    vec3 barycentrics{0.0f};
    float invW = 0.0f;  // 1/w_clip, affine in screen space: the perspective weight
    int varyingCount = 0;
    std::array<float, kMaxVaryingFloats> varyings{};  // the interpolated varyings (the shader's input)
    // ∂u/∂x, ∂v/∂x, ∂u/∂y, ∂v/∂y of the shader's texture coordinates (its derivative varying, which
    // trilinear filtering reads); zero for a shader without one.
    std::array<float, 4> uvDerivatives{};
};

// One fragment of a pixel's list as resolveFragmentLists composites it (fragment_lists.h).
struct ResolvedFragment {
    std::uint32_t submission = 0;  // its place in the pixel's list, oldest first
    float depth = 0.0f;            // window depth, the sort key
    BlendMode blend = BlendMode::Replace;
    vec4 color{0.0f};       // the fragment shader's output
    vec4 colorAfter{0.0f};  // the pixel's colour once this fragment is blended over it
};

// The resolve of one pixel: its fragments in compositing order (farthest first, equal depths in
// submission order), each blended with its own mode over the colour before.
struct ResolveEvent {
    int x = 0, y = 0;
    vec4 colorBefore{0.0f};
    std::span<const ResolvedFragment> fragments;  // valid during the hook only
};

// Why a triangle produced no fragments.
enum class TriangleFate : std::uint8_t {
    Drawn,
    NonFinite,
    OutsideFrustum,
    ClippedAway,
    ZeroArea,
    MissesSamples,  // its bounding box holds no pixel centre
    Culled,
};
inline constexpr EnumName<TriangleFate> kTriangleFateNames[] = {
    {TriangleFate::Drawn, "drawn"},
    {TriangleFate::NonFinite, "non-finite"},
    {TriangleFate::OutsideFrustum, "outside-frustum"},
    {TriangleFate::ClippedAway, "clipped-away"},
    {TriangleFate::ZeroArea, "zero-area"},
    {TriangleFate::MissesSamples, "misses-samples"},
    {TriangleFate::Culled, "culled"}};
constexpr std::span<const EnumName<TriangleFate>> enumNames(TriangleFate) {
    return kTriangleFateNames;
}

// Counters for one draw; cheap enough to keep always.
struct DrawStats {
    std::uint64_t vertices = 0;                 // vertex shader invocations
    std::uint64_t triangles = 0;                // triangles submitted
    std::uint64_t trianglesClipped = 0;         // crossed a frustum plane and went through the clipper
    std::uint64_t trianglesRejected = 0;        // non-finite, outside the frustum, or clipped away
    std::uint64_t trianglesCulled = 0;          // back/front-face culled
    std::uint64_t trianglesZeroArea = 0;        // zero area once snapped to fixed point
    std::uint64_t trianglesMissingSamples = 0;  // no pixel centre inside their bounding box
    std::uint64_t trianglesRasterized = 0;      // window triangles handed to the rasterizer (after clipping)
    std::uint64_t patchWalks = 0;  // of a triangle's walks over the tiles it touches, those of a few pixels'
                                   // done as patches (back end: drawAsPatches)
    std::uint64_t fragmentsShaded = 0;      // fragment shader invocations
    std::uint64_t fragmentsShadedBy16 = 0;  // of them, shaded sixteen at a time (two batches a call: wide.h)
    std::uint64_t fragmentsDepthFailed = 0;
    std::uint64_t fragmentsDiscarded = 0;
    std::uint64_t fragmentsWritten = 0;
    std::uint64_t fragmentsStored = 0;  // appended to fragment lists (FragmentOutput::AppendToLists)
    std::uint64_t tilesDrawn = 0;       // screen tiles the back end visited: those some triangle touches

    DrawStats& operator+=(const DrawStats& other);
};

std::ostream& operator<<(std::ostream& os, const ClipVertex& v);  // position only
std::ostream& operator<<(std::ostream& os, const ClipPolygon& polygon);
std::ostream& operator<<(std::ostream& os, const WindowVertex& v);
std::ostream& operator<<(std::ostream& os, const WindowTriangle& triangle);
std::ostream& operator<<(std::ostream& os, const EdgeFunction& edge);
std::ostream& operator<<(std::ostream& os, const TriangleSetup& setup);
std::ostream& operator<<(std::ostream& os, const CoverageBlock& block);
std::ostream& operator<<(std::ostream& os, const CoverageEvent& event);
std::ostream& operator<<(std::ostream& os, const ResolveEvent& event);
std::ostream& operator<<(std::ostream& os, FragmentFate fate);
std::ostream& operator<<(std::ostream& os, const FragmentEvent& event);
std::ostream& operator<<(std::ostream& os, TriangleFate fate);
std::ostream& operator<<(std::ostream& os, const DrawStats& stats);
std::string clipPlaneNames(std::uint8_t planes);  // "near+left", or "none"

}  // namespace facet
