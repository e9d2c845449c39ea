// The back end of a draw, tile by tile: rasterization (8×8 blocks) → early depth test → interpolation
// → fragment shader → blending, or appending to the per-pixel fragment lists that
// resolveFragmentLists() composites. Tiles run in parallel; inside a tile the triangles run in
// submission order, chunk after chunk, so the image is the same bytes for any thread count or tile size.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <type_traits>
#include <vector>

#include "bin.h"
#include "blend.h"
#include "depth_format.h"
#include "draw_plan.h"
#include "fragment_lists.h"
#include "fragment_stage.h"
#include "framebuffer.h"
#include "interpolate.h"
#include "observer.h"
#include "rasterize.h"
#include "shader.h"
#include "thread_pool.h"

namespace facet {

namespace detail {

// Fragments that passed the depth test, waiting to be shaded eight at a time: the fragments of tiny
// triangles share a batch. Each slot keeps its fragment's λ1, λ2 and triangle (setup and planes); the
// varyings are interpolated when the queue is shaded (interpolateQueue), each slot with its own
// triangle's planes, so a batch may mix triangles of one draw. No two queued fragments share a pixel: before
// a fragment is depth-tested at a pixel that holds a queued one, the queue is shaded, so every pixel still
// sees its fragments in submission order, and the image does not depend on how fragments were grouped. The
// slots in use are those of batch.mask: the first `count` for fragments queued one by one, or the passing
// lanes of a block row shaded whole (kRowShadedWhole), where slot = column.
struct FragmentQueue {
    int count = 0;
    int x[kBlockSize] = {}, y[kBlockSize] = {};
    float z[kBlockSize] = {};
    std::uint32_t triangle[kBlockSize] = {};
    FragmentBatch batch{};            // interpolated varyings, lane = queue slot (zeroed once per tile)
    FragmentLists::TileWriter lists;  // the tile's fragment lists, for AppendToLists draws
    // Each slot's barycentrics λ1, λ2 and its triangle's setup and varying planes (zeroed once per tile,
    // so that the lanes of empty slots compute with finite values).
    float b1[kBlockSize] = {}, b2[kBlockSize] = {};
    const TriangleSetup* setups[kBlockSize] = {};
    const float* planes[kBlockSize] = {};
    // For an observer only (written under Observer::enabled): each slot's 1/w.
    float invW[kBlockSize];

    // Bit (y mod 8)·8 + (x mod 8) set for each queued fragment's pixel (x, y): a filter that rules out
    // most rows without reading the slots, whose positions were just stored one by one (a wide load of
    // them would wait for those stores).
    std::uint64_t pixelsMod8 = 0;

    void remember(int pixelX, int pixelY) {
        pixelsMod8 |= std::uint64_t{1} << ((pixelY & 7) * 8 + (pixelX & 7));
    }

