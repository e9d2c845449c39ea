// facet bench --scaling: frames of a scene on 1, 2, 4, ... threads; speed-up, CPU time per frame, and the
// serial part of a frame from a trace of the pool's jobs (ThreadPool::startTrace) with Amdahl's bound.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iterator>
#include <memory>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

#include "base/errors.h"
#include "bench/bench.h"
#include "bench/process_stats.h"
#include "render/frame_kernels.h"
#include "render/renderer.h"

namespace facet {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr int kPredictedThreads = 16;  // the many-core machine the figures are stated for
// The spin limits timed at the largest thread count (ThreadPool::setSpinLimit), microseconds: what the
// default, kDefaultSpinLimit, was chosen from.
constexpr int kSpinLimitsUs[] = {0, 1, 5, 20, 100};

struct ScalingScene {
    fs::path model;
    int width = 0, height = 0;
};

// What one thread count measured: medians per frame.
struct ThreadCountResult {
    int threads = 0;
    double wallMs = 0.0, cpuMs = 0.0;
    double busyShare = 0.0;  // busyShareOf: the threads' time in jobs / their time, traced frames
};

// The serial part of a frame, from frames traced on one thread (where nothing waits), in the thread's CPU
// time: serialMs = the frame's time outside its jobs of two or more items (the caller alone: planning,
// sorting, gathering), measured from each job's span on the caller (PoolJobTrace::callerMs), plus the
// one-item jobs; workMs = the items of the other jobs. Both leave out the trace's own clock reads
// (PoolTrace::clockReadMs), so serialMs + workMs is about the untraced frame. f = serial / (serial + work);
// Amdahl: speed-up(P) = 1 / (f + (1 − f) / P). The job bound is tighter: a job of items W_j with longest
// item m_j takes at least max(W_j / P, m_j), so T(P) ≥ serial + Σ_j max(W_j / P, m_j) (a job of few
// tiles keeps few threads busy); its speed-up, (serial + work) / T(P), is the median over the traced
// frames (one frame's longest items move with the host's noise).
struct SerialPart {
    double tracedMs = 0.0;  // per frame, traced, clock reads included
    double serialMs = 0.0;  // per frame
    double workMs = 0.0;    // per frame
    double jobsPerFrame = 0.0;
    double medianGapUs = 0.0;       // between consecutive jobs of a frame: what a waiting worker waits
    double clockReadUs = 0.0;       // one read of the thread's CPU clock, taken off
    std::vector<double> jobBounds;  // per traced frame, at the number of threads the work was cut for
    double fraction() const { return serialMs + workMs > 0.0 ? serialMs / (serialMs + workMs) : 0.0; }
    double amdahl(int threads) const {
        const double f = fraction();
        return 1.0 / (f + (1.0 - f) / threads);
    }
    double jobBound() const { return jobBounds.empty() ? 1.0 : median(jobBounds); }
};

}  // namespace

double jobBoundOf(const PoolTrace& trace, const FrameSerialPart& frame, int threads) {
    double ms = frame.serialMs;
    for (const PoolJobTrace& job : trace.jobs)
        if (job.items > 1) ms += std::max(job.busyMs / threads, job.longestItemMs);
    return ms > 0.0 ? (frame.serialMs + frame.workMs) / ms : 1.0;
}

FrameSerialPart serialPartOf(const PoolTrace& trace, double frameCpuMs) {
    FrameSerialPart part;
    part.serialMs = frameCpuMs;
    for (const PoolJobTrace& job : trace.jobs) {
        // The job's span on the caller, and the halves of its two clock reads outside the span.
        part.serialMs -= job.callerMs + trace.clockReadMs;
        if (job.items > 1)
            part.workMs += job.busyMs;
        else
            part.serialMs += job.busyMs;
    }
    part.serialMs = std::max(part.serialMs, 0.0);
    return part;
}

double busyShareOf(const PoolTrace& trace, double frameWallMs) {
    double busyMs = 0.0, availableMs = 0.0;
    for (std::size_t t = 0; t < trace.threadBusyMs.size(); ++t) {
        double reads = 2.0 * static_cast<double>(trace.threadItems[t]);
        if (t == 0) reads += 2.0 * static_cast<double>(trace.jobs.size());
        busyMs += trace.threadBusyMs[t];
        availableMs += frameWallMs - reads * trace.clockReadMs;
    }
    return availableMs > 0.0 ? busyMs / availableMs : 0.0;
}

