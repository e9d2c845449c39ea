// The transparency sorter: the counts insertion sort promises (n − 1 comparisons and no move on a sorted
// order, one move per inversion), ties kept in the previous order, the fall-back to a sort from scratch,
// results equal to std::stable_sort's over many random frames, a turntable's cheap frames, NaN keys.
#include "render/transparency_sort.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace facet {
namespace {

using Order = std::vector<std::uint32_t>;

// The order the sorter promises: key descending, a NaN farther than anything else (NaNs equal).
bool farther(float a, float b) {
    if (std::isnan(a)) return !std::isnan(b);
    if (std::isnan(b)) return false;
    return a > b;
}

// `previous` stably sorted by `keys` descending: what insertion sort from the previous order must give.
Order stableSorted(Order previous, const std::vector<float>& keys) {
    std::stable_sort(previous.begin(), previous.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return farther(keys[a], keys[b]); });
    return previous;
}

Order identity(std::size_t n) {
    Order order(n);
    std::iota(order.begin(), order.end(), 0u);
    return order;
}

// Pairs that `order` has the wrong way round for `keys` (a nearer element before a strictly farther one).
std::size_t inversions(const Order& order, const std::vector<float>& keys) {
    std::size_t count = 0;
    for (std::size_t i = 0; i < order.size(); ++i)
        for (std::size_t j = i + 1; j < order.size(); ++j)
            count += farther(keys[order[j]], keys[order[i]]);
    return count;
}

Order sortOnce(TransparencySorter& sorter, const std::vector<float>& keys, SortAlgorithm algorithm,
               SortStats& stats) {
    const auto order = sorter.sort(keys, algorithm, stats);
    return Order(order.begin(), order.end());
}

TEST(TransparencySort, SortedInputCostsNMinusOneComparisonsAndNoMove) {
    const std::size_t n = 1000;
    std::vector<float> keys(n);
    for (std::size_t i = 0; i < n; ++i)
        keys[i] = static_cast<float>(n - i);  // already back to front
    TransparencySorter sorter;
    SortStats stats;
    EXPECT_EQ(sortOnce(sorter, keys, SortAlgorithm::InsertionWithMemory, stats), identity(n));
    EXPECT_TRUE(stats.fromScratch);
    EXPECT_EQ(stats.elements, n);

    EXPECT_EQ(sortOnce(sorter, keys, SortAlgorithm::InsertionWithMemory, stats), identity(n));
    EXPECT_FALSE(stats.fromScratch);
    EXPECT_EQ(stats.elements, n);
    EXPECT_EQ(stats.comparisons, n - 1);
    EXPECT_EQ(stats.moves, 0u);
}

TEST(TransparencySort, ReversedInputCostsOneMovePerPair) {
    const std::size_t n = 1000;
    std::vector<float> keys(n);
    for (std::size_t i = 0; i < n; ++i)
        keys[i] = static_cast<float>(i);
    TransparencySorter sorter;
    SortStats stats;
    const Order first = sortOnce(sorter, keys, SortAlgorithm::InsertionWithMemory, stats);  // n − 1, ..., 0
    ASSERT_TRUE(stats.fromScratch);
    ASSERT_EQ(first.front(), n - 1);

    for (std::size_t i = 0; i < n; ++i)
        keys[i] = -static_cast<float>(i);  // the remembered order is now exactly backwards
    ASSERT_EQ(inversions(first, keys), n * (n - 1) / 2);
    EXPECT_EQ(sortOnce(sorter, keys, SortAlgorithm::InsertionWithMemory, stats), identity(n));
    EXPECT_FALSE(stats.fromScratch);
    EXPECT_EQ(stats.moves, n * (n - 1) / 2);
    EXPECT_EQ(stats.comparisons, n * (n - 1) / 2);  // every element goes to the front: no stopping test
}

