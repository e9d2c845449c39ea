// The frame's hot path, compiled once per x86-64 instruction set and chosen when the program runs, so
// that one binary runs on any x86-64 CPU and uses the widest vector instructions the CPU has.
//
// frame_kernels.cpp (renderFrame of renderer.h with no observer: clears, the pipeline's stages, the
// shaders, texture sampling, the resolves) is compiled three times: for baseline x86-64 (SSE2, part of
// the library like any file), and for x86-64-v3 (AVX2, FMA, F16C, BMI2) and x86-64-v4 (AVX-512 F, BW,
// CD, DQ, VL) into objects of their own (src/render/CMakeLists.txt). Each of the latter two is linked
// with the pipeline's .cpp files compiled for the same level, and every symbol in it but its one entry
// point is made local: its copies of the inline functions and templates it uses (the pipeline's, GLM's,
// the standard library's) can neither replace the baseline copies nor be replaced by them, so no AVX
// instruction reaches the baseline path and the one-definition rule holds for the linker.
//
// The three paths compute the same bytes: floating point is IEEE everywhere, -ffp-contract=off keeps
// a·b + c from being fused on the FMA levels, and where the code uses an instruction of a level it
// gives the result of the portable version (tests/render/frame_kernels_test.cpp renders with each path
// the CPU can run and compares the images byte for byte).
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pipeline/names.h"

namespace facet {

struct PreparedScene;
struct FrameStats;
struct FrameMemory;
class Framebuffer;
struct DrawContext;

// The instruction sets the frame's hot path is compiled for, narrowest first.
enum class InstructionSet : std::uint8_t {
    Baseline,  // x86-64: SSE2, which every x86-64 CPU has
    Avx2,      // x86-64-v3: AVX2, FMA, F16C, BMI1/2, LZCNT, MOVBE (Intel Haswell, AMD Excavator and later)
    Avx512,    // x86-64-v4: the above and AVX-512 F, BW, CD, DQ, VL (Intel Skylake-SP, AMD Zen 4 and later)
};
inline constexpr EnumName<InstructionSet> kInstructionSetNames[] = {{InstructionSet::Baseline, "baseline"},
                                                                    {InstructionSet::Avx2, "avx2"},
                                                                    {InstructionSet::Avx512, "avx512"}};
constexpr std::span<const EnumName<InstructionSet>> enumNames(InstructionSet) {
    return kInstructionSetNames;
}

// One compiled copy of the hot path.
struct FrameKernels {
    InstructionSet instructionSet;
    // renderFrame(prepared, target, context, memory, terms) of renderer.h, compiled for instructionSet.
    FrameStats (*renderFrame)(const PreparedScene& prepared, Framebuffer& target, DrawContext& context,
                              FrameMemory& memory, std::uint8_t terms);
};

// The copies this build has (the baseline always; the others on x86-64 builds with dispatch on),
// narrowest first, whether or not this CPU can run them.
std::span<const FrameKernels> builtFrameKernels();

// Whether this CPU (and its operating system, which must save the wider registers) can run `set`.
bool cpuSupports(InstructionSet set);

// The copy renderFrame uses, chosen on first use (chooseInstructionSet below): the one the environment
// variable FACET_ISA names (baseline, avx2 or avx512), which makes any path testable on a CPU that has
// it; else the fastest copy `facet bench --instruction-sets` measured on this CPU model, when it
// recorded one (instructionSetTimingsFile); else the widest built one this CPU runs. Throws
// InputError, once and on every later call, when FACET_ISA names no instruction set or one this CPU or
// build does not have.
const FrameKernels& frameKernels();

// The same choice made by hand: a test or benchmark forcing one path. Throws InputError (as above) when `set`
// is not built or this CPU cannot run it. Not to be called while a frame renders.
void useFrameKernels(InstructionSet set);

// "avx2 (widest this CPU runs: avx512; built: baseline, avx2, avx512; measured fastest on this CPU model
// ...)": the copy in use and why, as `facet --version` and facet bench report it. Throws as
// frameKernels() does.
std::string describeFrameKernels();

// The choice of a copy ------------------------------------------------------------------------------

// One copy's median ms per frame, as facet bench --instruction-sets measured it.
struct MeasuredCopy {
    InstructionSet set;
    double msPerFrame;
};

// What the choice is made from: all of it read from the process and the machine by frameKernels().
struct InstructionSetChoiceInputs {
    std::string_view forced;                 // FACET_ISA's value; empty when it is unset
    std::span<const InstructionSet> built;   // the copies this build has, narrowest first
    std::span<const InstructionSet> runs;    // those this CPU runs, narrowest first (never empty)
    std::span<const MeasuredCopy> measured;  // this CPU model's recorded timings (may be empty)
};

struct InstructionSetChoice {
    InstructionSet set;
    std::string reason;  // why, for facet --version: "forced by FACET_ISA=avx2", "measured fastest ..."
};

// FACET_ISA when set (InputError when it names no copy, or one not built or not runnable here). Else
// the copy with the lowest measured time, when every copy this CPU runs has a measurement: AVX-512 is
// not always faster than AVX2 (on a 16-core Xeon the AVX2 copy drew 6% faster), so what this CPU
// model measured decides. Else the widest this CPU runs.
InstructionSetChoice chooseInstructionSet(const InstructionSetChoiceInputs& inputs);

// This CPU's model as CPUID's brand string says it ("AMD EPYC 9B45", "Intel(R) Xeon(R) Gold 6248"),
// without surrounding spaces: the key of the recorded timings.
std::string cpuModelName();

// Where facet bench --instruction-sets records its timings: $XDG_CACHE_HOME/facet/instruction-sets,
// else ~/.cache/facet/instruction-sets; empty when neither variable is set.
std::filesystem::path instructionSetTimingsFile();

// The recorded timings of `cpuModel` in the text of a timings file: one line per CPU model,
// "MODEL<tab>avx2=13.61<tab>avx512=13.42...", lines starting with '#' ignored. A line or entry that
// does not read (a file cut short, a name a later build added) is skipped: it is a cache, not input.
std::vector<MeasuredCopy> parseInstructionSetTimings(std::string_view text, std::string_view cpuModel);

// `text` (a timings file's, possibly empty) with `cpuModel`'s line replaced by `measured`.
std::string withInstructionSetTimings(std::string_view text, std::string_view cpuModel,
                                      std::span<const MeasuredCopy> measured);

// Writes `measured` as this CPU model's timings into instructionSetTimingsFile() (a new file put in place
// by rename, so that a run reading it at the same time sees the old or the new whole). Returns the file,
// or throws InputError when it cannot be written.
std::filesystem::path recordInstructionSetTimings(std::span<const MeasuredCopy> measured);

}  // namespace facet
