// The thread pool when a job's body throws: the exception reaches the caller of parallelFor, not
// std::terminate, and the pool runs the next job (a batch of renders goes on after a failed input).
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "thread_pool.h"

namespace facet {
namespace {

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

}  // namespace
}  // namespace facet
