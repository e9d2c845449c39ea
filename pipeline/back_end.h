// The back end of a draw, tile by tile: rasterization (8×8 blocks) → early depth test → interpolation
// → fragment shader → blending (color_write.h), or appending to the per-pixel fragment lists that
// resolveFragmentLists() composites. Tiles run in parallel; inside a tile the triangles run in
// submission order, chunk after chunk, so the image is the same bytes for any thread count or tile size.
//
// One walk serves every draw, single-sample and multisampled: drawTile → each triangle's blocks →
// each block row's depth test (per pixel, or per sample) → the fragment queue (fragment_queue.h) →
// shadeQueue → the depth write and the output merger. It is compiled per BackEndConfig, chosen once per
// draw (drawTileOfChunks); the blend mode and the colour buffer format are resolved once per draw into
// the output merger the walk calls (ColorWrite). The depth compare stays a switch in the depth test, one
// predicted branch per block row: resolved into masks once per draw it measured slower (docs/trade.md).
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "bin.h"
#include "color_write.h"
#include "depth_format.h"
#include "draw_plan.h"
#include "fragment_lists.h"
#include "fragment_queue.h"
#include "framebuffer.h"
#include "observer.h"
#include "rasterize.h"
#include "shader.h"
#include "thread_pool.h"

namespace facet {

// ---- The walks a shader's code holds ------------------------------------------------------------------

// The back end is compiled once per kind of draw (drawTileOfChunks below): a "walk" for each depth coding
// (Float, Unorm), sample mode and output of an unwatched draw, and two for watched draws (the step mode's).
// A draw takes exactly one. Each walk is a copy of the tile loop with the shader inlined, so a shader's
// code holds every walk unless it declares `static constexpr unsigned kCompiledWalks` (a set of these
// bits): a shader module compiled for the draws its scene makes holds only theirs (shaders/shader_module.h),
// and draw() refuses, before drawing anything, a draw whose walk its shader was compiled without.
namespace walk {
inline constexpr unsigned kFloatDepth = 1u << 0;  // one sample, blended into the colour buffer
inline constexpr unsigned kUnormDepth = 1u << 1;
inline constexpr unsigned kMultisampleFloatDepth = 1u << 2;  // two or more samples per pixel
inline constexpr unsigned kMultisampleUnormDepth = 1u << 3;
inline constexpr unsigned kListsFloatDepth = 1u << 4;  // appended to the fragment lists (exact transparency)
inline constexpr unsigned kListsUnormDepth = 1u << 5;
inline constexpr unsigned kWatched = 1u << 6;  // watched, blended (the depth coding chosen per fragment)
inline constexpr unsigned kWatchedLists = 1u << 7;
inline constexpr unsigned kAll = (1u << 8) - 1;
}  // namespace walk

// The walk of a draw: its coding of depths, whether it is multisampled (an unwatched draw only: a watched
// one is refused), where its fragments go, and whether it is watched; the one place the back end's
// choice of walk is written (drawTileOfChunks asks it of its template parameters, a caller of its plan).
constexpr unsigned backEndWalk(DepthCodingKind depth, bool multisampled, FragmentOutput output,
                               bool watched) {
    const bool lists = output == FragmentOutput::AppendToLists;
    if (watched) return lists ? walk::kWatchedLists : walk::kWatched;
    const bool unorm = depth == DepthCodingKind::Unorm;
    if (multisampled) return unorm ? walk::kMultisampleUnormDepth : walk::kMultisampleFloatDepth;
    if (lists) return unorm ? walk::kListsUnormDepth : walk::kListsFloatDepth;
    return unorm ? walk::kUnormDepth : walk::kFloatDepth;
}

inline unsigned backEndWalkOf(const DrawPlan& plan, bool watched) {
    return backEndWalk(depthCodingOf(plan.depthFormat), plan.samples > 1, plan.output, watched);
}

// The walks S's code holds: S::kCompiledWalks when it declares them, else every one.
template <class S>
constexpr unsigned compiledWalks() {
    if constexpr (requires { S::kCompiledWalks; })
        return S::kCompiledWalks;
    else
        return walk::kAll;
}

// Throws std::logic_error when S's code lacks the walk `plan` takes: a caller that compiled S for some
// draws (a shader module) gave it another.
template <class S>
void checkWalkCompiled(const DrawPlan& plan, bool watched) {
    if constexpr (compiledWalks<S>() != walk::kAll)
        if ((compiledWalks<S>() & backEndWalkOf(plan, watched)) == 0)
            throw std::logic_error("the shader's code was compiled without the back end this draw needs (" +
                                   std::string(watched ? "watched, " : "") +
                                   (plan.samples > 1 ? "multisampled, " : "") +
                                   (plan.output == FragmentOutput::AppendToLists ? "fragment lists, " : "") +
                                   std::string(nameOf(plan.depthFormat)) + " depth)");
}

namespace detail {

// What one compiled copy of the back end is for. Each choice here is a template parameter because it
// changes the walk's shape or data: the shader, the observer, the depth coding (float or unorm codes:
// DepthCoding), single-sample or multisampled (the count itself, 2 to 16, is the draw's: plan.samples),
// the output (the colour buffer or the fragment lists) and whether fragments get their texture
// coordinates' derivatives.
template <Shader S, class O, class D, bool kMultisampled, FragmentOutput kOutputTo, bool kWithDerivatives>
struct BackEndConfig {
    using Shader = S;
    using Observer = O;
    using Depth = D;
    using Uniforms = typename S::Uniforms;
    static constexpr bool kMultisample = kMultisampled;
    static constexpr FragmentOutput kOutput = kOutputTo;
    static constexpr bool kDerivatives = kWithDerivatives;
    static constexpr bool kObserving = O::enabled;
    // Whether the depth test itself writes the depths of the fragments that pass, a block row at a
    // time, rather than shadeQueue once they are shaded: when the shader cannot discard, a fragment
    // that passes is certain to be written, so its depth may be stored early. A row's eight depths are
    // then read and written whole; written one fragment at a time from the queue, they would have the
    // next row test of the same pixels wait for the store buffer (a load that spans several pending
    // smaller stores cannot take its value from them). Watched draws keep the late write, so that an
    // observer's "depth before" is the depth the fragment was tested against; multisampled ones write
    // each passing sample's depth when the fragment is kept. The same bytes either way.
    static constexpr bool kDepthWrittenAtTest = !kMultisampled && !kMayDiscard<S> && !O::enabled;
    using Queue = std::conditional_t<kMultisampled, MultisampleQueue, FragmentQueue>;
    // Whether batches are shaded two at a time (sixteen lanes: wide.h), the first kept waiting for the
    // second (ParkedBatch). Only where nothing reads what a waiting batch will write before it is
    // written: its depths were written at the test, and its colours are written before the next
    // batch's, so a later fragment at one of its pixels blends over it as it would have.
    static constexpr bool kShadesPairs = [] {
#if FACET_SIXTEEN_LANES
        return PairBatchShader<S> && kDepthWrittenAtTest && kOutputTo == FragmentOutput::Blend;
#else
        return false;
#endif
    }();
};

// A shaded-in-pairs walk's batch waiting for its partner: its fragments' pixels and interpolated
// varyings, and whether its slots are a block row's columns (writeFragments).
struct ParkedBatch {
    bool waiting = false;
    bool slotsAreColumns = false;
    int x[kBlockSize], y[kBlockSize];
    FragmentBatch batch;
};

struct NoMember {};

// One tile's walk: the draw's choices, the tile's planes and the queues, handed to every stage below.
template <class C>
struct TileWalk {
    TileWalk(const DrawPlan& plan, const typename C::Depth& depth, const typename C::Uniforms& uniforms,
             const FramebufferPlanes& target, DrawStats& stats, typename C::Observer& observer)
        : plan(plan),
          depth(depth),
          uniforms(uniforms),
          write(colorWriteFor(plan.blend, plan.colorBuffer)),
          target(target),
          stats(stats),
          observer(observer) {
        if constexpr (C::kMultisample) offsets = SampleOffsetsFixed(plan.samples);
    }

