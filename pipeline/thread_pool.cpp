#include "thread_pool.h"

#include <pthread.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdint>
#include <new>
#include <system_error>
#include <utility>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace facet {

namespace {

// How long a thread polls before it sleeps, waiting for the next job (a worker) or for the others to
// finish (the caller). A draw is one or two jobs, and a frame of many small draws (Lost Empire's
// transparent pass: 4,064) would otherwise pay a sleep and a wake-up, tens of microseconds, for each.
constexpr int kSpinRounds = 4000;  // of a pause instruction each: some tens of microseconds

void cpuRelax() {
#if defined(__x86_64__) || defined(__i386__)
    _mm_pause();
#endif
}

// True when `ready` became true while polling.
template <class Ready>
bool spinUntil(const Ready& ready) {
    for (int round = 0; round < kSpinRounds; ++round) {
        if (ready()) return true;
        cpuRelax();
    }
    return false;
}

std::atomic<ThreadShortfallReport> shortfallReport{nullptr};
std::atomic<bool> shortfallReported{false};

// Once per process: a batch or a trade makes many pools, and each would fall short the same way.
void reportShortfall(int started, int requested, const std::string& reason) {
    const ThreadShortfallReport report = shortfallReport.load();
    if (!report || shortfallReported.exchange(true)) return;
    const std::string goesOn = std::to_string(started) + (started == 1 ? " thread" : " threads");
    report("the system let Facet start only " + std::to_string(started) + " of the " +
           std::to_string(requested) + " threads asked for (" + reason + "); the work goes on with " +
           goesOn + ", more slowly");
}

// The most threads whose stacks fit in a quarter of the address-space limit (ulimit -v, RLIMIT_AS),
// the calling thread counted; no bound without a limit. Every thread reserves its whole stack (8 MiB
// by default) up front: under `ulimit -v 2000000`, 300 threads took all 2 GB at the 230th, and the
// render then had no memory left. The other three quarters stay for the work.
int threadsTheAddressSpaceAllows() {
    rlimit limit{};
    if (::getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return INT32_MAX;
    std::size_t stack = std::size_t{8} << 20;
#if defined(__GLIBC__)
    pthread_attr_t defaults;
    if (::pthread_getattr_default_np(&defaults) == 0) {
        std::size_t size = 0;
        if (::pthread_attr_getstacksize(&defaults, &size) == 0 && size > 0) stack = size;
        ::pthread_attr_destroy(&defaults);
    }
#endif
    const rlim_t stacks = limit.rlim_cur / 4 / stack;
    return static_cast<int>(std::min<rlim_t>(stacks, INT32_MAX - 1)) + 1;
}

}  // namespace

void setThreadShortfallReport(ThreadShortfallReport report) {
    shortfallReport.store(report);
    shortfallReported.store(false);
}

ThreadPool::ThreadPool(int threads, const ThreadStarter& start) {
    if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    requested_ = threads;
    // A thread the system refuses ends the starting, not the pool: the workers already started wait on
    // wake_, which lives as long as the pool, and run their share of every job (the caller runs the
    // rest). An exception escaping here would destroy running std::threads (std::terminate) or, once
    // caught, the condition variable they wait on.
    std::string refusal;
    const int allowed = threadsTheAddressSpaceAllows();
    if (allowed < threads) refusal = "the memory limit, ulimit -v, leaves room for the stacks of no more";
    try {
        const int starting = std::min(threads, allowed);
        workers_.reserve(static_cast<std::size_t>(starting - 1));  // push_back below cannot throw
        for (int t = 1; t < starting; ++t) {
            std::function<void()> run = [this, t] { workerLoop(t); };
            workers_.push_back(start ? start(std::move(run)) : std::thread(std::move(run)));
        }
    } catch (const std::system_error& e) {
        refusal = e.code().message();
    } catch (const std::bad_alloc&) {
        refusal = "out of memory";
    } catch (...) {  // a test's starter throwing something else: no worker is left behind
        stopWorkers();
        throw;
    }
    if (!refusal.empty()) reportShortfall(this->threads(), requested_, refusal);
}

ThreadPool::~ThreadPool() {
    stopWorkers();
}

void ThreadPool::stopWorkers() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    for (std::thread& worker : workers_)
        worker.join();
}

void ThreadPool::runItems(int thread) {
    for (std::size_t item = next_.fetch_add(1); item < count_; item = next_.fetch_add(1)) {
        try {
            (*body_)(item, thread);
        } catch (...) {
            // Kept for parallelFor to rethrow; no thread begins another item of this job.
            std::lock_guard lock(mutex_);
            if (!failure_) failure_ = std::current_exception();
            next_.store(count_);
        }
    }
}

void ThreadPool::workerLoop(int thread) {
    std::uint64_t seen = 0;
    for (;;) {
        spinUntil([&] {
            return stopping_.load(std::memory_order_acquire) ||
                   generation_.load(std::memory_order_acquire) != seen;
        });
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
            if (stopping_) return;
            seen = generation_;
            // A job the caller has already finished alone is not joined: on a machine busy with other
            // work a worker may wake long after its job ended, and the caller does not wait for it.
            if (!open_) continue;
            ++busy_;
        }
        runItems(thread);
        {
            std::lock_guard lock(mutex_);
            if (--busy_ == 0) done_.notify_one();
        }
    }
}

void ThreadPool::parallelFor(std::size_t count, const std::function<void(std::size_t, int)>& body) {
    if (count == 0) return;
    if (workers_.empty() || count == 1) {
        for (std::size_t item = 0; item < count; ++item)
            body(item, 0);
        return;
    }
    {
        std::lock_guard lock(mutex_);
        body_ = &body;
        count_ = count;
        next_.store(0);
        open_ = true;
        ++generation_;
    }
    wake_.notify_all();
    runItems(0);
    {
        // Every item has begun: from now on no worker joins this job, and only those that did are
        // waited for.
        std::lock_guard lock(mutex_);
        open_ = false;
    }
    spinUntil([&] { return busy_.load(std::memory_order_acquire) == 0; });
    std::unique_lock lock(mutex_);  // taken even when the spin saw the end: the workers' writes are seen
    done_.wait(lock, [&] { return busy_ == 0; });
    body_ = nullptr;
    if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
}

}  // namespace facet
