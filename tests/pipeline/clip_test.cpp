#include "clip.h"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace facet {
namespace {

ClipPolygon triangle(vec4 a, vec4 b, vec4 c, int varyingCount = 0) {
    ClipPolygon p;
    p.count = 3;
    p.varyingCount = varyingCount;
    p.vertices[0].position = a;
    p.vertices[1].position = b;
    p.vertices[2].position = c;
    return p;
}

bool allFinite(const ClipPolygon& p) {
    for (int i = 0; i < p.count; ++i)
        for (int k = 0; k < 4; ++k)
            if (!std::isfinite(p.vertices[i].position[k])) return false;
    return true;
}

TEST(ClipOutcode, NamesEveryPlaneOutside) {
    EXPECT_EQ(computeOutcode({0, 0, 0, 1}), 0);
    EXPECT_EQ(computeOutcode({1, 1, 1, 1}), 0);  // on the planes is inside
    EXPECT_EQ(computeOutcode({-2, 0, 0, 1}), kClipLeft);
    EXPECT_EQ(computeOutcode({2, 3, 0, 1}), kClipRight | kClipTop);
    EXPECT_EQ(computeOutcode({0, -2, -2, 1}), kClipBottom | kClipNear);
    EXPECT_EQ(computeOutcode({0, 0, 5, 1}), kClipFar);
    // Behind the eye: w < 0 fails −w ≤ x ≤ w for any x, and the w plane.
    EXPECT_EQ(computeOutcode({0, 0, 0, -1}) & kClipW, kClipW);
    EXPECT_EQ(computeOutcode({0, 0, 0, 0}), kClipW);
}

TEST(ClipOutcode, NonFiniteIsItsOwnVerdict) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    EXPECT_EQ(computeOutcode({nan, 0, 0, 1}), kNonFinite);
    EXPECT_EQ(computeOutcode({0, inf, 0, 1}), kNonFinite);
    EXPECT_EQ(computeOutcode({0, 0, 0, -inf}), kNonFinite);
}

// The vertex stage's eight-at-a-time outcodes are computeOutcode's, lane by lane, under both clip-depth
// ranges: random positions in and around the frustum, positions on its planes and at kMinClipW, and a
// NaN or an infinity in each coordinate (breaks caught: a plane's comparison turned round or given
// another plane's bit, the reversed-Z planes not taken, a non-finite lane keeping its plane bits).
TEST(ClipOutcode, EightAtOnceMatchOneAtATime) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<vec4> positions = {{1, 1, 1, 1},      {-1, -1, -1, 1},         {0, 0, 0, kMinClipW},
                                   {0, 0, 0, 0},      {0, 0, 0, -kMinClipW},   {2, -3, 0.5f, 1},
                                   {0, 0, 0, 1e-10f}, {0.5f, 0.5f, -0.5f, -1}, {0, 0, 1, 1}};
    for (int k = 0; k < 4; ++k)
        for (const float bad : {nan, inf, -inf}) {
            vec4 p(0.5f, -0.5f, 3.0f, 1.0f);
            p[k] = bad;
            positions.push_back(p);
        }
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> coordinate(-3.0f, 3.0f), w(-1.0f, 3.0f);
    while (positions.size() % 8 != 0 || positions.size() < 400)
        positions.push_back({coordinate(rng), coordinate(rng), coordinate(rng), w(rng)});
    for (const ClipDepthRange range : {ClipDepthRange::MinusWToW, ClipDepthRange::ReversedZeroToW})
        for (std::size_t group = 0; group < positions.size(); group += 8) {
            std::uint8_t codes[8];
            computeOutcodes(&positions[group], codes, range);
            for (std::size_t lane = 0; lane < 8; ++lane) {
                const vec4& p = positions[group + lane];
                EXPECT_EQ(codes[lane], computeOutcode(p, range))
                    << p.x << ", " << p.y << ", " << p.z << ", " << p.w
                    << (range == ClipDepthRange::MinusWToW ? " (-w..w)" : " (0..w)");
            }
        }
}

TEST(Clip, InsideTriangleIsUnchanged) {
    ClipPolygon p = triangle({-0.5f, -0.5f, 0, 1}, {0.5f, -0.5f, 0, 1}, {0, 0.5f, 0, 1});
    const ClipPolygon before = p;
    clipPolygon(p, kAllClipPlanes);
    ASSERT_EQ(p.count, 3);
    EXPECT_EQ(p.planesCut, 0);
    for (int i = 0; i < 3; ++i)
        EXPECT_EQ(p.vertices[i].position, before.vertices[i].position);
}

// A triangle with one vertex in front of the near plane (z < −w) loses that corner: the result is the
// quadrilateral with the two cut points computed by hand, t = d_in / (d_in − d_out).
TEST(Clip, NearPlaneCutsOneCornerIntoAQuad) {
    // v0 at z = −2, w = 1: d_near = w + z = −1 (outside). v1, v2 at z = 0, w = 1: d_near = 1 (inside).
    ClipPolygon p = triangle({0, 0, -2, 1}, {1, 0, 0, 1}, {0, 1, 0, 1}, 1);
    p.vertices[0].varyings[0] = 10.0f;
    p.vertices[1].varyings[0] = 20.0f;
    p.vertices[2].varyings[0] = 30.0f;
    clipPolygon(p, kClipNear);
    ASSERT_EQ(p.count, 4);
    EXPECT_EQ(p.planesCut, kClipNear);
    // Sutherland–Hodgman order: edge v0→v1 enters (cut point, then v1), v1→v2 keeps v2, v2→v0 leaves.
    // Cut on v1→v0 from v1: t = 1/(1+1) = 0.5 → (0.5, 0, −1, 1), varying 15.
    // Cut on v2→v0 from v2: t = 0.5 → (0, 0.5, −1, 1), varying 20.
    EXPECT_EQ(p.vertices[0].position, vec4(0.5f, 0, -1, 1));
    EXPECT_FLOAT_EQ(p.vertices[0].varyings[0], 15.0f);
    EXPECT_EQ(p.vertices[1].position, vec4(1, 0, 0, 1));
    EXPECT_EQ(p.vertices[2].position, vec4(0, 1, 0, 1));
    EXPECT_EQ(p.vertices[3].position, vec4(0, 0.5f, -1, 1));
    EXPECT_FLOAT_EQ(p.vertices[3].varyings[0], 20.0f);
    for (int i = 0; i < p.count; ++i)
        EXPECT_GE(planeDistance(p.vertices[i].position, kClipNear), 0.0f);
}