namespace {

// Frames traced on one thread (`context`'s pool has one), their work cut for `cutFor` threads (what a frame
// on that many runs as items).
SerialPart traceOneThread(const PreparedScene& prepared, Framebuffer& framebuffer, DrawContext& context,
                          FrameMemory& memory, int frames, int cutFor) {
    SerialPart part;
    context.cutForThreads = cutFor;
    std::vector<double> tracedMs, serialMs, workMs, gapsUs, clockReadUs;
    std::size_t jobs = 0;
    PoolTrace trace;
    for (int i = 0; i < frames; ++i) {
        // CPU time of the one thread, as the trace's items are timed: a shared machine's other processes
        // lengthen neither.
        context.pool.startTrace(trace);
        const double start = threadCpuMs();
        renderFrame(prepared, framebuffer, context, memory);
        const double ms = threadCpuMs() - start;
        context.pool.stopTrace();
        const FrameSerialPart frame = serialPartOf(trace, ms);
        for (std::size_t j = 1; j < trace.jobs.size(); ++j)
            gapsUs.push_back(1e3 * (trace.jobs[j].startMs - trace.jobs[j - 1].endMs));
        tracedMs.push_back(ms);
        serialMs.push_back(frame.serialMs);
        workMs.push_back(frame.workMs);
        clockReadUs.push_back(1e3 * trace.clockReadMs);
        jobs += trace.jobs.size();
        part.jobBounds.push_back(jobBoundOf(trace, frame, cutFor));
    }
    part.tracedMs = median(tracedMs);
    part.serialMs = median(serialMs);
    part.workMs = median(workMs);
    part.jobsPerFrame = static_cast<double>(jobs) / frames;
    part.medianGapUs = gapsUs.empty() ? 0.0 : median(gapsUs);
    part.clockReadUs = median(clockReadUs);
    context.cutForThreads = 0;
    return part;
}

// How long a worker takes to start a job posted to the pool, in microseconds (median of `trials`): asleep
// (spin limit 0, the job wakes it) or polling (no limit). A two-item job whose items wait for each other:
// the caller holds one, so a worker must take the other. The trials are 200 us apart, so that the
// sleeping worker is asleep.
double wakeUpMicroseconds(bool polling, int trials = 200) {
    ThreadPool pool(2);
    if (pool.threads() < 2) return 0.0;
    pool.setSpinLimit(polling ? std::chrono::nanoseconds(std::chrono::hours(1))
                              : std::chrono::nanoseconds(0));
    std::vector<double> us;
    for (int trial = 0; trial < trials; ++trial) {
        std::this_thread::sleep_for(std::chrono::microseconds(200));
        std::atomic<int> started{0};
        Clock::time_point workerStart;
        const Clock::time_point posted = Clock::now();
        pool.parallelFor(2, [&](std::size_t, int thread) {
            if (thread != 0) workerStart = Clock::now();
            ++started;
            while (started.load() < 2)
                std::this_thread::yield();
        });
        us.push_back(std::chrono::duration<double, std::micro>(workerStart - posted).count());
    }
    return median(us);
}

void benchScalingScene(const ScalingScene& bench, const std::vector<int>& counts, int frames,
                       std::ostream& out) {
    Scene scene = loadSceneOrModel(bench.model);
    scene.width = bench.width;
    scene.height = bench.height;
    const PreparedScene prepared = prepareScene(scene);

    // One context, framebuffer and frame memory per thread count; frames take turns across the counts,
    // so that a slow spell of a shared machine falls on all of them.
    struct Side {
        std::unique_ptr<DrawContext> context;
        std::unique_ptr<Framebuffer> framebuffer;
        FrameMemory memory;
        std::vector<double> wallMs, cpuMs, busyShare;
    };
    std::vector<Side> sides(counts.size());
    for (std::size_t c = 0; c < counts.size(); ++c) {
        sides[c].context = std::make_unique<DrawContext>(counts[c]);
        sides[c].framebuffer = std::make_unique<Framebuffer>(scene.width, scene.height);
        for (int i = 0; i < kWarmUpFrames; ++i)
            renderFrame(prepared, *sides[c].framebuffer, *sides[c].context, sides[c].memory);
    }
    PoolTrace trace;
    for (int i = 0; i < frames; ++i)
        for (Side& side : sides) {
            const double cpuStart = processCpuMs();
            const auto start = Clock::now();
            renderFrame(prepared, *side.framebuffer, *side.context, side.memory);
            side.wallMs.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
            side.cpuMs.push_back(processCpuMs() - cpuStart);
        }
    // Busy shares from traced frames of their own (the trace's clock reads stay out of the times above),
    // and the work in jobs of the largest count's frames against the same jobs on one thread: a frame on
    // one thread cut as the largest count cuts it, taking turns with them.
    std::vector<double> widestWorkMs, oneThreadWorkMs;
    const auto workMsOf = [](const PoolTrace& t) {
        double ms = 0.0;
        for (const double busy : t.threadBusyMs)
            ms += busy;
        return ms;
    };
    for (int i = 0; i < frames; ++i) {
        for (Side& side : sides) {
            side.context->pool.startTrace(trace);
            const auto start = Clock::now();
            renderFrame(prepared, *side.framebuffer, *side.context, side.memory);
            const double wall = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
            side.context->pool.stopTrace();
            side.busyShare.push_back(busyShareOf(trace, wall));
            if (&side == &sides.back()) widestWorkMs.push_back(workMsOf(trace));
        }
        if (sides.size() > 1) {
            DrawContext& one = *sides[0].context;
            one.cutForThreads = counts.back();
            one.pool.startTrace(trace);
            renderFrame(prepared, *sides[0].framebuffer, one, sides[0].memory);
            one.pool.stopTrace();
            one.cutForThreads = 0;
            oneThreadWorkMs.push_back(workMsOf(trace));
        }
    }
    // The largest count's frames with each spin limit, taking turns.
    DrawContext& widest = *sides.back().context;
    std::vector<std::vector<double>> spinWallMs(std::size(kSpinLimitsUs)),
        spinCpuMs(std::size(kSpinLimitsUs));
    for (int i = 0; i < frames; ++i)
        for (std::size_t l = 0; l < std::size(kSpinLimitsUs); ++l) {
            widest.pool.setSpinLimit(std::chrono::microseconds(kSpinLimitsUs[l]));
            const double cpuStart = processCpuMs();
            const auto start = Clock::now();
            renderFrame(prepared, *sides.back().framebuffer, widest, sides.back().memory);
            spinWallMs[l].push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
            spinCpuMs[l].push_back(processCpuMs() - cpuStart);
        }
    widest.pool.setSpinLimit(kDefaultSpinLimit);
    const int given = counts.back();
    const SerialPart serial =
        traceOneThread(prepared, *sides[0].framebuffer, *sides[0].context, sides[0].memory, frames, given);
    const SerialPart serialAt16 = given == kPredictedThreads
                                      ? serial
                                      : traceOneThread(prepared, *sides[0].framebuffer, *sides[0].context,
                                                       sides[0].memory, frames, kPredictedThreads);

    out << bench.model.filename().string() << " at " << scene.width << "x" << scene.height << ", "
        << prepared.triangleCount << " triangles\n"
        << "  threads   ms/frame   speed-up   efficiency   cpu ms/frame   cpu ratio   busy share\n";
    const double oneWall = median(sides[0].wallMs), oneCpu = median(sides[0].cpuMs);
    for (std::size_t c = 0; c < counts.size(); ++c) {
        const double wall = median(sides[c].wallMs), cpu = median(sides[c].cpuMs);
        out << std::fixed << std::setprecision(2) << std::setw(9) << sides[c].context->pool.threads()
            << std::setw(11) << wall << std::setw(10) << oneWall / wall << "x" << std::setw(12)
            << oneWall / wall / counts[c] << std::setw(15) << cpu << std::setw(11) << cpu / oneCpu << "x"
            << std::setw(12) << median(sides[c].busyShare) << "\n";
    }
    if (sides.size() > 1)
        out << "  work in jobs on " << widest.pool.threads() << " threads: " << median(widestWorkMs)
            << " ms per frame, " << median(widestWorkMs) / median(oneThreadWorkMs)
            << "x the same jobs' on one thread (traced frames taking turns; above 1: the work itself costs "
               "more,\n    its data moving between cores or the cores sharing caches and memory; the rest "
               "of the cpu ratio is waiting)\n";
    out << "  spin limit at " << widest.pool.threads() << " threads, ms/frame wall / cpu:";
    for (std::size_t l = 0; l < std::size(kSpinLimitsUs); ++l)
        out << (l ? "," : "") << "  " << kSpinLimitsUs[l] << " us"
            << (std::chrono::microseconds(kSpinLimitsUs[l]) == kDefaultSpinLimit ? " (default) " : " ")
            << median(spinWallMs[l]) << " / " << median(spinCpuMs[l]);
    out << "\n";
    // What the trace cut for `threads` shows and predicts for them.
    const auto printTrace = [&](const SerialPart& part, int threads) {
        out << std::setprecision(2) << "  one-thread trace, work cut for " << threads
            << " threads: " << part.jobsPerFrame << " jobs per frame, median gap " << std::setprecision(1)
            << part.medianGapUs << " us between jobs; per frame " << std::setprecision(2) << part.serialMs
            << " ms serial (outside jobs, or in one-item jobs) and " << part.workMs << " ms in jobs ("
            << part.tracedMs << " ms traced: the trace's clock reads, " << part.clockReadUs
            << " us each, left out)\n"
            << "    serial fraction " << std::setprecision(3) << part.fraction() << std::setprecision(2)
            << "; predicted speed-up at " << threads << " threads: Amdahl " << part.amdahl(threads)
            << "x, job bound " << part.jobBound() << "x (median of the traced frames)\n";
    };
    printTrace(serialAt16, kPredictedThreads);
    if (given != kPredictedThreads) printTrace(serial, given);
    out << std::flush;  // a long run shows its progress
}

}  // namespace