TEST(TransparencySort, MovesAreTheInversionsOfThePreviousOrder) {
    std::mt19937 random(7);
    std::normal_distribution<float> jitter(0.0f, 0.05f);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    const std::size_t n = 2000;
    std::vector<float> keys(n);
    for (float& key : keys)
        key = uniform(random);
    TransparencySorter sorter;
    SortStats stats;
    Order previous = sortOnce(sorter, keys, SortAlgorithm::InsertionWithMemory, stats);
    for (int frame = 0; frame < 5; ++frame) {
        for (float& key : keys)
            key += jitter(random);
        const std::size_t expected = inversions(previous, keys);
        previous = sortOnce(sorter, keys, SortAlgorithm::InsertionWithMemory, stats);
        EXPECT_EQ(stats.moves, expected);
        // Each move is one comparison; each element but the first adds at most one that stops its scan.
        EXPECT_GE(stats.comparisons, stats.moves);
        EXPECT_LE(stats.comparisons, stats.moves + n - 1);
    }
}

TEST(TransparencySort, TiesKeepThePreviousOrder) {
    TransparencySorter sorter;
    SortStats stats;
    // From scratch, ties come in index order, with either algorithm.
    const std::vector<float> tied = {1.0f, 2.0f, 1.0f, 2.0f, 1.0f};
    EXPECT_EQ(sortOnce(sorter, tied, SortAlgorithm::FromScratch, stats), (Order{1, 3, 0, 2, 4}));
    sorter.forget();
    EXPECT_EQ(sortOnce(sorter, tied, SortAlgorithm::InsertionWithMemory, stats), (Order{1, 3, 0, 2, 4}));

    // Remember a distinct order, then make everything equal: nothing moves.
    const std::vector<float> distinct = {3.0f, 5.0f, 1.0f, 4.0f, 2.0f};
    const Order remembered = sortOnce(sorter, distinct, SortAlgorithm::InsertionWithMemory, stats);
    EXPECT_EQ(remembered, (Order{1, 3, 0, 4, 2}));
    const std::vector<float> equal(5, 0.5f);
    EXPECT_EQ(sortOnce(sorter, equal, SortAlgorithm::InsertionWithMemory, stats), remembered);
    EXPECT_EQ(stats.moves, 0u);
    EXPECT_EQ(stats.comparisons, 4u);

    // Two groups of ties: each keeps the remembered order inside it; −0 ties with +0.
    const std::vector<float> groups = {0.0f, 7.0f, -0.0f, 0.0f, 7.0f};  // remembered: 1, 3, 0, 4, 2
    EXPECT_EQ(sortOnce(sorter, groups, SortAlgorithm::InsertionWithMemory, stats), (Order{1, 4, 3, 0, 2}));
}

TEST(TransparencySort, AChangedCountSortsFromScratch) {
    TransparencySorter sorter;
    SortStats stats;
    std::vector<float> keys = {1.0f, 3.0f, 2.0f};
    sortOnce(sorter, keys, SortAlgorithm::InsertionWithMemory, stats);
    EXPECT_TRUE(stats.fromScratch);
    sortOnce(sorter, keys, SortAlgorithm::InsertionWithMemory, stats);
    EXPECT_FALSE(stats.fromScratch);

    keys.push_back(2.5f);
    EXPECT_EQ(sortOnce(sorter, keys, SortAlgorithm::InsertionWithMemory, stats), (Order{1, 3, 2, 0}));
    EXPECT_TRUE(stats.fromScratch);
    EXPECT_EQ(stats.moves, 4u * keys.size());  // the radix sort's four passes
    EXPECT_EQ(stats.comparisons, 0u);
    sortOnce(sorter, keys, SortAlgorithm::InsertionWithMemory, stats);
    EXPECT_FALSE(stats.fromScratch);

    sorter.forget();
    sortOnce(sorter, keys, SortAlgorithm::InsertionWithMemory, stats);
    EXPECT_TRUE(stats.fromScratch);

    // FromScratch says so every time.
    sortOnce(sorter, keys, SortAlgorithm::FromScratch, stats);
    EXPECT_TRUE(stats.fromScratch);
    EXPECT_EQ(stats.moves, 0u);
}

