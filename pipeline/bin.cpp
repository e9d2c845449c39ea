#include "bin.h"

#include <algorithm>
#include <bit>

#include "sample_position.h"

namespace facet {

TileGrid makeTileGrid(const Viewport& viewport, int tileSize) {
    TileGrid grid;
    grid.tileSize = tileSize;
    if (tileSize > 0 && std::has_single_bit(static_cast<unsigned>(tileSize)))
        grid.tileShift = std::countr_zero(static_cast<unsigned>(tileSize));
    grid.area = {viewport.x, viewport.y, viewport.x + viewport.width - 1, viewport.y + viewport.height - 1};
    grid.firstColumn = grid.area.minX / tileSize;
    grid.firstRow = grid.area.minY / tileSize;
    grid.columns = grid.area.maxX / tileSize - grid.firstColumn + 1;
    grid.rows = grid.area.maxY / tileSize - grid.firstRow + 1;
    return grid;
}

PixelRect TileGrid::tileRect(int index) const {
    const int column = firstColumn + index % columns;
    const int row = firstRow + index / columns;
    return {std::max(column * tileSize, area.minX), std::max(row * tileSize, area.minY),
            std::min((column + 1) * tileSize - 1, area.maxX), std::min((row + 1) * tileSize - 1, area.maxY)};
}

int TileGrid::maxPartsPerSide() const {
    int side = 1;
    while (side < 4 && tileSize % (2 * side * kBlockSize) == 0)
        side *= 2;
    return side;
}

PixelRect TileGrid::tilePartRect(int index, int side, int part) const {
    const int partSize = tileSize / side;
    const int x = (firstColumn + index % columns) * tileSize + (part % side) * partSize;
    const int y = (firstRow + index / columns) * tileSize + (part / side) * partSize;
    return {std::max(x, area.minX), std::max(y, area.minY), std::min(x + partSize - 1, area.maxX),
            std::min(y + partSize - 1, area.maxY)};
}

int tilePartsPerSide(std::size_t weight, std::size_t totalWeight, int threads, int maxSide) {
    if (threads < 2) return 1;
    int side = 1;
    while (side < maxSide && weight * 2 * static_cast<std::size_t>(threads) >
                                 totalWeight * static_cast<std::size_t>(side * side))
        side *= 2;
    return side;
}

void appendTileParts(const TileGrid& grid, std::uint32_t tile, int gridTile, int side,
                     std::vector<TilePart>& parts) {
    bool first = true;
    for (int part = 0; part < side * side; ++part) {
        if (side > 1 && grid.tilePartRect(gridTile, side, part).empty()) continue;
        parts.push_back({tile, static_cast<std::uint8_t>(side), static_cast<std::uint8_t>(part), first});
        first = false;
    }
}

void binTriangle(const TileGrid& grid, const TriangleSetup& setup, std::uint32_t setupIndex,
                 std::vector<std::vector<std::uint32_t>>& bins, std::int64_t sampleReach,
                 std::vector<std::uint32_t>* touched) {
    // Pixel bounds are inside the viewport, so ≥ 0.
    const int c0 = std::max(grid.tileOf(setup.minX), grid.firstColumn) - grid.firstColumn;
    const int c1 = std::min(grid.tileOf(setup.maxX) - grid.firstColumn, grid.columns - 1);
    const int r0 = std::max(grid.tileOf(setup.minY), grid.firstRow) - grid.firstRow;
    const int r1 = std::min(grid.tileOf(setup.maxY) - grid.firstRow, grid.rows - 1);
    const bool single = c0 == c1 && r0 == r1;
    for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c) {
            const int tile = r * grid.columns + c;
            if (!single) {
                // Skip a tile wholly outside one edge: the edge's largest value over the tile's sample
                // points is at the corner its gradient points to (with multisampling, at most
                // sampleReach beyond the corner pixel's centre: a bound, never a miss).
                const PixelRect rect = grid.tileRect(tile);
                bool outside = false;
                for (const EdgeFunction& e : setup.edges) {
                    const std::int64_t x = e.a > 0 ? sampleCoordinate(rect.maxX) + sampleReach
                                                   : sampleCoordinate(rect.minX) - sampleReach;
                    const std::int64_t y = e.b > 0 ? sampleCoordinate(rect.maxY) + sampleReach
                                                   : sampleCoordinate(rect.minY) - sampleReach;
                    outside |= e.at(x, y) + e.bias() < 0;
                }
                if (outside) continue;
            }
            if (touched && bins[tile].empty()) touched->push_back(static_cast<std::uint32_t>(tile));
            bins[tile].push_back(setupIndex);
        }
}

}  // namespace facet