// One vertex behind the eye (w = −1), one on the eye plane (w = 0), one visible: a clipped polygon,
// every vertex with w ≥ kMinClipW and inside the frustum, no NaN.
TEST(Clip, VerticesAtAndBehindTheEyeGiveAFiniteVisiblePolygon) {
    ClipPolygon p = triangle({0, 0, 0.5f, -1}, {0.2f, 0.1f, 0.0f, 0.0f}, {0, 0, 0, 1});
    const std::uint8_t planes = computeOutcode(p.vertices[0].position) |
                                computeOutcode(p.vertices[1].position) |
                                computeOutcode(p.vertices[2].position);
    ASSERT_NE(planes & kClipW, 0);
    clipPolygon(p, planes);
    ASSERT_GE(p.count, 3);
    EXPECT_TRUE(allFinite(p));
    for (int i = 0; i < p.count; ++i) {
        EXPECT_GE(p.vertices[i].position.w, kMinClipW);
        const std::uint8_t code = computeOutcode(p.vertices[i].position);
        // Inside every plane up to the rounding of the intersection.
        for (std::uint8_t plane : {kClipLeft, kClipRight, kClipBottom, kClipTop, kClipNear, kClipFar})
            if (code & plane) {
                EXPECT_GT(planeDistance(p.vertices[i].position, plane), -1e-6f);
            }
    }
    const vec4 ndc = p.vertices[0].position / p.vertices[0].position.w;
    EXPECT_TRUE(std::isfinite(ndc.x) && std::isfinite(ndc.y) && std::isfinite(ndc.z));
}

TEST(Clip, TriangleWhollyBehindTheEyeVanishes) {
    ClipPolygon p = triangle({0, 0, 0, -1}, {1, 0, 0, -2}, {0, 1, 0, -0.5f});
    clipPolygon(p, kAllClipPlanes);
    EXPECT_EQ(p.count, 0);
}

TEST(Clip, WindingIsKept) {
    // Counter-clockwise in x/y; cut by the right plane at x = w = 1.
    ClipPolygon p = triangle({-0.5f, -0.5f, 0, 1}, {3, -0.5f, 0, 1}, {-0.5f, 0.8f, 0, 1});
    clipPolygon(p, kClipRight);
    ASSERT_EQ(p.count, 4);
    float area2 = 0;
    for (int i = 0; i < p.count; ++i) {
        const vec4& a = p.vertices[i].position;
        const vec4& b = p.vertices[(i + 1) % p.count].position;
        area2 += a.x * b.y - b.x * a.y;
    }
    EXPECT_GT(area2, 0.0f);
}

// Two triangles sharing an edge that crosses planes must produce bit-identical cut points on it,
// whatever direction each traverses the edge and whichever other planes cut them.
TEST(Clip, SharedEdgeGetsBitIdenticalCutPoints) {
    const vec4 a{-3.1f, 0.37f, 0.2f, 1.3f};
    const vec4 b{2.9f, -0.41f, -1.9f, 0.7f};
    ClipPolygon first = triangle(a, b, {0.1f, 2.7f, 0.3f, 1.1f});
    ClipPolygon second = triangle(b, a, {0.2f, -3.3f, 0.1f, 0.9f});
    clipPolygon(first, kAllClipPlanes);
    clipPolygon(second, kAllClipPlanes);
    ASSERT_GE(first.count, 3);
    ASSERT_GE(second.count, 3);
    // Every vertex of `first` that lies on the line a–b must appear, to the bit, in `second`.
    int shared = 0;
    for (int i = 0; i < first.count; ++i) {
        const vec4& v = first.vertices[i].position;
        // Points on segment a–b satisfy v = a + t·(b − a); test collinearity loosely, equality exactly.
        const vec4 d = b - a;
        const float t = (v.x - a.x) / d.x;
        if (std::abs(a.y + t * d.y - v.y) > 1e-4f || std::abs(a.w + t * d.w - v.w) > 1e-4f) continue;
        bool found = false;
        for (int j = 0; j < second.count; ++j)
            found |= second.vertices[j].position == v;
        EXPECT_TRUE(found) << "vertex " << i << " of the first triangle is not in the second";
        ++shared;
    }
    EXPECT_GE(shared, 2);
}

TEST(Clip, HugeCoordinatesStayFiniteOrVanish) {
    ClipPolygon p = triangle({1e30f, 1e30f, 0, 1}, {-0.5f, -0.5f, 0, 1}, {0.5f, -0.5f, 0, 1});
    clipPolygon(p, kAllClipPlanes);
    EXPECT_TRUE(allFinite(p));
    ClipPolygon q = triangle({3e38f, -3e38f, 3e38f, 1}, {-3e38f, 3e38f, -3e38f, 1}, {0, 0, 0, 1});
    clipPolygon(q, kAllClipPlanes);
    EXPECT_TRUE(allFinite(q));
}

}  // namespace
}  // namespace facet
