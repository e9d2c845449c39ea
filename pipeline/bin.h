// Binning: the seam between the front end (one triangle at a time) and the back end (one tile at a
// time, tiles in parallel). The viewport is cut into square tiles; each triangle is listed in the bin of
// every tile it may cover, in submission order, so a tile's triangles are drawn in the order they came.
// In: TriangleSetup. Out: its index appended to tile bins. (llvmpipe's setup/rast split.)
#pragma once

#include <cstdint>
#include <vector>

#include "state.h"
#include "types.h"

namespace facet {

inline constexpr int kDefaultTileSize = 64;  // pixels; a tile's colour and depth (64·64·20 B) fit in L2

struct TileGrid {
    int tileSize = kDefaultTileSize;    // pixels, a multiple of kBlockSize
    PixelRect area;                     // the viewport's pixels
    int firstColumn = 0, firstRow = 0;  // tiles sit on multiples of tileSize in the framebuffer
    int columns = 0, rows = 0;
    // log2(tileSize) when the size is a power of two (the default and every size the tests use), else −1.
    int tileShift = -1;

    int count() const { return columns * rows; }
    // The framebuffer column or row of tiles that pixel column or row p ≥ 0 lies in: p / tileSize, by a
    // shift when the size allows (binning asks four times per triangle; a division instruction costs
    // tens of cycles).
    int tileOf(int p) const { return tileShift >= 0 ? p >> tileShift : p / tileSize; }
    PixelRect tileRect(int index) const;  // the tile's pixels inside the viewport
    // The most parts a side of a tile may be cut into (tilePartRect): 1, 2 or 4, keeping each part a
    // multiple of kBlockSize wide, so that the back end places its blocks in a part as in a tile.
    int maxPartsPerSide() const;
    // Part `part` (row-major) of tile `index` cut into side × side squares of tileSize / side pixels,
    // inside the viewport (empty for a part of an edge tile wholly outside it). side divides tileSize.
    PixelRect tilePartRect(int index, int side, int part) const;
};

TileGrid makeTileGrid(const Viewport& viewport, int tileSize);

// One item of a back end: tile `tile` of a list of tiles (its index there), whole (side 1) or one of its
// side × side parts (TileGrid::tilePartRect). Each pixel of a part sees the tile's triangles in the
// same order, and a triangle's blocks are placed in a part as in a tile, so the bytes do not depend on
// the cut.
struct TilePart {
    std::uint32_t tile = 0;
    std::uint8_t side = 1, part = 0;
    bool first = true;  // the tile's first part inside the viewport: the one that counts the tile as drawn
};

// How many parts a side of a tile is cut into for `threads` threads: the tile holds `weight` of the
// back end's `totalWeight` (triangles binned to it, or draws touching it), and is cut, side by 2 up to
// maxSide, while a part would hold more than 1/(2·threads) of the total. A job of the pool lasts at
// least its longest item: cut for 16 threads, Lost Empire's transparent runs are 512 draws over 20–40
// tiles, and one tile held up to a fifth of its run's back end. One thread cuts nothing.
int tilePartsPerSide(std::size_t weight, std::size_t totalWeight, int threads, int maxSide);

// Appends tile `tile` of a list (grid tile gridTile) cut side × side: its parts inside the viewport.
void appendTileParts(const TileGrid& grid, std::uint32_t tile, int gridTile, int side,
                     std::vector<TilePart>& parts);

// Appends `setupIndex` to bins[t] for every tile t that the triangle's bounding box overlaps and that
// is not wholly outside one of its edges. `bins` has grid.count() entries. `sampleReach`: how far from
// its pixel's centre a sample may lie (sampleReachFixed of the draw's samples). `touched`, when given,
// gets each tile whose bin was empty before.
void binTriangle(const TileGrid& grid, const TriangleSetup& setup, std::uint32_t setupIndex,
                 std::vector<std::vector<std::uint32_t>>& bins, std::int64_t sampleReach = 0,
                 std::vector<std::uint32_t>* touched = nullptr);

// What the front end hands the back end for one chunk of consecutive triangles: their setups, the
// setups' varying planes, and for every tile the setups that may touch it, in submission order.
struct SetupChunk {
    std::vector<TriangleSetup> setups;
    std::vector<float> varyingPlanes;              // 3 · varyingCount floats per setup (types.h), in order
    std::vector<std::vector<std::uint32_t>> bins;  // per tile: indices into setups
    // The tiles whose bins are not empty, in the order they were first binned: what the back end
    // visits and the next batch empties, so that a draw of a few triangles (Lost Empire's transparent
    // pass: 4,064 draws) does not pass over every tile of the screen twice.
    std::vector<std::uint32_t> touchedTiles;
    DrawStats stats;
    ClipPolygon polygon;  // clipping scratch

    // The varying planes of one of this chunk's setups.
    const float* planesOf(const TriangleSetup& setup) const {
        return varyingPlanes.data() + setup.varyingPlaneOffset;
    }
};

}  // namespace facet
