// Rasterization: which pixel centres a triangle covers, walked as 2×2 quads with a coverage mask.
// In: TriangleSetup. Out: a Quad for every 2×2 block with at least one covered sample, in row order.
// The edge functions are stepped incrementally (adding a or b per pixel) and are exact integers, so the
// result equals evaluating each pixel on its own (coversSample, the test oracle), bit for bit.
#pragma once

#include "types.h"

namespace facet {

// The plain per-pixel test: is the centre of pixel (x, y) inside the triangle under the top-left rule?
// (Ignores the bounding box; used by tests as the reference the incremental walk must match.)
inline bool coversSample(const TriangleSetup& setup, int x, int y) {
    const std::int64_t px = std::int64_t{x} * kFixedOne + kFixedOne / 2;
    const std::int64_t py = std::int64_t{y} * kFixedOne + kFixedOne / 2;
    for (const EdgeFunction& e : setup.edges)
        if (e.at(px, py) + e.bias < 0) return false;
    return true;
}

// Calls visit(const Quad&) for each 2×2 block of the bounding box that has a covered sample.
template <class QuadVisitor>
void rasterizeTriangle(const TriangleSetup& setup, QuadVisitor&& visit) {
    if (setup.minX > setup.maxX || setup.minY > setup.maxY) return;

    // Quads are aligned to even pixel coordinates.
    const int startX = setup.minX & ~1;
    const int startY = setup.minY & ~1;

    // Edge values (with fill-rule bias) at the centre of pixel (startX, startY), and their steps.
    const std::int64_t px = std::int64_t{startX} * kFixedOne + kFixedOne / 2;
    const std::int64_t py = std::int64_t{startY} * kFixedOne + kFixedOne / 2;
    std::int64_t rowStart[3], stepX[3], stepY[3];
    for (int i = 0; i < 3; ++i) {
        const EdgeFunction& e = setup.edges[i];
        rowStart[i] = e.at(px, py) + e.bias;
        stepX[i] = e.a * kFixedOne;  // one pixel to the right
        stepY[i] = e.b * kFixedOne;  // one pixel down
    }
    const float invDoubleArea = static_cast<float>(1.0 / static_cast<double>(setup.doubleArea));

    Quad quad;
    for (int y = startY; y <= setup.maxY; y += 2) {
        std::int64_t e[3] = {rowStart[0], rowStart[1], rowStart[2]};
        for (int x = startX; x <= setup.maxX; x += 2) {
            quad.mask = 0;
            for (int lane = 0; lane < 4; ++lane) {
                const int dx = lane & 1;
                const int dy = lane >> 1;
                const int sx = x + dx;
                const int sy = y + dy;
                if (sx < setup.minX || sx > setup.maxX || sy < setup.minY || sy > setup.maxY) continue;
                const std::int64_t w0 = e[0] + dx * stepX[0] + dy * stepY[0];
                const std::int64_t w1 = e[1] + dx * stepX[1] + dy * stepY[1];
                const std::int64_t w2 = e[2] + dx * stepX[2] + dy * stepY[2];
                if ((w0 | w1 | w2) < 0) continue;  // some biased edge value is negative: outside
                quad.mask |= static_cast<std::uint8_t>(1u << lane);
                // Barycentrics from the unbiased edge values: λ_i = E_i / (2·area).
                quad.b1[lane] = static_cast<float>(w1 - setup.edges[1].bias) * invDoubleArea;
                quad.b2[lane] = static_cast<float>(w2 - setup.edges[2].bias) * invDoubleArea;
            }
            if (quad.mask) {
                quad.x = x;
                quad.y = y;
                visit(static_cast<const Quad&>(quad));
            }
            for (int i = 0; i < 3; ++i)
                e[i] += 2 * stepX[i];
        }
        for (int i = 0; i < 3; ++i)
            rowStart[i] += 2 * stepY[i];
    }
}

}  // namespace facet
