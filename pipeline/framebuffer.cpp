#include "framebuffer.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <limits>

#include "blend.h"
#include "thread_pool.h"

namespace facet {

namespace {

// What a cell of the framebuffer holds (Framebuffer::cellState_).
enum CellState : std::uint8_t {
    kCellDrawn = 0,        // pixels written since the last clear (or the clear values unknown)
    kCellHoldsClear = 1,   // the last clear's values, written and untouched since
    kCellPending = 2,      // to hold the last clear's values: not written yet
    kCellBeingWritten = 3  // pending, being written by one thread (settleCell)
};

// Writes `color` into [first, last): four pixels (64 bytes) per store where the instruction set has
// such stores, two or one otherwise, from a pattern held in registers. std::fill of a vec4 moves one
// pixel per store and reloads the value each time (a store through a vec4* might have changed it),
// which made the cells' clears a tenth of a 4K frame's instructions.
void fillColors(vec4* first, vec4* last, vec4 color) {
    using FourPixels = float __attribute__((vector_size(64)));
    const FourPixels pattern = {color.r, color.g, color.b, color.a, color.r, color.g, color.b, color.a,
                                color.r, color.g, color.b, color.a, color.r, color.g, color.b, color.a};
    for (; last - first >= 4; first += 4)
        std::memcpy(first, &pattern, sizeof pattern);
    for (; first != last; ++first)
        *first = color;
}

// Asks for the cache lines of [start, start + bytes), to be written.
void prefetchForWriting(const void* start, std::size_t bytes) {
    const char* first = static_cast<const char*>(start);
    for (std::size_t byte = 0; byte < bytes; byte += 64)
        __builtin_prefetch(first + byte, 1);
}

}  // namespace

Framebuffer::Framebuffer(int width, int height)
    : width_(width),
      height_(height),
      color_(static_cast<std::size_t>(width) * height, vec4(0.0f)),
      depth_(static_cast<std::size_t>(width) * height, DepthFormat::kClear),
      cellState_(static_cast<std::size_t>(cellsAcross()) * cellsDown(), kCellHoldsClear),
      clearedCellsKnown_(true),
      clearedColor_(0.0f),
      clearedDepth_(DepthFormat::kClear) {}

std::uint64_t Framebuffer::bytesFor(int width, int height, int samples) {
    const std::uint64_t pixels = std::uint64_t(std::max(width, 0)) * std::uint64_t(std::max(height, 0));
    const std::uint64_t perPixel = sizeof(vec4) + sizeof(DepthFormat::Stored);
    const std::uint64_t planes = samples > 1 ? 1 + std::uint64_t(samples) : 1;
    const std::uint64_t cells = std::uint64_t((width + kClearCell - 1) / kClearCell) *
                                std::uint64_t((height + kClearCell - 1) / kClearCell);
    const std::uint64_t most = std::numeric_limits<std::uint64_t>::max();
    if (pixels != 0 && perPixel * planes > most / pixels) return most;
    return pixels * perPixel * planes + cells;
}

std::uint64_t Framebuffer::bytesHeld() const {
    return color_.size() * sizeof(vec4) + depth_.size() * sizeof(DepthFormat::Stored) +
           sampleColor_.size() * sizeof(vec4) + sampleDepth_.size() * sizeof(DepthFormat::Stored) +
           cellState_.size();
}

void Framebuffer::clearColor(vec4 color) {
    settleClear();
    forgetClearedCells();
    fillColors(color_.data(), color_.data() + color_.size(), color);
}

void Framebuffer::clearDepth(DepthFormat::Stored depth) {
    settleClear();
    forgetClearedCells();
    std::fill(depth_.begin(), depth_.end(), depth);
}

std::size_t Framebuffer::clear(vec4 color, DepthFormat::Stored depth, ThreadPool& pool) {
    // Cells holding these very values (bit for bit), or pending with them, need nothing more. A cell
    // pending with other values was never written nor read: it now waits for these.
    const bool sameValues = clearedCellsKnown_ && std::memcmp(&color, &clearedColor_, sizeof color) == 0 &&
                            std::memcmp(&depth, &clearedDepth_, sizeof depth) == 0;
    std::size_t marked = 0, pending = 0;
    for (std::uint8_t& state : cellState_) {
        if (!sameValues || state == kCellDrawn) {
            state = kCellPending;
            ++marked;
        }
        pending += state == kCellPending;
    }
    pendingCells_ = pending;
    lists_.clear(pool);
    clearedCellsKnown_ = true;
    clearedColor_ = color;
    clearedDepth_ = depth;
    return marked;
}

void Framebuffer::writeClearValues(std::size_t cell) {
    // A cell's rows are short (1 KiB of colour, 256 B of depth) and a frame apart in memory, so the
    // hardware's stream prefetcher has little to go on and each row's first stores wait for memory: the
    // lines of the row kRowsAhead below are asked for (for writing) while this one is written. A 1080p
    // frame of large triangles (a 1k-triangle sphere, a third of it cells' clears) took ~2.5% less.
    constexpr int kRowsAhead = 2;
    const int across = cellsAcross();
    const int cellX = static_cast<int>(cell % static_cast<std::size_t>(across));
    const int cellY = static_cast<int>(cell / static_cast<std::size_t>(across));
    const int firstX = cellX * kClearCell, endX = std::min(width_, firstX + kClearCell);
    const int firstY = cellY * kClearCell, endY = std::min(height_, firstY + kClearCell);
    const auto samples = static_cast<std::size_t>(samples_);
    // Copies: the planes' stores cannot change them, so they stay in registers.
    const vec4 color = clearedColor_;
    const DepthFormat::Stored depth = clearedDepth_;
    for (int y = firstY; y < endY; ++y) {
        const std::size_t first = index(firstX, y), last = index(endX - 1, y) + 1;
        if (y + kRowsAhead < endY) {
            const std::size_t ahead = first + static_cast<std::size_t>(kRowsAhead) * width_;
            prefetchForWriting(color_.data() + ahead, (last - first) * sizeof(vec4));
            prefetchForWriting(depth_.data() + ahead, (last - first) * sizeof(DepthFormat::Stored));
        }
        fillColors(color_.data() + first, color_.data() + last, color);
        std::fill(depth_.data() + first, depth_.data() + last, depth);
        if (samples > 1) {
            fillColors(sampleColor_.data() + first * samples, sampleColor_.data() + last * samples, color);
            std::fill(sampleDepth_.data() + first * samples, sampleDepth_.data() + last * samples, depth);
        }
    }
}

void Framebuffer::settleCell(std::size_t cell) {
    std::atomic_ref<std::uint8_t> state(cellState_[cell]);
    std::uint8_t seen = state.load(std::memory_order_acquire);
    if (seen == kCellPending &&
        state.compare_exchange_strong(seen, kCellBeingWritten, std::memory_order_acquire)) {
        writeClearValues(cell);
        state.store(kCellHoldsClear, std::memory_order_release);
        state.notify_all();
        std::atomic_ref<std::size_t>(pendingCells_).fetch_sub(1, std::memory_order_release);
        return;
    }
    // Another thread is writing it (a few microseconds): wait until the values are there.
    while (seen == kCellBeingWritten) {
        state.wait(kCellBeingWritten, std::memory_order_acquire);
        seen = state.load(std::memory_order_acquire);
    }
}

void Framebuffer::settleAllCells() {
    for (std::size_t cell = 0; cell < cellState_.size(); ++cell)
        settleCell(cell);
}

void Framebuffer::finishClear(ThreadPool& pool) {
    if (pendingCells() == 0) return;
    const auto across = static_cast<std::size_t>(cellsAcross());
    pool.parallelFor(static_cast<std::size_t>(cellsDown()), [&](std::size_t band, int) {
        for (std::size_t cell = band * across; cell < (band + 1) * across; ++cell)
            settleCell(cell);
    });
}

FramebufferPlanes Framebuffer::planesToDraw(const PixelRect& area) {
    // The part of `area` inside the framebuffer (none, for an area beside it or a 0×0 framebuffer).
    const PixelRect inside{std::max(area.minX, 0), std::max(area.minY, 0), std::min(area.maxX, width_ - 1),
                           std::min(area.maxY, height_ - 1)};
    if (clearedCellsKnown_ && !inside.empty()) {
        // The cells `area` overlaps get the clear values if pending, then no longer hold them.
        const int across = cellsAcross();
        for (int cy = inside.minY / kClearCell; cy <= inside.maxY / kClearCell; ++cy)
            for (int cx = inside.minX / kClearCell; cx <= inside.maxX / kClearCell; ++cx) {
                const auto cell = static_cast<std::size_t>(cy) * across + cx;
                // Drawn already (a cell stays drawn until the next clear): nothing to write. The states
                // of a frame's cells share a few cache lines that every tile of every draw asks for;
                // storing kCellDrawn again each time made the threads take those lines from each other.
                std::atomic_ref<std::uint8_t> state(cellState_[cell]);
                if (state.load(std::memory_order_acquire) == kCellDrawn) continue;
                settleCell(cell);
                state.store(kCellDrawn, std::memory_order_relaxed);
            }
    }
    FramebufferPlanes planes;
    planes.width_ = width_;
    planes.samples_ = static_cast<std::size_t>(samples_);
    planes.color_ = color_.data();
    planes.depth_ = depth_.data();
    planes.sampleColor_ = sampleColor_.data();
    planes.sampleDepth_ = sampleDepth_.data();
    planes.lists_ = &lists_;
    return planes;
}

void Framebuffer::useSamples(int samples) {
    settleClear();
    forgetClearedCells();  // new sample planes hold nothing yet
    samples_ = samples;
    const std::size_t size = samples > 1 ? color_.size() * static_cast<std::size_t>(samples) : 0;
    if (size == 0) {
        LargeBuffer<vec4>().swap(sampleColor_);
        LargeBuffer<DepthFormat::Stored>().swap(sampleDepth_);
        return;
    }
    sampleColor_.resize(size);
    sampleDepth_.resize(size);
}

void Framebuffer::resolveSamples(ColorBufferFormat format, ThreadPool& pool) {
    if (samples_ <= 1) return;
    finishClear(pool);
    const int samples = samples_;
    const float weight = 1.0f / static_cast<float>(samples);  // exact: samples is a power of two
    pool.parallelFor(static_cast<std::size_t>(height_), [&](std::size_t row, int) {
        const int y = static_cast<int>(row);
        vec4 sum[16];
        for (int x = 0; x < width_; ++x) {
            const vec4* pixel = sampleColors(x, y);
            // Pairwise summation, (s0 + s1) + (s2 + s3) and so on: a fixed order, and equal samples
            // (a pixel inside one triangle) sum exactly, so the average is their value, bit for bit.
            for (int s = 0; s < samples; ++s)
                sum[s] = pixel[s];
            for (int count = samples; count > 1; count /= 2)
                for (int s = 0; s < count / 2; ++s)
                    sum[s] = sum[2 * s] + sum[2 * s + 1];
            color(x, y) = roundToColorBuffer(format, sum[0] * weight);
            depth(x, y) = sampleDepths(x, y)[0];
        }
    });
}

}  // namespace facet
