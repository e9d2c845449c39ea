// A small fixed pool of worker threads for data-parallel loops. The calling thread works too, so a
// pool of N threads runs N − 1 workers. Which thread runs which item never affects results: callers
// give every item its own output (a tile, a chunk of vertices), so images are the same for any count.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
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
    // One std::function call per item, not per pixel: items are tiles or chunks of work. Once every
    // item has begun, the caller waits only for the workers that joined the job: one that wakes later
    // (a machine busy with other work may not run it for milliseconds) skips the job.
    // When `body` throws (on any thread), the items not yet begun are skipped and the first exception
    // is rethrown here once every thread is done, so the pool can run the next job: a batch of renders
    // goes on after an input that ran out of memory.
    void parallelFor(std::size_t count, const std::function<void(std::size_t item, int thread)>& body);

  private:
    void workerLoop(int thread);
    void runItems(int thread);

    void stopWorkers();

    int requested_ = 1;
    std::vector<std::thread> workers_;
    std::mutex mutex_;
    std::condition_variable wake_;
    std::condition_variable done_;
    const std::function<void(std::size_t, int)>* body_ = nullptr;
    std::size_t count_ = 0;
    std::atomic<std::size_t> next_{0};
    // Changed under mutex_; atomic so that waiting threads may poll them before they sleep.
    std::atomic<int> busy_{0};                  // workers that joined the current job and are still in it
    bool open_ = false;                         // workers may still join the current job
    std::exception_ptr failure_;                // the current job's first exception
    std::atomic<std::uint64_t> generation_{0};  // bumped for every job, so a worker runs each job once
    std::atomic<bool> stopping_{false};
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
