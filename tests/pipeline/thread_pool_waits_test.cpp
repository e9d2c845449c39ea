// How the pool's threads wait between jobs: they poll for at most the spin limit, then sleep; a job
// wakes no more sleeping workers than it has items for; a traced pool accounts for every item. No test
// here times anything: each waits for a state the pool must reach, however slow the machine.
#include <atomic>
#include <chrono>
#include <cstddef>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "support/eventually.h"
#include "thread_pool.h"

namespace facet {
namespace {

using testing_support::eventually;

// Catches: a worker that polls for work forever (a spin not bounded by the clock) instead of sleeping.
TEST(ThreadPoolWaits, WorkersWithNoJobFallAsleep) {
    ThreadPool pool(3);
    ASSERT_EQ(pool.threads(), 3);
    std::vector<int> done(64, 0);
    pool.parallelFor(done.size(), [&](std::size_t item, int) { ++done[item]; });
    EXPECT_EQ(done, std::vector<int>(64, 1));
    EXPECT_TRUE(eventually([&] { return pool.sleepingWorkers() == 2; }));
    EXPECT_GE(pool.waits().slept, 2u);
}

// Catches: a spin limit that is not honoured (a fixed count of pause instructions, or a sleep before
// the limit): with an unbounded limit no worker ever sleeps, and every job is caught while polling.
TEST(ThreadPoolWaits, AnUnboundedSpinNeverSleeps) {
    ThreadPool pool(2);
    pool.setSpinLimit(std::chrono::hours(1));
    std::atomic<int> items{0};
    // The first job wakes a worker that fell asleep under the default limit before the new one was set.
    // On a busy machine the woken worker may not run before the caller has done every job alone: it
    // is waited for, so that it is polling from here on.
    pool.parallelFor(8, [&](std::size_t, int) { ++items; });
    ASSERT_TRUE(eventually([&] { return pool.sleepingWorkers() == 0; }));
    const std::uint64_t sleptBefore = pool.waits().slept;
    for (int job = 1; job < 20; ++job)
        pool.parallelFor(8, [&](std::size_t, int) { ++items; });
    EXPECT_EQ(items.load(), 20 * 8);
    EXPECT_EQ(pool.waits().slept, sleptBefore);
    EXPECT_EQ(pool.sleepingWorkers(), 0);
}

// Catches: a job that wakes every sleeping worker however few items it has (each woken for nothing pays
// a context switch), or that wakes too few to keep its items' promise. A two-item job whose items wait
// for each other: the caller holds one, so exactly one worker must wake and take the other, and the
// two other sleepers sleep on.
TEST(ThreadPoolWaits, AJobWakesOnlyAsManySleepersAsItHasItemsBeyondTheCaller) {
    ThreadPool pool(4);
    pool.setSpinLimit(std::chrono::nanoseconds(0));
    ASSERT_TRUE(eventually([&] { return pool.sleepingWorkers() == 3; }));
    const std::uint64_t sleptBefore = pool.waits().slept;
    std::atomic<int> started{0};
    pool.parallelFor(2, [&](std::size_t, int) {
        ++started;
        while (started.load() < 2)
            std::this_thread::yield();
    });
    EXPECT_EQ(started.load(), 2);
    ASSERT_TRUE(eventually([&] { return pool.sleepingWorkers() == 3; }));
    // The one woken worker went back to sleep once; the others never woke (all three would have been
    // counted asleep again had the job woken them all).
    EXPECT_EQ(pool.waits().slept, sleptBefore + 1);
}

// Catches: a trace that misses the items run on workers or on the caller alone (one-item jobs, a pool
// of one thread), or counts a job twice: each job's item count, every thread's busy time and every
// thread's item count add up.
TEST(ThreadPoolWaits, ATraceAccountsForEveryJobAndItem) {
    for (const int threads : {1, 3}) {
        ThreadPool pool(threads);
        PoolTrace trace;
        pool.startTrace(trace);
        const std::vector<std::size_t> jobs = {1, 5, 40, 2};
        for (const std::size_t items : jobs)
            pool.parallelFor(items, [](std::size_t, int) { std::this_thread::yield(); });
        pool.stopTrace();
        pool.parallelFor(7, [](std::size_t, int) {});  // not traced
        ASSERT_EQ(trace.jobs.size(), jobs.size()) << threads << " threads";
        ASSERT_EQ(trace.threadBusyMs.size(), static_cast<std::size_t>(threads));
        double busy = 0.0, threadBusy = 0.0;
        for (std::size_t j = 0; j < jobs.size(); ++j) {
            EXPECT_EQ(trace.jobs[j].items, jobs[j]);
            EXPECT_LE(trace.jobs[j].startMs, trace.jobs[j].endMs);
            EXPECT_LE(trace.jobs[j].longestItemMs, trace.jobs[j].busyMs);
            if (j > 0) {
                EXPECT_LE(trace.jobs[j - 1].endMs, trace.jobs[j].startMs);
            }
            busy += trace.jobs[j].busyMs;
        }
        for (const double ms : trace.threadBusyMs)
            threadBusy += ms;
        EXPECT_NEAR(busy, threadBusy, 1e-9 * (1.0 + busy));
        EXPECT_GT(busy, 0.0);
        // Every traced item counted once, on the thread that ran it (the untraced job's seven in none).
        ASSERT_EQ(trace.threadItems.size(), static_cast<std::size_t>(threads));
        std::uint64_t items = 0;
        for (const std::uint64_t count : trace.threadItems)
            items += count;
        EXPECT_EQ(items, 1u + 5u + 40u + 2u) << threads << " threads";
    }
}

// Catches: a trace that leaves its own clock reads in the items' times (on a machine where a read of a
// thread's CPU clock is a system call of about a microsecond, 20,000 items of nothing would read as 20 ms
// of work), or a trace that measures no read at all.
TEST(ThreadPoolWaits, ATraceLeavesOutItsOwnClockReads) {
    ThreadPool pool(1);
    PoolTrace trace;
    pool.startTrace(trace);
    constexpr std::size_t kItems = 20'000;
    pool.parallelFor(kItems, [](std::size_t, int) {});
    pool.stopTrace();
    ASSERT_EQ(trace.jobs.size(), 1u);
    ASSERT_GT(trace.clockReadMs, 0.0);
    // The items' own work (a call each: 0.2 us in one virtual machine, where a read is 1.4 us) is below
    // half a clock read; the reads are all in the caller's span.
    EXPECT_LT(trace.jobs[0].busyMs, 0.5 * kItems * trace.clockReadMs);
    EXPECT_GT(trace.jobs[0].callerMs, 1.5 * kItems * trace.clockReadMs);
}

}  // namespace
}  // namespace facet
