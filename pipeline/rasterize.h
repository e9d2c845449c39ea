// Rasterization: which pixel centres a triangle covers, found 8×8 block by block.
// In: TriangleSetup and the rectangle of pixels to cover (a tile). Out: a CoverageBlock for every block
// with a covered sample, in row order.
// Each block is first tested whole (Pineda's edge functions are linear, so an edge's extremes over a
// block sit at its corners): a block outside one edge is skipped, a block inside all three is covered
// without a per-pixel test, and only blocks an edge crosses are tested pixel by pixel, stepping the edge
// functions incrementally. All of it is exact integer arithmetic, so the result equals evaluating each
// pixel on its own (coversSample, the test oracle), bit for bit.
#pragma once

#include <algorithm>
#include <bit>
#include <climits>
#include <cstdint>

#include "sample_position.h"
#include "types.h"
#include "wide.h"

namespace facet {

// The plain per-pixel test, edge by edge: is the sample of pixel (x, y) inside the triangle under the
// top-left rule, which edges put it outside, and which edges it lies exactly on (ties the fill rule
// settles)? Ignores the bounding box. The reference the block walk must match (tests), and what an
// observer sees of coverage (pixel history).
inline CoverageEvent coverageAt(const TriangleSetup& setup, int x, int y) {
    const SamplePoint p = samplePosition(x, y);
    CoverageEvent event;
    event.x = x;
    event.y = y;
    event.triangle = setup.triangle;
    for (int i = 0; i < 3; ++i) {
        const EdgeFunction& e = setup.edges[static_cast<std::size_t>(i)];
        const std::int64_t value = e.at(p.x, p.y);
        event.edgeValues[static_cast<std::size_t>(i)] = value;
        const auto bit = static_cast<std::uint8_t>(1u << i);
        if (value == 0) event.tiedEdges |= bit;
        if (e.bias() == 0) event.topLeftEdges |= bit;
        if (value + e.bias() < 0) event.excludingEdges |= bit;
    }
    event.covered = event.excludingEdges == 0;
    return event;
}

// Is the sample of pixel (x, y) inside the triangle under the top-left rule?
inline bool coversSample(const TriangleSetup& setup, int x, int y) {
    return coverageAt(setup, x, y).covered;
}

// Bits of an 8×8 block's mask for the pixels inside `rect`.
inline std::uint64_t rectMask(int blockX, int blockY, const PixelRect& rect) {
    const int firstColumn = std::max(rect.minX - blockX, 0),
              lastColumn = std::min(rect.maxX - blockX, kBlockSize - 1);
    const int firstRow = std::max(rect.minY - blockY, 0),
              lastRow = std::min(rect.maxY - blockY, kBlockSize - 1);
    if (firstColumn > lastColumn || firstRow > lastRow) return 0;
    const std::uint64_t rowBits = ((std::uint64_t{1} << (lastColumn - firstColumn + 1)) - 1) << firstColumn;
    // rowBits in every byte (it is below 256), kept in the bytes of rows firstRow..lastRow: no loop over
    // the rows, whose count varies from block to block (a branch the CPU would often mispredict).
    const std::uint64_t rows = (~std::uint64_t{0} >> (64 - kBlockSize * (lastRow - firstRow + 1)))
                               << (kBlockSize * firstRow);
    return (rowBits * 0x0101010101010101u) & rows;
}

namespace detail {

// Coverage of a block that some edge crosses: one bit per sample where all three biased edge functions
// are ≥ 0, for rows [firstRow, lastRow] (the others stay 0). Edges that are ≥ 0 over the whole block
// are left out. When every remaining edge's values over the block fit in 32 bits (always, but for
// edges thousands of pixels long), a row of eight samples is tested with 32-bit lanes, which the
// compiler turns into SIMD; otherwise with 64-bit integers.
inline std::uint64_t partialBlockMask(const std::int64_t origin[3], const std::int64_t stepX[3],
                                      const std::int64_t stepY[3], const std::int64_t minOffset[3],
                                      const std::int64_t maxOffset[3], int firstRow, int lastRow) {
    int edges[3], count = 0;
    bool fits32 = true;
    for (int i = 0; i < 3; ++i) {
        if (origin[i] + minOffset[i] >= 0) continue;  // this edge covers the whole block
        edges[count++] = i;
        const std::int64_t low = origin[i] + minOffset[i], high = origin[i] + maxOffset[i];
        fits32 &= low >= INT32_MIN && high <= INT32_MAX;
    }
    std::uint64_t mask = 0;
    if (fits32) {
        // All three edges, each in its own register: an edge left out is 0 with no step, never
        // negative (indexing the edges by a count kept their rows in memory, a store and a reload per
        // edge and row on the loop's critical path).
        Int8 rowValue[3], down[3];
        using Unsigned8 = std::uint32_t __attribute__((vector_size(32)));
        const Unsigned8 column = {0, 1, 2, 3, 4, 5, 6, 7};
        for (int i = 0; i < 3; ++i) {
            rowValue[i] = Int8{};
            down[i] = Int8{};
            if (origin[i] + minOffset[i] >= 0) continue;  // left out, as above
            // Each lane's first value, first + x·stepX, fits in 32 bits, though a partial product may
            // not: computed modulo 2^32 (unsigned lanes, where wrapping is defined), it is exact.
            const auto first = static_cast<std::uint32_t>(origin[i] + firstRow * stepY[i]);
            const auto step = static_cast<std::uint32_t>(stepX[i]);
            rowValue[i] = std::bit_cast<Int8>(first + column * step);
            down[i] = Int8{} + static_cast<std::int32_t>(stepY[i]);
        }
        for (int y = firstRow; y <= lastRow; ++y) {
            // Step down only between rows of the block: one step past its last row could leave int32.
            if (y > firstRow)
                for (int i = 0; i < 3; ++i)
                    rowValue[i] += down[i];
            const Int8 all = rowValue[0] | rowValue[1] | rowValue[2];
            // A sample is covered where no edge value is negative: where the OR has no sign bit.
            mask |= static_cast<std::uint64_t>(~signMask(all) & 0xffu) << (y * kBlockSize);
        }
        return mask;
    }
    std::int64_t row[3] = {origin[0] + firstRow * stepY[0], origin[1] + firstRow * stepY[1],
                           origin[2] + firstRow * stepY[2]};
    for (int y = firstRow; y <= lastRow; ++y) {
        std::uint64_t rowBits = 0;
        for (int x = 0; x < kBlockSize; ++x) {
            std::int64_t all = 0;
            for (int k = 0; k < count; ++k)
                all |= row[edges[k]] + x * stepX[edges[k]];
            rowBits |= static_cast<std::uint64_t>(all >= 0) << x;
        }
        mask |= rowBits << (y * kBlockSize);
        for (int i = 0; i < 3; ++i)
            row[i] += stepY[i];
    }
    return mask;
}

}  // namespace detail

// Per edge of a triangle: the step of its function from one pixel to the next, and the offsets from a
// block's first sample to the block's smallest and largest value of the edge function (at opposite
// corners).
struct BlockEdgeSteps {
    std::int64_t stepX[3], stepY[3], minOffset[3], maxOffset[3];