    const DrawPlan& plan;
    const typename C::Depth& depth;
    const typename C::Uniforms& uniforms;
    const ColorWrite write;  // the draw's blend mode and colour buffer format
    const FramebufferPlanes target;
    DrawStats& stats;
    typename C::Observer& observer;
    typename C::Queue queue;
    // A block row shaded whole (kRowShadedWhole; single-sample only): slot = column.
    [[no_unique_address]] std::conditional_t<C::kMultisample, NoMember, FragmentQueue> rowQueue;
    // The draw's sample positions (multisampled only).
    [[no_unique_address]] std::conditional_t<C::kMultisample, SampleOffsetsFixed, NoMember> offsets;
    // The batch waiting to be shaded with the next (kShadesPairs only).
    [[no_unique_address]] std::conditional_t<C::kShadesPairs, ParkedBatch, NoMember> parked;
};

// ---- Shading and writing the queue ------------------------------------------------------------------

// Depth write, then blending or appending, for the shaded fragments of `written` (unwatched,
// single-sample). `slotsAreColumns`: the queue is a block row shaded whole, slot c at pixel
// (x[0] + c, y[0]); when all eight of its lanes are stored plainly, one copy writes the row's colours.
template <class C, class Queue>
[[gnu::always_inline]] inline void writeFragments(TileWalk<C>& walk, Queue& queue,
                                                  const vec4 (&shaded)[kBlockSize], unsigned written,
                                                  bool slotsAreColumns) {
    const FramebufferPlanes& target = walk.target;
    if constexpr (!C::kDepthWrittenAtTest) {
        if (walk.plan.depthWrite)
            for (unsigned lanes = written; lanes; lanes &= lanes - 1) {
                const int lane = std::countr_zero(lanes);
                target.depth(queue.x[lane], queue.y[lane]) = walk.depth.store(queue.z[lane]);
            }
    }
    if constexpr (C::kOutput == FragmentOutput::AppendToLists) {
        for (unsigned lanes = written; lanes; lanes &= lanes - 1) {
            const int lane = std::countr_zero(lanes);
            walk.stats.fragmentsStored += queue.lists.append(queue.x[lane], queue.y[lane], shaded[lane],
                                                             queue.z[lane], walk.plan.blend);
        }
    } else if (walk.write.plainStores) {
        if (slotsAreColumns && written == 0xffu) {
            std::memcpy(&target.color(queue.x[0], queue.y[0]), shaded, sizeof shaded);
            return;
        }
        if (written == 0xffu) {  // a full batch (the common case): eight stores, no branch per lane
            for (int lane = 0; lane < kBlockSize; ++lane)
                target.color(queue.x[lane], queue.y[lane]) = shaded[lane];
            return;
        }
        for (unsigned lanes = written; lanes; lanes &= lanes - 1) {
            const int lane = std::countr_zero(lanes);
            target.color(queue.x[lane], queue.y[lane]) = shaded[lane];
        }
    } else {
        walk.write.lanes(target, shaded, queue.x, queue.y, written);
    }
}

// The multisampled fragments of `written`: each into the samples of its pixel that it covers and that
// passed the depth test, with those samples' depths.
template <class C>
[[gnu::always_inline]] inline void writeSamples(TileWalk<C>& walk, const MultisampleQueue& queue,
                                                const vec4 (&shaded)[kBlockSize], unsigned written) {
    for (unsigned lanes = written; lanes; lanes &= lanes - 1) {
        const int lane = std::countr_zero(lanes);
        vec4* colors = walk.target.sampleColors(queue.x[lane], queue.y[lane]);
        typename C::Depth::Stored* depths = walk.target.sampleDepths(queue.x[lane], queue.y[lane]);
        const unsigned samples = queue.samplesPassed[lane];
        if (walk.write.plainStores) {  // one pass over the samples, as for an opaque draw's pixels
            for (unsigned bits = samples; bits; bits &= bits - 1) {
                const int s = std::countr_zero(bits);
                if (walk.plan.depthWrite) depths[s] = walk.depth.store(queue.sampleZ[lane][s]);
                colors[s] = shaded[lane];
            }
            continue;
        }
        if (walk.plan.depthWrite)
            for (unsigned bits = samples; bits; bits &= bits - 1) {
                const int s = std::countr_zero(bits);
                depths[s] = walk.depth.store(queue.sampleZ[lane][s]);
            }
        walk.write.samples(colors, samples, shaded[lane]);
    }
}

// The interpolation stage's view of the fragment in slot `lane`, for an observer's FragmentEvent.
template <class C>
FragmentEvent watchedFragment(const TileWalk<C>& walk, const FragmentQueue& queue, int lane) {
    using S = typename C::Shader;
    const int x = queue.x[lane], y = queue.y[lane];
    FragmentEvent event{x, y, queue.triangle[lane], queue.z[lane], walk.target.depth(x, y)};
    event.colorBefore = event.colorAfter = walk.target.color(x, y);
    describeInterpolation(event, queue.b1[lane], queue.b2[lane], queue.invW[lane], kVaryingsOf<S>);
    for (int k = 0; k < kVaryingsOf<S>; ++k)
        event.varyings[static_cast<std::size_t>(k)] = queue.batch.varyings[k][lane];
    if constexpr (derivativeVarying<S>() >= 0)  // watched draws always compute them
        for (int k = 0; k < 4; ++k)
            event.uvDerivatives[static_cast<std::size_t>(k)] = queue.batch.uvDerivatives[k][lane];
    return event;
}

// The same as writeFragments for a watched draw, a fragment at a time, each fragment's fate told to the
// observer (the step mode: for reading, not speed).
template <class C>
void writeWatched(TileWalk<C>& walk, FragmentQueue& queue, int n, const vec4 (&shaded)[kBlockSize],
                  unsigned live, unsigned kept) {
    for (int lane = 0; lane < n; ++lane) {
        if (!(live & (1u << lane))) continue;
        const int x = queue.x[lane], y = queue.y[lane];
        FragmentEvent event = watchedFragment(walk, queue, lane);
        if (!(kept & (1u << lane))) {
            event.fate = FragmentFate::Discarded;
            walk.observer.onFragment(event);
            continue;
        }
        if (walk.plan.depthWrite) walk.target.depth(x, y) = walk.depth.store(queue.z[lane]);
        if constexpr (C::kOutput == FragmentOutput::AppendToLists) {
            const bool stored = queue.lists.append(x, y, shaded[lane], queue.z[lane], walk.plan.blend);
            walk.stats.fragmentsStored += stored;
            event.fate = stored ? FragmentFate::Stored : FragmentFate::Dropped;
        } else {
            walk.write.lanes(walk.target, shaded, queue.x, queue.y, 1u << lane);
            event.fate = FragmentFate::Written;
            event.colorAfter = walk.target.color(x, y);
        }
        event.shaded = shaded[lane];
        walk.observer.onFragment(event);
    }
}

// A shaded-in-pairs walk: the interpolated queue waits in walk.parked for the next batch, or is shaded
// with the one waiting there in one sixteen-lane call, the waiting one written first.
template <class C>
void parkOrShadePair(TileWalk<C>& walk, FragmentQueue& queue, bool slotsAreColumns) {
    using S = typename C::Shader;
    ParkedBatch& parked = walk.parked;
    FragmentBatch& batch = queue.batch;
    if (!parked.waiting) {
        parked.waiting = true;
        parked.slotsAreColumns = slotsAreColumns;
        std::memcpy(parked.x, queue.x, sizeof parked.x);
        std::memcpy(parked.y, queue.y, sizeof parked.y);
        std::memcpy(parked.batch.varyings, batch.varyings, kVaryingsOf<S> * sizeof(Float8));
        if constexpr (C::kDerivatives)
            std::memcpy(parked.batch.uvDerivatives, batch.uvDerivatives, sizeof batch.uvDerivatives);
        if constexpr (wantsBarycentrics<S>())
            std::memcpy(parked.batch.barycentrics, batch.barycentrics, sizeof batch.barycentrics);
        parked.batch.mask = batch.mask;
    } else {
#if FACET_SIXTEEN_LANES
        const Vec4x16 colors = S::fragmentBatchPair(parked.batch, batch, walk.uniforms);
        vec4 first[kBlockSize], second[kBlockSize];
        storeTransposed(lowHalf(colors), first);
        storeTransposed(highHalf(colors), second);
        const unsigned shaded =
            static_cast<unsigned>(std::popcount(parked.batch.mask) + std::popcount(batch.mask));
        walk.stats.fragmentsShaded += shaded;
        walk.stats.fragmentsShadedBy16 += shaded;
        walk.stats.fragmentsWritten += shaded;
        writeFragments(walk, parked, first, parked.batch.mask, parked.slotsAreColumns);
        writeFragments(walk, queue, second, batch.mask, slotsAreColumns);
        parked.waiting = false;
#endif
    }
    batch.mask = 0;
    queue.pixelsMod8 = 0;
}

// The batch still waiting at the end of a shaded-in-pairs walk, shaded alone (the bits it would have
// had with a partner).
template <class C>
void shadeParked(TileWalk<C>& walk) {
    ParkedBatch& parked = walk.parked;
    if (!parked.waiting) return;
    parked.waiting = false;
    vec4 shaded[kBlockSize];
    storeTransposed(C::Shader::fragmentBatch(parked.batch, walk.uniforms), shaded);
    const unsigned n = static_cast<unsigned>(std::popcount(parked.batch.mask));
    walk.stats.fragmentsShaded += n;
    walk.stats.fragmentsWritten += n;
    writeFragments(walk, parked, shaded, parked.batch.mask, parked.slotsAreColumns);
}

// The queued fragments (or a block row shaded whole, `slotsAreColumns`, interpolated with its row):
// interpolation, the fragment shader, then the depth write and the output.
// Left to the compiler (out of line, as it chooses): the walk calls it from three places.
template <class C, class Queue>
void shadeQueue(TileWalk<C>& walk, Queue& queue, bool slotsAreColumns = false) {
    const int n = queue.count;
    if (n == 0) return;
    queue.count = 0;
    if (!slotsAreColumns) interpolateQueue<typename C::Shader, C::kDerivatives>(queue);
    if constexpr (C::kShadesPairs) {
        parkOrShadePair(walk, queue, slotsAreColumns);
        return;
    }
    vec4 shaded[kBlockSize];
    const unsigned kept = runFragmentShader<typename C::Shader>(queue, n, walk.uniforms, shaded, walk.stats);
    const unsigned live = queue.batch.mask;
    queue.batch.mask = 0;
    queue.pixelsMod8 = 0;
    walk.stats.fragmentsDiscarded += static_cast<unsigned>(std::popcount(live & ~kept));
    if constexpr (C::kOutput == FragmentOutput::Blend)
        walk.stats.fragmentsWritten += static_cast<unsigned>(std::popcount(live & kept));
    if constexpr (C::kObserving)
        writeWatched(walk, queue, n, shaded, live, kept);
    else if constexpr (C::kMultisample)
        writeSamples(walk, queue, shaded, live & kept);
    else
        writeFragments(walk, queue, shaded, live & kept, slotsAreColumns);
}

// ---- The depth test of a block row, per pixel -------------------------------------------------------

// One row of a block: its pixels' barycentrics and depths at their centres.
struct BlockRow {
    int x, y;
    unsigned mask;  // covered columns
    Float8 b1, b2, z;
};

// The depth test of a row's covered pixels, eight stored depths at once when the row is inside the
// framebuffer; with kDepthWrittenAtTest, the passing depths written. Returns the columns that passed.
template <class C>
[[gnu::always_inline]] inline unsigned depthTestRow(TileWalk<C>& walk, const BlockRow& row) {
    using Depth = typename C::Depth;
    typename Depth::Stored* depthRow = &walk.target.depth(row.x, row.y);
    unsigned passed = row.mask;
    const bool wholeRow = row.x + kBlockSize <= walk.target.width();  // inside the framebuffer
    if (walk.plan.depthTest) {
        if (wholeRow) {
            passed &= signMask(walk.depth.passes(walk.plan.depthCompare, row.z, Depth::load8(depthRow)));
        } else {
            for (int lane = 0; lane < kBlockSize; ++lane)
                if ((row.mask >> lane) & 1u)
                    if (!walk.depth.passes(walk.plan.depthCompare, row.z[lane], depthRow[lane]))
                        passed &= ~(1u << lane);
        }
    }
    if constexpr (C::kDepthWrittenAtTest) {
        if (walk.plan.depthWrite && passed) {
            if (wholeRow) {
                const auto z = select(laneMaskOf(passed), walk.depth.store(row.z), Depth::load8(depthRow));
                std::memcpy(depthRow, &z, sizeof z);
            } else {
                for (unsigned lanes = passed; lanes; lanes &= lanes - 1) {
                    const int lane = std::countr_zero(lanes);
                    depthRow[lane] = walk.depth.store(row.z[lane]);
                }
            }
        }
    }
    walk.stats.fragmentsDepthFailed += static_cast<unsigned>(std::popcount(row.mask & ~passed));
    return passed;
}

// A watched draw's fragments that failed the depth test, told to the observer.
template <class C>
void watchDepthFailed(TileWalk<C>& walk, const TriangleSetup& setup, const float* planes, const BlockRow& row,
                      unsigned failed) {
    for (unsigned lanes = failed; lanes; lanes &= lanes - 1) {
        const int lane = std::countr_zero(lanes);
        const int x = row.x + lane;
        FragmentEvent event{x, row.y, setup.triangle, row.z[lane], walk.target.depth(x, row.y)};
        event.colorBefore = event.colorAfter = walk.target.color(x, row.y);
        event.fate = FragmentFate::DepthFailed;
        describeInterpolation(event, row.b1[lane], row.b2[lane],
                              interpolateInvW(setup, row.b1[lane], row.b2[lane]), setup.varyingCount);
        interpolateVaryings(setup, planes, row.b1[lane], row.b2[lane], event.varyings.data());
        walk.observer.onFragment(event);
    }
}

// A row's passing pixels, shaded: the row as one batch of its own when most passed (kRowShadedWhole,
// its varyings interpolated straight into the batch, lane = column), else each into the queue.
// `uvSlopes`: the triangle's texture coordinate slopes, computed at the block's first row shaded whole.
template <class C>
[[gnu::always_inline]] inline void shadePassingRow(TileWalk<C>& walk, const TriangleSetup& setup,
                                                   const float* planes, const BlockRow& row, unsigned passed,
                                                   VaryingPairSlopes& uvSlopes, bool& haveSlopes) {
    using S = typename C::Shader;
    FragmentQueue& queue = walk.queue;
    FragmentQueue& rowQueue = walk.rowQueue;
    const bool rowShadedWhole = std::popcount(passed) >= kRowShadedWhole;
    if (rowShadedWhole) {
        if constexpr (C::kDerivatives) {
            if (!haveSlopes) uvSlopes = VaryingPairSlopes(setup, planes, derivativeVarying<S>());
            haveSlopes = true;
        }
        interpolateRowWide<S, C::kDerivatives>(setup, planes, uvSlopes, row.b1, row.b2, rowQueue.batch);
        // Slot = column; the slots of lanes that failed are not live (batch.mask) and not read.
        const Int8 column = {0, 1, 2, 3, 4, 5, 6, 7};
        const Int8 rowX = column + row.x, rowY = Int8{} + row.y;
        const Int8 triangle = Int8{} + static_cast<std::int32_t>(setup.triangle);
        std::memcpy(rowQueue.x, &rowX, sizeof rowX);
        std::memcpy(rowQueue.y, &rowY, sizeof rowY);
        std::memcpy(rowQueue.z, &row.z, sizeof row.z);
        std::memcpy(rowQueue.triangle, &triangle, sizeof triangle);
        std::memcpy(rowQueue.b1, &row.b1, sizeof row.b1);
        std::memcpy(rowQueue.b2, &row.b2, sizeof row.b2);
    }
    // The passing fragments of a row not shaded whole go to the queue (a row shaded whole has nothing to
    // do here unless watched: its slots' 1/w). Unwatched, as many as the queue has room for at once,
    // the queue shaded when full, then the rest: the slots and batches of queueing them one by one.
    if constexpr (!C::kObserving) {
        if (!rowShadedWhole && passed) {
            const unsigned now = lowestSetBits(passed, kBlockSize - queue.count);
            queueRow(queue, setup, planes, row.x, row.y, row.z, row.b1, row.b2, now);
            if (queue.count == kBlockSize) shadeQueue(walk, queue);
            if (const unsigned later = passed & ~now)
                queueRow(queue, setup, planes, row.x, row.y, row.z, row.b1, row.b2, later);
        }
    } else {  // watched: one by one, each slot's 1/w recorded (λ1 and λ2 are in the slot already)
        for (unsigned lanes = passed; lanes; lanes &= lanes - 1) {
            const int lane = std::countr_zero(lanes);
            int slot = lane;  // a row shaded whole: its slots are its columns, filled above
            if (!rowShadedWhole)
                slot = queueFragment(queue, setup, planes, row.x + lane, row.y, row.z[lane], row.b1[lane],
                                     row.b2[lane]);
            (rowShadedWhole ? rowQueue : queue).invW[slot] =
                interpolateInvW(setup, row.b1[lane], row.b2[lane]);
            if (queue.count == kBlockSize) shadeQueue(walk, queue);
        }
    }
    if (rowShadedWhole) {
        rowQueue.count = kBlockSize;
        rowQueue.batch.mask = passed;
        constexpr bool kSlotsAreColumns = true;
        shadeQueue(walk, rowQueue, kSlotsAreColumns);
    }
}

// One covered row of a block, per pixel: depth test (before shading: the shader cannot change depth,
// so testing early gives the same image and skips hidden fragments), then shading.
template <class C>
[[gnu::always_inline]] inline void pixelRow(TileWalk<C>& walk, const TriangleSetup& setup,
                                            const float* planes, const BlockBarycentrics& barycentrics,
                                            const CoverageBlock& block, int row, unsigned rowMask,
                                            VaryingPairSlopes& uvSlopes, bool& haveSlopes) {
    BlockRow r{block.x, block.y + row, rowMask, {}, {}, {}};
    barycentrics.row(row, r.b1, r.b2);
    r.z = interpolateDepth(setup, r.b1, r.b2);
    const unsigned passed = depthTestRow(walk, r);
    if constexpr (C::kObserving) watchDepthFailed(walk, setup, planes, r, rowMask & ~passed);
    shadePassingRow(walk, setup, planes, r, passed, uvSlopes, haveSlopes);
}

// ---- The depth test of a block row, per sample ------------------------------------------------------

// A multisampled block: the mask of its pixels with a covered sample, and its mask at each sample.
struct SampleCoverageBlock {
    int x = 0, y = 0;
    std::uint64_t mask = 0;
    std::uint64_t coverage[kMaxSamples];
};

// The depth test at each covered sample of a row's pixels: λᵢ = Eᵢ(sample) / (2·area), Eᵢ(sample) =
// Eᵢ(centre) + aᵢ·dx + bᵢ·dy exact in integers, then z as interpolateDepth gives it at a pixel centre.
// Fills each pixel's passing samples and their depths, its first covered sample's λ1 and λ2, and
// `partial`, the pixels with an uncovered sample. Returns the pixels with a sample that passed.
template <class C>
[[gnu::always_inline]] inline unsigned depthTestSamples(TileWalk<C>& walk, const TriangleSetup& setup,
                                                        const SampleCoverageBlock& block, int row,
                                                        unsigned rowMask, std::uint32_t* samplesPassed,
                                                        float (*sampleZ)[kMaxSamples], float* centroidB1,
                                                        float* centroidB2, unsigned& partial) {
    const double invArea = 1.0 / static_cast<double>(setup.doubleArea);
    const EdgeFunction& e1 = setup.edges[1];
    const EdgeFunction& e2 = setup.edges[2];
    const SampleOffsetsFixed& offsets = walk.offsets;
    const int shift = row * kBlockSize, y = block.y + row;
    unsigned passed = 0;
    for (unsigned lanes = rowMask; lanes; lanes &= lanes - 1) {
        const int lane = std::countr_zero(lanes);
        const int x = block.x + lane;
        const SamplePoint centre = samplePosition(x, y);
        const std::int64_t e1Centre = e1.at(centre.x, centre.y), e2Centre = e2.at(centre.x, centre.y);
        const typename C::Depth::Stored* stored = walk.target.sampleDepths(x, y);
        std::uint32_t pass = 0;
        bool first = true;
        for (int s = 0; s < offsets.count; ++s) {
            if (!((block.coverage[s] >> (shift + lane)) & 1u)) {
                partial |= 1u << lane;
                continue;
            }
            const std::int64_t e1Sample = e1Centre + e1.a * offsets.x[s] + e1.b * offsets.y[s];
            const std::int64_t e2Sample = e2Centre + e2.a * offsets.x[s] + e2.b * offsets.y[s];
            const float b1 = static_cast<float>(static_cast<double>(e1Sample) * invArea);
            const float b2 = static_cast<float>(static_cast<double>(e2Sample) * invArea);
            if (first) {  // the centroid sample if the pixel is only partly covered
                centroidB1[lane] = b1;
                centroidB2[lane] = b2;
                first = false;
            }
            const float z = interpolateDepth(setup, b1, b2);
            if (walk.plan.depthTest && !walk.depth.passes(walk.plan.depthCompare, z, stored[s])) continue;
            pass |= 1u << s;
            sampleZ[lane][s] = z;
        }
        samplesPassed[lane] = pass;
        if (pass) passed |= 1u << lane;
    }
    return passed;
}

// One covered row of a multisampled block: each covered sample's depth from the depth plane at the
// sample, tested against that sample's stored depth; a pixel with a sample that passed is queued once,
// its varyings interpolated at the pixel's centroid sample (GLSL's `centroid`, Direct3D's centroid
// rule): the centre when the triangle covers every sample of the pixel, else its first covered sample
// in the pattern's order. At the centre, a pixel the triangle only grazes would take varyings
// extrapolated beyond the triangle: a position behind the neighbouring wall, whose ray to the light is
// then blocked (dark seams in ray-cast shadows), or a texel outside the triangle's part of the texture.
template <class C>
[[gnu::always_inline]] inline void sampleRow(TileWalk<C>& walk, const TriangleSetup& setup,
                                             const float* planes, const BlockBarycentrics& barycentrics,
                                             const SampleCoverageBlock& block, int row, unsigned rowMask) {
    MultisampleQueue& queue = walk.queue;
    const int y = block.y + row;
    std::uint32_t samplesPassed[kBlockSize];
    float sampleZ[kBlockSize][kMaxSamples];
    float centroidB1[kBlockSize], centroidB2[kBlockSize];
    unsigned partial = 0;
    const unsigned passed = depthTestSamples(walk, setup, block, row, rowMask, samplesPassed, sampleZ,
                                             centroidB1, centroidB2, partial);
    walk.stats.fragmentsDepthFailed += static_cast<unsigned>(std::popcount(rowMask & ~passed));
    if (!passed) return;

    // The shading point: the pixel centre, or the centroid sample of a partly covered pixel.
    Float8 b1{}, b2{};
    barycentrics.row(row, b1, b2);
    for (unsigned lanes = passed & partial; lanes; lanes &= lanes - 1) {
        const int lane = std::countr_zero(lanes);
        b1[lane] = centroidB1[lane];
        b2[lane] = centroidB2[lane];
    }
    const Float8 z = interpolateDepth(setup, b1, b2);
    for (unsigned lanes = passed; lanes; lanes &= lanes - 1) {
        const int lane = std::countr_zero(lanes);
        const int slot = queueFragment(queue, setup, planes, block.x + lane, y, z[lane], b1[lane], b2[lane]);
        queue.samplesPassed[slot] = samplesPassed[lane];
        for (unsigned samples = samplesPassed[lane]; samples; samples &= samples - 1) {
            const int s = std::countr_zero(samples);
            queue.sampleZ[slot][s] = sampleZ[lane][s];
        }
        if (queue.count == kBlockSize) shadeQueue(walk, queue);
    }
}

// ---- The walk ---------------------------------------------------------------------------------------

// The covered rows of one block (only those between the first and the last covered one: a small
// triangle's block has one to three, not eight), per pixel or per sample. A queued fragment at one of a
// row's pixels reaches the framebuffer before the row is tested.
template <class C, class Block>
[[gnu::always_inline]] inline void drawBlock(TileWalk<C>& walk, const TriangleSetup& setup,
                                             const float* planes, const Block& block) {
    const BlockBarycentrics barycentrics(setup, block.x, block.y);
    [[maybe_unused]] VaryingPairSlopes uvSlopes;  // for rows shaded whole, at the block's first such row
    [[maybe_unused]] bool haveSlopes = false;
    const int firstRow = std::countr_zero(block.mask) / kBlockSize;
    const int lastRow = (63 - std::countl_zero(block.mask)) / kBlockSize;
    for (int row = firstRow; row <= lastRow; ++row) {
        const unsigned rowMask = static_cast<unsigned>(block.mask >> (row * kBlockSize)) & 0xffu;
        if (!rowMask) continue;
        if (walk.queue.count && walk.queue.holdsAny(block.y + row, block.x, rowMask))
            shadeQueue(walk, walk.queue);
        if constexpr (C::kMultisample)
            sampleRow(walk, setup, planes, barycentrics, block, row, rowMask);
        else
            pixelRow(walk, setup, planes, barycentrics, block, row, rowMask, uvSlopes, haveSlopes);
    }
}

// ---- The walk of a triangle of a few pixels -----------------------------------------------------------

// The lanes a patch (rasterize.h) is walked with: sixteen in the AVX-512 copy (4×4 or 8×2 pixels),
// eight elsewhere (4×2 or 8×1). The depth test and the queue take them eight at a time: two rows of a
// narrow patch, one row of a wide one.
#if FACET_SIXTEEN_LANES
using PatchLanes = Intx16;
inline Float8 patchHalf(Floatx16 v, int half) {
    return half == 0 ? lowHalf(v) : highHalf(v);
}
#else
using PatchLanes = Int8;
#endif
inline Float8 patchHalf(Float8 v, int) {
    return v;
}

// The rows of a patch kColumns wide in one half (eight lanes).
template <int kColumns>
inline constexpr int kRowsPerHalf = kBlockSize / kColumns;
// The lane bits of one row of such a patch.
template <int kColumns>
inline constexpr unsigned kPatchRowBits = (1u << kColumns) - 1u;

// The depth test of the eight lanes of a patch half at (x, y): two rows of four pixels, lane = row · 4 +
// column, or one row of eight, for the `covered` lanes, as depthTestRow does for a block row; the rows
// are inside the tile. Returns the lanes that passed.
template <class C, int kColumns>
[[gnu::always_inline]] inline unsigned depthTestPatchRows(TileWalk<C>& walk, int x, int y, Float8 z,
                                                          unsigned covered) {
    using Stored = typename C::Depth::Stored;
    static_assert(std::is_same_v<Stored, float>, "a half's stored depths load as eight floats");
    using Float4 = float __attribute__((vector_size(16)));
    Stored* top = &walk.target.depth(x, y);
    Stored* bottom = nullptr;  // a narrow half's second row (a wide half's row may be the last one)
    if constexpr (kColumns == kNarrowPatch) bottom = &walk.target.depth(x, y + 1);
    Float8 stored;
    if constexpr (kColumns == kWidePatch) {
        std::memcpy(&stored, top, sizeof stored);
    } else {
        Float4 topDepths, bottomDepths;
        std::memcpy(&topDepths, top, sizeof topDepths);
        std::memcpy(&bottomDepths, bottom, sizeof bottomDepths);
        stored = __builtin_shufflevector(topDepths, bottomDepths, 0, 1, 2, 3, 4, 5, 6, 7);
    }
    unsigned passed = covered;
    if (walk.plan.depthTest) passed &= signMask(walk.depth.passes(walk.plan.depthCompare, z, stored));
    if constexpr (C::kDepthWrittenAtTest) {
        if (walk.plan.depthWrite && passed) {
            const Float8 written = select(laneMaskOf(passed), walk.depth.store(z), stored);
            if constexpr (kColumns == kWidePatch) {
                std::memcpy(top, &written, sizeof written);
            } else {
                const Float4 topWritten = __builtin_shufflevector(written, written, 0, 1, 2, 3);
                const Float4 bottomWritten = __builtin_shufflevector(written, written, 4, 5, 6, 7);
                std::memcpy(top, &topWritten, sizeof topWritten);
                std::memcpy(bottom, &bottomWritten, sizeof bottomWritten);
            }
        }
    }
    walk.stats.fragmentsDepthFailed += static_cast<unsigned>(std::popcount(covered & ~passed));
    return passed;
}

// The passing lanes of a patch half at (x, y), queued (as many as the queue has room for, the queue
// shaded when full, then the rest), as shadePassingRow queues a block row's.
template <class C, int kColumns>
[[gnu::always_inline]] inline void queuePatchRows(TileWalk<C>& walk, const TriangleSetup& setup,
                                                  const float* planes, int x, int y, Float8 z, Float8 b1,
                                                  Float8 b2, unsigned passed) {
    const Int8 lane = {0, 1, 2, 3, 4, 5, 6, 7};
    const Int8 pixelX = lane % kColumns + x, pixelY = lane / kColumns + y;
    const auto filterBits = [&](unsigned lanes) {
        std::uint64_t bits = 0;
        for (int row = 0; row < kRowsPerHalf<kColumns>; ++row)
            bits |= std::uint64_t{FragmentQueue::filterBitsOf(
                        x, (lanes >> (row * kColumns)) & kPatchRowBits<kColumns>)}
                    << (((y + row) & 7) * 8);
        return bits;
    };
    FragmentQueue& queue = walk.queue;
    const unsigned now = lowestSetBits(passed, kBlockSize - queue.count);
    queueLanes(queue, setup, planes, pixelX, pixelY, z, b1, b2, now, filterBits(now));
    if (queue.count == kBlockSize) shadeQueue(walk, queue);
    if (const unsigned later = passed & ~now)
        queueLanes(queue, setup, planes, pixelX, pixelY, z, b1, b2, later, filterBits(later));
}

// A triangle that fitsPatch, over one patch kColumns wide at (x, y) inside the tile: coverage,
// barycentrics and depth of every lane at once, then the depth test and queueing eight lanes at a time.
// The same fragments, with the same bits, as the block walk gives (tests: PatchWalk).
template <class C, int kColumns>
[[gnu::always_inline]] inline void drawPatch(TileWalk<C>& walk, const TriangleSetup& setup,
                                             const float* planes, const PixelRect& rect, int x, int y) {
    constexpr int kRows = kPatchRows<PatchLanes, kColumns>;
    PatchLanes e1, e2;
    const unsigned covered = patchCoverage<PatchLanes, kColumns>(setup, x, y, rect, e1, e2);
    if (!covered) return;
    // A queued fragment at one of the patch's pixels reaches the framebuffer before they are tested.
    if (walk.queue.count) {
        for (int row = 0; row < kRows; ++row) {
            const unsigned columns = (covered >> (row * kColumns)) & kPatchRowBits<kColumns>;
            if (columns && walk.queue.holdsAny(y + row, x, columns)) {
                shadeQueue(walk, walk.queue);
                break;
            }
        }
    }
    const double inverse = 1.0 / static_cast<double>(setup.doubleArea);
    const auto b1 = barycentricLanes(e1, inverse), b2 = barycentricLanes(e2, inverse);
    const auto z = interpolateDepth(setup, b1, b2);
    for (int half = 0; half < kRows / kRowsPerHalf<kColumns>; ++half) {
        const unsigned halfCovered = (covered >> (half * kBlockSize)) & 0xffu;
        if (!halfCovered) continue;
        const int rowY = y + kRowsPerHalf<kColumns> * half;
        const Float8 halfZ = patchHalf(z, half);
        const unsigned passed = depthTestPatchRows<C, kColumns>(walk, x, rowY, halfZ, halfCovered);
        if (passed)
            queuePatchRows<C, kColumns>(walk, setup, planes, x, rowY, halfZ, patchHalf(b1, half),
                                        patchHalf(b2, half), passed);
    }
}

// Whether a walk draws triangles of a few pixels as patches: unwatched (an observer is shown the block
// walk's coverage decisions) and single-sample.
template <class C>
inline constexpr bool kWalksPatches = !C::kMultisample && !C::kObserving;

// The most rows a triangle walked as patches may span, in a stack of patches one above the other: a
// triangle a few pixels wide and up to eight tall (a sliver of a dense mesh or of a wall seen edge-on)
// then takes two narrow patches of sixteen lanes where the block walk would take a pass per row.
inline constexpr int kPatchStackRows = 8;

// A triangle whose box is at most kColumns by kPatchStackRows pixels: its pixels in `area` (a tile or
// part of one) walked as a stack of patches placed over them inside the area (as firstBlockAt places a
// block), if the area can hold the stack (at least a patch wide and the stack high, as all but tiny
// framebuffers' tiles are). Returns false, having drawn nothing, if it cannot.
template <class C, int kColumns>
[[gnu::always_inline]] inline bool drawPatchStack(TileWalk<C>& walk, const TriangleSetup& setup,
                                                  const float* planes, const PixelRect& area) {
    constexpr int kRows = kPatchRows<PatchLanes, kColumns>;
    const PixelRect pixels = rasterRect(setup, area);
    if (pixels.empty()) return true;  // binned to the tile, but beside this part of it
    const int patches = (pixels.maxY - pixels.minY) / kRows + 1;
    if (area.maxX - area.minX + 1 < kColumns || area.maxY - area.minY + 1 < patches * kRows) return false;
    ++walk.stats.patchWalks;
    const int x = std::min(pixels.minX, area.maxX - (kColumns - 1));
    int y = std::min(pixels.minY, area.maxY - (patches * kRows - 1));
    for (int patch = 0; patch < patches; ++patch, y += kRows)
        drawPatch<C, kColumns>(walk, setup, planes, pixels, x, y);
    return true;
}

// The most rows a triangle walked as wide patches may span: two, a flat strip (the edge-on walls and
// sliver rows of a block world, a few pixels tall and five to eight wide), which the block walk sets a
// block up for and then walks row by row. Taller ones keep the block walk, whose set-up is shared by
// more rows: for them it measured no slower than a stack of wide patches (docs/performance.md).
inline constexpr int kWideStackRows = 2;

// A triangle that fitsPatch kWidePatch columns and kWideStackRows rows, walked as wide patches.
// Out of line: inlined into the tile walk beside the narrow stack, it slowed the narrow triangles'
// walk, which most triangles of a dense mesh take.
template <class C>
[[gnu::noinline]] bool drawWidePatches(TileWalk<C>& walk, const TriangleSetup& setup, const float* planes,
                                       const PixelRect& area) {
    return drawPatchStack<C, kWidePatch>(walk, setup, planes, area);
}

// A triangle of a few pixels in a tile (or part) `area`: its pixels in the area walked as a stack of
// narrow patches if its box is at most four columns by kPatchStackRows rows, or of wide ones if at most
// eight by kWideStackRows (and its edges are short: fitsPatch). Returns false, having drawn nothing, for
// any other triangle (the block walk draws it).
template <class C>
[[gnu::always_inline]] inline bool drawAsPatches(TileWalk<C>& walk, const TriangleSetup& setup,
                                                 const float* planes, const PixelRect& area) {
    if (fitsPatch(setup, kNarrowPatch, kPatchStackRows))
        return drawPatchStack<C, kNarrowPatch>(walk, setup, planes, area);
    return fitsPatch(setup, kWidePatch, kWideStackRows) && drawWidePatches(walk, setup, planes, area);
}

// Calls visit(block) for every block of the triangle in `area` with a covered sample: a CoverageBlock
// (rasterizeBlocks), or, multisampled, an aligned block with its coverage at each of the draw's samples
// (blockCoverage at the sample's offset).
template <class C, class Visit>
[[gnu::always_inline]] inline void forEachBlock(const TileWalk<C>& walk, const TriangleSetup& setup,
                                                const PixelRect& area, Visit&& visit) {
    if constexpr (!C::kMultisample) {
        rasterizeBlocks(setup, area, visit);
    } else {
        const PixelRect rect = rasterRect(setup, area);
        if (rect.empty()) return;
        const BlockEdgeSteps steps(setup);
        const SampleOffsetsFixed& offsets = walk.offsets;
        SampleCoverageBlock block;
        for (block.y = rect.minY & ~(kBlockSize - 1); block.y <= rect.maxY; block.y += kBlockSize) {
            for (block.x = rect.minX & ~(kBlockSize - 1); block.x <= rect.maxX; block.x += kBlockSize) {
                block.mask = 0;
                for (int s = 0; s < offsets.count; ++s) {
                    bool inside = false;
                    block.coverage[s] = blockCoverage(setup, steps, block.x, block.y, rect, offsets.x[s],
                                                      offsets.y[s], inside);
                    block.mask |= block.coverage[s];
                }
                if (block.mask) visit(static_cast<const SampleCoverageBlock&>(block));
            }
        }
    }
}

// Asks for the stored depths the triangle's first rows in `rect` will test, a triangle ahead: the
// depth test's loads would otherwise wait on memory each time a tile's rows are first read in a frame.
// Small triangles (most of a dense mesh's) fit in the rows asked for.
inline void prefetchDepthRows(const TriangleSetup& setup, const PixelRect& rect,
                              const FramebufferPlanes& target) {
    constexpr int kRows = 8;
    const PixelRect box = rasterRect(setup, rect);
    if (box.empty()) return;
    const int lastRow = std::min(box.maxY, box.minY + kRows - 1);
    for (int y = box.minY; y <= lastRow; ++y) {
        __builtin_prefetch(&target.depth(box.minX, y));
        __builtin_prefetch(&target.depth(box.maxX, y));
    }
}

// Setups were written by the front end a while ago: asks early for the one after next, and for the next
// one's planes (its setup, asked for one triangle ago, says where they are; reading the offset of a
// setup not yet in cache would stall on it here) and the depths it will test (single-sample).
template <class C>
[[gnu::always_inline]] inline void prefetchAhead(const TileWalk<C>& walk, const SetupChunk& chunk,
                                                 const std::vector<std::uint32_t>& bin, std::size_t k,
                                                 const PixelRect& rect) {
    if (k + 2 < bin.size()) {
        const char* afterNext = reinterpret_cast<const char*>(&chunk.setups[bin[k + 2]]);
        __builtin_prefetch(afterNext);  // its two cache lines
        __builtin_prefetch(afterNext + 64);
    }
    if (k + 1 < bin.size()) {
        const TriangleSetup& next = chunk.setups[bin[k + 1]];
        __builtin_prefetch(chunk.planesOf(next));
        if constexpr (!C::kMultisample) prefetchDepthRows(next, rect, walk.target);
    }
}

// One tile, or the part `rect` of it (`inPart`: drawBatchTiles and drawRun cut a tile in parts): its
// triangles from every chunk, in submission order, each block by block. An observer also
// sees the coverage decision at every sample of a triangle's bounding box inside the tile, before its
// fragments.
template <class C>
void drawTile(TileWalk<C>& walk, const PixelRect& rect, bool inPart, std::size_t tile,
              std::span<const SetupChunk> chunks) {
    if constexpr (C::kOutput == FragmentOutput::AppendToLists)
        walk.queue.lists = walk.rowQueue.lists = walk.target.fragmentLists().writer(rect.minX, rect.minY);
    for (const SetupChunk& chunk : chunks) {
        const std::vector<std::uint32_t>& bin = chunk.bins[tile];
        for (std::size_t k = 0; k < bin.size(); ++k) {
            const TriangleSetup& setup = chunk.setups[bin[k]];
            // Binned to the tile, but beside this part of it: passed over before its prefetches.
            if (inPart && rasterRect(setup, rect).empty()) continue;
            prefetchAhead(walk, chunk, bin, k, rect);
            const float* planes = chunk.planesOf(setup);
            if constexpr (C::kObserving) {
                for (int y = std::max(rect.minY, setup.minY); y <= std::min(rect.maxY, setup.maxY); ++y)
                    for (int x = std::max(rect.minX, setup.minX); x <= std::min(rect.maxX, setup.maxX); ++x)
                        walk.observer.onCoverage(coverageAt(setup, x, y));
            }
            if constexpr (kWalksPatches<C>)
                if (drawAsPatches(walk, setup, planes, rect)) continue;
            forEachBlock(walk, setup, rect,
                         [&](const auto& block) { drawBlock(walk, setup, planes, block); });
        }
    }
    shadeQueue(walk, walk.queue);
    if constexpr (C::kShadesPairs) shadeParked(walk);
}

// ---- Choosing the walk, once per draw ---------------------------------------------------------------

// One tile drawn with the walk compiled for C.
template <class C>
void drawTileAs(const PixelRect& rect, bool inPart, std::size_t tile, std::span<const SetupChunk> chunks,
                const DrawPlan& plan, const typename C::Depth& depth, const typename C::Uniforms& uniforms,
                Framebuffer& framebuffer, DrawStats& stats, typename C::Observer& observer) {
    TileWalk<C> walk(plan, depth, uniforms, framebuffer.planesToDraw(rect), stats, observer);
    drawTile(walk, rect, inPart, tile, chunks);
}

// The pixels `rect` of one tile (the whole tile, or a part of it: `inPart`) of a draw's set-up chunks,
// with the walk chosen for the draw: the depth coding, single or
// multisampled, the output, and whether fragments get their texture coordinates' derivatives (the
// draw's shader reads them: drawUsesDerivatives). Watched draws (the step mode) are for reading, not
// speed: one walk per shader, observer and output, with the depth coding chosen per fragment and the
// derivatives computed whenever the shader has them. Same bytes as the unwatched walks.
template <Shader S, class Observer>
void drawTileOfChunks(const PixelRect& rect, bool inPart, std::size_t tile,
                      std::span<const SetupChunk> chunks, const DrawPlan& plan,
                      const typename S::Uniforms& uniforms, Framebuffer& target, DrawStats& stats,
                      Observer& observer) {
    // Only the walks S's code holds are compiled (compiledWalks); draw() has refused any other.
    const auto drawAs =
        [&]<class Depth, bool kMultisample, FragmentOutput kOutput, bool kDerivatives>(const Depth& depth) {
            using C = BackEndConfig<S, Observer, Depth, kMultisample, kOutput, kDerivatives>;
            if constexpr ((compiledWalks<S>() &
                           backEndWalk(Depth::kKind, kMultisample, kOutput, Observer::enabled)) != 0)
                drawTileAs<C>(rect, inPart, tile, chunks, plan, depth, uniforms, target, stats, observer);
        };
    const auto drawWith = [&]<bool kDerivatives>(const auto& depth) {
        using Depth = std::decay_t<decltype(depth)>;
        constexpr auto kLists = FragmentOutput::AppendToLists, kBlend = FragmentOutput::Blend;
        if (!Observer::enabled && plan.samples > 1)  // never watched (draw() refuses it), never lists
            drawAs.template operator()<Depth, true, kBlend, kDerivatives>(depth);
        else if (plan.output == kLists)
            drawAs.template operator()<Depth, false, kLists, kDerivatives>(depth);
        else
            drawAs.template operator()<Depth, false, kBlend, kDerivatives>(depth);
    };
    if constexpr (Observer::enabled) {
        drawWith.template operator()<(derivativeVarying<S>() >= 0)>(
            DepthCoding<DepthCodingKind::PerFragment>(plan.depthFormat));
    } else {
        withDepthCoding(plan.depthFormat, [&](const auto& depth) {
            if constexpr (derivativeVarying<S>() >= 0)
                if (drawUsesDerivatives<S>(uniforms)) return drawWith.template operator()<true>(depth);
            drawWith.template operator()<false>(depth);
        });
    }
}

// Appends the tiles the chunks binned a triangle to (each chunk's list) to `tiles`.
inline void appendTouchedTiles(std::span<const SetupChunk> chunks, std::vector<std::uint32_t>& tiles) {
    for (const SetupChunk& chunk : chunks)
        tiles.insert(tiles.end(), chunk.touchedTiles.begin(), chunk.touchedTiles.end());
}

// Sorts the tiles and drops repeats.
inline void sortUniqueTiles(std::vector<std::uint32_t>& tiles) {
    std::sort(tiles.begin(), tiles.end());
    tiles.erase(std::unique(tiles.begin(), tiles.end()), tiles.end());
}

}  // namespace detail

// The back end for one batch of set-up chunks: only the tiles some triangle touches (a draw of a few
// triangles then costs little more than its triangles, and a single tile is drawn on the calling
// thread without waking the pool), in tile order, in parallel unless `inOrder`; each tile with the
// draw's walk (drawTileOfChunks), cut in parts (tilePartsPerSide: the triangles binned to it against
// the batch's) when the batch is cut for `threads` threads. A tile's fragment list has one writer
// (FragmentLists::writer): a draw that appends to lists draws its tiles whole. Returns the number of
// tiles drawn.
template <Shader S, class Observer>
std::size_t drawBatchTiles(const TileGrid& grid, std::span<const SetupChunk> chunks, const DrawPlan& plan,
                           const typename S::Uniforms& uniforms, Framebuffer& target, ThreadPool& pool,
                           bool inOrder, int threads, std::vector<std::uint32_t>& activeTiles,
                           std::vector<TilePart>& parts, std::vector<std::uint32_t>& tileWeights,
                           std::span<DrawStats> threadStats, Observer& observer) {
    activeTiles.clear();
    detail::appendTouchedTiles(chunks, activeTiles);
    detail::sortUniqueTiles(activeTiles);
    const int maxSide = inOrder || plan.output == FragmentOutput::AppendToLists ? 1 : grid.maxPartsPerSide();
    parts.clear();
    if (maxSide == 1 || threads < 2 || activeTiles.size() == 1) {
        for (std::size_t active = 0; active < activeTiles.size(); ++active)
            parts.push_back({static_cast<std::uint32_t>(active)});
    } else {
        // The triangles binned to each tile, from the tiles each chunk touched (on the calling thread,
        // between two jobs: not every chunk's bin of every active tile).
        tileWeights.resize(static_cast<std::size_t>(grid.count()));  // all 0 (reset below)
        std::size_t binned = 0;
        for (const SetupChunk& chunk : chunks)
            for (const std::uint32_t tile : chunk.touchedTiles) {
                tileWeights[tile] += static_cast<std::uint32_t>(chunk.bins[tile].size());
                binned += chunk.bins[tile].size();
            }
        for (std::size_t active = 0; active < activeTiles.size(); ++active) {
            const std::uint32_t tile = activeTiles[active];
            appendTileParts(grid, static_cast<std::uint32_t>(active), static_cast<int>(tile),
                            tilePartsPerSide(tileWeights[tile], binned, threads, maxSide), parts);
            tileWeights[tile] = 0;
        }
    }
    forEachItem(pool, inOrder, parts.size(), [&](std::size_t item, int thread) {
        const TilePart& part = parts[item];
        const std::uint32_t tile = activeTiles[part.tile];
        detail::drawTileOfChunks<S>(grid.tilePartRect(static_cast<int>(tile), part.side, part.part),
                                    part.side > 1, tile, chunks, plan, uniforms, target,
                                    threadStats[static_cast<std::size_t>(thread)], observer);
    });
    return activeTiles.size();
}

}  // namespace facet
