// `facet bench`: times whole frames of a model and prints medians (never a pass/fail test).
// `facet bench --instruction-sets` times the frame with each copy of its hot path (frame_kernels.h).
// `facet bench --vs-mesa` times Facet against Mesa's llvmpipe (mesa_peer.h) on the same scenes.
// `facet bench --sort` times the transparency sorter (transparency_sort.h) on a turntable.
// `facet bench --transparency` times the transparency modes side by side.
// `facet bench --reference` times the reference renderer, Embree's ray casting and shadows.
// One file per mode (frame_bench, instruction_set_bench, transparency_bench, mesa_bench, sort_bench,
// reference_bench); what they measure with and draw their charts with is in process_stats.h and chart.h, for
// any command that times.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <optional>
#include <utility>

#include "scene/scene.h"

namespace facet {

struct Scene;
struct PoolTrace;

struct BenchOptions {
    std::filesystem::path model;  // OBJ or scene file
    int width = 1920;
    int height = 1080;
    int frames = 30;  // timed frames, after one untimed warm-up frame
    int threads = 0;  // 0: one per hardware thread
    // --cut-for: plain frames' work cut into the items a frame on this many threads runs, whatever
    // `threads` (0: cut for `threads`). The image is the same; the work a bigger machine would do can be
    // counted on a small one.
    int cutFor = 0;
    // --aa: the anti-aliasing of the timed frames (the scene file's, else none, when not given).
    std::optional<Antialiasing> antialiasing;
    // --shader FILE, --uniform NAME=VALUE: the frame drawn with a shader of one's own, timed against
    // the built-in per-pixel Blinn-Phong frame of the same model.
    std::optional<ShaderSpec> shader;
    std::vector<UniformValue> uniforms;

    // --instruction-sets
    bool instructionSets = false;

    // --vs-mesa
    bool vsMesa = false;
    bool quick = false;  // a shorter sweep, for a smoke run (the caller also lowers `frames`)
    std::filesystem::path csv = "out/bench-scaling.csv";
    std::filesystem::path chart = "out/bench-scaling.png";
    std::filesystem::path sharedModels = "../shared/models";  // the largest model is found here
    std::filesystem::path smallModel = "models/spot/spot_triangulated.obj";  // drawn at 3840×2160

    // --sort
    bool sort = false;

    // --transparency
    bool transparency = false;
    float degreesPerFrame = 1.0f;  // the turntable's step

    // --scaling
    bool scaling = false;

    // --reference (writes `csv`, out/bench-reference.csv unless given)
    bool reference = false;
    std::filesystem::path ground = "models/fog-and-glass/ground.obj";  // the shadows' ground, a quad at y = 0