void runScalingBench(const BenchOptions& options, bool modelGiven, std::ostream& out) {
    if (options.frames < 1) throw InputError("--frames must be at least 1");
    const std::vector<int> counts = threadSweep(options.threads);
    std::vector<ScalingScene> scenes;
    if (modelGiven) {
        scenes.push_back({options.model, options.width, options.height});
    } else {
        // The named scenes of --vs-mesa.
        scenes.push_back({options.model, 1920, 1080});
        if (fs::is_directory(options.sharedModels)) {
            const fs::path largest = largestModel(options.sharedModels).first;
            if (!largest.empty()) scenes.push_back({largest, 1920, 1080});
        }
        scenes.push_back({options.smallModel, 3840, 2160});
    }
    out << std::fixed << "facet bench --scaling: the same frames on ";
    for (std::size_t c = 0; c < counts.size(); ++c)
        out << (c ? ", " : "") << counts[c];
    out << " threads, taking turns frame by frame; " << options.frames << " timed frames each after "
        << kWarmUpFrames << " warm-up\n"
        << "code       compiled for " << describeFrameKernels() << "; " << std::thread::hardware_concurrency()
        << " hardware threads\n"
        << "wake-up    a worker starts a posted job after " << std::setprecision(1)
        << wakeUpMicroseconds(false) << " us asleep, " << wakeUpMicroseconds(true)
        << " us polling (medians); a waiting thread polls for "
        << std::chrono::duration<double, std::micro>(kDefaultSpinLimit).count() << " us, then sleeps\n"
        << "columns    medians per frame; speed-up = 1-thread ms / ms; efficiency = speed-up / threads;\n"
        << "           cpu ratio = cpu ms / 1-thread cpu ms (1.00: no CPU spent waiting or sharing);\n"
        << "           busy share = the threads' time in jobs / (threads x wall, less the trace's clock "
           "reads), traced frames apart\n";
    for (const ScalingScene& scene : scenes)
        benchScalingScene(scene, counts, options.frames, out);
}

}  // namespace facet
