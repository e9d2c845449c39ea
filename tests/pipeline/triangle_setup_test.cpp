#include "triangle_setup.h"

#include <bit>

#include <gtest/gtest.h>

#include "rasterize.h"

namespace facet {
namespace {

DrawState stateOf(int width, int height, CullMode cull = CullMode::None) {
    DrawState s;
    s.viewport = {0, 0, width, height};
    s.raster.cull = cull;
    return s;
}

WindowVertex at(float x, float y, float z = 0.5f) {
    WindowVertex v;
    v.window = {x, y};
    v.xFixed = static_cast<std::int64_t>(std::llround(x * kFixedOne));
    v.yFixed = static_cast<std::int64_t>(std::llround(y * kFixedOne));
    v.z = z;
    v.invW = 1.0f;
    return v;
}

WindowTriangle tri(WindowVertex a, WindowVertex b, WindowVertex c) {
    WindowTriangle t;
    t.vertices = {a, b, c};
    return t;
}

int countCovered(const WindowTriangle& t, const DrawState& s) {
    TriangleSetup setup;
    if (setupTriangle(t, s, setup, nullptr) != TriangleFate::Drawn) return 0;
    int n = 0;
    rasterizeBlocks(
        setup, PixelRect{0, 0, s.viewport.x + s.viewport.width - 1, s.viewport.y + s.viewport.height - 1},
        [&](const CoverageBlock& b) { n += std::popcount(b.mask); });
    return n;
}

// The bounding box's pixel range: the first pixel whose sample lies at or after a coordinate and the
// last at or before it, for coordinates on both sides of 0 and on sample points themselves.
// Breaks caught: either shift rounding the other way (towards −∞ for the first pixel, or the ½-pixel
// sample offset left out).
TEST(SamplePosition, PixelsSampledFromAndUpToACoordinate) {
    for (std::int64_t c = -5 * kFixedOne - 3; c <= 5 * kFixedOne + 3; ++c) {
        const std::int64_t first = firstPixelSampledFrom(c), last = lastPixelSampledUpTo(c);
        ASSERT_GE(sampleCoordinate(static_cast<int>(first)), c) << c;
        ASSERT_LT(sampleCoordinate(static_cast<int>(first - 1)), c) << c;
        ASSERT_LE(sampleCoordinate(static_cast<int>(last)), c) << c;
        ASSERT_GT(sampleCoordinate(static_cast<int>(last + 1)), c) << c;
    }
}

TEST(TriangleSetup, SignedAreaAndFacing) {
    // On a y-down screen, (0,0) → (0,4) → (4,0) turns counter-clockwise: negative orient2d.
    const WindowTriangle ccw = tri(at(0, 0), at(0, 4), at(4, 0));
    EXPECT_EQ(signedDoubleArea(ccw), -16 * kFixedOne * kFixedOne);
    EXPECT_TRUE(isFrontFacing(signedDoubleArea(ccw), FrontFace::CounterClockwise));
    EXPECT_FALSE(isFrontFacing(signedDoubleArea(ccw), FrontFace::Clockwise));
    EXPECT_TRUE(isCulled(false, CullMode::Back));
    EXPECT_FALSE(isCulled(true, CullMode::Back));
    EXPECT_TRUE(isCulled(true, CullMode::Front));
    EXPECT_FALSE(isCulled(false, CullMode::None));
}

// Facing is decided before the bounding box, as in OpenGL: a back face lying between pixel centres is
// culled (and counted so), while the same triangle unculled, or a front face there, misses the samples.
// Break caught: the facing test moved back after the box (the back face reported as missing samples).
TEST(TriangleSetup, FacingIsCulledBeforeTheBoundingBox) {
    const WindowTriangle front = tri(at(3.6f, 3.6f), at(3.6f, 4.4f), at(4.4f, 3.6f));
    const WindowTriangle back = tri(at(3.6f, 3.6f), at(4.4f, 3.6f), at(3.6f, 4.4f));
    TriangleSetup setup;
    EXPECT_EQ(setupTriangle(back, stateOf(16, 16, CullMode::Back), setup, nullptr), TriangleFate::Culled);
    EXPECT_FALSE(setup.frontFacing);
    EXPECT_EQ(setupTriangle(back, stateOf(16, 16, CullMode::None), setup, nullptr),
              TriangleFate::MissesSamples);
    EXPECT_EQ(setupTriangle(front, stateOf(16, 16, CullMode::Back), setup, nullptr),
              TriangleFate::MissesSamples);
}

TEST(TriangleSetup, BackFacesAreCulledFrontFacesKept) {
    const WindowTriangle ccw = tri(at(0, 0), at(0, 4), at(4, 0));
    const WindowTriangle cw = tri(at(0, 0), at(4, 0), at(0, 4));
    TriangleSetup setup;
    EXPECT_EQ(setupTriangle(ccw, stateOf(8, 8, CullMode::Back), setup, nullptr), TriangleFate::Drawn);
    EXPECT_TRUE(setup.frontFacing);
    EXPECT_EQ(setupTriangle(cw, stateOf(8, 8, CullMode::Back), setup, nullptr), TriangleFate::Culled);
    EXPECT_EQ(setupTriangle(ccw, stateOf(8, 8, CullMode::Front), setup, nullptr), TriangleFate::Culled);
    // Either winding covers the same pixels when nothing is culled.
    EXPECT_EQ(countCovered(ccw, stateOf(8, 8)), countCovered(cw, stateOf(8, 8)));
}

TEST(TriangleSetup, TopLeftClassification) {
    EXPECT_TRUE(isTopLeft(5, 0));    // horizontal, pointing right: top edge of a positive triangle
    EXPECT_FALSE(isTopLeft(-5, 0));  // horizontal, pointing left: bottom edge
    EXPECT_TRUE(isTopLeft(3, -2));   // going up: left edge
    EXPECT_FALSE(isTopLeft(3, 2));   // going down: right edge
}

// An edge's bias is not stored but read off its coefficients (its direction is (b, −a)). For every
// direction, zero components included, bias() is 0 exactly where isTopLeft says so of that direction;
// the edges setup builds around a triangle of either winding have one top-left edge.
// Breaks caught: the direction read the wrong way round ((a, b), or −b: every edge's ties flip to the
// other triangle).
TEST(TriangleSetup, AnEdgesBiasIsTheTopLeftRuleOfItsDirection) {
    for (int dx = -2; dx <= 2; ++dx)
        for (int dy = -2; dy <= 2; ++dy) {
            if (dx == 0 && dy == 0) continue;
            const EdgeFunction e{-dy, dx, 0};
            EXPECT_EQ(e.bias(), isTopLeft(dx, dy) ? 0 : -1) << "direction (" << dx << ", " << dy << ")";
        }
    for (const bool clockwise : {false, true}) {
        const WindowTriangle t = clockwise ? tri(at(0.5f, 0.5f), at(1.5f, 6.5f), at(6.5f, 1.5f))
                                           : tri(at(0.5f, 0.5f), at(6.5f, 1.5f), at(1.5f, 6.5f));
        TriangleSetup setup;
        ASSERT_EQ(setupTriangle(t, stateOf(8, 8), setup, nullptr), TriangleFate::Drawn);
        int topLeft = 0;
        for (const EdgeFunction& e : setup.edges)
            topLeft += e.bias() == 0;
        // The edge from (0.5, 0.5) down to (1.5, 6.5) is its one left edge; it has no horizontal one.
        EXPECT_EQ(topLeft, 1) << "clockwise " << clockwise;
    }
}

// Direct3D's rasterization-rules example: the square (0,0)–(5,5) split along its diagonal. The five
// pixel centres on the diagonal belong to the triangle for which it is a left edge: 15 + 10 pixels.
TEST(TriangleSetup, SquareSplitAlongDiagonalGivesFifteenAndTen) {
    const DrawState s = stateOf(8, 8);
    const WindowTriangle upperRight = tri(at(0, 0), at(5, 0), at(5, 5));
    const WindowTriangle lowerLeft = tri(at(0, 0), at(5, 5), at(0, 5));
    EXPECT_EQ(countCovered(upperRight, s), 15);
    EXPECT_EQ(countCovered(lowerLeft, s), 10);
}

// Edges through pixel centres: the left and top edges of a square take their samples, the right and
// bottom ones do not, so the square (0.5,0.5)–(4.5,4.5) covers exactly the 4×4 pixels 0..3.
TEST(TriangleSetup, EdgesThroughSampleCentresFollowTheTopLeftRule) {
    const DrawState s = stateOf(8, 8);
    const WindowTriangle a = tri(at(0.5f, 0.5f), at(4.5f, 0.5f), at(4.5f, 4.5f));
    const WindowTriangle b = tri(at(0.5f, 0.5f), at(4.5f, 4.5f), at(0.5f, 4.5f));
    TriangleSetup sa, sb;
    ASSERT_EQ(setupTriangle(a, s, sa, nullptr), TriangleFate::Drawn);
    ASSERT_EQ(setupTriangle(b, s, sb, nullptr), TriangleFate::Drawn);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            const int covered = coversSample(sa, x, y) + coversSample(sb, x, y);
            EXPECT_EQ(covered, (x <= 3 && y <= 3) ? 1 : 0) << "pixel " << x << "," << y;
        }
}

TEST(TriangleSetup, ZeroAreaIsCulledButSliversAreNot) {
    TriangleSetup setup;
    const DrawState s = stateOf(64, 64);
    // Collinear points, and points that become collinear once snapped to 1/256 px.
    EXPECT_EQ(setupTriangle(tri(at(1, 1), at(5, 5), at(9, 9)), s, setup, nullptr), TriangleFate::ZeroArea);
    EXPECT_EQ(setupTriangle(tri(at(1, 1), at(5, 1.0005f), at(9, 1)), s, setup, nullptr),
              TriangleFate::ZeroArea);
    // A sliver one sub-pixel step tall, 40 px long, lying across sample centres: kept, and it covers them.
    const WindowTriangle sliver = tri(at(0, 10.5f), at(40, 10.5f), at(40, 10.5f + 1.0f / 256));
    ASSERT_EQ(setupTriangle(sliver, s, setup, nullptr), TriangleFate::Drawn);
    EXPECT_GT(countCovered(sliver, s), 0);
}

// A triangle that fits between pixel centres covers nothing and is dropped before any plane is set up;
// one that holds a centre is kept.
TEST(TriangleSetup, TrianglesBetweenPixelCentresAreSkipped) {
    TriangleSetup setup;
    const DrawState s = stateOf(16, 16);
    EXPECT_EQ(setupTriangle(tri(at(3.6f, 3.6f), at(4.4f, 3.6f), at(3.6f, 4.4f)), s, setup, nullptr),
              TriangleFate::MissesSamples);
    EXPECT_EQ(setupTriangle(tri(at(3.4f, 3.4f), at(4.4f, 3.4f), at(3.4f, 4.4f)), s, setup, nullptr),
              TriangleFate::Drawn);
    EXPECT_EQ(countCovered(tri(at(3.4f, 3.4f), at(4.4f, 3.4f), at(3.4f, 4.4f)), s), 1);
}

TEST(TriangleSetup, BoundingBoxIsClampedToTheViewport) {
    DrawState s = stateOf(64, 64);
    s.viewport = {8, 4, 16, 10};
    TriangleSetup setup;
    ASSERT_EQ(setupTriangle(tri(at(-100, -100), at(300, -100), at(-100, 300)), s, setup, nullptr),
              TriangleFate::Drawn);
    EXPECT_EQ(setup.minX, 8);
    EXPECT_EQ(setup.maxX, 23);
    EXPECT_EQ(setup.minY, 4);
    EXPECT_EQ(setup.maxY, 13);
    EXPECT_EQ(countCovered(tri(at(-100, -100), at(300, -100), at(-100, 300)), s), 16 * 10);
}

TEST(TriangleSetup, BarycentricsAreOneAtTheirVertex) {
    // Vertices on sample centres: the λ of each vertex is exactly 1 there.
    const WindowTriangle t = tri(at(0.5f, 0.5f, 0.1f), at(6.5f, 0.5f, 0.2f), at(0.5f, 6.5f, 0.3f));
    TriangleSetup setup;
    ASSERT_EQ(setupTriangle(t, stateOf(8, 8), setup, nullptr), TriangleFate::Drawn);
    // At vertex 0's sample (the centre of pixel 0, 0) λ is exactly (1, 0, 0): the edge functions
    // opposite v1 and v2 vanish there, and the one opposite v0 equals twice the area.
    EXPECT_TRUE(coversSample(setup, 0, 0));
    EXPECT_EQ(setup.edges[1].at(kFixedOne / 2, kFixedOne / 2), 0);
    EXPECT_EQ(setup.edges[2].at(kFixedOne / 2, kFixedOne / 2), 0);
    EXPECT_EQ(setup.edges[0].at(kFixedOne / 2, kFixedOne / 2), setup.doubleArea);
    EXPECT_FLOAT_EQ(setup.z0 + setup.dz1, 0.2f);
    EXPECT_FLOAT_EQ(setup.z0 + setup.dz2, 0.3f);
}

// The front end reuses one TriangleSetup for every triangle of an unwatched draw, so setup must write
// each field a drawn triangle's setup has (all but the triangle's number, which the caller sets).
// Break caught: a field left out of setupTriangle (a triangle would inherit its predecessor's value).
TEST(TriangleSetup, ADrawnTriangleWritesEveryFieldOfItsSetup) {
    const WindowTriangle t = tri(at(0.5f, 0.5f, 0.1f), at(6.5f, 1.5f, 0.2f), at(1.5f, 6.5f, 0.3f));
    TriangleSetup fresh;
    ASSERT_EQ(setupTriangle(t, stateOf(8, 8), fresh, nullptr), TriangleFate::Drawn);
    TriangleSetup reused;
    reused.edges.fill(EdgeFunction{7, 7, 7});
    reused.doubleArea = 7;
    reused.frontFacing = !fresh.frontFacing;
    reused.perspective = !fresh.perspective;
    reused.minX = reused.minY = reused.maxX = reused.maxY = 7;
    reused.z0 = reused.dz1 = reused.dz2 = reused.invW0 = reused.dInvW1 = reused.dInvW2 = 7.0f;
    reused.varyingCount = reused.flatVaryingCount = 7;
    reused.varyingPlaneOffset = 7;
    ASSERT_EQ(setupTriangle(t, stateOf(8, 8), reused, nullptr), TriangleFate::Drawn);
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(reused.edges[i].a, fresh.edges[i].a) << i;
        EXPECT_EQ(reused.edges[i].b, fresh.edges[i].b) << i;
        EXPECT_EQ(reused.edges[i].c, fresh.edges[i].c) << i;
    }
    EXPECT_EQ(reused.doubleArea, fresh.doubleArea);
    EXPECT_EQ(reused.frontFacing, fresh.frontFacing);
    EXPECT_EQ(reused.perspective, fresh.perspective);
    EXPECT_EQ(reused.minX, fresh.minX);
    EXPECT_EQ(reused.minY, fresh.minY);
    EXPECT_EQ(reused.maxX, fresh.maxX);
    EXPECT_EQ(reused.maxY, fresh.maxY);
    for (const auto field : {&TriangleSetup::z0, &TriangleSetup::dz1, &TriangleSetup::dz2,
                             &TriangleSetup::invW0, &TriangleSetup::dInvW1, &TriangleSetup::dInvW2})
        EXPECT_EQ(reused.*field, fresh.*field);
    EXPECT_EQ(reused.varyingCount, fresh.varyingCount);
    EXPECT_EQ(reused.flatVaryingCount, fresh.flatVaryingCount);
    EXPECT_EQ(reused.varyingPlaneOffset, fresh.varyingPlaneOffset);
}

}  // namespace
}  // namespace facet
