#include "fragment_lists.h"

#include <algorithm>
#include <bit>
#include <ostream>
#include <stdexcept>
#include <string>

#include "blend.h"
#include "framebuffer.h"
#include "thread_pool.h"

namespace facet {

static_assert(sizeof(FragmentLists::Node) == 24, "a stored fragment is 24 bytes");
static_assert(static_cast<std::uint32_t>(BlendMode::Multiply) < 8, "a BlendMode fits in a node's 3 bits");

namespace {

// Lists no longer than this are sorted by insertion (stable, and linear on lists submitted in order);
// longer ones by std::sort. Keys are unique, so both give the same order.
constexpr std::size_t kInsertionSortLimit = 24;

// Each resolving thread's gather array starts with room for lists this long (4 KB), so that which thread
// meets the longest list does not change the memory held; longer lists grow it, once.
constexpr std::size_t kScratchEntries = 256;

// A key whose unsigned order is "farther first, then older first": the depth's bits mapped to an
// unsigned integer that orders like the float (negatives flipped), inverted so that larger depths
// come first, above the fragment's position in submission order.
std::uint64_t sortKey(float depth, std::uint32_t submission) {
    const auto bits = std::bit_cast<std::uint32_t>(depth + 0.0f);  // −0 → +0: equal depths tie
    const std::uint32_t ordered = (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
    return (std::uint64_t{~ordered} << 32) | submission;
}

}  // namespace

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
    w.pool_ = &pools_[static_cast<std::size_t>(y / tileSize_) * columns_ + x / tileSize_];
    w.heads_ = heads_.data();
    w.width_ = width_;
    return w;
}

PixelRect FragmentLists::tileRect(int tile) const {
    const int column = tile % columns_, row = tile / columns_;
    return {column * tileSize_, row * tileSize_, std::min((column + 1) * tileSize_, width_) - 1,
            std::min((row + 1) * tileSize_, height_) - 1};
}

void FragmentLists::clear(ThreadPool& pool) {
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

void FragmentLists::resolveTile(int tile, Framebuffer& target, ResolveScratch& scratch) const {
    const TilePool& pool = pools_[static_cast<std::size_t>(tile)];
    scratch.stats.dropped += pool.dropped;
    if (pool.nodes.empty()) return;
    const Node* nodes = pool.nodes.data();
    std::vector<Entry>& entries = scratch.entries;
    const PixelRect rect = tileRect(tile);
    for (int y = rect.minY; y <= rect.maxY; ++y) {
        const std::uint32_t* heads = &heads_[pixelIndex(0, y)];
        for (int x = rect.minX; x <= rect.maxX; ++x) {
            const std::uint32_t head = heads[x];
            if (head == kEnd) continue;
            vec4& color = target.color(x, y);
            const Node& newest = nodes[head];
            if (newest.previous() == kEnd) {
                // One fragment: nothing to sort.
                color = blend(newest.blend(), newest.color, color);
                ++scratch.stats.fragments;
                ++scratch.stats.pixels;
                scratch.stats.longestList = std::max(scratch.stats.longestList, 1u);
                continue;
            }
            // Gather the list (newest first), then put it in submission order.
            entries.clear();
            for (std::uint32_t k = head; k != kEnd; k = nodes[k].previous())
                entries.push_back(Entry{0, k});
            std::reverse(entries.begin(), entries.end());
            const std::size_t n = entries.size();
            for (std::size_t i = 0; i < n; ++i)
                entries[i].key = sortKey(nodes[entries[i].node].depth, static_cast<std::uint32_t>(i));

            // Farthest first, equal depths in submission order.
            if (n <= kInsertionSortLimit) {
                for (std::size_t i = 1; i < n; ++i) {
                    const Entry e = entries[i];
                    std::size_t j = i;
                    for (; j > 0 && entries[j - 1].key > e.key; --j)
                        entries[j] = entries[j - 1];
                    entries[j] = e;
                }
            } else {
                std::sort(entries.begin(), entries.end(),
                          [](const Entry& a, const Entry& b) { return a.key < b.key; });
            }

            vec4 c = color;
            for (const Entry& e : entries) {
                const Node& node = nodes[e.node];
                c = blend(node.blend(), node.color, c);
            }
            color = c;
            scratch.stats.fragments += n;
            ++scratch.stats.pixels;
            scratch.stats.longestList = std::max(scratch.stats.longestList, static_cast<std::uint32_t>(n));
        }
    }
}

FragmentListStats resolveFragmentLists(Framebuffer& target, ThreadPool& pool) {
    FragmentLists& lists = target.fragmentLists();
    if (lists.scratch_.size() < static_cast<std::size_t>(pool.threads())) {
        lists.scratch_.resize(static_cast<std::size_t>(pool.threads()));
        for (FragmentLists::ResolveScratch& s : lists.scratch_)
            s.entries.reserve(kScratchEntries);
    }
    for (FragmentLists::ResolveScratch& s : lists.scratch_)
        s.stats = FragmentListStats{};
    const FragmentLists& reading = lists;
    pool.parallelFor(lists.pools_.size(), [&](std::size_t tile, int thread) {
        reading.resolveTile(static_cast<int>(tile), target, lists.scratch_[static_cast<std::size_t>(thread)]);
    });
    FragmentListStats total;
    for (const FragmentLists::ResolveScratch& s : lists.scratch_) {
        total.fragments += s.stats.fragments;
        total.pixels += s.stats.pixels;
        total.longestList = std::max(total.longestList, s.stats.longestList);
        total.dropped += s.stats.dropped;
    }
    total.bytesHeld = lists.bytesHeld();
    return total;
}

}  // namespace facet
