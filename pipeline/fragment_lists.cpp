#include "fragment_lists.h"

#include <algorithm>
#include <bit>
#include <ostream>
#include <stdexcept>
#include <string>

#include "fragment_lists_resolve.h"

namespace facet {

static_assert(sizeof(FragmentLists::Node) == 24, "a stored fragment is 24 bytes");
static_assert(static_cast<std::uint32_t>(BlendMode::OverGL) < 8, "a BlendMode fits in a node's 3 bits");

std::ostream& operator<<(std::ostream& os, const FragmentListStats& s) {
    os << s.fragments << " fragments in " << s.pixels << " pixel lists (longest " << s.longestList << "), "
       << s.bytesHeld << " bytes held";
    if (s.dropped) os << "; " << s.dropped << " dropped: a tile's pool was full";
    return os;
}

void FragmentLists::prepare(int width, int height, int tileSize) {
    if (width == width_ && height == height_ && tileSize == tileSize_) return;
    if (!empty())
        throw std::invalid_argument(
            "the fragment lists hold fragments of a " + std::to_string(width_) + "x" +
            std::to_string(height_) + " target drawn in tiles of " + std::to_string(tileSize_) +
            " pixels; clear them before drawing into them at " + std::to_string(width) + "x" +
            std::to_string(height) + " in tiles of " + std::to_string(tileSize));
    if (tileSize != tileSize_ || width != width_ || height != height_) {
        pools_.clear();  // their tiles change: the next frame grows them anew
        nodeBytesHeld_ = 0;
    }
    if (width != width_ || height != height_)
        heads_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), kEnd);
    width_ = width;
    height_ = height;
    tileSize_ = tileSize;
    columns_ = (width + tileSize - 1) / tileSize;
    rows_ = (height + tileSize - 1) / tileSize;
    pools_.resize(static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_));
}

FragmentLists::TileWriter FragmentLists::writer(int x, int y) {
    TileWriter w;
    w.lists_ = this;
    w.pool_ = &pools_[static_cast<std::size_t>(y / tileSize_) * columns_ + x / tileSize_];
    w.heads_ = heads_.data();
    w.width_ = width_;
    return w;
}

bool FragmentLists::grow(std::vector<Node>& nodes) {
    const std::size_t capacity = nodes.capacity(),
                      next = std::min<std::size_t>(nextCapacity(capacity), kMaxNodesPerTile);
    const std::uint64_t more = nodeBytes(next) - nodeBytes(capacity);
    std::atomic_ref<std::uint64_t> heldBytes(nodeBytesHeld_), refusedBytes(refusedBytes_);
    const std::uint64_t held = heldBytes.fetch_add(more, std::memory_order_relaxed) + more;
    if (held > byteBudget_) {
        heldBytes.fetch_sub(more, std::memory_order_relaxed);
        std::uint64_t refused = refusedBytes.load(std::memory_order_relaxed);
        while (held > refused &&
               !refusedBytes.compare_exchange_weak(refused, held, std::memory_order_relaxed)) {
        }
        return false;
    }
    nodes.reserve(next);
    return true;
}

PixelRect FragmentLists::tileRect(int tile) const {
    const int column = tile % columns_, row = tile / columns_;
    return {column * tileSize_, row * tileSize_, std::min((column + 1) * tileSize_, width_) - 1,
            std::min((row + 1) * tileSize_, height_) - 1};
}

void FragmentLists::clear(ThreadPool& pool) {
    refusedBytes_ = 0;
    pool.parallelFor(pools_.size(), [&](std::size_t tile, int) {
        TilePool& tilePool = pools_[tile];
        tilePool.dropped = 0;
        if (tilePool.nodes.empty()) return;  // no head in the tile points anywhere
        tilePool.nodes.clear();
        const PixelRect rect = tileRect(static_cast<int>(tile));
        for (int y = rect.minY; y <= rect.maxY; ++y)
            std::fill_n(heads_.begin() + static_cast<std::ptrdiff_t>(pixelIndex(rect.minX, y)),
                        rect.maxX - rect.minX + 1, kEnd);
    });
}

std::uint64_t FragmentLists::size() const {
    std::uint64_t n = 0;
    for (const TilePool& p : pools_)
        n += p.nodes.size();
    return n;
}

std::uint64_t FragmentLists::dropped() const {
    std::uint64_t n = 0;
    for (const TilePool& p : pools_)
        n += p.dropped;
    return n;
}

std::size_t FragmentLists::bytesHeld() const {
    std::size_t bytes = heads_.capacity() * sizeof(std::uint32_t) + pools_.capacity() * sizeof(TilePool) +
                        scratch_.capacity() * sizeof(ResolveScratch);
    for (const TilePool& p : pools_)
        bytes += p.nodes.capacity() * sizeof(Node);
    for (const ResolveScratch& s : scratch_)
        bytes += s.entries.capacity() * sizeof(Entry);
    return bytes;
}

std::vector<FragmentLists::Node> FragmentLists::fragmentsAt(int x, int y) const {
    std::vector<Node> list;
    if (!allocated()) return list;
    const std::vector<Node>& nodes =
        pools_[static_cast<std::size_t>(y / tileSize_) * columns_ + x / tileSize_].nodes;
    for (std::uint32_t k = heads_[pixelIndex(x, y)]; k != kEnd; k = nodes[k].previous())
        list.push_back(nodes[k]);
    std::reverse(list.begin(), list.end());
    return list;
}

FragmentListStats resolveFragmentLists(Framebuffer& target, ThreadPool& pool) {
    NullObserver none;
    return target.fragmentLists().resolve(target, pool, none);
}

}  // namespace facet