    // Does a queued fragment sit in row y, at a column of [x, x + 8) whose bit is set in `columns`?
    bool holdsAny(int rowY, int firstX, unsigned columns) const {
        // Column c is pixel firstX + c, whose filter bit is (firstX + c) mod 8: the columns rotated.
        const unsigned shift = static_cast<unsigned>(firstX) & 7u;
        const unsigned rotated = ((columns << shift) | (columns >> ((8u - shift) & 7u))) & 0xffu;
        const unsigned rowBits = static_cast<unsigned>(pixelsMod8 >> ((rowY & 7) * 8)) & 0xffu;
        if (!(rowBits & rotated)) return false;
        bool found = false;
        for (int i = 0; i < count; ++i) {
            const unsigned column = static_cast<unsigned>(x[i] - firstX);
            found |= y[i] == rowY && column < kBlockSize && ((columns >> column) & 1u);
        }
        return found;
    }
};

// A block row whose depth test passed at least this many of its eight pixels is shaded as one batch of
// its own, its varyings interpolated straight into the batch (lane = column), rather than queued. The
// trade: shading a batch costs about as much whether 6 or 8 lanes are live, while a queued fragment
// costs its slot's bookkeeping and, when the batch mixes triangles, a share of one more interpolation
// and blend per triangle (interpolateQueue); near 5 live lanes the two are about even. A row of a big
// triangle is shaded at once; the slivers of small ones share batches through the queue.
inline constexpr int kRowShadedWhole = 6;

// Whether the depth test itself writes the depths of the fragments that pass, a block row at a time,
// rather than the queue once they are shaded: when the shader cannot discard, a fragment that passes
// is certain to be written, so its depth may be stored early. A row's eight depths are then read and
// written whole; written one fragment at a time from the queue, they would have the next row test of
// the same pixels wait for the store buffer (a load that spans several pending smaller stores cannot
// take its value from them). Watched draws keep the late write, so that an observer's "depth before"
// is the depth the fragment was tested against. The same bytes either way.
template <Shader S, class Observer>
inline constexpr bool kDepthWrittenAtTest = !kMayDiscard<S> && !Observer::enabled;

// The interpolation stage's view of one fragment, for an observer's FragmentEvent.
inline void describeInterpolation(FragmentEvent& event, float b1, float b2, float invW, int varyingCount) {
    event.barycentrics = vec3(1.0f - b1 - b2, b1, b2);
    event.invW = invW;
    event.varyingCount = varyingCount;
}

// Shader S's varying floats and how many of them are flat: every setup of S's draws has these counts,
// known here when compiling, so that interpolation's and the queue's loops over varyings unroll.
template <Shader S>
inline constexpr int kVaryingsOf = kVaryingFloatCount<typename S::Varyings>;
template <Shader S>
inline constexpr int kFlatVaryingsOf = flatVaryingFloats<S>();

// Puts a fragment that passed the depth test at pixel (x, y), with barycentrics (b1, b2) of `setup`,
// into the next queue slot; its varyings are interpolated when the queue is shaded. Returns the slot.
inline int queueFragment(FragmentQueue& queue, const TriangleSetup& setup, const float* planes, int x, int y,
                         float z, float b1, float b2) {
    const int slot = queue.count++;
    queue.batch.mask |= 1u << slot;
    queue.remember(x, y);
    queue.x[slot] = x;
    queue.y[slot] = y;
    queue.z[slot] = z;
    queue.triangle[slot] = setup.triangle;
    queue.b1[slot] = b1;
    queue.b2[slot] = b2;
    queue.setups[slot] = &setup;
    queue.planes[slot] = planes;
    return slot;
}

// The varyings (and texture coordinate derivatives) of a block row's eight lanes at once, into `out`.
template <Shader S, bool kDerivatives>
void interpolateRowWide(const TriangleSetup& setup, const float* planes, const VaryingPairSlopes& uvSlopes,
                        Float8 b1, Float8 b2, FragmentBatch& out) {
    constexpr int kUv = derivativeVarying<S>();
    interpolateVaryings<Float8, kVaryingsOf<S>, kFlatVaryingsOf<S>>(setup, planes, b1, b2, out.varyings);
    if constexpr (kDerivatives)
        interpolateDerivatives<Float8>(setup, uvSlopes, b1, b2, &out.varyings[kUv], out.uvDerivatives);
}

// The varyings (and texture coordinate derivatives) of the queued fragments, into queue.batch, when the
// queue is shaded: the slots of each triangle eight lanes at once, from each slot's own λ1, λ2 (a lane
// gets the bits interpolating it alone gives: interpolate.h). A batch of the fragments of a few small
// triangles then costs a wide interpolation per triangle, where interpolating each fragment as it was
// queued cost one per fragment (or per block row, plus a copy of every varying per fragment).
template <Shader S, bool kDerivatives>
void interpolateQueue(FragmentQueue& queue) {
    Float8 b1, b2;
    std::memcpy(&b1, queue.b1, sizeof b1);
    std::memcpy(&b2, queue.b2, sizeof b2);
    unsigned remaining = queue.batch.mask;
    while (remaining) {
        const int lead = std::countr_zero(remaining);
        const TriangleSetup& setup = *queue.setups[lead];
        const float* planes = queue.planes[lead];
        unsigned group = 0;  // the live slots of lead's triangle
        for (unsigned lanes = remaining; lanes; lanes &= lanes - 1) {
            const int lane = std::countr_zero(lanes);
            if (queue.setups[lane] == &setup) group |= 1u << lane;
        }
        remaining &= ~group;
        VaryingPairSlopes uvSlopes;
        if constexpr (kDerivatives) uvSlopes = VaryingPairSlopes(setup, planes, derivativeVarying<S>());
        if (group == queue.batch.mask) {  // one triangle (the common case): straight into the batch
            interpolateRowWide<S, kDerivatives>(setup, planes, uvSlopes, b1, b2, queue.batch);
            return;
        }
        FragmentBatch groupVaryings;
        interpolateRowWide<S, kDerivatives>(setup, planes, uvSlopes, b1, b2, groupVaryings);
        const Int8 take = laneMaskOf(group);
        for (int k = 0; k < kVaryingsOf<S>; ++k)
            queue.batch.varyings[k] = select(take, groupVaryings.varyings[k], queue.batch.varyings[k]);
        if constexpr (kDerivatives)
            for (int k = 0; k < 4; ++k)
                queue.batch.uvDerivatives[k] =
                    select(take, groupVaryings.uvDerivatives[k], queue.batch.uvDerivatives[k]);
    }
}

// The fragment shader for the n queued fragments, into shaded[0..n): eight lanes at once when the
// shader can. Returns the mask of the lanes kept (not discarded). Shared by the single-sample and the
// multisample back ends, so a fragment is shaded by the same code in both.
template <Shader S>
unsigned runFragmentShader(FragmentQueue& queue, int n, const typename S::Uniforms& uniforms,
                           vec4 (&shaded)[kBlockSize], DrawStats& stats) {
    unsigned kept = queue.batch.mask;
    stats.fragmentsShaded += static_cast<unsigned>(std::popcount(kept));
    if constexpr (BatchShader<S>) {
        storeTransposed(S::fragmentBatch(queue.batch, uniforms), shaded);
    } else {
        float varyings[kMaxVaryingFloats];
        for (int lane = 0; lane < n; ++lane) {
            if (!(kept & (1u << lane))) continue;
            for (int k = 0; k < kVaryingFloatCount<typename S::Varyings>; ++k)
                varyings[k] = queue.batch.varyings[k][lane];
            shaded[lane] = vec4(0.0f);  // what a discarded lane holds (never read)
            if (!shadeFragment<S>(varyings, uniforms, shaded[lane])) kept &= ~(1u << lane);
        }
    }
    return kept;
}

// The fragment shader, then the depth write and blending (or appending to the fragment lists) for the
// queued fragments. Compiled for each FragmentOutput, depth coding (Depth, a DepthCoding: float or
// unorm) and whether the colour buffer rounds what it stores (kRoundColor: the half and 8-bit formats,
// whose rounding is chosen per fragment from the plan, a branch the predictor always gets right),
// chosen per draw (drawBatchTiles), so the default float path is exactly what it would be without
// fragment lists or other formats. (A template per format would multiply the back end's copies, one
// per shader, without making any of them faster.)
//
// An opaque draw (Replace) into the float colour buffer, unwatched, whose depths the test wrote, only
// stores colours. `slotsAreColumns`: the queue is a block row shaded whole (kRowShadedWhole), slot c at
// pixel (x[0] + c, y[0]); when all eight of its lanes are written, such a draw stores the row's colours
// with one copy into the framebuffer's row.
template <Shader S, FragmentOutput kOutput, class Depth, bool kRoundColor, bool kDerivatives, class Observer>
void shadeQueue(FragmentQueue& queue, const DrawPlan& plan, const Depth& depth,
                const typename S::Uniforms& uniforms, const FramebufferPlanes& target, DrawStats& stats,
                Observer& observer, bool slotsAreColumns = false) {
    constexpr bool kObserving = Observer::enabled;
    const int n = queue.count;
    if (n == 0) return;
    queue.count = 0;

    // A row shaded whole was interpolated with its row (depthTestBlock); queued fragments are now.
    if (!slotsAreColumns) interpolateQueue<S, kDerivatives>(queue);
    vec4 shaded[kBlockSize];
    const unsigned kept = runFragmentShader<S>(queue, n, uniforms, shaded, stats);
    const unsigned live = queue.batch.mask;
    queue.batch.mask = 0;
    queue.pixelsMod8 = 0;
    stats.fragmentsDiscarded += static_cast<unsigned>(std::popcount(live & ~kept));
    if constexpr (kOutput == FragmentOutput::Blend)
        stats.fragmentsWritten += static_cast<unsigned>(std::popcount(live & kept));

    if constexpr (!kObserving && kOutput == FragmentOutput::Blend && !kRoundColor &&
                  kDepthWrittenAtTest<S, Observer>) {
        if (plan.blend == BlendMode::Replace) {
            // The depths are written already and Replace needs no destination: only the colours to
            // store, with no per-lane choice of blend mode or rounding.
            const unsigned written = live & kept;
            if (slotsAreColumns && written == 0xffu) {
                std::memcpy(&target.color(queue.x[0], queue.y[0]), shaded, sizeof shaded);
                return;
            }
            for (unsigned lanes = written; lanes; lanes &= lanes - 1) {
                const int lane = std::countr_zero(lanes);
                target.color(queue.x[lane], queue.y[lane]) = shaded[lane];
            }
            return;
        }
    }

    // Depth write, then blending into the colour buffer or appending to the pixel's fragment list.
    for (int lane = 0; lane < n; ++lane) {
        if (!(live & (1u << lane))) continue;
        const int x = queue.x[lane], y = queue.y[lane];
        FragmentEvent event;
        if constexpr (kObserving) {
            event = FragmentEvent{x, y, queue.triangle[lane], queue.z[lane], target.depth(x, y)};
            event.colorBefore = event.colorAfter = target.color(x, y);
            constexpr int kVaryings = kVaryingFloatCount<typename S::Varyings>;
            describeInterpolation(event, queue.b1[lane], queue.b2[lane], queue.invW[lane], kVaryings);
            for (int k = 0; k < kVaryings; ++k)
                event.varyings[static_cast<std::size_t>(k)] = queue.batch.varyings[k][lane];
            if constexpr (derivativeVarying<S>() >= 0)  // watched draws always compute them
                for (int k = 0; k < 4; ++k)
                    event.uvDerivatives[static_cast<std::size_t>(k)] = queue.batch.uvDerivatives[k][lane];
        }
        if (!(kept & (1u << lane))) {
            if constexpr (kObserving) {
                event.fate = FragmentFate::Discarded;
                observer.onFragment(event);
            }
            continue;
        }
        if (!kDepthWrittenAtTest<S, Observer> && plan.depthWrite)
            target.depth(x, y) = depth.store(queue.z[lane]);
        if constexpr (kOutput == FragmentOutput::AppendToLists) {
            const bool stored = queue.lists.append(x, y, shaded[lane], queue.z[lane], plan.blend);
            stats.fragmentsStored += stored;
            if constexpr (kObserving) event.fate = stored ? FragmentFate::Stored : FragmentFate::Dropped;
        } else {
            vec4& destination = target.color(x, y);
            // Replace (every opaque draw) stores the fragment as a whole; the other modes go through
            // the switch of blend(), whose per-component code is slower for it.
            destination = plan.blend == BlendMode::Replace ? shaded[lane]
                                                           : blend(plan.blend, shaded[lane], destination);
            if constexpr (kRoundColor) destination = roundToColorBuffer(plan.colorBuffer, destination);
            if constexpr (kObserving) {
                event.fate = FragmentFate::Written;
                event.colorAfter = destination;
            }
        }
        if constexpr (kObserving) {
            event.shaded = shaded[lane];
            observer.onFragment(event);
        }
    }
}

// The covered pixels of one block: barycentrics, depth, and the depth test (before shading: the shader
// cannot change depth, so testing early gives the same image and skips hidden fragments). Fragments
// that pass go to the queue, which is shaded whenever it holds eight. kDerivatives (a draw whose shader
// reads them: drawUsesDerivatives): each queued fragment also gets its texture coordinates' derivatives,
// from its own triangle's planes.
template <Shader S, FragmentOutput kOutput, class Depth, bool kRoundColor, bool kDerivatives, class Observer>
void depthTestBlock(const TriangleSetup& setup, const float* planes, const CoverageBlock& block,
                    FragmentQueue& queue, FragmentQueue& rowQueue, const DrawPlan& plan, const Depth& depth,
                    const typename S::Uniforms& uniforms, const FramebufferPlanes& target, DrawStats& stats,
                    Observer& observer) {
    constexpr bool kObserving = Observer::enabled;
    const BlockBarycentrics barycentrics(setup, block.x, block.y);
    constexpr int kUv = derivativeVarying<S>();
    VaryingPairSlopes uvSlopes;  // for rows shaded whole, computed at the block's first such row
    [[maybe_unused]] bool haveSlopes = false;

    // Only the rows between the first and the last covered one (the mask is never 0): a small
    // triangle's block has one to three, not eight.
    const int firstRow = std::countr_zero(block.mask) / kBlockSize;
    const int lastRow = (63 - std::countl_zero(block.mask)) / kBlockSize;
    for (int row = firstRow; row <= lastRow; ++row) {
        const unsigned rowMask = static_cast<unsigned>(block.mask >> (row * kBlockSize)) & 0xffu;
        if (!rowMask) continue;
        const int y = block.y + row;

        // Barycentrics and depth for the row's eight lanes.
        Float8 b1{}, b2{};
        barycentrics.row(row, b1, b2);
        const Float8 z = interpolateDepth(setup, b1, b2);

        // A queued fragment at one of these pixels must reach the framebuffer before they are tested.
        if (queue.count && queue.holdsAny(y, block.x, rowMask))
            shadeQueue<S, kOutput, Depth, kRoundColor, kDerivatives>(queue, plan, depth, uniforms, target,
                                                                     stats, observer);

        typename Depth::Stored* depthRow = &target.depth(block.x, y);
        unsigned passed = rowMask;
        const bool wholeRow = block.x + kBlockSize <= target.width();  // inside the framebuffer
        if (plan.depthTest) {
            if (wholeRow) {
                // Eight stored depths at once.
                const Int8 pass = depth.passes(plan.depthCompare, z, Depth::load8(depthRow));
                passed &= signMask(pass);
            } else {
                for (int lane = 0; lane < kBlockSize; ++lane)
                    if ((rowMask >> lane) & 1u)
                        if (!depth.passes(plan.depthCompare, z[lane], depthRow[lane]))
                            passed &= ~(1u << lane);
            }
        }
        if constexpr (kDepthWrittenAtTest<S, Observer>) {
            if (plan.depthWrite && passed) {
                if (wholeRow) {
                    const auto row = select(laneMaskOf(passed), depth.store(z), Depth::load8(depthRow));
                    std::memcpy(depthRow, &row, sizeof row);
                } else {
                    for (unsigned lanes = passed; lanes; lanes &= lanes - 1) {
                        const int lane = std::countr_zero(lanes);
                        depthRow[lane] = depth.store(z[lane]);
                    }
                }
            }
        }
        // A row that mostly passed is shaded whole, straight from its own batch (kRowShadedWhole); the
        // fragments of other rows are queued.
        const bool rowShadedWhole = std::popcount(passed) >= kRowShadedWhole;
        if (rowShadedWhole) {
            if constexpr (kDerivatives) {
                if (!haveSlopes) uvSlopes = VaryingPairSlopes(setup, planes, kUv);
                haveSlopes = true;
            }
            interpolateRowWide<S, kDerivatives>(setup, planes, uvSlopes, b1, b2, rowQueue.batch);
        }
        stats.fragmentsDepthFailed += static_cast<unsigned>(std::popcount(rowMask & ~passed));
        if constexpr (kObserving) {
            for (unsigned lanes = rowMask & ~passed; lanes; lanes &= lanes - 1) {
                const int lane = std::countr_zero(lanes);
                FragmentEvent event{block.x + lane, y, setup.triangle, z[lane], depthRow[lane]};
                event.colorBefore = event.colorAfter = target.color(block.x + lane, y);
                event.fate = FragmentFate::DepthFailed;
                describeInterpolation(event, b1[lane], b2[lane], interpolateInvW(setup, b1[lane], b2[lane]),
                                      setup.varyingCount);
                interpolateVaryings(setup, planes, b1[lane], b2[lane], event.varyings.data());
                observer.onFragment(event);
            }
        }
        if (rowShadedWhole) {
            // Slot = column; the slots of lanes that failed are not live (batch.mask) and not read.
            const Int8 column = {0, 1, 2, 3, 4, 5, 6, 7};
            const Int8 rowX = column + block.x, rowY = Int8{} + y;
            const Int8 triangle = Int8{} + static_cast<std::int32_t>(setup.triangle);
            std::memcpy(rowQueue.x, &rowX, sizeof rowX);
            std::memcpy(rowQueue.y, &rowY, sizeof rowY);
            std::memcpy(rowQueue.z, &z, sizeof z);
            std::memcpy(rowQueue.triangle, &triangle, sizeof triangle);
            std::memcpy(rowQueue.b1, &b1, sizeof b1);
            std::memcpy(rowQueue.b2, &b2, sizeof b2);
        }
        // The passing fragments of a row not shaded whole go to the queue (a row shaded whole has
        // nothing to do here unless watched).
        const unsigned queued = rowShadedWhole && !kObserving ? 0u : passed;
        for (unsigned lanes = queued; lanes; lanes &= lanes - 1) {
            const int lane = std::countr_zero(lanes);
            int slot = lane;  // a row shaded whole: its slots are its columns, filled above
            if (!rowShadedWhole)
                slot = queueFragment(queue, setup, planes, block.x + lane, y, z[lane], b1[lane], b2[lane]);
            if constexpr (kObserving) {  // λ1 and λ2 are in the slot already
                FragmentQueue& into = rowShadedWhole ? rowQueue : queue;
                into.invW[slot] = interpolateInvW(setup, b1[lane], b2[lane]);
            }
            if (queue.count == kBlockSize)
                shadeQueue<S, kOutput, Depth, kRoundColor, kDerivatives>(queue, plan, depth, uniforms, target,
                                                                         stats, observer);
        }
        if (rowShadedWhole) {
            rowQueue.count = kBlockSize;
            rowQueue.batch.mask = passed;
            constexpr bool kSlotsAreColumns = true;
            shadeQueue<S, kOutput, Depth, kRoundColor, kDerivatives>(rowQueue, plan, depth, uniforms, target,
                                                                     stats, observer, kSlotsAreColumns);
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

// One tile: its triangles from every chunk, in submission order. An observer also sees the coverage
// decision at every sample of a triangle's bounding box inside the tile, before its fragments.
template <Shader S, FragmentOutput kOutput, class Depth, bool kRoundColor, bool kDerivatives, class Observer>
void drawTile(const PixelRect& rect, std::size_t tile, std::span<const SetupChunk> chunks,
              const DrawPlan& plan, const Depth& depth, const typename S::Uniforms& uniforms,
              Framebuffer& framebuffer, DrawStats& stats, Observer& observer) {
    const FramebufferPlanes target = framebuffer.planesToDraw(rect);
    FragmentQueue queue, rowQueue;
    if constexpr (kOutput == FragmentOutput::AppendToLists)
        queue.lists = rowQueue.lists = target.fragmentLists().writer(rect.minX, rect.minY);
    for (const SetupChunk& chunk : chunks) {
        const std::vector<std::uint32_t>& bin = chunk.bins[tile];
        for (std::size_t k = 0; k < bin.size(); ++k) {
            // Setups were written by the front end a while ago: ask early for the one after next, and
            // for the next one's planes (its setup, asked for one triangle ago, says where they are;
            // reading the offset of a setup not yet in cache would stall on it here).
            if (k + 2 < bin.size()) {
                const char* afterNext = reinterpret_cast<const char*>(&chunk.setups[bin[k + 2]]);
                __builtin_prefetch(afterNext);
                __builtin_prefetch(afterNext + 64);
                __builtin_prefetch(afterNext + 128);
            }
            if (k + 1 < bin.size()) {
                const TriangleSetup& next = chunk.setups[bin[k + 1]];
                __builtin_prefetch(chunk.planesOf(next));
                prefetchDepthRows(next, rect, target);
            }
            const TriangleSetup& setup = chunk.setups[bin[k]];
            const float* planes = chunk.planesOf(setup);
            if constexpr (Observer::enabled) {
                for (int y = std::max(rect.minY, setup.minY); y <= std::min(rect.maxY, setup.maxY); ++y)
                    for (int x = std::max(rect.minX, setup.minX); x <= std::min(rect.maxX, setup.maxX); ++x)
                        observer.onCoverage(coverageAt(setup, x, y));
            }
            rasterizeBlocks(setup, rect, [&](const CoverageBlock& block) {
                depthTestBlock<S, kOutput, Depth, kRoundColor, kDerivatives>(
                    setup, planes, block, queue, rowQueue, plan, depth, uniforms, target, stats, observer);
            });
        }
    }
    shadeQueue<S, kOutput, Depth, kRoundColor, kDerivatives>(queue, plan, depth, uniforms, target, stats,
                                                             observer);
}

// ---- Multisampling ----------------------------------------------------------------------------------
// Coverage and depth per sample, shading once per pixel and triangle (plan.samples > 1, the standard
// positions of sample_position.h). Unobserved Blend draws only (the step mode refuses anti-aliasing,
// fragment lists are per pixel), so a shader gets two copies more per depth coding and derivatives
// choice, not one per observer, output and rounding; the colour buffer's rounding is chosen at run time.

inline constexpr int kMaxSamples = 16;

// The queue of multisampled fragments: for each slot, which of its pixel's samples passed the depth
// test and their depths, written when the fragment is shaded and kept.
struct MultisampleQueue : FragmentQueue {
    std::uint32_t samplesPassed[kBlockSize];
    float sampleZ[kBlockSize][kMaxSamples];
};

// A draw's sample positions as fixed-point offsets from the pixel centre.
struct SampleOffsetsFixed {
    int count = 0;
    std::int64_t x[kMaxSamples], y[kMaxSamples];

    explicit SampleOffsetsFixed(int samples) {
        for (const SampleOffset& offset : standardSamplePositions(samples)) {
            x[count] = sampleOffsetFixed(offset.x);
            y[count] = sampleOffsetFixed(offset.y);
            ++count;
        }
    }
};

// Shades the queued fragments (runFragmentShader, as the single-sample back end does) and blends each
// kept fragment's colour into every sample of its pixel that it covers and that passed the depth test,
// writing those samples' depths.
template <Shader S, class Depth, bool kDerivatives>
void shadeMultisampleQueue(MultisampleQueue& queue, const DrawPlan& plan, const Depth& depth,
                           const typename S::Uniforms& uniforms, const FramebufferPlanes& target,
                           DrawStats& stats) {
    const int n = queue.count;
    if (n == 0) return;
    queue.count = 0;
    interpolateQueue<S, kDerivatives>(queue);
    vec4 shaded[kBlockSize];
    const unsigned kept = runFragmentShader<S>(queue, n, uniforms, shaded, stats);
    queue.batch.mask = 0;
    queue.pixelsMod8 = 0;
    for (int lane = 0; lane < n; ++lane) {
        if (!(kept & (1u << lane))) {
            ++stats.fragmentsDiscarded;
            continue;
        }
        vec4* colors = target.sampleColors(queue.x[lane], queue.y[lane]);
        typename Depth::Stored* depths = target.sampleDepths(queue.x[lane], queue.y[lane]);
        for (unsigned samples = queue.samplesPassed[lane]; samples; samples &= samples - 1) {
            const int s = std::countr_zero(samples);
            if (plan.depthWrite) depths[s] = depth.store(queue.sampleZ[lane][s]);
            colors[s] = roundToColorBuffer(plan.colorBuffer, blend(plan.blend, shaded[lane], colors[s]));
        }
        ++stats.fragmentsWritten;
    }
}

// The pixels of one block with a covered sample (coverage[s]: the block's mask at sample s): each
// covered sample's depth from the depth plane at the sample, tested against that sample's stored
// depth; a pixel with a sample that passed is queued once, its varyings interpolated at the pixel's
// centroid sample (GLSL's `centroid`, Direct3D's centroid rule): the centre when the triangle covers
// every sample of the pixel, else its first covered sample in the pattern's order. At the centre, a
// pixel the triangle only grazes would take varyings extrapolated beyond the triangle: a position
// behind the neighbouring wall, whose ray to the light is then blocked (dark seams in ray-cast
// shadows), or a texel outside the triangle's part of the texture.
template <Shader S, class Depth, bool kDerivatives>
void depthTestMultisampleBlock(const TriangleSetup& setup, const float* planes, int blockX, int blockY,
                               const std::uint64_t* coverage, std::uint64_t covered,
                               const SampleOffsetsFixed& offsets, MultisampleQueue& queue,
                               const DrawPlan& plan, const Depth& depth, const typename S::Uniforms& uniforms,
                               const FramebufferPlanes& target, DrawStats& stats) {
    const BlockBarycentrics barycentrics(setup, blockX, blockY);
    const double invArea = 1.0 / static_cast<double>(setup.doubleArea);
    const EdgeFunction& e1 = setup.edges[1];
    const EdgeFunction& e2 = setup.edges[2];

    for (int row = 0; row < kBlockSize; ++row) {
        const int shift = row * kBlockSize;
        const unsigned rowMask = static_cast<unsigned>(covered >> shift) & 0xffu;
        if (!rowMask) continue;
        const int y = blockY + row;
        if (queue.count && queue.holdsAny(y, blockX, rowMask))
            shadeMultisampleQueue<S, Depth, kDerivatives>(queue, plan, depth, uniforms, target, stats);

        // The depth test at each covered sample: λᵢ = Eᵢ(sample) / (2·area), Eᵢ(sample) = Eᵢ(centre) +
        // aᵢ·dx + bᵢ·dy exact in integers, then z as interpolateDepth gives it at a pixel centre.
        unsigned passed = 0, partial = 0;
        std::uint32_t samplesPassed[kBlockSize];
        float sampleZ[kBlockSize][kMaxSamples];
        float centroidB1[kBlockSize], centroidB2[kBlockSize];
        for (unsigned lanes = rowMask; lanes; lanes &= lanes - 1) {
            const int lane = std::countr_zero(lanes);
            const int x = blockX + lane;
            const SamplePoint centre = samplePosition(x, y);
            const std::int64_t e1Centre = e1.at(centre.x, centre.y), e2Centre = e2.at(centre.x, centre.y);
            const typename Depth::Stored* stored = target.sampleDepths(x, y);
            std::uint32_t pass = 0;
            bool first = true;
            for (int s = 0; s < offsets.count; ++s) {
                if (!((coverage[s] >> (shift + lane)) & 1u)) {
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
                if (plan.depthTest && !depth.passes(plan.depthCompare, z, stored[s])) continue;
                pass |= 1u << s;
                sampleZ[lane][s] = z;
            }
            samplesPassed[lane] = pass;
            if (pass) passed |= 1u << lane;
        }
        stats.fragmentsDepthFailed += static_cast<unsigned>(std::popcount(rowMask & ~passed));
        if (!passed) continue;

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
            const int slot =
                queueFragment(queue, setup, planes, blockX + lane, y, z[lane], b1[lane], b2[lane]);
            queue.samplesPassed[slot] = samplesPassed[lane];
            for (unsigned samples = samplesPassed[lane]; samples; samples &= samples - 1) {
                const int s = std::countr_zero(samples);
                queue.sampleZ[slot][s] = sampleZ[lane][s];
            }
            if (queue.count == kBlockSize)
                shadeMultisampleQueue<S, Depth, kDerivatives>(queue, plan, depth, uniforms, target, stats);
        }
    }
}

// One tile of a multisampled draw: its triangles from every chunk, in submission order, block by block
// with each block's coverage at every sample (blockCoverage at the sample's offset).
template <Shader S, class Depth, bool kDerivatives>
void drawMultisampleTile(const PixelRect& tileRect, std::size_t tile, std::span<const SetupChunk> chunks,
                         const DrawPlan& plan, const Depth& depth, const typename S::Uniforms& uniforms,
                         Framebuffer& framebuffer, DrawStats& stats) {
    const FramebufferPlanes target = framebuffer.planesToDraw(tileRect);
    const SampleOffsetsFixed offsets(plan.samples);
    MultisampleQueue queue;
    for (const SetupChunk& chunk : chunks) {
        for (const std::uint32_t index : chunk.bins[tile]) {
            const TriangleSetup& setup = chunk.setups[index];
            const PixelRect rect = rasterRect(setup, tileRect);
            if (rect.empty()) continue;
            const BlockEdgeSteps steps(setup);
            for (int by = rect.minY & ~(kBlockSize - 1); by <= rect.maxY; by += kBlockSize) {
                for (int bx = rect.minX & ~(kBlockSize - 1); bx <= rect.maxX; bx += kBlockSize) {
                    std::uint64_t coverage[kMaxSamples], covered = 0;
                    for (int s = 0; s < offsets.count; ++s) {
                        bool inside = false;
                        coverage[s] =
                            blockCoverage(setup, steps, bx, by, rect, offsets.x[s], offsets.y[s], inside);
                        covered |= coverage[s];
                    }
                    if (covered == 0) continue;
                    depthTestMultisampleBlock<S, Depth, kDerivatives>(setup, chunk.planesOf(setup), bx, by,
                                                                      coverage, covered, offsets, queue, plan,
                                                                      depth, uniforms, target, stats);
                }
            }
        }
    }
    shadeMultisampleQueue<S, Depth, kDerivatives>(queue, plan, depth, uniforms, target, stats);
}

// One tile of a draw's set-up chunks, with the draw's choices resolved here: the FragmentOutput, the
// depth coding, whether colours are rounded to the colour buffer's format, whether fragments get their
// texture coordinates' derivatives, and multisampling (a few branches per tile, beside its pixels).
template <Shader S, class Observer>
void drawTileOfChunks(const TileGrid& grid, std::size_t tile, std::span<const SetupChunk> chunks,
                      const DrawPlan& plan, const typename S::Uniforms& uniforms, Framebuffer& target,
                      DrawStats& stats, Observer& observer) {
    const PixelRect rect = grid.tileRect(static_cast<int>(tile));
    if constexpr (Observer::enabled) {
        // Watched draws (the step mode) are for reading, not speed: one copy of the tile loop per shader
        // and observer, with the depth coding and the colour buffer's rounding chosen per fragment
        // (rounding to the float format is the identity), and texture-coordinate derivatives computed
        // whenever the shader has them (a shader reads them only when the draw wants them). Same bytes
        // as the unwatched copies.
        constexpr bool kDerivatives = derivativeVarying<S>() >= 0;
        using Depth = DepthCoding<DepthCodingKind::PerFragment>;
        const Depth depth(plan.depthFormat);
        if (plan.output == FragmentOutput::AppendToLists)
            drawTile<S, FragmentOutput::AppendToLists, Depth, false, kDerivatives>(
                rect, tile, chunks, plan, depth, uniforms, target, stats, observer);
        else
            drawTile<S, FragmentOutput::Blend, Depth, true, kDerivatives>(rect, tile, chunks, plan, depth,
                                                                          uniforms, target, stats, observer);
        return;
    } else {
        const auto drawWith = [&]<bool kDerivatives>() {
            withDepthCoding(plan.depthFormat, [&](const auto& depth) {
                using Depth = std::decay_t<decltype(depth)>;
                // Multisampling; never observed (draw() refuses it).
                if (plan.samples > 1) {
                    drawMultisampleTile<S, Depth, kDerivatives>(rect, tile, chunks, plan, depth, uniforms,
                                                                target, stats);
                    return;
                }
                const auto drawOutput = [&]<FragmentOutput kOutput, bool kRoundColor>() {
                    drawTile<S, kOutput, Depth, kRoundColor, kDerivatives>(rect, tile, chunks, plan, depth,
                                                                           uniforms, target, stats, observer);
                };
                // Appended fragments reach the colour buffer in the resolve, which rounds them.
                if (plan.output == FragmentOutput::AppendToLists)
                    drawOutput.template operator()<FragmentOutput::AppendToLists, false>();
                else if (plan.colorBuffer != ColorBufferFormat::Float)
                    drawOutput.template operator()<FragmentOutput::Blend, true>();
                else
                    drawOutput.template operator()<FragmentOutput::Blend, false>();
            });
        };
        if constexpr (derivativeVarying<S>() >= 0) {
            if (drawUsesDerivatives<S>(uniforms)) {
                drawWith.template operator()<true>();
                return;
            }
        }
        drawWith.template operator()<false>();
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
// draw's choices resolved (drawTileOfChunks). Returns the number of tiles drawn.
template <Shader S, class Observer>
std::size_t drawBatchTiles(const TileGrid& grid, std::span<const SetupChunk> chunks, const DrawPlan& plan,
                           const typename S::Uniforms& uniforms, Framebuffer& target, ThreadPool& pool,
                           bool inOrder, std::vector<std::uint32_t>& activeTiles,
                           std::span<DrawStats> threadStats, Observer& observer) {
    activeTiles.clear();
    detail::appendTouchedTiles(chunks, activeTiles);
    detail::sortUniqueTiles(activeTiles);
    forEachItem(pool, inOrder, activeTiles.size(), [&](std::size_t active, int thread) {
        detail::drawTileOfChunks<S>(grid, activeTiles[active], chunks, plan, uniforms, target,
                                    threadStats[static_cast<std::size_t>(thread)], observer);
    });
    return activeTiles.size();
}

}  // namespace facet