TEST(TransparencySort, EmptyAndSingleElement) {
    TransparencySorter sorter;
    SortStats stats;
    EXPECT_TRUE(sorter.sort({}, SortAlgorithm::InsertionWithMemory, stats).empty());
    EXPECT_TRUE(stats.fromScratch);
    EXPECT_EQ(stats.comparisons, 0u);
    EXPECT_TRUE(sorter.sort({}, SortAlgorithm::InsertionWithMemory, stats).empty());
    EXPECT_FALSE(stats.fromScratch);  // an empty order is remembered too
    const std::vector<float> one = {4.0f};
    EXPECT_EQ(sortOnce(sorter, one, SortAlgorithm::InsertionWithMemory, stats), (Order{0}));
    EXPECT_TRUE(stats.fromScratch);
    EXPECT_EQ(sortOnce(sorter, one, SortAlgorithm::InsertionWithMemory, stats), (Order{0}));
    EXPECT_EQ(stats.comparisons, 0u);
}

// Random keys, some repeated, over many frames: insertion with memory gives exactly the stable sort of
// its previous order, from scratch the stable sort of the identity; both are permutations.
TEST(TransparencySort, RandomFramesMatchStableSort) {
    std::mt19937 random(11);
    TransparencySorter insertion, scratch;
    Order previous;
    for (int frame = 0; frame < 60; ++frame) {
        const std::size_t n = frame < 20 ? 500 : frame < 40 ? 3000 : 3001;  // count changes twice
        std::uniform_real_distribution<float> uniform(-10.0f, 10.0f);
        std::vector<float> keys(n);
        for (float& key : keys)
            key = frame % 3 == 0 ? std::round(uniform(random)) : uniform(random);  // ties on some frames

        SortStats stats;
        const Order order = sortOnce(insertion, keys, SortAlgorithm::InsertionWithMemory, stats);
        const bool fresh = previous.size() != n;
        EXPECT_EQ(stats.fromScratch, fresh) << "frame " << frame;
        EXPECT_EQ(order, stableSorted(fresh ? identity(n) : previous, keys)) << "frame " << frame;
        Order sortedCopy = order;
        std::sort(sortedCopy.begin(), sortedCopy.end());
        EXPECT_EQ(sortedCopy, identity(n)) << "frame " << frame;
        previous = order;

        EXPECT_EQ(sortOnce(scratch, keys, SortAlgorithm::FromScratch, stats), stableSorted(identity(n), keys))
            << "frame " << frame;
        EXPECT_GT(stats.comparisons, n);
    }
}

// A turntable: random points on a unit sphere turning 0.2° per frame about the vertical axis, key the
// depth seen from +z. Between two frames few pairs swap, so insertion sort does far fewer moves than the
// n²/4 of a random order, and its comparisons are about n + moves.
TEST(TransparencySort, TurntableFramesAreCheap) {
    std::mt19937 random(3);
    std::normal_distribution<float> normal;
    const std::size_t n = 5000;
    std::vector<float> x(n), z(n);
    for (std::size_t i = 0; i < n; ++i) {
        float p[3] = {normal(random), normal(random), normal(random)};
        const float length = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        x[i] = p[0] / length;
        z[i] = p[2] / length;
    }
    const double step = 0.2 * std::numbers::pi / 180.0;
    std::vector<float> keys(n);
    TransparencySorter sorter;
    SortStats stats;
    std::size_t totalMoves = 0;
    const int frames = 30;
    for (int frame = 0; frame <= frames; ++frame) {
        const double angle = frame * step;
        const float c = static_cast<float>(std::cos(angle)), s = static_cast<float>(std::sin(angle));
        for (std::size_t i = 0; i < n; ++i)
            keys[i] = 5.0f - (-s * x[i] + c * z[i]);  // eye at z = 5: key = −z_view = distance along the axis
        const Order order = sortOnce(sorter, keys, SortAlgorithm::InsertionWithMemory, stats);
        ASSERT_TRUE(std::is_sorted(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
            return farther(keys[a], keys[b]);
        }));
        if (frame == 0) continue;
        ASSERT_FALSE(stats.fromScratch);
        totalMoves += stats.moves;
        EXPECT_LT(stats.moves, n * n / 4 / 50) << "frame " << frame;
        EXPECT_GE(stats.comparisons, stats.moves + n - 1 - n / 100) << "frame " << frame;
        EXPECT_LE(stats.comparisons, stats.moves + n - 1) << "frame " << frame;
    }
    EXPECT_GT(totalMoves, 0u);  // it did turn
}

