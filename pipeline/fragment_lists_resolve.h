// The resolve of the per-pixel fragment lists (fragment_lists.h): each pixel's list sorted by depth,
// farthest first (equal depths in submission order), and composited over the framebuffer's colour,
// each fragment with its own blend mode. One template for the plain resolve (NullObserver, tiles in
// parallel) and the observed one (on the calling thread, every pixel's resolve shown to the observer).
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

#include "blend.h"
#include "depth_format.h"
#include "fragment_lists.h"
#include "framebuffer.h"
#include "observer.h"
#include "thread_pool.h"

namespace facet {

namespace detail {

// Lists no longer than this are sorted by insertion (stable, and linear on lists submitted in order);
// longer ones by std::sort. Keys are unique, so both give the same order.
inline constexpr std::size_t kInsertionSortLimit = 24;

// Each resolving thread's gather array starts with room for lists this long (4 KB), so that which thread
// meets the longest list does not change the memory held; longer lists grow it, once.
inline constexpr std::size_t kScratchEntries = 256;

// A key whose unsigned order is "farther first, then older first": the depth's bits mapped to an
// unsigned integer that orders like the float (negatives flipped), inverted when smaller depths are
// nearer (DepthFormat) so that farther depths come first, above the fragment's position in submission
// order.
template <bool kLessIsNearer = true>
std::uint64_t resolveSortKey(float depth, std::uint32_t submission) {
    const auto bits = std::bit_cast<std::uint32_t>(depth + 0.0f);  // −0 → +0: equal depths tie
    const std::uint32_t ordered = (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
    const std::uint32_t fartherFirst = kLessIsNearer ? ~ordered : ordered;
    return (std::uint64_t{fartherFirst} << 32) | submission;
}

}  // namespace detail

namespace detail {

// A list's entries farthest first, equal depths in submission order (their keys: resolveSortKey).
template <class Entry>
void sortFarthestFirst(std::vector<Entry>& entries) {
    const std::size_t n = entries.size();
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
}

}  // namespace detail

template <bool kLessIsNearer, ColorBufferFormat kColor, class Observer>
void FragmentLists::resolveTile(int tile, Framebuffer& target, ResolveScratch& scratch,
                                Observer& observer) const {
    const TilePool& pool = pools_[static_cast<std::size_t>(tile)];
    scratch.stats.dropped += pool.dropped;
    if (pool.nodes.empty()) return;
    const Node* nodes = pool.nodes.data();
    [[maybe_unused]] std::vector<ResolvedFragment> observed;  // an observer's view of one pixel's list
    const PixelRect rect = tileRect(tile);
    const FramebufferPlanes planes = target.planesToDraw(rect);
    for (int y = rect.minY; y <= rect.maxY; ++y) {
        const std::uint32_t* heads = &heads_[pixelIndex(0, y)];
        for (int x = rect.minX; x <= rect.maxX; ++x) {
            const std::uint32_t head = heads[x];
            if (head == kEnd) continue;
            resolvePixel<kLessIsNearer, kColor>(x, y, nodes, head, planes.color(x, y), scratch, observed,
                                                observer);
        }
    }
}

// One pixel's list, from its newest node `head`, composited over `color` farthest first.
template <bool kLessIsNearer, ColorBufferFormat kColor, class Observer>
[[gnu::always_inline]] inline void FragmentLists::resolvePixel(int x, int y, const Node* nodes,
                                                               std::uint32_t head, vec4& color,
                                                               ResolveScratch& scratch,
                                                               std::vector<ResolvedFragment>& observed,
                                                               Observer& observer) const {
    constexpr bool kObserving = Observer::enabled;
    std::vector<Entry>& entries = scratch.entries;
    const Node& newest = nodes[head];
    if (newest.previous() == kEnd) {
        // One fragment: nothing to sort.
        if constexpr (kObserving) {
            const vec4 before = color;
            observed.assign(1, ResolvedFragment{0, newest.depth, newest.blend(), newest.color, vec4(0.0f)});
            observed[0].colorAfter = roundToColorBuffer<kColor>(blend(newest.blend(), newest.color, before));
            observer.onResolve(ResolveEvent{x, y, before, observed});
        }
        color = roundToColorBuffer<kColor>(blend(newest.blend(), newest.color, color));
        ++scratch.stats.fragments;
        ++scratch.stats.pixels;
        scratch.stats.longestList = std::max(scratch.stats.longestList, 1u);
        return;
    }
    // Gather the list (newest first), then put it in submission order.
    entries.clear();
    for (std::uint32_t k = head; k != kEnd; k = nodes[k].previous())
        entries.push_back(Entry{0, k});
    std::reverse(entries.begin(), entries.end());
    const std::size_t n = entries.size();
    for (std::size_t i = 0; i < n; ++i)
        entries[i].key = detail::resolveSortKey<kLessIsNearer>(nodes[entries[i].node].depth,
                                                               static_cast<std::uint32_t>(i));

    detail::sortFarthestFirst(entries);

    vec4 c = color;
    if constexpr (kObserving) observed.clear();
    for (const Entry& e : entries) {
        const Node& node = nodes[e.node];
        c = roundToColorBuffer<kColor>(blend(node.blend(), node.color, c));
        if constexpr (kObserving)
            observed.push_back(ResolvedFragment{static_cast<std::uint32_t>(e.key & 0xffffffffu), node.depth,
                                                node.blend(), node.color, c});
    }
    if constexpr (kObserving) observer.onResolve(ResolveEvent{x, y, color, observed});
    color = c;
    scratch.stats.fragments += n;
    ++scratch.stats.pixels;
    scratch.stats.longestList = std::max(scratch.stats.longestList, static_cast<std::uint32_t>(n));
}

template <class Observer>
FragmentListStats FragmentLists::resolve(Framebuffer& target, ThreadPool& pool, Observer& observer) {
    if (scratch_.size() < static_cast<std::size_t>(pool.threads())) {
        scratch_.resize(static_cast<std::size_t>(pool.threads()));
        for (ResolveScratch& s : scratch_)
            s.entries.reserve(detail::kScratchEntries);
    }
    for (ResolveScratch& s : scratch_)
        s.stats = FragmentListStats{};
    // The formats chosen once for the whole resolve, as drawTileOfChunks chooses a draw's walk.
    withDepthFormat(depthFormat_, [&](auto depthFormat) {
        constexpr bool kLessIsNearer = decltype(depthFormat)::kLessIsNearer;
        switch (colorBuffer_) {
            case ColorBufferFormat::Half:
                resolveTiles<kLessIsNearer, ColorBufferFormat::Half>(target, pool, observer);
                return;
            case ColorBufferFormat::Unorm8:
                resolveTiles<kLessIsNearer, ColorBufferFormat::Unorm8>(target, pool, observer);
                return;
            case ColorBufferFormat::Float:
                break;
        }
        resolveTiles<kLessIsNearer, ColorBufferFormat::Float>(target, pool, observer);
    });
    FragmentListStats total;
    for (const ResolveScratch& s : scratch_) {
        total.fragments += s.stats.fragments;
        total.pixels += s.stats.pixels;
        total.longestList = std::max(total.longestList, s.stats.longestList);
        total.dropped += s.stats.dropped;
    }
    total.bytesHeld = bytesHeld();
    return total;
}

template <bool kLessIsNearer, ColorBufferFormat kColor, class Observer>
void FragmentLists::resolveTiles(Framebuffer& target, ThreadPool& pool, Observer& observer) {
    const FragmentLists& reading = *this;
    forEachItem(pool, Observer::enabled, pools_.size(), [&](std::size_t tile, int thread) {
        reading.resolveTile<kLessIsNearer, kColor>(static_cast<int>(tile), target,
                                                   scratch_[static_cast<std::size_t>(thread)], observer);
    });
}

// resolveFragmentLists (fragment_lists.h), on the calling thread, each pixel's resolve shown to the
// observer (Observer::onResolve) in tile order, row by row inside a tile.
template <class Observer>
FragmentListStats resolveFragmentLists(Framebuffer& target, ThreadPool& pool, Observer&& observer) {
    return target.fragmentLists().resolve(target, pool, observer);
}

}  // namespace facet
