#include "thread_pool.h"

#include <pthread.h>
#include <sys/resource.h>
#include <time.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <new>
#include <stdexcept>
#include <system_error>
#include <utility>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace facet {

namespace {

using Clock = std::chrono::steady_clock;

void cpuRelax() {
#if defined(__x86_64__) || defined(__i386__)
    _mm_pause();
#endif
}

// True when `ready` became true while polling, for at most `limit`. The clock is read every 16 pause
// instructions: a pause takes about 10 cycles on some CPUs and about 140 on others, so a count of them
// would be a tenfold different time; a clock read (vDSO) costs about as much as one pause.
template <class Ready>
bool spinUntil(const Ready& ready, std::chrono::nanoseconds limit) {
    if (ready()) return true;
    if (limit.count() <= 0) return false;
    const Clock::time_point deadline = Clock::now() + limit;
    for (unsigned round = 1;; ++round) {
        cpuRelax();
        if (ready()) return true;
        if (round % 16 == 0 && Clock::now() >= deadline) return false;
    }
}

// The calling thread's CPU time: an item's time in a trace, which the time slices other processes take
// from a shared machine do not lengthen.
std::int64_t threadCpuNs() {
    timespec now{};
    ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return std::int64_t{now.tv_sec} * 1'000'000'000 + now.tv_nsec;
}

// What one read of threadCpuNs costs: the median difference of two reads back to back (PoolTrace::clockReadMs
// says why that is what an item's time holds of them).
std::int64_t clockReadNs() {
    constexpr int kPairs = 63;
    std::array<std::int64_t, kPairs> differences{};
    for (std::int64_t& difference : differences) {
        const std::int64_t first = threadCpuNs();
        difference = threadCpuNs() - first;
    }
    std::nth_element(differences.begin(), differences.begin() + kPairs / 2, differences.end());
    return differences[kPairs / 2];
}

double msBetween(Clock::time_point from, Clock::time_point to) {
    return std::chrono::duration<double, std::milli>(to - from).count();
}

std::atomic<ThreadShortfallReport> shortfallReport{nullptr};
std::atomic<bool> shortfallReported{false};

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

// Once per process: a batch or a trade makes many pools, and each would fall short the same way.
void reportThreadShortfall(int started, int requested, const std::string& reason) {
    const ThreadShortfallReport report = shortfallReport.load();
    if (!report || shortfallReported.exchange(true)) return;
    const std::string goesOn = std::to_string(started) + (started == 1 ? " thread" : " threads");
    report("the system let Facet start only " + std::to_string(started) + " of the " +
           std::to_string(requested) + " threads asked for (" + reason + "); the work goes on with " +
           goesOn + ", more slowly");
}

ThreadPool::ThreadPool(int threads, const ThreadStarter& start) {
    if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    requested_ = threads;
    // A thread the system refuses ends the starting, not the pool: the workers already started wait on
    // wake_, which lives as long as the pool, and run their share of every job (the caller runs the
    // rest). An exception escaping here would destroy running std::threads (std::terminate) or, once
    // caught, the condition variable they wait on.
    slots_ = std::make_unique<ThreadSlot[]>(static_cast<std::size_t>(threads));
    ranges_ = std::make_unique<ItemRange[]>(static_cast<std::size_t>(threads));
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
    if (!refusal.empty()) reportThreadShortfall(this->threads(), requested_, refusal);
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

// Runs the current job's items until none is left; a traced pool (startTrace) times each item into this
// thread's slot.
void ThreadPool::runItems(int thread, bool traced) {
    ThreadSlot& slot = slots_[static_cast<std::size_t>(thread)];
    // The job's body and size, read once: they stay fixed while the job runs (set under mutex_ before
    // any thread joins it), and read per item they would be read beside the claims of the other threads.
    const std::function<void(std::size_t, int)>& body = *body_;
    const std::size_t count = count_;
    for (std::size_t item = claimItem(thread); item < count; item = claimItem(thread)) {
        const std::int64_t start = traced ? threadCpuNs() : 0;
        try {
            body(item, thread);
        } catch (...) {
            // Kept for parallelFor to rethrow; no thread begins another item of this job.
            std::lock_guard lock(mutex_);
            if (!failure_) failure_ = std::current_exception();
            claimNoMore();
        }
        if (traced) {
            // Not clamped at 0: an item shorter than the reads' noise then averages out over a job.
            const std::int64_t ns = threadCpuNs() - start - clockReadNs_;
            slot.jobBusyNs += ns;
            slot.jobLongestItemNs = std::max(slot.jobLongestItemNs, ns);
            ++slot.jobItems;
        }
    }
}

namespace {

std::uint64_t packRange(std::uint64_t next, std::uint64_t end) {
    return next | end << 32;
}

}  // namespace

// Thread t's own items: the t-th of threads() equal parts of the items, in order.
void ThreadPool::shareItems(std::size_t count) {
    const auto n = static_cast<std::uint64_t>(threads());
    for (std::uint64_t t = 0; t < n; ++t)
        ranges_[t].items.store(packRange(count * t / n, count * (t + 1) / n), std::memory_order_relaxed);
}

std::size_t ThreadPool::claimItem(int thread) {
    const int n = threads();
    for (int k = 0; k < n; ++k) {
        std::atomic<std::uint64_t>& items = ranges_[static_cast<std::size_t>((thread + k) % n)].items;
        std::uint64_t range = items.load(std::memory_order_relaxed);
        for (;;) {
            const std::uint64_t next = range & 0xffffffffu, end = range >> 32;
            if (next >= end) break;
            // Its own range's first item, or another's last.
            const std::uint64_t claimed = k == 0 ? packRange(next + 1, end) : packRange(next, end - 1);
            if (items.compare_exchange_weak(range, claimed)) return k == 0 ? next : end - 1;
        }
    }
    return count_;
}

void ThreadPool::claimNoMore() {
    for (int t = 0; t < threads(); ++t)
        ranges_[static_cast<std::size_t>(t)].items.store(0);
}

void ThreadPool::workerLoop(int thread) {
    ThreadSlot& slot = slots_[static_cast<std::size_t>(thread)];
    std::uint64_t seen = 0;
    for (;;) {
        const bool caught = spinUntil(
            [&] {
                return stopping_.load(std::memory_order_acquire) ||
                       generation_.load(std::memory_order_acquire) != seen;
            },
            spinLimit());
        bool traced = false;
        {
            std::unique_lock lock(mutex_);
            if (!caught && !stopping_ && generation_ == seen) {
                slot.slept.fetch_add(1, std::memory_order_relaxed);
                ++sleeping_;
                wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
                --sleeping_;
            } else if (caught) {
                slot.caughtSpinning.fetch_add(1, std::memory_order_relaxed);
            }
            if (stopping_) return;
            seen = generation_;
            // A job the caller has already finished alone is not joined: on a machine busy with other
            // work a worker may wake long after its job ended, and the caller does not wait for it.
            if (!open_) continue;
            ++busy_;
            traced = trace_ != nullptr;
        }
        runItems(thread, traced);
        {
            std::lock_guard lock(mutex_);
            if (--busy_ == 0) done_.notify_one();
        }
    }
}

void ThreadPool::parallelFor(std::size_t count, const std::function<void(std::size_t, int)>& body) {
    if (count == 0) return;
    if (count > kMaxItems) throw std::length_error("ThreadPool::parallelFor: more than 2^32 - 1 items");
    const Clock::time_point start = trace_ ? Clock::now() : Clock::time_point{};
    const std::int64_t callerStartNs = trace_ ? threadCpuNs() : 0;
    if (workers_.empty() || count == 1) {
        if (!trace_) {
            for (std::size_t item = 0; item < count; ++item)
                body(item, 0);
            return;
        }
        {
            std::lock_guard lock(mutex_);
            body_ = &body;
            count_ = count;
            shareItems(count);
        }
        slots_[0].jobBusyNs = slots_[0].jobLongestItemNs = 0;
        slots_[0].jobItems = 0;
        runItems(0, true);
        body_ = nullptr;
        recordJob(start, callerStartNs, count);
        if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
        return;
    }
    int wakeUps = 0;
    bool wakeAll = false;
    {
        std::lock_guard lock(mutex_);
        body_ = &body;
        count_ = count;
        shareItems(count);
        open_ = true;
        ++generation_;
        if (trace_)
            for (int t = 0; t < threads(); ++t) {
                ThreadSlot& slot = slots_[static_cast<std::size_t>(t)];
                slot.jobBusyNs = slot.jobLongestItemNs = 0;
                slot.jobItems = 0;
            }
        // The caller takes an item itself: a job of k items needs at most k − 1 workers, and a worker
        // woken for nothing costs a context switch. Polling workers need no call.
        wakeUps = static_cast<int>(std::min<std::size_t>(count - 1, static_cast<std::size_t>(sleeping_)));
        wakeAll = wakeUps == sleeping_;
    }
    if (wakeAll)
        wake_.notify_all();
    else
        for (int w = 0; w < wakeUps; ++w)
            wake_.notify_one();
    runItems(0, trace_ != nullptr);
    {
        // Every item has begun: from now on no worker joins this job, and only those that did are
        // waited for.
        std::lock_guard lock(mutex_);
        open_ = false;
    }
    spinUntil([&] { return busy_.load(std::memory_order_acquire) == 0; }, spinLimit());
    std::unique_lock lock(mutex_);  // taken even when the spin saw the end: the workers' writes are seen
    done_.wait(lock, [&] { return busy_ == 0; });
    body_ = nullptr;
    if (trace_) recordJob(start, callerStartNs, count);
    if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
}

void ThreadPool::recordJob(Clock::time_point start, std::int64_t callerStartNs, std::size_t count) {
    PoolJobTrace job;
    job.callerMs = static_cast<double>(threadCpuNs() - callerStartNs) * 1e-6;
    job.startMs = msBetween(traceStart_, start);
    job.endMs = msBetween(traceStart_, Clock::now());
    job.items = static_cast<std::uint32_t>(std::min<std::size_t>(count, UINT32_MAX));
    std::int64_t busyNs = 0, longestNs = 0;
    for (int t = 0; t < threads(); ++t) {
        const ThreadSlot& slot = slots_[static_cast<std::size_t>(t)];
        trace_->threadBusyMs[static_cast<std::size_t>(t)] += static_cast<double>(slot.jobBusyNs) * 1e-6;
        trace_->threadItems[static_cast<std::size_t>(t)] += slot.jobItems;
        busyNs += slot.jobBusyNs;
        longestNs = std::max(longestNs, slot.jobLongestItemNs);
    }
    job.busyMs = static_cast<double>(std::max<std::int64_t>(busyNs, 0)) * 1e-6;
    job.longestItemMs = static_cast<double>(std::max<std::int64_t>(longestNs, 0)) * 1e-6;
    trace_->jobs.push_back(job);
}

void ThreadPool::startTrace(PoolTrace& trace) {
    trace.threadBusyMs.assign(static_cast<std::size_t>(threads()), 0.0);
    trace.threadItems.assign(static_cast<std::size_t>(threads()), 0);
    trace.jobs.clear();
    clockReadNs_ = clockReadNs();
    trace.clockReadMs = static_cast<double>(clockReadNs_) * 1e-6;
    traceStart_ = Clock::now();
    std::lock_guard lock(mutex_);  // the workers read trace_ under the lock
    trace_ = &trace;
}

void ThreadPool::stopTrace() {
    std::lock_guard lock(mutex_);
    trace_ = nullptr;
}

PoolWaits ThreadPool::waits() const {
    PoolWaits total;
    for (int t = 1; t < threads(); ++t) {
        total.caughtSpinning +=
            slots_[static_cast<std::size_t>(t)].caughtSpinning.load(std::memory_order_relaxed);
        total.slept += slots_[static_cast<std::size_t>(t)].slept.load(std::memory_order_relaxed);
    }
    return total;
}

int ThreadPool::sleepingWorkers() {
    std::lock_guard lock(mutex_);
    return sleeping_;
}

}  // namespace facet
