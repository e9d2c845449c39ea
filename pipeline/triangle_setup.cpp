#include "triangle_setup.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "depth_format.h"
#include "sample_position.h"

namespace facet {

namespace {

// The edge function of edge a → b: E(p) = signedDoubleArea(a, b, p) written as a·x + b·y + c.
EdgeFunction makeEdge(const WindowVertex& from, const WindowVertex& to) {
    EdgeFunction e;
    e.a = static_cast<std::int32_t>(from.yFixed - to.yFixed);
    e.b = static_cast<std::int32_t>(to.xFixed - from.xFixed);
    e.c = from.xFixed * to.yFixed - from.yFixed * to.xFixed;
    return e;
}

// Varyings [first, last) of the planes' three rows: the value at v0 and the differences to v1 and v2 of
// a·s (s = 1/w when perspective-correct, else 1). Restrict-qualified, so that the compiler computes
// several varyings per instruction (the rows never overlap each other nor the vertices' varyings); each
// value is the same product and difference either way.
void writePlaneRows(const float* __restrict a0, const float* __restrict a1, const float* __restrict a2,
                    float s0, float s1, float s2, int first, int last, float* __restrict atV0,
                    float* __restrict toV1, float* __restrict toV2) {
    for (int k = first; k < last; ++k) {
        const float p0 = a0[k] * s0;
        atV0[k] = p0;
        toV1[k] = a1[k] * s1 - p0;
        toV2[k] = a2[k] * s2 - p0;
    }
}

// The bounding box of the pixels whose sample (sample_position.h) may be inside, clamped to the
// viewport and to the fixed-point budget before any loop runs.
[[gnu::always_inline]] inline void setBoundingBox(const WindowTriangle& triangle, const DrawState& state,
                                                  TriangleSetup& setup) {
    const WindowVertex& t0 = triangle.vertices[0];
    const WindowVertex& t1 = triangle.vertices[1];
    const WindowVertex& t2 = triangle.vertices[2];
    const std::int64_t minXf = std::min(std::min(t0.xFixed, t1.xFixed), t2.xFixed);
    const std::int64_t maxXf = std::max(std::max(t0.xFixed, t1.xFixed), t2.xFixed);
    const std::int64_t minYf = std::min(std::min(t0.yFixed, t1.yFixed), t2.yFixed);
    const std::int64_t maxYf = std::max(std::max(t0.yFixed, t1.yFixed), t2.yFixed);
    // Multisampling: the pixels some sample of which may be inside, those whose centre lies within the
    // samples' reach of the triangle's extent.
    const Viewport& vp = state.viewport;
    const std::int64_t reach = sampleReachFixed(state.samples);
    setup.minX = static_cast<int>(std::max<std::int64_t>(firstPixelSampledFrom(minXf - reach), vp.x));
    setup.minY = static_cast<int>(std::max<std::int64_t>(firstPixelSampledFrom(minYf - reach), vp.y));
    setup.maxX =
        static_cast<int>(std::min<std::int64_t>(lastPixelSampledUpTo(maxXf + reach), vp.x + vp.width - 1));
    setup.maxY =
        static_cast<int>(std::min<std::int64_t>(lastPixelSampledUpTo(maxYf + reach), vp.y + vp.height - 1));
}

// The varyings' planes in barycentric form (value = v0 + λ1·(v1 − v0) + λ2·(v2 − v0), of a·s with s =
// 1/w when perspective-correct, else 1), vertices in `order`, into varyingPlanes' three rows
// (TriangleSetup::varyingPlaneOffset): values at v0, differences to v1, to v2; flat varyings take the
// provoking vertex's value.
[[gnu::always_inline]] inline void writeVaryingPlanes(const WindowTriangle& triangle,
                                                      const std::array<int, 3>& order, TriangleSetup& setup,
                                                      float* varyingPlanes) {
    const WindowVertex& v0 = triangle.vertices[order[0]];
    const WindowVertex& v1 = triangle.vertices[order[1]];
    const WindowVertex& v2 = triangle.vertices[order[2]];
    setup.varyingCount = triangle.varyingCount;
    const float* a0 = triangle.varyings[order[0]];
    const float* a1 = triangle.varyings[order[1]];
    const float* a2 = triangle.varyings[order[2]];
    const float s0 = setup.perspective ? v0.invW : 1.0f;
    const float s1 = setup.perspective ? v1.invW : 1.0f;
    const float s2 = setup.perspective ? v2.invW : 1.0f;
    setup.flatVaryingCount = triangle.flatVaryingCount;
    const int n = triangle.varyingCount;
    float* const atV0 = varyingPlanes;
    float* const toV1 = varyingPlanes + n;
    float* const toV2 = varyingPlanes + 2 * n;
    for (int k = 0; k < triangle.flatVaryingCount; ++k) {
        atV0[k] = triangle.provokingVaryings[k];
        toV1[k] = 0.0f;
        toV2[k] = 0.0f;
    }
    writePlaneRows(a0, a1, a2, s0, s1, s2, triangle.flatVaryingCount, n, atV0, toV1, toV2);
}

}  // namespace

float depthOffset(const TriangleSetup& setup, const DepthOffset& offset, DepthBufferFormat format) {
    // z = z0 + λ1·dz1 + λ2·dz2 with λi = Ei(x, y) / doubleArea, Ei = a·x + b·y + c in fixed units:
    // ∂z/∂x = (dz1·a1 + dz2·a2) · kFixedOne / doubleArea per pixel, and likewise with b for y.
    const double perPixel = double(kFixedOne) / double(setup.doubleArea);
    const double dzdx =
        (setup.dz1 * double(setup.edges[1].a) + setup.dz2 * double(setup.edges[2].a)) * perPixel;
    const double dzdy =
        (setup.dz1 * double(setup.edges[1].b) + setup.dz2 * double(setup.edges[2].b)) * perPixel;
    const double slope = std::max(std::abs(dzdx), std::abs(dzdy));
    const float resolution = withDepthFormat(format, [](auto f) { return decltype(f)::kResolution; });
    return float(offset.factor * slope + offset.units * double(resolution));
}

TriangleFate setupTriangle(const WindowTriangle& triangle, const DrawState& state, TriangleSetup& setup,
                           float* varyingPlanes) {
    // Cull on the snapped area and on facing, before the bounding box is worked out: half of a closed
    // mesh goes here.
    const std::int64_t area = signedDoubleArea(triangle);
    const TriangleFate fate = areaFate(area, state.raster);
    if (fate == TriangleFate::ZeroArea) return fate;
    setup.frontFacing = isFrontFacing(area, state.raster.frontFace);
    if (fate == TriangleFate::Culled) return fate;
    setBoundingBox(triangle, state, setup);

    // A triangle between sample points covers none: common for the sub-pixel triangles of dense meshes.
    if (setup.boxEmpty()) return TriangleFate::MissesSamples;

    // Make the orientation positive by swapping v1 and v2, so every edge function is ≥ 0 inside.
    std::array<int, 3> order = {0, 1, 2};
    if (area < 0) std::swap(order[1], order[2]);
    const WindowVertex& v0 = triangle.vertices[order[0]];
    const WindowVertex& v1 = triangle.vertices[order[1]];
    const WindowVertex& v2 = triangle.vertices[order[2]];
    setup.doubleArea = area < 0 ? -area : area;

    // Edge functions: edges[i] is opposite vertex i, so E_i(p) / doubleArea = λ_i.
    setup.edges[0] = makeEdge(v1, v2);
    setup.edges[1] = makeEdge(v2, v0);
    setup.edges[2] = makeEdge(v0, v1);

    // Attribute planes in barycentric form, value = v0 + λ1·(v1 − v0) + λ2·(v2 − v0).
    // Window depth is affine in screen space; a varying a is not, but a/w and 1/w are.
    setup.z0 = v0.z;
    setup.dz1 = v1.z - v0.z;
    setup.dz2 = v2.z - v0.z;
    if (state.depth.offset.any()) setup.z0 += depthOffset(setup, state.depth.offset, state.depth.format);
    setup.invW0 = v0.invW;
    setup.dInvW1 = v1.invW - v0.invW;
    setup.dInvW2 = v2.invW - v0.invW;
    setup.perspective = state.interpolation == Interpolation::PerspectiveCorrect;
    writeVaryingPlanes(triangle, order, setup, varyingPlanes);
    setup.varyingPlaneOffset = 0;  // the caller's buffer; the front end sets its offset in the chunk
    return TriangleFate::Drawn;
}

}  // namespace facet
