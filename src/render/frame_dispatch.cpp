// Which compiled copy of the frame's hot path renders (frame_kernels.h): the one FACET_ISA names, the
// fastest measured on this CPU model, or the widest this CPU runs.
#include <cpuid.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include "base/errors.h"
#include "base/quote.h"
#include "render/frame_kernels.h"
#include "render/renderer.h"

// The entry points of the copies (frame_kernels.cpp); the wider ones exist when the build defines
// FACET_DISPATCH (src/render/CMakeLists.txt).
extern "C" const facet::FrameKernels* facet_frame_kernels_baseline();
#if defined(FACET_DISPATCH)
extern "C" const facet::FrameKernels* facet_frame_kernels_avx2();
extern "C" const facet::FrameKernels* facet_frame_kernels_avx512();
#endif

namespace facet {

namespace {

namespace fs = std::filesystem;

std::vector<FrameKernels> collectBuiltKernels() {
    std::vector<FrameKernels> built{*facet_frame_kernels_baseline()};
#if defined(FACET_DISPATCH)
    built.push_back(*facet_frame_kernels_avx2());
    built.push_back(*facet_frame_kernels_avx512());
#endif
    return built;
}

const FrameKernels* findBuilt(InstructionSet set) {
    for (const FrameKernels& kernels : builtFrameKernels())
        if (kernels.instructionSet == set) return &kernels;
    return nullptr;
}

bool contains(std::span<const InstructionSet> sets, InstructionSet set) {
    return std::find(sets.begin(), sets.end(), set) != sets.end();
}

// "baseline, avx2, avx512", for messages.
std::string namesList(std::span<const InstructionSet> sets) {
    std::string list;
    for (const InstructionSet set : sets) {
        if (!list.empty()) list += ", ";
        list += nameOf(set);
    }
    return list;
}

std::vector<InstructionSet> builtSets() {
    std::vector<InstructionSet> sets;
    for (const FrameKernels& kernels : builtFrameKernels())
        sets.push_back(kernels.instructionSet);
    return sets;
}

std::vector<InstructionSet> runnableSets() {
    std::vector<InstructionSet> sets;
    for (const FrameKernels& kernels : builtFrameKernels())
        if (cpuSupports(kernels.instructionSet)) sets.push_back(kernels.instructionSet);
    return sets;
}

// Throws, with the reason, unless this build has `set` and this CPU runs it.
void checkUsable(InstructionSet set, std::span<const InstructionSet> built,
                 std::span<const InstructionSet> runs, std::string_view source) {
    std::string where(source);
    if (!contains(built, set))
        throw InputError(where + ": this build of facet has no " + std::string(nameOf(set)) +
                         " code (built: " + namesList(built) + ")");
    if (!contains(runs, set))
        throw InputError(where + ": this CPU cannot run " + std::string(nameOf(set)) +
                         " instructions (it runs: " + namesList(runs) + ")");
}

std::string millisecondsText(double ms) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f", ms);
    return text;
}

// The recorded timings of this CPU model; none when the file is missing or unreadable.
std::vector<MeasuredCopy> recordedTimings() {
    const fs::path file = instructionSetTimingsFile();
    if (file.empty()) return {};
    std::ifstream in(file, std::ios::binary);
    if (!in) return {};
    std::ostringstream text;
    text << in.rdbuf();
    return parseInstructionSetTimings(text.str(), cpuModelName());
}

// F16C (CPUID leaf 1, ECX bit 29), which clang's __builtin_cpu_supports does not name.
bool cpuHasF16c() {
    unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
    return __get_cpuid(1, &eax, &ebx, &ecx, &edx) && (ecx & bit_F16C);
}

struct Choice {
    std::once_flag once;
    const FrameKernels* kernels = nullptr;    // in use
    const FrameKernels* automatic = nullptr;  // chosen on first use, and why
    std::string reason;
    std::string error;  // why FACET_ISA cannot be followed, kept to be thrown on every call
};

// The choice of chooseInstructionSet on this process's environment, CPU and recorded timings. A bad
// FACET_ISA is an error, not a silent fallback: a test or benchmark that forces a path must not
// measure another. The timings are read only when FACET_ISA is unset, so that it always wins.
Choice& choice() {
    static Choice c;
    std::call_once(c.once, [] {
        try {
            const char* forced = std::getenv("FACET_ISA");
            const std::vector<InstructionSet> built = builtSets(), runs = runnableSets();
            const std::vector<MeasuredCopy> measured =
                forced && *forced ? std::vector<MeasuredCopy>{} : recordedTimings();
            InstructionSetChoice chosen = chooseInstructionSet({forced ? forced : "", built, runs, measured});
            c.kernels = c.automatic = findBuilt(chosen.set);
            c.reason = std::move(chosen.reason);
            if (!measured.empty()) c.reason += ", recorded in " + instructionSetTimingsFile().string();
        } catch (const InputError& e) {
            c.error = e.what();
        }
    });
    return c;
}

}  // namespace

