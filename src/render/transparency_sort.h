// Back-to-front order of transparent triangles, re-sorted every frame by insertion sort starting from the
// previous frame's order. Between two frames of an animation the depths change little, so the old
// order is almost sorted already: insertion sort then costs O(n + inversions), about O(n), where a sort
// from scratch pays O(n log n) whatever the input. The sorter counts its comparisons and moves so the
// claim can be checked frame by frame (`facet render --stats`, `facet bench --sort`).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace facet {

enum class SortAlgorithm {
    InsertionWithMemory,  // insertion sort of the previous frame's order (from scratch on the first frame)
    FromScratch,          // std::sort of 0, 1, ..., n − 1 every frame (the comparison)
    RadixFromScratch,     // LSD radix sort of the keys' bits every frame: O(n), no comparisons at all
};

struct SortStats {
    std::size_t elements = 0;
    std::size_t comparisons = 0;  // key comparisons (FromScratch: calls of std::sort's comparator)
    // Element moves: insertion sort's shifts by one place, so on a remembered order exactly the number of
    // inversions between it and the new keys. Always 0 for FromScratch:
    // std::sort and std::stable_sort move elements by swaps, partitions and merges that are not
    // comparable with shifts, and counting them would take an instrumented element type inside the sort
    // being timed; their cost is O(n log n) whatever the input. Compare their comparisons instead.
    // A radix sort (RadixFromScratch, and InsertionWithMemory's first frame) counts its 4·n writes.
    std::size_t moves = 0;
    bool fromScratch = false;  // no usable previous order (first frame, or the count changed)
};

class TransparencySorter {
  public:
    // Orders the elements 0 .. keys.size() − 1 back to front: by key descending (a larger key is
    // farther from the eye), ties kept in the previous order (in index order when from scratch), so the
    // result is deterministic. Returns the order (valid until the next call) and fills `stats`.
    // InsertionWithMemory starts from the order the previous call returned when it had the same element
    // count; otherwise (first frame, changed count) it sorts from scratch with the radix sort (the
    // stable sort's order; stats.moves = 4·n, no comparisons) and says so in stats.fromScratch. FromScratch
    // uses std::sort (introsort: in place, no buffer to allocate, the usual baseline) with ties broken by
    // index, which makes its result deterministic and the same as a stable sort's. A NaN key counts as
    // farther than +∞ (drawn first), all NaNs equal to each other; −0 equals +0. At most 2³² − 1 elements
    // (std::length_error beyond).
    std::span<const std::uint32_t> sort(std::span<const float> keys, SortAlgorithm algorithm,
                                        SortStats& stats);

    // Drops the remembered order: the next sort starts from scratch.
    void forget();

  private:
    // What the sorts move: a key turned into an unsigned integer of the same order (NaN and −0 made
    // canonical, so the comparison is a strict weak order) next to its element, contiguous, so a
    // comparison reads neighbouring memory instead of gathering keys[order[j]].
    struct Entry {
        std::uint32_t key;
        std::uint32_t index;
    };

    void radixSort(std::span<const float> keys);

    std::vector<std::uint32_t> order_;
    std::vector<Entry> entries_;       // scratch, kept to avoid an allocation per frame
    std::vector<Entry> radixScratch_;  // the radix sort's second buffer
    bool remembered_ = false;          // order_ holds a previous result (it may be empty)
};

}  // namespace facet
