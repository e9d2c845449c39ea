// A small fixed pool of worker threads for data-parallel loops. The calling thread works too, so a
// pool of N threads runs N − 1 workers. Which thread runs which item never affects results: callers
// give every item its own output (a tile, a chunk of vertices), so images are the same for any count.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace facet {

// Starts one worker thread running `run`: std::thread's constructor by default. It throws
// std::system_error when the system refuses the thread (a process limit such as `ulimit -u`, or no
// address space left for its stack under `ulimit -v`). Tests pass one that fails at the k-th thread.
using ThreadStarter = std::function<std::thread(std::function<void()> run)>;

// Where a pool that could not start every thread it was asked for says so: one line in plain words,
// e.g. "the system let Facet start only 3 of the 8 threads asked for (Resource temporarily
// unavailable); the work goes on with 3, more slowly". The program sets it once (to print a warning);
// it is called once, however many pools fall short after it was set. Unset: nothing is said.
using ThreadShortfallReport = void (*)(const std::string& message);
void setThreadShortfallReport(ThreadShortfallReport report);
// Says through that report that only `started` of the `requested` threads could be started, and why;
// once per process, like a pool that falls short (a batch's lanes, which start threads of their own).
void reportThreadShortfall(int started, int requested, const std::string& reason);

// How long a waiting thread polls before it sleeps (a worker waiting for the next job, the caller for
// the workers to finish): about what a sleep and a wake-up cost, so that polling never burns more
// than twice what sleeping at once would (the rule of the rent-or-buy problem), and far less than the
// gaps between the jobs of a frame of many small draws. docs/performance.md gives the measurements.
inline constexpr std::chrono::nanoseconds kDefaultSpinLimit = std::chrono::microseconds(5);

// One job of a traced pool (ThreadPool::startTrace): when it began and ended, in ms since the trace
// began, its items, their summed time and the longest one's (on any thread), each item's time without
// the trace's own clock reads (PoolTrace::clockReadMs).
struct PoolJobTrace {
    double startMs = 0.0, endMs = 0.0;
    std::uint32_t items = 0;
    double busyMs = 0.0;         // Σ of the items' times: the job's work
    double longestItemMs = 0.0;  // no number of threads finishes the job sooner
    // The caller's CPU time from posting the job to its return, clock reads included: on one thread the
    // whole job, so that a frame's time outside its jobs is measured, not inferred from the items.
    double callerMs = 0.0;
};

// What a traced pool did (ThreadPool::startTrace): each thread's time running items (thread 0: the
// caller's), and every job. facet bench --scaling derives the serial part of a frame from it.
struct PoolTrace {
    std::vector<double> threadBusyMs;
    std::vector<std::uint64_t> threadItems;  // the items each thread ran (two clock reads each)
    std::vector<PoolJobTrace> jobs;
    // What one read of a thread's CPU clock costs (a system call: about a microsecond in some virtual
    // machines), measured when the trace starts. An item's time, from one read to the next, holds one
    // read's cost whatever the point inside the call where the clock is sampled: the end of the first
    // read and the start of the second; so does the time between two reads back to back, which is how
    // it is measured. It is taken off every item, and a frame of 10,000 tiny items is not 14 ms longer.
    double clockReadMs = 0.0;
};

// How the pool's workers waited for jobs since the pool started (ThreadPool::waits).
struct PoolWaits {
    std::uint64_t caughtSpinning = 0;  // the job came while the worker polled
    std::uint64_t slept = 0;           // the worker went to sleep (and was woken, or is asleep now)
};

class ThreadPool {
  public:
    // threads ≤ 0: one per hardware thread. A pool never fails for want of threads: it keeps the
    // workers it could start (possibly none: the calling thread then does all the work) and reports
    // the shortfall once (setThreadShortfallReport). Images are the same for any number of threads.
    explicit ThreadPool(int threads = 0, const ThreadStarter& start = nullptr);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    int threads() const { return static_cast<int>(workers_.size()) + 1; }
    // The threads the pool was asked for (after `threads ≤ 0` became the hardware's count): more than
    // threads() when the system refused some.
    int requestedThreads() const { return requested_; }