std::span<const FrameKernels> builtFrameKernels() {
    static const std::vector<FrameKernels> built = collectBuiltKernels();
    return built;
}

bool cpuSupports(InstructionSet set) {
    // libgcc's checks include the operating system's: AVX counts only when XGETBV says it saves the
    // YMM registers, AVX-512 only when it saves the ZMM and mask registers.
    __builtin_cpu_init();
    switch (set) {
        case InstructionSet::Baseline:
            return true;
        case InstructionSet::Avx2:
            return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && cpuHasF16c() &&
                   __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2");
        case InstructionSet::Avx512:
            return cpuSupports(InstructionSet::Avx2) && __builtin_cpu_supports("avx512f") &&
                   __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512cd") &&
                   __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl");
    }
    return false;
}

const FrameKernels& frameKernels() {
    Choice& c = choice();
    if (!c.kernels) throw InputError(c.error);
    return *c.kernels;
}

void useFrameKernels(InstructionSet set) {
    Choice& c = choice();
    const std::vector<InstructionSet> built = builtSets(), runs = runnableSets();
    checkUsable(set, built, runs, "the instruction set asked for");
    c.kernels = findBuilt(set);
    c.error.clear();
}

std::string describeFrameKernels() {
    const FrameKernels& kernels = frameKernels();
    const std::string reason = &kernels == choice().automatic ? choice().reason : "chosen by the program";
    const std::vector<InstructionSet> runs = runnableSets();
    return std::string(nameOf(kernels.instructionSet)) +
           " (widest this CPU runs: " + std::string(nameOf(runs.back())) +
           "; built: " + namesList(builtSets()) + "; " + reason + ")";
}

InstructionSetChoice chooseInstructionSet(const InstructionSetChoiceInputs& inputs) {
    if (!inputs.forced.empty()) {
        const std::string source = "FACET_ISA=" + inQuotes(inputs.forced);
        const std::optional<InstructionSet> set = parseName<InstructionSet>(inputs.forced);
        if (!set)
            throw InputError(source + " names no instruction set (one of: " + namesList(inputs.built) + ")");
        checkUsable(*set, inputs.built, inputs.runs, "FACET_ISA=" + std::string(inputs.forced));
        return {*set, "forced by FACET_ISA=" + std::string(inputs.forced)};
    }
    const InstructionSet widest = inputs.runs.back();
    // The measured copies that run here; the timings count only when they cover every such copy (a
    // record from a build with fewer copies would otherwise never let a new one be tried).
    std::vector<MeasuredCopy> usable;
    for (const InstructionSet set : inputs.runs)
        for (const MeasuredCopy& copy : inputs.measured)
            if (copy.set == set) {
                usable.push_back(copy);
                break;
            }
    if (usable.size() != inputs.runs.size())
        return {widest,
                "not measured on this CPU model, so the widest (facet bench --instruction-sets "
                "measures the copies)"};
    // The fastest; on a tie the wider, which was the choice without a measurement.
    const MeasuredCopy* fastest = &usable.front();
    for (const MeasuredCopy& copy : usable)
        if (copy.msPerFrame <= fastest->msPerFrame) fastest = &copy;
    std::string reason = "measured fastest on this CPU model by facet bench --instruction-sets:";
    for (const MeasuredCopy& copy : usable)
        reason += std::string(copy.set == usable.front().set ? " " : ", ") + std::string(nameOf(copy.set)) +
                  " " + millisecondsText(copy.msPerFrame) + " ms";
    reason += " per frame";
    return {fastest->set, reason};
}

