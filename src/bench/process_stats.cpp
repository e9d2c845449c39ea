#include "bench/process_stats.h"

#include <algorithm>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <string>

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

}  // namespace facet
