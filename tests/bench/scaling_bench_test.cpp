// facet bench --scaling, the thread sweep, and the CPU time per frame against one thread's.
#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/bench.h"
#include "bench/process_stats.h"
#include "pipeline/thread_pool.h"

namespace facet {
namespace {

// The bundled cow at 64×48, one frame: quick enough for a test.
BenchOptions tinySpot(int threads) {
    BenchOptions options;
    options.model = std::filesystem::path(FACET_SOURCE_DIR) / "models/spot/spot_triangulated.obj";
    options.width = 64;
    options.height = 48;
    options.frames = 1;
    options.threads = threads;
    return options;
}

// Catches: a sweep that skips the count asked for, repeats a count, or does not double from 1.
TEST(ThreadSweep, DoublesFromOneAndEndsAtTheCountAskedFor) {
    for (int threads = 1; threads <= 40; ++threads) {
        const std::vector<int> counts = threadSweep(threads);
        ASSERT_FALSE(counts.empty());
        EXPECT_EQ(counts.front(), 1);
        EXPECT_EQ(counts.back(), threads);
        for (std::size_t c = 1; c + 1 < counts.size(); ++c)
            EXPECT_EQ(counts[c], 2 * counts[c - 1]) << threads;
        for (std::size_t c = 1; c < counts.size(); ++c)
            EXPECT_LT(counts[c - 1], counts[c]) << threads;
        EXPECT_LE(counts.back(), 2 * counts[counts.size() > 1 ? counts.size() - 2 : 0]) << threads;
    }
}

// Catches: a --scaling report that leaves out a thread count of the sweep, whose serial fraction is not a
// fraction (a trace that misses jobs gives more than the frame, or less than nothing), or that drops the
// work in jobs on the largest count against one thread's (or traces no job for either: 0 ms, or nan).
TEST(ScalingBench, ReportsEveryThreadCountAndASerialFraction) {
    std::ostringstream out;
    runScalingBench(tinySpot(3), true, out);
    const std::string report = out.str();
    for (const int threads : {1, 2, 3})
        EXPECT_TRUE(
            std::regex_search(report, std::regex("\n +" + std::to_string(threads) + " +[0-9.]+ +[0-9.]+x")))
            << threads << " threads missing from:\n"
            << report;
    std::smatch match;
    ASSERT_TRUE(std::regex_search(report, match, std::regex("serial fraction ([-0-9.]+)"))) << report;
    const double fraction = std::stod(match[1]);
    EXPECT_GE(fraction, 0.0) << report;
    EXPECT_LE(fraction, 1.0) << report;
    EXPECT_NE(report.find("Amdahl"), std::string::npos) << report;
    // Predictions for 16 threads and for the largest count swept, each from a trace cut for that many.
    EXPECT_NE(report.find("work cut for 16 threads"), std::string::npos) << report;
    EXPECT_NE(report.find("work cut for 3 threads"), std::string::npos) << report;
    EXPECT_NE(report.find("predicted speed-up at 3 threads"), std::string::npos) << report;
    // The largest count's work in jobs against the same jobs on one thread: a time and a ratio.
    ASSERT_TRUE(std::regex_search(
        report, match, std::regex("work in jobs on 3 threads: ([0-9.]+) ms per frame, ([0-9.]+)x the same")))
        << report;
    EXPECT_GT(std::stod(match[1]), 0.0) << report;
    EXPECT_GT(std::stod(match[2]), 0.0) << report;
}

// CPU time of the calling thread spent spinning until `ms` of it have passed.
void spinCpu(double ms) {
    const double start = threadCpuMs();
    while (threadCpuMs() - start < ms) {
    }
}

// Catches: a serial part inferred from the items' times with the trace's clock reads in it (20,000 empty
// items would add 20,000 reads: about 25 ms where a read is a microsecond), a one-item job counted as
// work that threads share, or a job's span not taken off the frame. The frame: 3 ms alone, 20,000 empty
// items, four items of 1 ms, one item of 0.5 ms (serial too: nothing can share it).
TEST(ScalingBench, MeasuresTheSerialPartOfAFrameWithoutTheTracesCost) {
    ThreadPool pool(1);
    // What 20,000 empty items cost untraced (their calls and hand-out, work that stays in the frame's): a
    // fraction of a read on a plain build, several times more under the sanitizers, which instrument the
    // calls and the trace's own bookkeeping of each item alike.
    const double untracedStart = threadCpuMs();
    pool.parallelFor(20'000, [](std::size_t, int) {});
    const double emptyItemsMs = threadCpuMs() - untracedStart;
    PoolTrace trace;
    pool.startTrace(trace);
    const double start = threadCpuMs();
    spinCpu(3.0);
    pool.parallelFor(20'000, [](std::size_t, int) {});
    pool.parallelFor(4, [](std::size_t, int) { spinCpu(1.0); });
    pool.parallelFor(1, [](std::size_t, int) { spinCpu(0.5); });
    const double frameMs = threadCpuMs() - start;
    pool.stopTrace();
    const FrameSerialPart part = serialPartOf(trace, frameMs);
    EXPECT_GT(part.serialMs, 3.4);
    EXPECT_LT(part.serialMs, 4.2);
    // The empty items' calls, the trace's bookkeeping of them (about the calls' cost again) and the reads'
    // cost beyond the back-to-back pairs' stay in the work: less than half of what the reads would add.
    EXPECT_GT(part.workMs, 3.9);
    EXPECT_LT(part.workMs, 4.1 + 2.0 * emptyItemsMs + 0.5 * 20'000 * trace.clockReadMs)
        << "untraced items " << emptyItemsMs << " ms, a read " << trace.clockReadMs << " ms";
}

// Catches: a busy share that leaves the trace's clock reads in the threads' time (a frame of 12,000 items
// whose reads are system calls of a microsecond looked a quarter idle on one thread), counts one read
// per item instead of two, or takes the caller's two reads per job off every thread's time.
TEST(ScalingBench, ABusyShareLeavesOutTheTracesClockReads) {
    PoolTrace trace;
    trace.clockReadMs = 0.001;
    trace.threadBusyMs = {30.0, 20.0};
    trace.threadItems = {1000, 500};
    trace.jobs.resize(3);
    // Thread 0 (the caller): 40 − (2·1000 + 2·3) reads; thread 1: 40 − 2·500 reads, of 1 us each.
    EXPECT_DOUBLE_EQ(busyShareOf(trace, 40.0), 50.0 / ((40.0 - 2.006) + (40.0 - 1.0)));
    // No reads: the plain share.
    trace.clockReadMs = 0.0;
    EXPECT_DOUBLE_EQ(busyShareOf(trace, 40.0), 50.0 / 80.0);
}

// Catches: a job bound that counts a one-item job's time as work shared by the threads (it is in the
// serial part already), that takes W / P or the longest item alone instead of the larger, or that leaves
// out the serial part.
TEST(ScalingBench, AJobLastsAtLeastItsShareAndItsLongestItem) {
    PoolTrace trace;
    trace.jobs.resize(3);
    trace.jobs[0].items = 4;  // 8 ms of work over 4 threads: 2 ms, longer than its longest item
    trace.jobs[0].busyMs = 8.0;
    trace.jobs[0].longestItemMs = 1.0;
    trace.jobs[1].items = 2;  // its longest item, 1.5 ms, bounds it
    trace.jobs[1].busyMs = 2.0;
    trace.jobs[1].longestItemMs = 1.5;
    trace.jobs[2].items = 1;  // serial: counted in the frame's serial part
    trace.jobs[2].busyMs = 5.0;
    trace.jobs[2].longestItemMs = 5.0;
    const FrameSerialPart frame{6.0, 10.0};  // 1 ms outside jobs + the 5 ms one-item job; 8 + 2 in jobs
    EXPECT_DOUBLE_EQ(jobBoundOf(trace, frame, 4), 16.0 / (6.0 + 2.0 + 1.5));
    EXPECT_DOUBLE_EQ(jobBoundOf(trace, frame, 1), 16.0 / (6.0 + 8.0 + 2.0));
}

// Catches: the frame bench dropping the CPU time per frame, or setting it against one thread's when it
// runs on one thread (the ratio would be 1 by construction).
TEST(FrameBench, SetsTheCpuTimeAgainstOneThreadsOnlyOnMoreThreads) {
    std::ostringstream one, two;
    runBench(tinySpot(1), one);
    runBench(tinySpot(2), two);
    EXPECT_NE(one.str().find("cpu/frame  median"), std::string::npos) << one.str();
    EXPECT_EQ(one.str().find("one thread:"), std::string::npos) << one.str();
    EXPECT_TRUE(std::regex_search(two.str(), std::regex("one thread: [0-9.]+ ms, ratio [0-9.]+")))
        << two.str();
}

}  // namespace
}  // namespace facet
