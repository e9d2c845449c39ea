#include "render/transparency_sort.h"

#include <algorithm>
#include <bit>
#include <limits>
#include <stdexcept>

namespace facet {

namespace {

// The float's order as an unsigned integer: a larger key gives a larger integer. Negative floats have
// their bits flipped (so −1 < −0.5), positive ones the sign bit set (so they sit above every negative
// one). Every NaN becomes the positive quiet NaN, which lands above +∞ (farthest), and −0 becomes +0,
// so that integer equality is float equality plus "NaN equals NaN": a strict weak order with no
// surprise for std::sort.
std::uint32_t sortableKey(float key) {
    std::uint32_t bits = std::bit_cast<std::uint32_t>(key);
    if (key != key) bits = 0x7FC00000u;  // NaN (no -ffast-math in this project, so this test holds)
    if (key == 0.0f) bits = 0u;          // −0 → +0
    return (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
}

}  // namespace

std::span<const std::uint32_t> TransparencySorter::sort(std::span<const float> keys, SortAlgorithm algorithm,
                                                        SortStats& stats) {
    if (keys.size() > std::numeric_limits<std::uint32_t>::max())
        throw std::length_error("TransparencySorter: more than 2^32 - 1 elements");
    const std::size_t n = keys.size();
    stats = SortStats{};
    stats.elements = n;
    entries_.resize(n);

    // InsertionWithMemory with no order to start from (first frame, changed count) takes the radix sort
    // too: the stable sort's order in O(n) (5–7× faster than std::stable_sort on Lost Empire's 225k
    // keys: `facet bench --sort`), so a one-shot render pays little for it.
    const bool nothingRemembered = !remembered_ || order_.size() != n;
    if (algorithm == SortAlgorithm::RadixFromScratch ||
        (algorithm == SortAlgorithm::InsertionWithMemory && nothingRemembered)) {
        radixSort(keys);
        stats.moves = 4 * n;  // four passes of one write per element; no comparisons
        stats.fromScratch = true;
        return order_;
    }
    if (algorithm == SortAlgorithm::FromScratch) {
        for (std::size_t i = 0; i < n; ++i)
            entries_[i] = {sortableKey(keys[i]), static_cast<std::uint32_t>(i)};
        std::size_t comparisons = 0;
        // Key descending, then index ascending: one 64-bit comparison; no two entries are equal, so the
        // result is the stable sort's and does not depend on std::sort's pivots.
        const auto rank = [](Entry e) {
            return (static_cast<std::uint64_t>(e.key) << 32) | static_cast<std::uint32_t>(~e.index);
        };
        std::sort(entries_.begin(), entries_.end(), [&](Entry a, Entry b) {
            ++comparisons;
            return rank(a) > rank(b);
        });
        stats.comparisons = comparisons;
        stats.fromScratch = true;
    } else {
        // The previous order with this frame's keys: one gather per element, not one per comparison.
        for (std::size_t i = 0; i < n; ++i)
            entries_[i] = {sortableKey(keys[order_[i]]), order_[i]};

        // Insertion sort, descending. Element i is compared with its left neighbours while they are
        // strictly nearer (a smaller key), each of which shifts one place right: `shifted` moves and as
        // many comparisons that said "nearer", plus the one that stopped the scan unless it reached the
        // front. Equal keys stop the scan, so ties keep the previous order.
        std::size_t comparisons = 0, moves = 0;
        Entry* const e = entries_.data();
        for (std::size_t i = 1; i < n; ++i) {
            const Entry x = e[i];
            if (!(e[i - 1].key < x.key)) {  // in place already: the common case between two frames
                ++comparisons;
                continue;
            }
            std::size_t j = i;
            do {
                e[j] = e[j - 1];
                --j;
            } while (j > 0 && e[j - 1].key < x.key);
            e[j] = x;
            moves += i - j;
            comparisons += (i - j) + (j > 0 ? 1 : 0);
        }
        stats.comparisons = comparisons;
        stats.moves = moves;
    }

    order_.resize(n);
    for (std::size_t i = 0; i < n; ++i)
        order_[i] = entries_[i].index;
    remembered_ = true;
    return order_;
}

// Least-significant-digit radix sort, four passes of 8 bits over ~key (so ascending ~key is descending
// key). Each pass is a stable counting sort, and the input is in index order, so ties end in index
// order: the same result as FromScratch.
void TransparencySorter::radixSort(std::span<const float> keys) {
    const std::size_t n = keys.size();
    entries_.resize(n);
    radixScratch_.resize(n);
    for (std::size_t i = 0; i < n; ++i)
        entries_[i] = {~sortableKey(keys[i]), static_cast<std::uint32_t>(i)};
    Entry* from = entries_.data();
    Entry* to = radixScratch_.data();
    for (int shift = 0; shift < 32; shift += 8) {
        std::size_t start[256] = {};
        for (std::size_t i = 0; i < n; ++i)
            ++start[(from[i].key >> shift) & 0xFFu];
        std::size_t sum = 0;
        for (std::size_t& s : start) {
            const std::size_t count = s;
            s = sum;
            sum += count;
        }
        for (std::size_t i = 0; i < n; ++i)
            to[start[(from[i].key >> shift) & 0xFFu]++] = from[i];
        std::swap(from, to);
    }
    // Four passes: the sorted entries are back in entries_.
    order_.resize(n);
    for (std::size_t i = 0; i < n; ++i)
        order_[i] = entries_[i].index;
    remembered_ = true;
}

void TransparencySorter::forget() {
    order_.clear();
    remembered_ = false;
}

}  // namespace facet
