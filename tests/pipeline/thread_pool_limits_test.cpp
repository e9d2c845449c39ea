// The thread pool when the system refuses threads (a process limit such as `ulimit -u`, or no address
// space left for a stack under `ulimit -v`): it keeps the workers it could start, runs every job with
// them, reports the shortfall once, and never aborts (std::terminate) or leaves a worker waiting on a
// condition variable that is gone.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "thread_pool.h"

namespace facet {
namespace {

// A starter that starts real threads until the k-th worker, which the "system" refuses as
// pthread_create does under a process limit (EAGAIN).
ThreadStarter refusingFrom(int k) {
    auto started = std::make_shared<int>(0);
    return [started, k](std::function<void()> run) {
        if (++*started >= k)
            throw std::system_error(std::make_error_code(std::errc::resource_unavailable_try_again));
        return std::thread(std::move(run));
    };
}

// Runs `items` items and returns how often each ran and which threads ran them.
struct JobRecord {
    std::vector<int> runs;
    std::set<int> threads;
};
JobRecord runJob(ThreadPool& pool, std::size_t items) {
    JobRecord record{std::vector<int>(items, 0), {}};
    std::mutex mutex;
    pool.parallelFor(items, [&](std::size_t item, int thread) {
        std::this_thread::sleep_for(std::chrono::microseconds(200));  // so that every worker gets items
        std::lock_guard lock(mutex);
        ++record.runs[item];
        record.threads.insert(thread);
    });
    return record;
}

// Catches: a refused thread escaping the constructor (std::terminate on the running std::threads, the
// rc 134 of `ulimit -u 6 --threads 8`), or the pool dropping the two workers it did start.
TEST(ThreadPoolLimits, KeepsTheWorkersItStartedWhenTheThirdIsRefused) {
    ThreadPool pool(8, refusingFrom(3));
    EXPECT_EQ(pool.requestedThreads(), 8);
    EXPECT_EQ(pool.threads(), 3);  // two workers and the calling thread
    constexpr std::size_t kItems = 400;
    for (int round = 0; round < 3; ++round) {
        const JobRecord record = runJob(pool, kItems);
        EXPECT_EQ(record.runs, std::vector<int>(kItems, 1)) << "round " << round;
        for (int thread : record.threads)
            EXPECT_LT(thread, pool.threads()) << "a thread number past the pool's threads";
    }
}

// Catches: a pool whose every worker is refused failing or hanging instead of running its jobs on the
// calling thread (the `ulimit -u 3` case, where the process itself is the whole limit).
TEST(ThreadPoolLimits, RunsOnTheCallingThreadWhenEveryWorkerIsRefused) {
    ThreadPool pool(4, refusingFrom(1));
    EXPECT_EQ(pool.threads(), 1);
    const JobRecord record = runJob(pool, 50);
    EXPECT_EQ(record.runs, std::vector<int>(50, 1));
    EXPECT_EQ(record.threads, std::set<int>{0});
}

std::vector<std::string> reports;
void keepReport(const std::string& message) {
    reports.push_back(message);
}

// Catches: the shortfall said once per pool (a batch or a trade makes dozens of pools: the user would
// read the same warning dozens of times), not at all, or with numbers other than the pool's.
TEST(ThreadPoolLimits, ReportsTheShortfallOnceWithTheNumbersOfThePool) {
    reports.clear();
    setThreadShortfallReport(keepReport);
    {
        ThreadPool first(8, refusingFrom(3));
        ThreadPool second(8, refusingFrom(3));
        ThreadPool whole(2);  // not short: never reported
    }
    setThreadShortfallReport(nullptr);
    ASSERT_EQ(reports.size(), 1u);
    EXPECT_NE(reports[0].find("only 3 of the 8 threads"), std::string::npos) << reports[0];
    EXPECT_NE(reports[0].find(std::system_category().message(EAGAIN)), std::string::npos) << reports[0];
    EXPECT_EQ(reports[0].find('\n'), std::string::npos) << "one line";
}

// Catches: a pool asked for all it got saying it fell short (the warning on every ordinary run).
TEST(ThreadPoolLimits, SaysNothingWhenEveryThreadStarts) {
    reports.clear();
    setThreadShortfallReport(keepReport);
    { ThreadPool pool(3, refusingFrom(3)); }  // two workers asked, two started
    setThreadShortfallReport(nullptr);
    EXPECT_TRUE(reports.empty()) << reports.front();
}

// Catches: a starter failing for another reason leaving the workers already started running while
// their std::thread objects are destroyed (std::terminate) or waiting on a freed condition variable.
TEST(ThreadPoolLimits, AnotherFailureOfTheStarterJoinsTheStartedWorkersFirst) {
    auto started = std::make_shared<int>(0);
    const ThreadStarter failing = [started](std::function<void()> run) {
        if (++*started == 3) throw std::logic_error("a starter's own bug");
        return std::thread(std::move(run));
    };
    EXPECT_THROW(ThreadPool(6, failing), std::logic_error);
}

// The real std::thread under a real limit, in a forked child: RLIMIT_NPROC 1 leaves no thread to the
// process (root is exempt from the limit, so the child first becomes "nobody"). The child's exit status
// is its pool's threads(), or 100 + a failure.
// Catches: the default starter's refusal (std::system_error from std::thread) not being caught: the
// child aborts (rc 134) or reports the internal error; or a job that hangs (the alarm fails it).
TEST(ThreadPoolLimits, AProcessLimitOfOneLeavesThePoolTheCallingThread) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        ::alarm(20);
        const rlimit one{1, 1};
        if (::setrlimit(RLIMIT_NPROC, &one) != 0) ::_exit(101);
        if (::geteuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0)) ::_exit(102);
        ThreadPool pool(8);
        std::atomic<int> done{0};
        pool.parallelFor(64, [&](std::size_t, int) { ++done; });
        ::_exit(done == 64 ? pool.threads() : 103);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status)) << "the child died of signal " << WTERMSIG(status);
    EXPECT_EQ(WEXITSTATUS(status), 1) << "expected the calling thread alone (100+: the child failed)";
}

}  // namespace
}  // namespace facet
