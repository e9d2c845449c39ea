#include "rasterize.h"

#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "triangle_setup.h"

namespace facet {
namespace {

WindowVertex fixedAt(std::int64_t xFixed, std::int64_t yFixed) {
    WindowVertex v;
    v.xFixed = xFixed;
    v.yFixed = yFixed;
    v.invW = 1.0f;
    return v;
}

// The quad walk must report exactly the pixels the plain per-pixel test covers, inside the bounds,
// each once, with the barycentrics the edge functions give.
TEST(Rasterize, QuadWalkMatchesPerPixelOracleOnRandomTriangles) {
    std::mt19937 rng(20261124);
    const int width = 37, height = 29;
    DrawState state;
    state.viewport = {0, 0, width, height};
    state.raster.cull = CullMode::None;
    std::uniform_int_distribution<std::int64_t> coordX(-10 * kFixedOne, (width + 10) * kFixedOne);
    std::uniform_int_distribution<std::int64_t> coordY(-10 * kFixedOne, (height + 10) * kFixedOne);
    int trianglesChecked = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        WindowTriangle t;
        for (auto& v : t.vertices)
            v = fixedAt(coordX(rng), coordY(rng));
        TriangleSetup setup;
        if (setupTriangle(t, state, setup) != TriangleFate::Drawn) continue;
        ++trianglesChecked;
        std::vector<int> walked(width * height, 0);
        rasterizeTriangle(setup, [&](const Quad& q) {
            EXPECT_EQ(q.x % 2, 0);
            EXPECT_EQ(q.y % 2, 0);
            for (int lane = 0; lane < 4; ++lane) {
                if (!((q.mask >> lane) & 1)) continue;
                const int x = q.x + (lane & 1), y = q.y + (lane >> 1);
                ASSERT_TRUE(x >= 0 && x < width && y >= 0 && y < height);
                ++walked[y * width + x];
                const std::int64_t px = x * kFixedOne + kFixedOne / 2, py = y * kFixedOne + kFixedOne / 2;
                EXPECT_FLOAT_EQ(q.b1[lane], static_cast<float>(setup.edges[1].at(px, py)) /
                                                static_cast<float>(setup.doubleArea));
            }
        });
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                ASSERT_EQ(walked[y * width + x], coversSample(setup, x, y) ? 1 : 0)
                    << "trial " << trial << " pixel " << x << "," << y;
    }
    EXPECT_GT(trianglesChecked, 1500);
}

TEST(Rasterize, OddBoundsAndTheLastRowAndColumn) {
    for (auto [width, height] : {std::pair{1, 1}, {3, 7}, {4097, 1}}) {
        DrawState state;
        state.viewport = {0, 0, width, height};
        state.raster.cull = CullMode::None;
        // A triangle much larger than the viewport covers every pixel once, including the last ones.
        WindowTriangle t;
        t.vertices = {fixedAt(-5 * kFixedOne, -5 * kFixedOne), fixedAt(3 * width * kFixedOne, -5 * kFixedOne),
                      fixedAt(-5 * kFixedOne, 3 * height * kFixedOne + 20 * kFixedOne)};
        TriangleSetup setup;
        ASSERT_EQ(setupTriangle(t, state, setup), TriangleFate::Drawn);
        std::vector<int> walked(static_cast<std::size_t>(width) * height, 0);
        rasterizeTriangle(setup, [&](const Quad& q) {
            for (int lane = 0; lane < 4; ++lane)
                if ((q.mask >> lane) & 1) ++walked[(q.y + (lane >> 1)) * width + q.x + (lane & 1)];
        });
        for (int v : walked)
            ASSERT_EQ(v, 1) << width << "x" << height;
    }
}

TEST(Rasterize, EmptyBoundsVisitNothing) {
    TriangleSetup setup;  // default bounds are empty (max < min)
    int visits = 0;
    rasterizeTriangle(setup, [&](const Quad&) { ++visits; });
    EXPECT_EQ(visits, 0);
}

}  // namespace
}  // namespace facet
