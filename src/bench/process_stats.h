// What a timed command measures besides wall-clock time: medians, CPU time, the process's memory, and
// which CPUs it may run on (facet bench; any command that charts and measures).
#pragma once

#include <sched.h>

#include <string>
#include <string_view>
#include <vector>

namespace facet {

inline constexpr double kMiB = 1024.0 * 1024.0;
// Frames rendered and not timed before a timed run, per renderer and thread count: llvmpipe compiles its
// shader variants on the first draw, and a frame's fresh buffers fault their pages in.
inline constexpr int kWarmUpFrames = 2;

// The median of `values` (the mean of the middle two for an even count); values must not be empty.
double median(std::vector<double> values);

// The thread counts a sweep times: 1, 2, 4, ... up to `threads` and `threads` itself (≤ 0: the
// hardware's count), e.g. 1 2 4 8 12 for 12.
std::vector<int> threadSweep(int threads);

// CPU time of the whole process (every thread), to show how many cores a frame kept busy.
double processCpuMs();

// CPU time of the calling thread: on a machine shared with other work, wall-clock time would charge a
// long sort for the time slices other processes take in the middle of it, and a short one far less often.
double threadCpuMs();

// Keeps the process on `threads` of the CPUs it may use, where it may use more, so that neither
// renderer can keep more than `threads` cores busy (llvmpipe's binning thread and raster threads, or
// any helper thread, share them). Threads inherit the set from the thread that starts them, so this
// must come before any is started. The previous set is restored at the end.
class CpuLimit {
  public:
    explicit CpuLimit(int threads);
    ~CpuLimit();
    CpuLimit(const CpuLimit&) = delete;
    CpuLimit& operator=(const CpuLimit&) = delete;

    bool limited() const { return limited_; }
    int available() const { return available_; }  // CPUs the process may use without the limit
    std::string cpus() const {                    // "CPU 0", "CPUs 0,1"
        std::string text = cpus_.find(',') == std::string::npos ? "CPU " : "CPUs ";
        text += cpus_;
        return text;
    }

  private:
    cpu_set_t saved_;
    int available_ = 0;
    bool limited_ = false;
    std::string cpus_;  // "0" or "0,1"
};

// A field of /proc/self/status in MiB ("VmRSS", "VmHWM": "VmHWM:    123456 kB"); −1 where unavailable.
double statusMiB(std::string_view key);

// Resets the kernel's resident-set high-water mark (VmHWM) to the current resident set: writing "5" to
// /proc/self/clear_refs (Linux ≥ 4.0, proc(5)). False where that is not possible.
bool resetPeakResidentSet();

// Hands freed heap memory back to the system, so the resident set reflects what is in use.
void trimHeap();

// How long one core takes to see a cache line another core just wrote, in nanoseconds: two threads hand
// a counter back and forth for about `milliseconds` and the time is divided by the hand-offs. Two-thread
// frames depend on it (every stage hands its output to the other core): on one virtual machine it read
// 55–90 ns or 190–230 ns depending on where the host placed the two cores, and two-thread frames took up
// to a third longer in the second state. A value far above those means the two threads could not run
// at once (other work on the machine). Returns 0 on a machine with one hardware thread, or when the
// system refuses the second thread (a process limit).
double coreHandoffNanoseconds(double milliseconds = 20.0);

// The bench header's line about coreHandoffNanoseconds, for `threads` ≥ 2 ("" below): "cores      one
// core sees another's write after N ns ...", or that the two threads could not run at once.
std::string coreHandoffLine(int threads);

}  // namespace facet
