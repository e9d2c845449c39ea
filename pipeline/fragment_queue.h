// The back end's fragment queue: fragments that passed the depth test wait here to be interpolated and
// shaded eight at a time (a batch of the fragment shader), in an order that keeps every pixel's
// fragments in submission order. Shared by the single-sample and the multisampled walk (back_end.h).
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>

#include "fragment_lists.h"
#include "fragment_stage.h"
#include "interpolate.h"
#include "rasterize.h"
#include "sample_position.h"
#include "shader.h"
#include "types.h"

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
    // The per-slot arrays hold kBlockSize slots and as many again: a block row's fragments are appended
    // eight lanes wide (queueRow), its dead lanes landing past the last slot in use.
    static constexpr int kSlotRoom = 2 * kBlockSize;
    int count = 0;
    int x[kSlotRoom] = {}, y[kSlotRoom] = {};
    float z[kSlotRoom] = {};
    std::uint32_t triangle[kSlotRoom] = {};
    FragmentBatch batch{};            // interpolated varyings, lane = queue slot (zeroed once per tile)
    FragmentLists::TileWriter lists;  // the tile's fragment lists, for AppendToLists draws
    // Each slot's barycentrics λ1, λ2 and its triangle's setup and varying planes (zeroed once per tile,
    // so that the lanes of empty slots compute with finite values).
    float b1[kSlotRoom] = {}, b2[kSlotRoom] = {};
    const TriangleSetup* setups[kSlotRoom] = {};
    const float* planes[kSlotRoom] = {};
    // For an observer only (written under Observer::enabled): each slot's 1/w.
    float invW[kBlockSize];

    // Bit (y mod 8)·8 + (x mod 8) set for each queued fragment's pixel (x, y): a filter that rules out
    // most rows without reading the slots, whose positions were just stored one by one (a wide load of
    // them would wait for those stores).
    std::uint64_t pixelsMod8 = 0;

    void remember(int pixelX, int pixelY) {
        pixelsMod8 |= std::uint64_t{1} << ((pixelY & 7) * 8 + (pixelX & 7));
    }

    // Column c of a row starting at pixel firstX has filter bit (firstX + c) mod 8: `columns` rotated.
    static unsigned filterBitsOf(int firstX, unsigned columns) {
        const unsigned shift = static_cast<unsigned>(firstX) & 7u;
        return ((columns << shift) | (columns >> ((8u - shift) & 7u))) & 0xffu;
    }

    // Does a queued fragment sit in row y, at a column of [x, x + 8) whose bit is set in `columns`?
    bool holdsAny(int rowY, int firstX, unsigned columns) const {
        const unsigned rotated = filterBitsOf(firstX, columns);
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

// Puts the fragments of `lanes` (at most kBlockSize − queue.count of them), lane i at pixel (x[i], y[i])
// with depth z[i] and barycentrics (b1[i], b2[i]) of `setup`, into the next queue slots in lane order:
// the slots queueFragment would give them one by one, filled eight lanes at a time (the lanes packed to
// the front by one permutation), with no branch on which lanes they are. `filterBits`: the lanes'
// pixels' bits of FragmentQueue::pixelsMod8.
inline void queueLanes(FragmentQueue& queue, const TriangleSetup& setup, const float* planes, Int8 x, Int8 y,
                       Float8 z, Float8 b1, Float8 b2, unsigned lanes, std::uint64_t filterBits) {
    const int first = queue.count, n = std::popcount(lanes);
    const Int8 packed = packedLaneIndices(lanes);
    const auto pack = [&](auto v) {
        return std::bit_cast<decltype(v)>(permuteLanes(std::bit_cast<Float8>(v), packed));
    };
    const Int8 triangle = Int8{} + static_cast<std::int32_t>(setup.triangle);
    const Int8 packedX = pack(x), packedY = pack(y);
    const Float8 packedZ = pack(z), packedB1 = pack(b1), packedB2 = pack(b2);
    std::memcpy(&queue.x[first], &packedX, sizeof packedX);
    std::memcpy(&queue.y[first], &packedY, sizeof packedY);
    std::memcpy(&queue.z[first], &packedZ, sizeof packedZ);
    std::memcpy(&queue.triangle[first], &triangle, sizeof triangle);
    std::memcpy(&queue.b1[first], &packedB1, sizeof packedB1);
    std::memcpy(&queue.b2[first], &packedB2, sizeof packedB2);
    for (int slot = first; slot < first + kBlockSize; ++slot) {
        queue.setups[slot] = &setup;
        queue.planes[slot] = planes;
    }
    queue.count = first + n;
    queue.batch.mask |= ((1u << n) - 1u) << first;
    queue.pixelsMod8 |= filterBits;
}

// The fragments of block row (rowX, rowY) in `columns` (lane = column), queued as queueLanes does.
inline void queueRow(FragmentQueue& queue, const TriangleSetup& setup, const float* planes, int rowX,
                     int rowY, Float8 z, Float8 b1, Float8 b2, unsigned columns) {
    const Int8 column = {0, 1, 2, 3, 4, 5, 6, 7};
    queueLanes(queue, setup, planes, column + rowX, Int8{} + rowY, z, b1, b2, columns,
               std::uint64_t{FragmentQueue::filterBitsOf(rowX, columns)} << ((rowY & 7) * 8));
}

// The varyings (and texture coordinate derivatives) of a block row's eight lanes at once, into `out`.
template <Shader S, bool kDerivatives>
void interpolateRowWide(const TriangleSetup& setup, const float* planes, const VaryingPairSlopes& uvSlopes,
                        Float8 b1, Float8 b2, FragmentBatch& out) {
    constexpr int kUv = derivativeVarying<S>();
    interpolateVaryings<Float8, kVaryingsOf<S>, kFlatVaryingsOf<S>>(setup, planes, b1, b2, out.varyings);
    if constexpr (kDerivatives)
        interpolateDerivatives<Float8>(setup, uvSlopes, b1, b2, &out.varyings[kUv], out.uvDerivatives);
    if constexpr (wantsBarycentrics<S>()) {
        out.barycentrics[0] = b1;
        out.barycentrics[1] = b2;
    }
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
    if constexpr (wantsBarycentrics<S>()) {  // each slot's own λ1, λ2, whichever its triangle
        queue.batch.barycentrics[0] = b1;
        queue.batch.barycentrics[1] = b2;
    }
    unsigned remaining = queue.batch.mask;
    while (remaining) {
        const int lead = std::countr_zero(remaining);
        const TriangleSetup& setup = *queue.setups[lead];
        const float* planes = queue.planes[lead];
        unsigned group = 0;  // the live slots of lead's triangle (all eight compared: no branch per slot)
        for (int lane = 0; lane < kBlockSize; ++lane)
            group |= static_cast<unsigned>(queue.setups[lane] == &setup) << lane;
        group &= remaining;
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
    } else if constexpr (DiscardingBatchShader<S>) {
        storeTransposed(S::fragmentBatch(queue.batch, uniforms, kept), shaded);
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

// ---- Multisampling ----------------------------------------------------------------------------------

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

    SampleOffsetsFixed() = default;
    explicit SampleOffsetsFixed(int samples) {
        for (const SampleOffset& offset : standardSamplePositions(samples)) {
            x[count] = sampleOffsetFixed(offset.x);
            y[count] = sampleOffsetFixed(offset.y);
            ++count;
        }
    }
};

}  // namespace detail

}  // namespace facet
