// The frame's code compiled once per instruction set (render/frame_kernels.h): every copy this CPU can
// run draws the same bytes, renderFrame runs the copy chosen, and a copy the CPU cannot run is refused.
// (tests/cli/other_cpus_test.sh runs the program on emulated CPUs without AVX and without AVX-512,
// and checks there that FACET_ISA cannot force a copy the CPU lacks.)
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "render/frame_kernels.h"
#include "render/renderer.h"

namespace facet {
namespace {

// Restores the process's choice when a test that forces one ends.
class FrameKernelsTest : public ::testing::Test {
  protected:
    void TearDown() override { useFrameKernels(initial_); }
    const InstructionSet initial_ = frameKernels().instructionSet;
};

// The copies this CPU can run, narrowest first.
std::vector<InstructionSet> runnableSets() {
    std::vector<InstructionSet> sets;
    for (const FrameKernels& kernels : builtFrameKernels())
        if (cpuSupports(kernels.instructionSet)) sets.push_back(kernels.instructionSet);
    return sets;
}

struct Drawn {
    std::vector<vec4> color;
    std::vector<DepthFormat::Stored> depth;
    FrameStats stats;
};

// Two frames of `prepared` (the second reuses the first's transparent order) through the dispatched
// renderFrame with `set` forced, on two threads.
Drawn drawWith(InstructionSet set, const PreparedScene& prepared, int width, int height) {
    useFrameKernels(set);
    Framebuffer framebuffer(width, height);
    DrawContext context(2);
    FrameMemory memory;
    Drawn drawn;
    renderFrame(prepared, framebuffer, context, memory);
    drawn.stats = renderFrame(prepared, framebuffer, context, memory);
    drawn.color.assign(framebuffer.colorSpan().begin(), framebuffer.colorSpan().end());
    drawn.depth.assign(framebuffer.depthSpan().begin(), framebuffer.depthSpan().end());
    return drawn;
}

// A bundled model (under models/) prepared for a frame of width × height.
PreparedScene preparedAt(const char* file, int width, int height) {
    Scene scene = loadSceneOrModel(std::string(FACET_SOURCE_DIR "/models/") + file);
    scene.width = width;
    scene.height = height;
    return prepareScene(scene);
}

struct Variant {
    std::string name;
    std::string file;  // under models/
    std::function<void(Scene&)> change;
};

// One variant per name E's table offers: `file` with `apply(scene, value)`.
template <class E, class Apply>
void addEveryValue(std::vector<Variant>& list, const std::string& label, const char* file, Apply apply) {
    for (const EnumName<E>& entry : enumNames(E{}))
        list.push_back({label + " " + std::string(entry.name), file,
                        [apply, value = entry.value](Scene& s) { apply(s, value); }});
}

// Every bundled scene, and the textured spot through each choice that reaches different code: shading
// frequencies, reflection models, the approximations, colour and depth buffer formats, anti-aliasing,
// texture filters, transparency modes, the OpenGL preset.
std::vector<Variant> variants() {
    std::vector<Variant> list;
    for (const char* file : {"example-scene.json", "fog-and-glass.json", "intersecting-quads.json",
                             "lighting-scene.json", "near-plane.json", "shadows.json", "shared-edge.json"})
        list.push_back({file, file, [](Scene&) {}});
    const char* spot = "spot/spot_triangulated.obj";
    addEveryValue<ShadingFrequency>(list, "shading", spot,
                                    [](Scene& s, ShadingFrequency v) { s.lighting.shading = v; });
    addEveryValue<ReflectionModel>(list, "reflection", spot,
                                   [](Scene& s, ReflectionModel v) { s.lighting.model = v; });
    addEveryValue<ColorBufferFormat>(list, "color buffer", spot,
                                     [](Scene& s, ColorBufferFormat v) { s.pipeline.colorBuffer = v; });
    addEveryValue<DepthBufferFormat>(list, "depth buffer", spot,
                                     [](Scene& s, DepthBufferFormat v) { s.pipeline.depth = v; });
    addEveryValue<TextureFilter>(list, "texture filter", spot,
                                 [](Scene& s, TextureFilter v) { s.textures.filter = v; });
    addEveryValue<TransparencyMode>(list, "transparency", "fog-and-glass.json",
                                    [](Scene& s, TransparencyMode v) { s.transparency.mode = v; });
    list.push_back({"exact powers, fast normalize", spot, [](Scene& s) {
                        s.lighting.powers = MathPrecision::Exact;
                        s.lighting.normalize = Normalization::Fast;
                    }});
    list.push_back({"gl preset", spot, [](Scene& s) { s.lighting.preset = LightingPreset::GL; }});
    for (const Antialiasing aa : {Antialiasing::Msaa4, Antialiasing::Ssaa4})
        list.push_back({"antialiasing " + std::string(nameOf(aa)), spot,
                        [aa](Scene& s) { s.pipeline.antialiasing = aa; }});
    list.push_back({"affine, no culling", spot, [](Scene& s) {
                        s.pipeline.interpolation = Interpolation::Affine;
                        s.pipeline.cull = CullMode::None;
                    }});
    return list;
}

// Every copy this CPU runs draws every variant to the same colour and depth bytes as the baseline copy.
// Breaks if a copy is compiled so that it rounds differently (-ffp-contract=fast, which fuses a·b + c
// on the FMA levels; -ffast-math's reassociation) or if an instruction-set path of the code (F16C's
// half conversion, the eight-lane rsqrt, the sign mask) stops giving its portable twin's result.
TEST_F(FrameKernelsTest, EveryCopyThisCpuRunsDrawsTheSameBytes) {
    const std::vector<InstructionSet> sets = runnableSets();
    std::string compared;
    for (const InstructionSet set : sets)
        compared += std::string(compared.empty() ? "" : ", ") + std::string(nameOf(set));
    RecordProperty("instruction_sets", compared);
    if (sets.size() < 2) GTEST_SKIP() << "this CPU runs only the " << compared << " copy";
    constexpr int kWidth = 96, kHeight = 72;
    for (const Variant& variant : variants()) {
        SCOPED_TRACE(variant.name);
        Scene scene = loadSceneOrModel(std::string(FACET_SOURCE_DIR "/models/") + variant.file);
        scene.width = kWidth;
        scene.height = kHeight;
        variant.change(scene);
        const PreparedScene prepared = prepareScene(scene);
        const Drawn baseline = drawWith(InstructionSet::Baseline, prepared, kWidth, kHeight);
        ASSERT_GT(baseline.stats.draw.fragmentsShaded, 0u);
        for (const InstructionSet set : sets) {
            SCOPED_TRACE(nameOf(set));
            const Drawn drawn = drawWith(set, prepared, kWidth, kHeight);
            EXPECT_EQ(drawn.stats.instructionSet, set);
            EXPECT_EQ(drawn.stats.draw.fragmentsShaded, baseline.stats.draw.fragmentsShaded);
            EXPECT_EQ(drawn.stats.draw.fragmentsWritten, baseline.stats.draw.fragmentsWritten);
            ASSERT_EQ(drawn.color.size(), baseline.color.size());
            EXPECT_EQ(
                std::memcmp(drawn.color.data(), baseline.color.data(), drawn.color.size() * sizeof(vec4)), 0);
            ASSERT_EQ(drawn.depth.size(), baseline.depth.size());
            EXPECT_EQ(std::memcmp(drawn.depth.data(), baseline.depth.data(),
                                  drawn.depth.size() * sizeof(DepthFormat::Stored)),
                      0);
        }
    }
}

// The AVX-512 copy shades most fragments sixteen at a time, two batches a call (wide.h), and the
// narrower copies all eight at a time. Breaks if the back end stops pairing batches where it has
// sixteen lanes (the test above then compares eight lanes with eight), or if a batch is counted twice or
// not at all.
TEST_F(FrameKernelsTest, OnlyTheAvx512CopyShadesSixteenFragmentsAtATime) {
    const PreparedScene prepared = preparedAt("spot/spot_triangulated.obj", 160, 120);
    for (const InstructionSet set : runnableSets()) {
        SCOPED_TRACE(nameOf(set));
        const DrawStats stats = drawWith(set, prepared, 160, 120).stats.draw;
        ASSERT_GT(stats.fragmentsShaded, 1000u);
        EXPECT_EQ(stats.fragmentsWritten, stats.fragmentsShaded);
        if (set == InstructionSet::Avx512)
            EXPECT_GT(stats.fragmentsShadedBy16, stats.fragmentsShaded * 9 / 10);
        else
            EXPECT_EQ(stats.fragmentsShadedBy16, 0u);
    }
}

// renderFrame runs the copy chosen: its stats name the copy that drew. Breaks if the dispatcher always
// calls one copy (the images alone could not tell: they are the same bytes).
TEST_F(FrameKernelsTest, RenderFrameRunsTheChosenCopy) {
    const PreparedScene prepared = preparedAt("cube/cube.obj", 16, 12);
    for (const InstructionSet set : runnableSets()) {
        SCOPED_TRACE(nameOf(set));
        useFrameKernels(set);
        EXPECT_EQ(frameKernels().instructionSet, set);
        Framebuffer framebuffer(16, 12);
        DrawContext context(1);
        FrameMemory memory;
        EXPECT_EQ(renderFrame(prepared, framebuffer, context, memory).instructionSet, set);
    }
}

// The default is the widest copy the CPU runs (FACET_ISA unset, no timings recorded for this CPU model),
// and describeFrameKernels says so. Breaks if the choice stops at a narrower copy than the CPU allows.
TEST(FrameKernels, TheWidestCopyTheCpuRunsIsTheDefault) {
    if (std::getenv("FACET_ISA")) GTEST_SKIP() << "FACET_ISA is set: the choice is forced";
    if (describeFrameKernels().find("measured fastest") != std::string::npos)
        GTEST_SKIP()
            << "facet bench --instruction-sets recorded timings for this CPU: the choice follows them";
    const InstructionSet widest = runnableSets().back();
    EXPECT_EQ(frameKernels().instructionSet, widest);
    const std::string expected =
        std::string(nameOf(widest)) + " (widest this CPU runs: " + std::string(nameOf(widest));
    EXPECT_EQ(describeFrameKernels().rfind(expected, 0), 0u) << describeFrameKernels();
}

// A copy the CPU cannot run is refused with a message, and the choice stays as it was: the build's
// lack named first where the build has no such copy either (a portable build on a CPU without AVX-512),
// else the CPU's. Breaks if useFrameKernels (or FACET_ISA, which goes through the same check) could select
// code that would fault on this CPU, or if the message blamed the CPU for a copy the build lacks.
TEST_F(FrameKernelsTest, ACopyTheCpuCannotRunIsRefused) {
    EXPECT_TRUE(cpuSupports(InstructionSet::Baseline));
    for (const EnumName<InstructionSet>& entry : kInstructionSetNames) {
        if (cpuSupports(entry.value)) continue;
        SCOPED_TRACE(entry.name);
        bool built = false;
        for (const FrameKernels& kernels : builtFrameKernels())
            built = built || kernels.instructionSet == entry.value;
        const std::string reason = built ? "this CPU cannot run " + std::string(entry.name)
                                         : "this build of facet has no " + std::string(entry.name) + " code";
        try {
            useFrameKernels(entry.value);
            ADD_FAILURE() << "accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
        }
        EXPECT_EQ(frameKernels().instructionSet, initial_);
    }
}

// The build has every copy, narrowest first: the baseline, and with dispatch (x86-64's default) the
// AVX2 and AVX-512 ones. Breaks if a copy is left out of the dispatcher's list: it would never run.
TEST(FrameKernels, TheBuildHasEveryCopyNarrowestFirst) {
    const std::span<const FrameKernels> built = builtFrameKernels();
    ASSERT_FALSE(built.empty());
    EXPECT_EQ(built.front().instructionSet, InstructionSet::Baseline);
#if defined(FACET_DISPATCH_BUILD)
    ASSERT_EQ(built.size(), std::size(kInstructionSetNames));
    for (std::size_t k = 0; k < built.size(); ++k)
        EXPECT_EQ(built[k].instructionSet, kInstructionSetNames[k].value);
#else
    EXPECT_EQ(built.size(), 1u);
#endif
}

}  // namespace
}  // namespace facet