    // Calls body(item, thread) for every item in [0, count), spread over the threads, and returns when
    // all are done. `thread` in [0, threads()) names the calling thread, for per-thread scratch.
    // Thread t's own items are the t-th of threads() equal parts of [0, count), run in order; a thread
    // done with its own takes the last items left of the others' parts. So the same job on the same
    // pool gives a thread the same items (the same tiles) from one frame to the next.
    // One std::function call per item, not per pixel: items are tiles or chunks of work. Once every
    // item has begun, the caller waits only for the workers that joined the job: one that wakes later
    // (a machine busy with other work may not run it for milliseconds) skips the job.
    // When `body` throws (on any thread), the items not yet begun are skipped and the first exception
    // is rethrown here once every thread is done, so the pool can run the next job: a batch of renders
    // goes on after an input that ran out of memory.
    // At most kMaxItems items (std::length_error beyond).
    void parallelFor(std::size_t count, const std::function<void(std::size_t item, int thread)>& body);
    static constexpr std::size_t kMaxItems = 0xffffffffu;

    // How long a waiting thread polls before it sleeps (kDefaultSpinLimit unless set); 0: it sleeps at
    // once. Set between jobs. Bounded by the clock, not by a count of pause instructions, whose cost
    // differs tenfold between CPUs.
    void setSpinLimit(std::chrono::nanoseconds limit) { spinLimitNs_.store(limit.count()); }
    std::chrono::nanoseconds spinLimit() const { return std::chrono::nanoseconds(spinLimitNs_.load()); }

    // How the workers waited, summed over them; and how many sleep now, waiting for a job.
    PoolWaits waits() const;
    int sleepingWorkers();

    // Records every job and each thread's busy time into `trace` (cleared here) until stopTrace(): two
    // clock reads per item, so only benchmarks turn it on. Called between jobs; `trace` must outlive it.
    void startTrace(PoolTrace& trace);
    void stopTrace();

  private:
    // One thread's counters, on a cache line of its own: only that thread writes them.
    struct alignas(64) ThreadSlot {
        std::atomic<std::uint64_t> caughtSpinning{0}, slept{0};
        std::int64_t jobBusyNs = 0, jobLongestItemNs = 0;  // traced: the current job's items on this thread
        std::uint64_t jobItems = 0;                        // traced: how many of them
    };

    void workerLoop(int thread);
    void runItems(int thread, bool traced);
    void recordJob(std::chrono::steady_clock::time_point start, std::int64_t callerStartNs,
                   std::size_t count);

    void stopWorkers();

    int requested_ = 1;
    std::vector<std::thread> workers_;
    std::mutex mutex_;
    std::condition_variable wake_;
    std::condition_variable done_;
    const std::function<void(std::size_t, int)>* body_ = nullptr;
    std::size_t count_ = 0;
    // One thread's share of a job's items, [next, end), as next + end · 2^32 in one word: the thread
    // claims its own from the front, then the others' that are left from the back (the items their
    // owners would come to last, so that the same items change hands from one frame to the next).
    // Each on a cache line of its own (claimed once an item), apart from the fields the threads poll
    // between jobs (generation_, busy_) and read per job (body_, count_).
    struct alignas(64) ItemRange {
        std::atomic<std::uint64_t> items{0};
    };
    // Cuts [0, count) into the threads' ranges (under mutex_, before any thread joins the job).
    void shareItems(std::size_t count);
    // The next unclaimed item for `thread` (its own range first), or count_ when none is left.
    std::size_t claimItem(int thread);
    // Ends the job's claiming: every range emptied (a failed item).
    void claimNoMore();
    // Changed under mutex_; atomic so that waiting threads may poll them before they sleep.
    alignas(64) std::atomic<int> busy_{0};      // workers that joined the current job and are still in it
    bool open_ = false;                         // workers may still join the current job
    std::exception_ptr failure_;                // the current job's first exception
    std::atomic<std::uint64_t> generation_{0};  // bumped for every job, so a worker runs each job once
    std::atomic<bool> stopping_{false};
    std::atomic<std::int64_t> spinLimitNs_{kDefaultSpinLimit.count()};
    int sleeping_ = 0;  // workers asleep on wake_ (under mutex_): a job wakes no more than it has items for
    std::unique_ptr<ThreadSlot[]> slots_;
    std::unique_ptr<ItemRange[]> ranges_;  // one per thread
    PoolTrace* trace_ = nullptr;
    std::chrono::steady_clock::time_point traceStart_;
    std::int64_t clockReadNs_ = 0;  // the trace's PoolTrace::clockReadMs, in ns
};

// pool.parallelFor(count, body), or the same items in order on the calling thread (thread 0) when
// `inOrder`: observed draws run so, and their hooks see a stable order.
template <class Body>
void forEachItem(ThreadPool& pool, bool inOrder, std::size_t count, const Body& body) {
    if (inOrder) {
        for (std::size_t item = 0; item < count; ++item)
            body(item, 0);
    } else {
        pool.parallelFor(count, body);
    }
}

}  // namespace facet