    // --batch LIST (batch_bench.h): the list of inputs rendered by one process and by shards
    std::filesystem::path batchList;
};

// The scene a benchmark draws: options.model (an OBJ file or a scene) at the options' size and
// anti-aliasing. Throws
// InputError for options.frames < 1 or a model that does not load.
Scene benchScene(const BenchOptions& options);

// Renders options.frames frames on options.threads threads and prints a report to `out`:
// the median, minimum and maximum milliseconds per frame, the triangle and fragment counts, and the
// cost of clearing the framebuffer alone (the floor under any frame). Throws InputError on bad input.
// With options.shader: the frames drawn with that shader and the same model's frames drawn with the
// built-in per-pixel Blinn-Phong shader take turns, and the report gives both medians (wall-clock and
// the process's CPU time) and their ratios, the shader's over the built-in's.
void runBench(const BenchOptions& options, std::ostream& out);

// The frame of options.model timed with each copy of the hot path this CPU runs (baseline, avx2, avx512:
// what FACET_ISA chooses among), each with its own framebuffer and frame memory, the copies taking turns
// frame by frame: prints each copy's median ms per frame and its ratio to the widest copy's, and whether
// its image is byte-identical to the widest's. The copy the program had chosen is in use again
// afterwards. Throws InputError on bad input, std::runtime_error when an image differs (a bug: every
// copy must give the same bytes).
void runInstructionSetBench(const BenchOptions& options, std::ostream& out);

// The transparency modes side by side: options.model with every surface half transparent (opacity 0.5),
// on a turntable of options.degreesPerFrame per frame, drawn with "sorted" (insertion sort with memory),
// "unsorted" and "exact" (per-pixel fragment lists): median ms per frame, the sort's and the resolve's
// share, and the memory the fragment lists hold. Throws InputError on bad input.
void runTransparencyBench(const BenchOptions& options, std::ostream& out);

// Renders each benchmark scene through Facet and through Mesa llvmpipe (OSMesa, when it can be loaded),
// frames alternating, on the same number of threads, and prints per scene the median ms per frame of
// each, their ratio, whether the two images agree, and the peak memory of Facet's render. Scenes:
// options.model at 1920×1080 with one point light; the largest model of options.sharedModels;
// options.smallModel at 3840×2160; a triangle sweep (icospheres of 1k to 1M triangles) and a
// resolution sweep (options.model at 640×480 to 3840×2160), written to options.csv and drawn to
// options.chart. Without OSMesa it says so and times Facet alone. Throws InputError on bad input.
void runMesaComparison(const BenchOptions& options, std::ostream& out);

// The OBJ file under `folder` (recursively) with the most triangles, and their count: the largest scene
// of --vs-mesa and --scaling. Empty when there is none.
std::pair<std::filesystem::path, std::size_t> largestModel(const std::filesystem::path& folder);

// Frames of options.model at the options' size (with modelGiven; else the named scenes of
// runMesaComparison: options.model at 1920×1080, the largest model of options.sharedModels at
// 1920×1080, options.smallModel at 3840×2160) on 1, 2, 4, ... threads up to options.threads
// (threadSweep), frames taking turns across the counts: per count the median wall-clock and CPU ms
// per frame, speed-up and CPU ratio to one thread, and the threads' busy share; from a trace of the
// pool's jobs on one thread, the serial fraction of a frame and the speed-up Amdahl's law and the jobs'
// sizes allow at 16 threads and at the largest count. Throws InputError on bad input.
void runScalingBench(const BenchOptions& options, bool modelGiven, std::ostream& out);

// A frame's serial part from the trace of its jobs on one thread (ThreadPool::startTrace) and its CPU time:
// serialMs = the time outside its jobs of two or more items (each job's span on the caller and its clock
// reads taken off) plus the one-item jobs' items; workMs = the items of the other jobs. The trace's own
// clock reads are in neither, so their sum is the frame's time untraced.
struct FrameSerialPart {
    double serialMs = 0.0, workMs = 0.0;
};
FrameSerialPart serialPartOf(const PoolTrace& trace, double frameCpuMs);

// A traced frame's speed-up bound on `threads` threads: a job of two or more items, of work W_j and
// longest item m_j, lasts at least max(W_j / threads, m_j), and the serial part (`frame`) all of its time:
// (serial + work) / (serial + Σ_j max(W_j / threads, m_j)).
double jobBoundOf(const PoolTrace& trace, const FrameSerialPart& frame, int threads);

// The share of a traced frame's threads' time spent in jobs: the items' times summed over the threads,
// over each thread's wall-clock time `frameWallMs` less the trace's own clock reads on that thread (two
// per item, and two per job on the caller), which the items' times leave out too: else a frame of many
// small items would look idle for the reads' time where a read is a system call.
double busyShareOf(const PoolTrace& trace, double frameWallMs);

// Treats every triangle of options.model (at least 50,000 of them, or InputError) as transparent and
// turns the model on a turntable (about the vertical axis through its bounding box's centre, camera as
// `facet render` frames it). Each frame computes one key per triangle (view-space depth of the centroid)
// and orders the triangles back to front twice, by insertion sort from the previous frame's order and by
// std::sort from scratch, for angular steps of 6°, 1°, 0.3°, 0.1°, 0.03° and 0.01° per frame, and prints
// per step the median ms per frame of each, their ratio, their comparisons and moves, and the keys' cost
// (options.frames frames per step after 1 warm-up, fewer where a step would take too long). Single thread.
void runSortBench(const BenchOptions& options, std::ostream& out);

// The reference renderer's speed and what shadows cost the rasterizer, printed as tables and written to
// options.csv (one line per row of the tables):
//   - renderReference on options.model at the options' size with 1 and 4×4 = 16 samples per pixel, on 1,
//     2, 4, ... threads up to options.threads (threadSweep): median ms per frame (BVH build included, as
//     facet render --renderer reference pays it), the BVH's share, camera rays per second of tracing and
//     shading;
//   - the ray casting alone (RayScene::nearestOpaque8 on the same camera rays, 1 per pixel, generated
//     beforehand): packets of 8 and single rays, the scene's face culling and none, on the same thread
//     counts;
//   - the BVH build (RayScene of the model), median of a few builds;
//   - the rasterizer (options.threads) drawing options.model on options.ground with 1, 2 and 4
//     directional lights that cast ray-cast shadows, or shadow maps of 1024, 2048 and 4096 texels, or
//     none: median ms of prepareShadows (BVH or maps, rebuilt every frame as for a moving scene) and of
//     the draw, and the cost per shadowing light: (ms with k such lights − ms with k lights without
//     shadows) / k, of the draw alone (one BVH serves every light) and of the whole frame.
// Configurations alternate frame by frame (a shared machine drifts); 1-sample reference frames and
// rasterizer frames: options.frames each, 16-sample ones: at most 3. Throws InputError on bad input.
void runReferenceBench(const BenchOptions& options, std::ostream& out);

}  // namespace facet
