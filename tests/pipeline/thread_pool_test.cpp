// The thread pool: when a job's body throws, the exception reaches the caller of parallelFor, not
// std::terminate, and the pool runs the next job (a batch of renders goes on after a failed input);
// each thread runs its own share of a job's items first, then helps with the others'.
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "support/eventually.h"
#include "thread_pool.h"

namespace facet {
namespace {

using testing_support::eventually;

// An item that throws on a worker thread: parallelFor rethrows it after every thread is done, and the
// same pool then runs a whole job. Breaks if runItems lets the exception escape a worker (the test
// program terminates) or the failure is not cleared (the second job throws again).
TEST(ThreadPool, AnExceptionOfAnItemReachesTheCallerAndThePoolGoesOn) {
    ThreadPool pool(4);
    constexpr std::size_t kItems = 200;
    for (int round = 0; round < 3; ++round) {
        // The workers' items throw; the caller's thread sleeps on its own, so the workers get items.
        EXPECT_THROW(pool.parallelFor(kItems,
                                      [](std::size_t, int thread) {
                                          if (thread != 0) throw std::runtime_error("a worker's item");
                                          std::this_thread::sleep_for(std::chrono::milliseconds(1));
                                      }),
                     std::runtime_error)
            << "round " << round;
    }
    std::vector<int> done(kItems, 0);
    pool.parallelFor(kItems, [&](std::size_t item, int) { ++done[item]; });
    EXPECT_EQ(done, std::vector<int>(kItems, 1));
}

// Jobs of one to three items, most of them finished by the caller alone before a worker wakes (the
// caller no longer waits for workers that did not join): every item of every job still runs exactly
// once, and no worker that wakes late runs an item of a job that has ended (it would count into the
// next job's array, or into one freed). Breaks if a late worker joins a closed job, or if the caller
// returns while a worker that joined is still running an item.
TEST(ThreadPool, ShortJobsRunEachItemOnceWhateverTheWorkersWakeUpTimes) {
    ThreadPool pool(3);
    for (int round = 0; round < 2000; ++round) {
        const std::size_t items = 1 + static_cast<std::size_t>(round % 3);
        std::vector<int> done(items, 0);
        pool.parallelFor(items, [&](std::size_t item, int thread) {
            if (thread != 0) std::this_thread::yield();  // a worker's item ends late
            ++done[item];
        });
        EXPECT_EQ(done, std::vector<int>(items, 1)) << "round " << round;
        // Now and then the workers fall asleep before the next job.
        if (round % 500 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
}

// Two threads, four items: thread 0's share is items 0 and 1, thread 1's items 2 and 3. Item 0 waits
// until item 2 has begun, item 3 until item 1 has: each thread must begin with its own first item and
// go on to its own second, so item 1 runs on thread 0 and item 3 on thread 1. Breaks if the threads
// take items in one shared order (the worker then takes item 1 while the caller waits in item 0), so
// that a tile goes to whichever core comes first rather than the one whose cache holds its pixels.
TEST(ThreadPool, EachThreadRunsItsOwnShareOfTheItemsFirst) {
    ThreadPool pool(2);
    ASSERT_EQ(pool.threads(), 2);
    for (int round = 0; round < 20; ++round) {
        std::atomic<bool> begun[4] = {false, false, false, false};
        std::atomic<int> ranOn[4] = {-1, -1, -1, -1};
        std::atomic<bool> timedOut{false};
        pool.parallelFor(4, [&](std::size_t item, int thread) {
            ranOn[item] = thread;
            begun[item] = true;
            if (item == 0 && !eventually([&] { return begun[2].load(); })) timedOut = true;
            if (item == 3 && !eventually([&] { return begun[1].load(); })) timedOut = true;
        });
        ASSERT_FALSE(timedOut) << "round " << round;
        EXPECT_EQ(ranOn[0], 0) << "round " << round;
        EXPECT_EQ(ranOn[1], 0) << "round " << round;
        EXPECT_EQ(ranOn[2], 1) << "round " << round;
        EXPECT_EQ(ranOn[3], 1) << "round " << round;
    }
}

// A thread held up in its first item: the other thread runs the rest of its share, taking it from the
// back (the items the held-up thread would come to last), while the held-up thread, once free, goes
// on from the front; every item runs once. Item 0 (thread 0's) waits until thread 1 has run ten of
// thread 0's items, and the tenth waits until item 1 has begun. Breaks if a thread runs only its own
// share (item 0 waits in vain: the test times out), if a thread takes another's items from the front
// (thread 1 then runs item 1, not items 40 to 49), or if an item is claimed twice or never.
TEST(ThreadPool, AThreadThatIsHeldUpHasTheLastItemsOfItsShareRunByTheOthers) {
    ThreadPool pool(2);
    ASSERT_EQ(pool.threads(), 2);
    constexpr std::size_t kItems = 100;  // thread 0's share: items 0 to 49
    std::vector<std::atomic<int>> done(kItems), ranOn(kItems);
    std::atomic<int> taken{0};  // thread 0's items run by thread 1
    std::atomic<bool> timedOut{false}, begunOne{false};
    pool.parallelFor(kItems, [&](std::size_t item, int thread) {
        ++done[item];
        ranOn[item] = thread;
        if (item == 1) begunOne = true;
        if (item == 0 && !eventually([&] { return taken.load() >= 10; })) timedOut = true;
        if (thread != 0 && item < kItems / 2 && ++taken == 10 && !eventually([&] { return begunOne.load(); }))
            timedOut = true;
    });
    ASSERT_FALSE(timedOut);
    for (std::size_t item = 0; item < kItems; ++item)
        EXPECT_EQ(done[item], 1) << "item " << item;
    EXPECT_EQ(ranOn[1], 0);
    for (std::size_t item = 40; item < kItems / 2; ++item)
        EXPECT_EQ(ranOn[item], 1) << "item " << item;
}

// A job of more items than a share can count is refused, not cut short. Breaks if the check is
// dropped (the items' count would wrap in the shares' 32-bit halves and most items never run).
TEST(ThreadPool, AJobOfMoreThanTheItemsAShareCountsIsRefused) {
    ThreadPool pool(2);
    bool ran = false;
    EXPECT_THROW(pool.parallelFor(ThreadPool::kMaxItems + 1, [&](std::size_t, int) { ran = true; }),
                 std::length_error);
    EXPECT_FALSE(ran);
}

}  // namespace
}  // namespace facet
