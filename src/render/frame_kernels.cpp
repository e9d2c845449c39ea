// One copy of the frame's hot path: renderFrame with no observer, instantiated here with everything it
// inlines. This file is compiled once per instruction set (frame_kernels.h); the build names the copy
// with FACET_KERNELS_SET (an InstructionSet value) and its entry point with FACET_KERNELS_ENTRY, the
// only symbol of a wider copy left global. Without them it is the baseline copy, part of facet_render.
#include "render/frame_kernels.h"

#include "render/renderer.h"

#ifndef FACET_KERNELS_SET
#define FACET_KERNELS_SET Baseline
#define FACET_KERNELS_ENTRY facet_frame_kernels_baseline
#endif

namespace facet {
namespace {

FrameStats renderFrameUnobserved(const PreparedScene& prepared, Framebuffer& target, DrawContext& context,
                                 FrameMemory& memory, std::uint8_t terms) {
    NullObserver unobserved;
    FrameStats stats = renderFrame(prepared, target, context, memory, unobserved, terms);
    stats.instructionSet = InstructionSet::FACET_KERNELS_SET;
    return stats;
}

constexpr FrameKernels kKernels{InstructionSet::FACET_KERNELS_SET, &renderFrameUnobserved};

}  // namespace
}  // namespace facet

// A C name: the dispatcher (frame_dispatch.cpp) declares the entry points it was built with.
extern "C" const facet::FrameKernels* FACET_KERNELS_ENTRY() {
    return &facet::kKernels;
}
