// The depth of the vertices the clipper makes on a huge triangle (clip.h, clipEdgePoint; state.h,
// DepthFromW): a ground of ±1e6 units seen from 2 units above it with a near plane of 0.01, in the eye
// space the camera rescales by 2^-20 (scene/camera.h, viewScale), so near n ≈ 9.5e-9 and far f ≈ 0.95.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "clip.h"
#include "depth_format.h"
#include "glsl.h"
#include "viewport.h"

namespace facet {
namespace {

constexpr double kScale = 0x1p-20;             // the camera's rescaling for a scene of ~1e6 units
constexpr double kNear = 0.01 * kScale;        // "near": 0.01
constexpr double kFar = 1e6 * kScale;          // about the far plane the camera's framing picks
constexpr double kHeight = 2.0 * kScale;       // the eye above the ground
constexpr double kHalf = 1e6 * kScale;         // the ground's half size
constexpr double kTanHalfFovy = 0.5773502692;  // fovy 60°
constexpr double kAspect = 4.0 / 3.0;

// OpenGL's perspective projection (column-major: p[column][row]), in double as the camera builds it.
glm::dmat4 openGlProjection() {
    glm::dmat4 p(0.0);
    p[0][0] = 1.0 / (kAspect * kTanHalfFovy);
    p[1][1] = 1.0 / kTanHalfFovy;
    p[2][2] = -(kFar + kNear) / (kFar - kNear);
    p[2][3] = -1.0;
    p[3][2] = -2.0 * kFar * kNear / (kFar - kNear);
    return p;
}

// Reversed Z: z' = (w − z)/2 (scene/camera.h, drawnClipFromView).
glm::dmat4 reversedProjection() {
    glm::dmat4 remap(1.0);
    remap[2][2] = -0.5;
    remap[3][2] = 0.5;
    return remap * openGlProjection();
}

// z_c = slope·w + offset as state.h derives it for each projection, written out from n and f.
DepthFromW openGlDepthFromW() {
    return {true, (kFar + kNear) / (kFar - kNear), -2.0 * kFar * kNear / (kFar - kNear)};
}
DepthFromW reversedDepthFromW() {
    return {true, -kNear / (kFar - kNear), kFar * kNear / (kFar - kNear)};
}

// A ground triangle (y_e = −height, the eye looking level along −z) reaching ±1e6 units ahead and
// behind, its corners transformed in float as a vertex shader does (gl_Position = P·p).
ClipPolygon groundTriangle(const glm::dmat4& projection) {
    const mat4 p(projection);
    const vec4 corners[3] = {vec4(float(-kHalf), float(-kHeight), float(-kHalf), 1.0f),
                             vec4(float(kHalf), float(-kHeight), float(-kHalf), 1.0f),
                             vec4(0.0f, float(-kHeight), float(kHalf), 1.0f)};
    ClipPolygon polygon;
    polygon.count = 3;
    for (int k = 0; k < 3; ++k)
        polygon.vertices[k].position = p * corners[k];
    return polygon;
}

std::uint8_t outcodesOf(const ClipPolygon& polygon, ClipDepthRange range) {
    std::uint8_t planes = 0;
    for (int k = 0; k < polygon.count; ++k)
        planes |= computeOutcode(polygon.vertices[k].position, range);
    return planes;
}

// Whether window depth `z` passes the draw's "nearer" test against the cleared far plane of `format`.
bool passesAgainstClear(DepthBufferFormat format, float z) {
    return withDepthFormat(format, [&](auto f) {
        using F = decltype(f);
        return F::passes(nearerPasses(format, CompareOp::Less), z, F::kClear);
    });
}

// The nearest vertex of the clipped ground (the bottom edge of the image, ~3.5 units ahead) keeps a
// window depth that passes the test against the cleared buffer in every format, as reversed Z's did;
// and every made vertex's depth is the projection's at its w, 1 − z_w ≈ n/w.
// Catches: the clipper's new vertices interpolating z_c = w from the corners (window depth 1 in float,
// unorm16 and unorm24: "1 < 1" fails and the ground vanishes).
TEST(NearClipDepth, HugeGroundKeepsDepthsTheTestCanPass) {
    const DepthBufferFormat formats[] = {DepthBufferFormat::Float, DepthBufferFormat::Unorm16,
                                         DepthBufferFormat::Unorm24, DepthBufferFormat::ReversedFloat};
    for (DepthBufferFormat format : formats) {
        SCOPED_TRACE(std::string(nameOf(format)));
        const bool reversed = format == DepthBufferFormat::ReversedFloat;
        const ClipDepthRange range = clipDepthRange(format);
        ClipPolygon polygon = groundTriangle(reversed ? reversedProjection() : openGlProjection());
        const DepthFromW fromW = reversed ? reversedDepthFromW() : openGlDepthFromW();
        clipPolygon(polygon, outcodesOf(polygon, range), range, fromW);
        ASSERT_GE(polygon.count, 3);
        const Viewport viewport{0, 0, 160, 120, 0.0f, 1.0f};
        int nearest = 0;
        for (int k = 0; k < polygon.count; ++k) {
            const vec4 p = polygon.vertices[k].position;
            if (p.w < polygon.vertices[nearest].position.w) nearest = k;
            // The window depth the projection gives at this w, in double: OpenGL's 0.5 + 0.5·(a + b/w),
            // reversed Z's a' + b'/w.
            const double ndc = fromW.slope + fromW.offset / double(p.w);
            const double exact = reversed ? ndc : 0.5 + 0.5 * ndc;
            const float z = toWindow(p, viewport, kMaxSubpixelBits, format).z;
            EXPECT_NEAR(z, exact, 1e-6) << "vertex " << k << " at w = " << p.w;
        }
        const vec4 near = polygon.vertices[nearest].position;
        // The bottom of the view meets the ground 2/tan(30°) ≈ 3.46 units ahead.
        EXPECT_NEAR(near.w / kScale, 2.0 / kTanHalfFovy, 0.05);
        const float z = toWindow(near, viewport, kMaxSubpixelBits, format).z;
        EXPECT_TRUE(passesAgainstClear(format, z)) << "window depth " << z;
    }
}

// Without the relation (a user's vertex shader) the made vertices are interpolated as before: the
// depth is the straight line's between the corners.
// Catches: the relation applied to draws that did not give one (DepthFromW unknown).
TEST(NearClipDepth, UnknownRelationInterpolates) {
    ClipPolygon polygon = groundTriangle(openGlProjection());
    const ClipPolygon corners = polygon;
    clipPolygon(polygon, outcodesOf(polygon, ClipDepthRange::MinusWToW));
    ASSERT_GE(polygon.count, 3);
    for (int k = 0; k < polygon.count; ++k) {
        const vec4 p = polygon.vertices[k].position;
        // Every point of the corners' plane in clip space (z, w both affine along the triangle): z − w
        // stays within the corners' range of z − w.
        float lo = 0, hi = 0;
        for (int c = 0; c < 3; ++c) {
            const vec4 q = corners.vertices[c].position;
            lo = c == 0 ? q.z - q.w : std::min(lo, q.z - q.w);
            hi = c == 0 ? q.z - q.w : std::max(hi, q.z - q.w);
        }
        EXPECT_GE(p.z - p.w, lo - 1e-7f);
        EXPECT_LE(p.z - p.w, hi + 1e-7f);
    }
}

// An ordinary triangle cut by the near and side planes: interpolation resolves its depths, so the
// clipper keeps them, bit for bit what it makes without the relation.
// Catches: the relation applied where interpolating the corners resolves the depth (every clipped
// triangle's depths moved by a rounding: ties between coplanar surfaces, such as a glass cube's bottom
// face on the ground, decided otherwise in the bundled scenes).
TEST(NearClipDepth, OrdinaryTrianglesKeepInterpolatedDepths) {
    const double n = 0.1, f = 60.0;
    const DepthFromW fromW{true, (f + n) / (f - n), -2.0 * f * n / (f - n)};
    // Eye-space points from 0.05 to 40 units ahead, projected by hand in float: w = −z_e,
    // z_c = a·w + b, the x and y of a 60° view.
    const auto clip = [&](double x, double y, double zEye) {
        const double w = -zEye;
        return vec4(float(1.3 * x), float(1.7 * y), float(fromW.slope * w + fromW.offset), float(w));
    };
    const vec4 triangles[][3] = {{clip(0.0, -1.0, -0.05), clip(-30.0, -1.0, -40.0), clip(30.0, -1.0, -40.0)},
                                 {clip(-5.0, 0.3, -2.0), clip(9.0, -2.0, -3.0), clip(1.0, 6.0, -20.0)},
                                 {clip(-1.0, -1.5, 0.5), clip(20.0, -1.5, -25.0), clip(-20.0, 2.0, -59.0)}};
    for (const auto& corners : triangles) {
        ClipPolygon withRelation;
        withRelation.count = 3;
        for (int k = 0; k < 3; ++k)
            withRelation.vertices[k].position = corners[k];
        ClipPolygon interpolated = withRelation;
        const std::uint8_t planes = outcodesOf(withRelation, ClipDepthRange::MinusWToW);
        ASSERT_NE(planes, 0);
        clipPolygon(withRelation, planes, ClipDepthRange::MinusWToW, fromW);
        clipPolygon(interpolated, planes, ClipDepthRange::MinusWToW);
        ASSERT_EQ(withRelation.count, interpolated.count);
        ASSERT_GE(withRelation.count, 3);
        for (int k = 0; k < withRelation.count; ++k)
            EXPECT_EQ(withRelation.vertices[k].position, interpolated.vertices[k].position) << "vertex " << k;
    }
}

}  // namespace
}  // namespace facet
