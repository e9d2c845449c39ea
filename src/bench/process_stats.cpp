#include "bench/process_stats.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <string>
#include <system_error>
#include <thread>

#include <fcntl.h>
#include <unistd.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace facet {

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

std::vector<int> threadSweep(int threads) {
    if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    std::vector<int> counts;
    for (int count = 1; count < threads; count *= 2)
        counts.push_back(count);
    counts.push_back(threads);
    return counts;
}

double processCpuMs() {
    timespec now{};
    ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) * 1e3 + static_cast<double>(now.tv_nsec) * 1e-6;
}

double threadCpuMs() {
    timespec now{};
    ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) * 1e3 + static_cast<double>(now.tv_nsec) * 1e-6;
}

CpuLimit::CpuLimit(int threads) {
    CPU_ZERO(&saved_);
    if (::sched_getaffinity(0, sizeof saved_, &saved_) != 0) return;
    available_ = CPU_COUNT(&saved_);
    if (threads >= available_) return;
    cpu_set_t limited;
    CPU_ZERO(&limited);
    for (int cpu = 0, kept = 0; cpu < CPU_SETSIZE && kept < threads; ++cpu) {
        if (!CPU_ISSET(cpu, &saved_)) continue;
        CPU_SET(cpu, &limited);
        if (kept++) cpus_ += ',';
        cpus_ += std::to_string(cpu);
    }
    limited_ = ::sched_setaffinity(0, sizeof limited, &limited) == 0;
}

CpuLimit::~CpuLimit() {
    if (limited_) ::sched_setaffinity(0, sizeof saved_, &saved_);
}

double statusMiB(std::string_view key) {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.size() > key.size() && line.compare(0, key.size(), key) == 0 && line[key.size()] == ':')
            return std::strtod(line.c_str() + key.size() + 1, nullptr) / 1024.0;
    return -1.0;
}

bool resetPeakResidentSet() {
    const int file = ::open("/proc/self/clear_refs", O_WRONLY);
    if (file < 0) return false;
    const bool written = ::write(file, "5", 1) == 1;
    ::close(file);
    return written;
}

void trimHeap() {
#if defined(__GLIBC__)
    ::malloc_trim(0);
#endif
}

double coreHandoffNanoseconds(double milliseconds) {
    if (std::thread::hardware_concurrency() < 2) return 0.0;
    // The counter alone on its cache line: the caller writes odd values, the partner answers with the
    // next even one. The caller stops at the deadline (checked every 256 hand-offs, and while waiting,
    // so that a partner the system does not run cannot hold it) and then tells the partner to stop.
    struct alignas(64) Line {
        std::atomic<std::uint64_t> value{0};
    };
    Line counter, stop;
    std::thread partner;
    try {
        partner = std::thread([&] {
            while (!stop.value.load(std::memory_order_relaxed)) {
                const std::uint64_t v = counter.value.load(std::memory_order_acquire);
                if (v % 2 == 1) counter.value.store(v + 1, std::memory_order_release);
            }
        });
    } catch (const std::system_error&) {  // a process limit refused the thread: nothing to measure
        return 0.0;
    }
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    const auto deadline = start + std::chrono::duration<double, std::milli>(milliseconds);
    std::uint64_t handOffs = 0;
    for (std::uint64_t v = 1;; v += 2) {
        counter.value.store(v, std::memory_order_release);
        bool late = false;
        for (std::uint32_t spins = 1; counter.value.load(std::memory_order_acquire) != v + 1; ++spins)
            if (spins % 4096 == 0 && Clock::now() > deadline) {
                late = true;
                break;
            }
        if (late) break;
        handOffs += 2;
        if (handOffs % 512 == 0 && Clock::now() > deadline) break;
    }
    const double elapsedNs = std::chrono::duration<double, std::nano>(Clock::now() - start).count();
    stop.value.store(1, std::memory_order_relaxed);
    partner.join();
    return handOffs == 0 ? elapsedNs : elapsedNs / static_cast<double>(handOffs);
}

std::string coreHandoffLine(int threads) {
    if (threads < 2) return "";
    const double ns = coreHandoffNanoseconds();
    if (ns <= 0.0) return "";
    // A hand-off takes well under a microsecond between cores that run at once; far more means one of
    // the two threads waited for a core (other work on the machine) and the figure says nothing.
    if (ns > 5000.0)
        return "cores      two threads did not run at once when measured (other work on this machine?): "
               "two-thread timings now are not representative\n";
    return "cores      one core sees another's write after " + std::to_string(static_cast<long>(ns + 0.5)) +
           " ns (measured now; where this reads ~200 rather than ~60, as a virtual machine's cores placed "
           "far apart do, two-thread frames take up to a third longer)\n";
}

}  // namespace facet
