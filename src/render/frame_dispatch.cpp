// Which compiled copy of the frame's hot path renders (frame_kernels.h): the widest this CPU runs, or
// the one FACET_ISA names.
#include <cpuid.h>

#include <cstdlib>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

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

// The names of the built copies that `keep` accepts, comma-separated, for messages.
std::string namesList(bool (*keep)(InstructionSet)) {
    std::string list;
    for (const FrameKernels& kernels : builtFrameKernels()) {
        if (!keep(kernels.instructionSet)) continue;
        if (!list.empty()) list += ", ";
        list += nameOf(kernels.instructionSet);
    }
    return list;
}

bool everyCopy(InstructionSet) {
    return true;
}

// The widest built copy this CPU runs.
const FrameKernels& widestSupported() {
    const FrameKernels* widest = &builtFrameKernels().front();
    for (const FrameKernels& kernels : builtFrameKernels())
        if (cpuSupports(kernels.instructionSet)) widest = &kernels;
    return *widest;
}

// The copy for `set`, or the reason it cannot run here.
const FrameKernels& checkedKernels(InstructionSet set, std::string_view source) {
    const FrameKernels* kernels = findBuilt(set);
    std::string where(source);
    if (!kernels)
        throw InputError(where + ": this build of facet has no " + std::string(nameOf(set)) +
                         " code (built: " + namesList(everyCopy) + ")");
    if (!cpuSupports(set))
        throw InputError(where + ": this CPU cannot run " + std::string(nameOf(set)) +
                         " instructions (it runs: " + namesList(cpuSupports) + ")");
    return *kernels;
}

// The choice: FACET_ISA when set, the widest otherwise. A bad FACET_ISA is an error, not a silent
// fallback: a test or benchmark that forces a path must not measure another.
const FrameKernels& chooseKernels() {
    const char* forced = std::getenv("FACET_ISA");
    if (!forced || !*forced) return widestSupported();
    const std::optional<InstructionSet> set = parseName<InstructionSet>(forced);
    if (!set)
        throw InputError("FACET_ISA=" + inQuotes(forced) +
                         " names no instruction set (one of: " + namesList(everyCopy) + ")");
    return checkedKernels(*set, std::string("FACET_ISA=") + forced);
}

// F16C (CPUID leaf 1, ECX bit 29), which clang's __builtin_cpu_supports does not name.
bool cpuHasF16c() {
    unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
    return __get_cpuid(1, &eax, &ebx, &ecx, &edx) && (ecx & bit_F16C);
}

struct Choice {
    std::once_flag once;
    const FrameKernels* kernels = nullptr;
    std::string error;  // why FACET_ISA cannot be followed, kept to be thrown on every call
};

Choice& choice() {
    static Choice c;
    std::call_once(c.once, [] {
        try {
            c.kernels = &chooseKernels();
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
    c.kernels = &checkedKernels(set, "the instruction set asked for");
    c.error.clear();
}

std::string describeFrameKernels() {
    std::string text(nameOf(frameKernels().instructionSet));
    text += " (widest this CPU runs: ";
    text += nameOf(widestSupported().instructionSet);
    text += "; built: ";
    text += namesList(everyCopy);
    text += ")";
    return text;
}

FrameStats renderFrame(const PreparedScene& prepared, Framebuffer& target, DrawContext& context,
                       FrameMemory& memory, std::uint8_t terms) {
    return frameKernels().renderFrame(prepared, target, context, memory, terms);
}

}  // namespace facet