TEST(TransparencySort, NaNKeysSortFarthestAndKeepAStrictWeakOrder) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    const std::vector<float> keys = {1.0f, nan, -inf, inf, -nan, 2.0f, nan, 0.0f};
    TransparencySorter scratch, insertion;
    SortStats stats;
    const Order expected = {1, 4, 6, 3, 5, 0, 7, 2};  // NaNs (index order), +∞, 2, 1, 0, −∞
    EXPECT_EQ(sortOnce(scratch, keys, SortAlgorithm::FromScratch, stats), expected);
    EXPECT_EQ(sortOnce(insertion, keys, SortAlgorithm::InsertionWithMemory, stats), expected);

    // Many frames of random keys with NaNs mixed in, through both algorithms (with a debug standard
    // library, a comparator that is not a strict weak order would be caught here).
    std::mt19937 random(5);
    std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
    std::vector<float> noisy(4000);
    Order previous;
    for (int frame = 0; frame < 10; ++frame) {
        for (float& key : noisy)
            key = uniform(random) < -0.9f ? nan : uniform(random);
        const Order order = sortOnce(insertion, noisy, SortAlgorithm::InsertionWithMemory, stats);
        EXPECT_EQ(order, stableSorted(previous.empty() ? identity(noisy.size()) : previous, noisy));
        EXPECT_TRUE(std::isnan(noisy[order.front()]));
        EXPECT_FALSE(std::isnan(noisy[order.back()]));
        previous = order;
        EXPECT_EQ(sortOnce(scratch, noisy, SortAlgorithm::FromScratch, stats),
                  stableSorted(identity(noisy.size()), noisy));
    }
}

// The radix sort gives exactly std::sort's order (key descending, ties by index), NaN and ±0 included,
// without a single comparison.
TEST(TransparencySort, RadixSortGivesTheSameOrderAsStdSort) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> key(-100.0f, 100.0f);
    for (int trial = 0; trial < 20; ++trial) {
        std::vector<float> keys(1000 + 37 * trial);
        for (float& k : keys)
            k = trial % 3 == 0 ? std::round(key(rng) / 10.0f) : key(rng);  // many ties in some trials
        keys[3] = std::nanf("");
        keys[7] = -0.0f;
        keys[8] = 0.0f;
        keys[9] = -std::numeric_limits<float>::infinity();
        TransparencySorter radix, scratch;
        SortStats radixStats, scratchStats;
        const auto a = radix.sort(keys, SortAlgorithm::RadixFromScratch, radixStats);
        const std::vector<std::uint32_t> radixOrder(a.begin(), a.end());
        const auto b = scratch.sort(keys, SortAlgorithm::FromScratch, scratchStats);
        EXPECT_EQ(radixOrder, std::vector<std::uint32_t>(b.begin(), b.end())) << "trial " << trial;
        EXPECT_EQ(radixStats.comparisons, 0u);
        EXPECT_EQ(radixStats.moves, 4 * keys.size());
        EXPECT_TRUE(radixStats.fromScratch);
    }
}

}  // namespace
}  // namespace facet
