// facet bench --instruction-sets: the frame with each copy of its hot path this CPU runs, frames taking
// turns, medians side by side and the images compared byte for byte; the medians are recorded for this
// CPU model, and later runs use the fastest copy (frame_kernels.h, chooseInstructionSet).
#include <chrono>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/errors.h"
#include "bench/bench.h"
#include "bench/process_stats.h"
#include "render/frame_kernels.h"
#include "render/renderer.h"

namespace facet {

namespace {

// One copy of the hot path under test: its own framebuffer and frame memory, so that each copy's frames
// follow its own previous frame, as a program using only that copy would draw them.
struct TimedCopy {
    TimedCopy(InstructionSet instructionSet, int width, int height)
        : set(instructionSet), framebuffer(width, height) {}
    InstructionSet set;
    Framebuffer framebuffer;
    FrameMemory memory;
    std::vector<double> frameMs;
};

constexpr int kFramesToRecord = 5;

// Puts back the copy the program had chosen, however the benchmark ends.
struct RestoreFrameKernels {
    InstructionSet chosen;
    ~RestoreFrameKernels() { useFrameKernels(chosen); }
};

std::string joinedNames(const std::vector<InstructionSet>& sets) {
    std::string names;
    for (const InstructionSet set : sets)
        names += (names.empty() ? "" : ", ") + std::string(nameOf(set));
    return names;
}

// Records the medians for this CPU model, so that later runs use the fastest copy, and says so. A run
// of fewer than kFramesToRecord frames per copy is a smoke test: its medians are not a measurement.
void recordVerdict(const std::vector<std::unique_ptr<TimedCopy>>& copies, int frames, std::ostream& out) {
    std::vector<MeasuredCopy> measured;
    for (const auto& copy : copies)
        measured.push_back({copy->set, median(copy->frameMs)});
    out << "verdict    ";
    if (frames < kFramesToRecord) {
        out << "not recorded: fewer than " << kFramesToRecord << " frames per copy\n";
        return;
    }
    try {
        const std::filesystem::path file = recordInstructionSetTimings(measured);
        const std::vector<InstructionSet> runs = [&] {
            std::vector<InstructionSet> sets;
            for (const MeasuredCopy& copy : measured)
                sets.push_back(copy.set);
            return sets;
        }();
        const InstructionSetChoice next = chooseInstructionSet({"", runs, runs, measured});
        out << nameOf(next.set) << " is the fastest here; recorded in " << file.string()
            << ", which later runs on this CPU model follow unless FACET_ISA is set\n";
    } catch (const InputError& e) {
        out << "not recorded: " << e.what() << "\n";
    }
}

}  // namespace

void runInstructionSetBench(const BenchOptions& options, std::ostream& out) {
    const Scene scene = benchScene(options);
    const PreparedScene prepared = prepareScene(scene);
    // frameKernels() first: it throws, as every frame would, when FACET_ISA names no usable copy.
    const RestoreFrameKernels restore{frameKernels().instructionSet};
    const std::string chosenBefore = describeFrameKernels();
    std::vector<InstructionSet> built, runnable;
    for (const FrameKernels& kernels : builtFrameKernels()) {
        built.push_back(kernels.instructionSet);
        if (cpuSupports(kernels.instructionSet)) runnable.push_back(kernels.instructionSet);
    }
    std::vector<std::unique_ptr<TimedCopy>> copies;
    for (const InstructionSet set : runnable)
        copies.push_back(std::make_unique<TimedCopy>(set, scene.width, scene.height));

    DrawContext context(options.threads);
    for (auto& copy : copies) {  // warm-up: caches, buffers, threads; the images compared below
        useFrameKernels(copy->set);
        renderFrame(prepared, copy->framebuffer, context, copy->memory);
    }
    using Clock = std::chrono::steady_clock;
    const std::size_t n = copies.size();
    for (int frame = 0; frame < options.frames; ++frame) {
        // The copies take turns, each frame starting one further on, so that neither a slow spell of
        // the machine nor the order favours one.
        for (std::size_t k = 0; k < n; ++k) {
            TimedCopy& copy = *copies[(static_cast<std::size_t>(frame) + k) % n];
            useFrameKernels(copy.set);
            const auto start = Clock::now();
            renderFrame(prepared, copy.framebuffer, context, copy.memory);
            copy.frameMs.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
        }
    }

    const TimedCopy& widest = *copies.back();
    const std::span<const vec4> widestImage = widest.framebuffer.colorSpan();
    out << std::fixed << std::setprecision(2);
    out << "model      " << options.model.string() << "\n";
    out << "image      " << scene.width << "x" << scene.height << ", " << context.pool.threads()
        << (context.pool.threads() == 1 ? " thread" : " threads") << ", built-in Blinn-Phong shader\n";
    out << "code       built: " << joinedNames(built) << "; this CPU runs: " << joinedNames(runnable) << "\n";
    out << "cpu        " << cpuModelName() << "; frames use " << chosenBefore << "\n";
    out << "frames     " << options.frames << " timed per copy after 1 warm-up, the copies taking turns\n";
    std::vector<InstructionSet> differing;
    for (const auto& copy : copies) {
        const std::span<const vec4> image = copy->framebuffer.colorSpan();
        const bool identical = std::memcmp(image.data(), widestImage.data(), image.size_bytes()) == 0;
        if (!identical) differing.push_back(copy->set);
        const double ms = median(copy->frameMs);
        out << std::left << std::setw(11) << nameOf(copy->set) << std::right << "median " << std::setw(8)
            << ms << " ms  " << std::setw(5) << ms / median(widest.frameMs) << "× " << nameOf(widest.set)
            << "'s";
        if (copy.get() != &widest)
            out << (identical ? "  image identical to " : "  IMAGE DIFFERS from ") << nameOf(widest.set)
                << "'s";
        out << "\n";
    }
    if (differing.empty()) recordVerdict(copies, options.frames, out);
    if (!differing.empty())
        throw std::runtime_error("facet bench --instruction-sets: the image of " + joinedNames(differing) +
                                 " differs from " + std::string(nameOf(widest.set)) +
                                 "'s; every copy must give the same bytes");
}

}  // namespace facet
