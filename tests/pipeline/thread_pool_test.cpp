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

}  // namespace
}  // namespace facet
