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
};

struct SortStats {
    std::size_t elements = 0;
    std::size_t comparisons = 0;  // key comparisons
    std::size_t moves = 0;        // element moves (insertion sort: shifts by one place)
    bool fromScratch = false;     // no usable previous order (first frame, or the count changed)
};

class TransparencySorter {
  public:
    // Orders the elements 0 .. keys.size() − 1 back to front: by key descending (a larger key is
    // farther from the eye), ties kept in the previous order (in index order when from scratch), so the
    // result is deterministic. Returns the order (valid until the next call) and fills `stats`.
    // InsertionWithMemory starts from the order the previous call returned when it had the same element
    // count; otherwise (first frame, changed count) it sorts from scratch with std::stable_sort and
    // says so in stats.fromScratch.
    std::span<const std::uint32_t> sort(std::span<const float> keys, SortAlgorithm algorithm,
                                        SortStats& stats);

    // Drops the remembered order: the next sort starts from scratch.
    void forget();

  private:
    std::vector<std::uint32_t> order_;
};

}  // namespace facet