std::string cpuModelName() {
    // CPUID leaves 0x80000002–4: the brand string, 48 bytes, padded with spaces and ended by a zero.
    unsigned words[12] = {};
    for (unsigned leaf = 0; leaf < 3; ++leaf)
        if (!__get_cpuid(0x80000002u + leaf, &words[4 * leaf], &words[4 * leaf + 1], &words[4 * leaf + 2],
                         &words[4 * leaf + 3]))
            return "unknown CPU";
    std::string brand(reinterpret_cast<const char*>(words), sizeof words);
    brand.resize(brand.find('\0') == std::string::npos ? brand.size() : brand.find('\0'));
    const std::size_t first = brand.find_first_not_of(' ');
    if (first == std::string::npos) return "unknown CPU";
    return brand.substr(first, brand.find_last_not_of(' ') - first + 1);
}

fs::path instructionSetTimingsFile() {
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
        return fs::path(xdg) / "facet" / "instruction-sets";
    if (const char* home = std::getenv("HOME"); home && *home)
        return fs::path(home) / ".cache" / "facet" / "instruction-sets";
    return {};
}

std::vector<MeasuredCopy> parseInstructionSetTimings(std::string_view text, std::string_view cpuModel) {
    std::vector<MeasuredCopy> measured;
    while (!text.empty()) {
        const std::size_t end = std::min(text.find('\n'), text.size());
        std::string_view line = text.substr(0, end);
        text.remove_prefix(std::min(end + 1, text.size()));
        const std::size_t tab = line.find('\t');
        if (line.empty() || line.front() == '#' || tab == std::string_view::npos ||
            line.substr(0, tab) != cpuModel)
            continue;
        measured.clear();  // the last line of a model counts
        line.remove_prefix(tab + 1);
        while (!line.empty()) {
            const std::size_t next = std::min(line.find('\t'), line.size());
            const std::string_view entry = line.substr(0, next);
            line.remove_prefix(std::min(next + 1, line.size()));
            const std::size_t equals = entry.find('=');
            if (equals == std::string_view::npos) continue;
            const std::optional<InstructionSet> set = parseName<InstructionSet>(entry.substr(0, equals));
            double ms = 0.0;
            const std::string_view number = entry.substr(equals + 1);
            const auto [at, error] = std::from_chars(number.data(), number.data() + number.size(), ms);
            if (!set || error != std::errc() || at != number.data() + number.size() || !std::isfinite(ms) ||
                ms <= 0.0)
                continue;
            measured.push_back({*set, ms});
        }
    }
    return measured;
}

std::string withInstructionSetTimings(std::string_view text, std::string_view cpuModel,
                                      std::span<const MeasuredCopy> measured) {
    std::string result;
    while (!text.empty()) {
        const std::size_t end = std::min(text.find('\n'), text.size());
        const std::string_view line = text.substr(0, end);
        text.remove_prefix(std::min(end + 1, text.size()));
        const std::size_t tab = line.find('\t');
        if (tab != std::string_view::npos && line.substr(0, tab) == cpuModel) continue;
        if (!line.empty()) result.append(line).append("\n");
    }
    if (result.empty())
        result =
            "# facet bench --instruction-sets: median ms per frame of each copy of the frame's code, per "
            "CPU model; facet uses the fastest (delete this file to forget)\n";
    result.append(cpuModel);
    // Appended piece by piece: GCC 12 reports a false -Wrestrict on chains of std::string operator+.
    for (const MeasuredCopy& copy : measured)
        result.append("\t").append(nameOf(copy.set)).append("=").append(millisecondsText(copy.msPerFrame));
    result += '\n';
    return result;
}

fs::path recordInstructionSetTimings(std::span<const MeasuredCopy> measured) {
    const fs::path file = instructionSetTimingsFile();
    if (file.empty()) throw InputError("cannot record the timings: neither XDG_CACHE_HOME nor HOME is set");
    std::string old;
    if (std::ifstream in(file, std::ios::binary); in) {
        std::ostringstream text;
        text << in.rdbuf();
        old = text.str();
    }
    std::error_code error;
    fs::create_directories(file.parent_path(), error);
    const fs::path temporary = file.string() + "." + std::to_string(::getpid());
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        out << withInstructionSetTimings(old, cpuModelName(), measured);
        if (!out.flush()) {
            fs::remove(temporary, error);
            throw InputError("cannot write " + temporary.string());
        }
    }
    fs::rename(temporary, file, error);
    if (error) {
        fs::remove(temporary, error);
        throw InputError("cannot write " + file.string() + ": " + error.message());
    }
    return file;
}

FrameStats renderFrame(const PreparedScene& prepared, Framebuffer& target, DrawContext& context,
                       FrameMemory& memory, std::uint8_t terms) {
    return frameKernels().renderFrame(prepared, target, context, memory, terms);
}

}  // namespace facet