    explicit BlockEdgeSteps(const TriangleSetup& setup) {
        constexpr std::int64_t kSpan = (kBlockSize - 1) * kFixedOne;
        for (int i = 0; i < 3; ++i) {
            const EdgeFunction& e = setup.edges[i];
            stepX[i] = e.a * kFixedOne;
            stepY[i] = e.b * kFixedOne;
            minOffset[i] = std::min<std::int64_t>(0, e.a * kSpan) + std::min<std::int64_t>(0, e.b * kSpan);
            maxOffset[i] = std::max<std::int64_t>(0, e.a * kSpan) + std::max<std::int64_t>(0, e.b * kSpan);
        }
    }
};

// The covered samples of the pixels of block (bx, by) inside `rect`, one bit per pixel, for the samples
// at (dx, dy) fixed-point units from each pixel's centre (0, 0: the centre itself; multisampling's
// positions otherwise, where the edge function is E(centre) + a·dx + b·dy, exact). `inside`: whether all
// three edges cover the whole block.
[[gnu::always_inline]] inline std::uint64_t blockCoverage(const TriangleSetup& setup,
                                                          const BlockEdgeSteps& steps, int bx, int by,
                                                          const PixelRect& rect, std::int64_t dx,
                                                          std::int64_t dy, bool& inside) {
    // Biased edge values at the block's first sample, that of pixel (bx, by).
    const SamplePoint first = samplePosition(bx, by);
    std::int64_t origin[3];
    bool outside = false;
    inside = true;
    for (int i = 0; i < 3; ++i) {
        origin[i] = setup.edges[i].at(first.x + dx, first.y + dy) + setup.edges[i].bias();
        outside |= origin[i] + steps.maxOffset[i] < 0;
        inside &= origin[i] + steps.minOffset[i] >= 0;
    }
    if (outside) return 0;  // trivially rejected: wholly outside one edge

    const std::uint64_t inRect = rectMask(bx, by, rect);
    if (inside) return inRect;
    const int firstRow = std::max(rect.minY - by, 0), lastRow = std::min(rect.maxY - by, kBlockSize - 1);
    return detail::partialBlockMask(origin, steps.stepX, steps.stepY, steps.minOffset, steps.maxOffset,
                                    firstRow, lastRow) &
           inRect;
}

// The rectangle of pixels a triangle's blocks are walked over: `area` ∩ the triangle's bounds.
inline PixelRect rasterRect(const TriangleSetup& setup, const PixelRect& area) {
    return {std::max(area.minX, setup.minX), std::max(area.minY, setup.minY), std::min(area.maxX, setup.maxX),
            std::min(area.maxY, setup.maxY)};
}

// Where the blocks over `rect` (a triangle's pixels in `area`) start along one axis: at the multiple
// of kBlockSize at or before rect's first pixel, unless rect fits in one block's span: then one block
// is placed over it, inside `area` when area is at least a block wide, so that the back end's row
// loads and stores stay in its tile. A small triangle is then one block, not the two to four aligned
// blocks it straddles in most positions (a triangle of a dense mesh, a few pixels across, straddles a
// block boundary more often than not), and its rows are walked once.
inline int firstBlockAt(int rectMin, int rectMax, int areaMin, int areaMax) {
    if (rectMax - rectMin < kBlockSize && areaMax - areaMin + 1 >= kBlockSize)
        return std::min(rectMin, areaMax - (kBlockSize - 1));
    return rectMin & ~(kBlockSize - 1);
}

// Calls visit(const CoverageBlock&) for every block of `rect` ∩ the triangle's bounds with a covered
// sample: 8×8 blocks aligned to multiples of 8, or placed over the triangle along an axis where its
// pixels fit in one block (firstBlockAt).
template <class BlockVisitor>
void rasterizeBlocks(const TriangleSetup& setup, const PixelRect& area, BlockVisitor&& visit) {
    const PixelRect rect = rasterRect(setup, area);
    if (rect.empty()) return;
    const BlockEdgeSteps steps(setup);
    const int firstBlockX = firstBlockAt(rect.minX, rect.maxX, area.minX, area.maxX);
    const int firstBlockY = firstBlockAt(rect.minY, rect.maxY, area.minY, area.maxY);
    CoverageBlock block;
    for (int by = firstBlockY; by <= rect.maxY; by += kBlockSize) {
        for (int bx = firstBlockX; bx <= rect.maxX; bx += kBlockSize) {
            bool inside = false;
            const std::uint64_t mask = blockCoverage(setup, steps, bx, by, rect, 0, 0, inside);
            if (mask == 0) continue;
            block.x = bx;
            block.y = by;
            block.mask = mask;
            block.fullyCovered = inside;
            visit(static_cast<const CoverageBlock&>(block));
        }
    }
}

// ---- Patches: the walk of a triangle of a few pixels --------------------------------------------------

// A patch is kColumns pixels wide, four (kNarrowPatch) or eight (kWidePatch), and as many rows as a
// lane vector I holds (sixteen lanes: four rows or two; eight lanes: two rows or one), lane = row ·
// kColumns + column: a triangle whose pixels fit in one is tested, depth-tested and queued in one pass
// of lane vectors, where the block walk spends a pass per row of eight lanes (most of them outside so
// small a triangle) and sets up each block for edges of any length.
inline constexpr int kNarrowPatch = 4, kWidePatch = 8;
template <class I, int kColumns>
inline constexpr int kPatchRows = int(sizeof(I) / sizeof(std::int32_t)) / kColumns;

// Edges of a triangle walked as patches are at most this long along each axis (fixed units, 16 pixels).
// Its box lies within its vertices' extent and a patch is placed at most 7 pixels beyond the box, so
// every patch sample is within 23 pixels of each vertex and every edge function value there,
// E = a·dx + b·dy from an edge's first vertex, has |E| ≤ 2 · 16·256 · 23·256 < 2^26: 32 bits with room
// to spare. Checked on the edges themselves, not the box, which is clamped to the viewport.
inline constexpr std::int64_t kMaxPatchEdge = 16 * kFixedOne;

// Whether the triangle's edges are short enough for a patch (kMaxPatchEdge).
inline bool hasPatchEdges(const TriangleSetup& setup) {
    bool shortEdges = true;
    for (const EdgeFunction& e : setup.edges)
        shortEdges &=
            e.a <= kMaxPatchEdge && e.a >= -kMaxPatchEdge && e.b <= kMaxPatchEdge && e.b >= -kMaxPatchEdge;
    return shortEdges;
}

// Whether the triangle's pixels fit in `columns` columns and `rows` rows (a stack of patches when `rows`
// is more than one patch holds), and its edges are short (kMaxPatchEdge).
inline bool fitsPatch(const TriangleSetup& setup, int columns, int rows) {
    return setup.maxX - setup.minX < columns && setup.maxY - setup.minY < rows && hasPatchEdges(setup);
}

// The coverage of the patch at pixel (x, y) by a triangle that fitsPatch: bit `lane` set where all three
// biased edge functions are ≥ 0 at the lane's sample (the top-left rule, as coversSample decides) and
// the lane's pixel is inside `rect`. Also gives E₁ and E₂ unbiased at each lane's sample, for its
// barycentrics. Each value is E(first sample) + column·a·kFixedOne + row·b·kFixedOne, exact in 32 bits
// for such a triangle (kMaxPatchEdge).
template <class I, int kColumns>
[[gnu::always_inline]] inline unsigned patchCoverage(const TriangleSetup& setup, int x, int y,
                                                     const PixelRect& rect, I& e1, I& e2) {
    constexpr int kLanes = kColumns * kPatchRows<I, kColumns>;
    I column, row;
    for (int lane = 0; lane < kLanes; ++lane) {
        column[lane] = lane % kColumns;
        row[lane] = lane / kColumns;
    }
    const SamplePoint first = samplePosition(x, y);
    I biased[3], unbiased[3];
    for (int i = 0; i < 3; ++i) {
        const EdgeFunction& e = setup.edges[i];
        const auto origin = static_cast<std::int32_t>(e.at(first.x, first.y));
        unbiased[i] = origin + column * static_cast<std::int32_t>(e.a * kFixedOne) +
                      row * static_cast<std::int32_t>(e.b * kFixedOne);
        biased[i] = unbiased[i] + static_cast<std::int32_t>(e.bias());
    }
    e1 = unbiased[1];
    e2 = unbiased[2];
    const I inRect = (column >= rect.minX - x) & (column <= rect.maxX - x) & (row >= rect.minY - y) &
                     (row <= rect.maxY - y);
    // Covered where no biased value is negative (the OR has no sign bit) and the pixel is in rect.
    return signMask(~(biased[0] | biased[1] | biased[2]) & inRect);
}

}  // namespace facet
