// TEMPORARY until the real sorter lands: std::stable_sort from scratch every frame.
#include <algorithm>
#include <numeric>

#include "transparency_sort.h"

namespace facet {

std::span<const std::uint32_t> TransparencySorter::sort(std::span<const float> keys, SortAlgorithm,
                                                        SortStats& stats) {
    order_.resize(keys.size());
    std::iota(order_.begin(), order_.end(), 0u);
    std::stable_sort(order_.begin(), order_.end(), [&](std::uint32_t a, std::uint32_t b) { return keys[a] > keys[b]; });
    stats = {keys.size(), 0, 0, true};
    return order_;
}

void TransparencySorter::forget() { order_.clear(); }

}  // namespace facet
