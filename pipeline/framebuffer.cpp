#include "framebuffer.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>

#include "blend.h"
#include "thread_pool.h"

namespace facet {

Framebuffer::Framebuffer(int width, int height)
    : width_(width),
      height_(height),
      color_(static_cast<std::size_t>(width) * height, vec4(0.0f)),
      depth_(static_cast<std::size_t>(width) * height, DepthFormat::kClear),
      cellHoldsClear_(static_cast<std::size_t>(cellsAcross()) * cellsDown(), 1),
      clearedCellsKnown_(true),
      clearedColor_(0.0f),
      clearedDepth_(DepthFormat::kClear) {}

void Framebuffer::clearColor(vec4 color) {
    forgetClearedCells();
    std::fill(color_.begin(), color_.end(), color);
}

void Framebuffer::clearDepth(DepthFormat::Stored depth) {
    forgetClearedCells();
    std::fill(depth_.begin(), depth_.end(), depth);
}

std::size_t Framebuffer::clear(vec4 color, DepthFormat::Stored depth, ThreadPool& pool) {
    // Cells still holding these very values (bit for bit) need no writes.
    const bool sameValues = clearedCellsKnown_ && std::memcmp(&color, &clearedColor_, sizeof color) == 0 &&
                            std::memcmp(&depth, &clearedDepth_, sizeof depth) == 0;
    const auto samples = static_cast<std::size_t>(samples_);
    const int across = cellsAcross(), down = cellsDown();
    std::vector<std::size_t> written(static_cast<std::size_t>(down), 0);

    // A band of cells (kClearCell rows) per item; in a band, each run of cells that needs writing is
    // filled row by row across every plane.
    pool.parallelFor(static_cast<std::size_t>(down), [&](std::size_t band, int) {
        const int firstRow = static_cast<int>(band) * kClearCell;
        const int lastRow = std::min(height_, firstRow + kClearCell);
        std::uint8_t* cells = cellHoldsClear_.data() + band * static_cast<std::size_t>(across);
        for (int cell = 0; cell < across;) {
            if (sameValues && cells[cell]) {
                ++cell;
                continue;
            }
            int runEnd = cell + 1;
            while (runEnd < across && !(sameValues && cells[runEnd]))
                ++runEnd;
            const int firstX = cell * kClearCell, endX = std::min(width_, runEnd * kClearCell);
            for (int y = firstRow; y < lastRow; ++y) {
                const std::size_t first = index(firstX, y), last = index(endX - 1, y) + 1;
                std::fill(color_.data() + first, color_.data() + last, color);
                std::fill(depth_.data() + first, depth_.data() + last, depth);
                if (samples > 1) {
                    std::fill(sampleColor_.data() + first * samples, sampleColor_.data() + last * samples,
                              color);
                    std::fill(sampleDepth_.data() + first * samples, sampleDepth_.data() + last * samples,
                              depth);
                }
            }
            std::fill(cells + cell, cells + runEnd, std::uint8_t{1});
            written[band] += static_cast<std::size_t>(runEnd - cell);
            cell = runEnd;
        }
    });
    lists_.clear(pool);
    clearedCellsKnown_ = true;
    clearedColor_ = color;
    clearedDepth_ = depth;
    std::size_t total = 0;
    for (const std::size_t n : written)
        total += n;
    return total;
}

FramebufferPlanes Framebuffer::planesToDraw(const PixelRect& area) {
    // The part of `area` inside the framebuffer (none, for an area beside it or a 0×0 framebuffer).
    const PixelRect inside{std::max(area.minX, 0), std::max(area.minY, 0), std::min(area.maxX, width_ - 1),
                           std::min(area.maxY, height_ - 1)};
    if (clearedCellsKnown_ && !inside.empty()) {
        const int across = cellsAcross();
        for (int cy = inside.minY / kClearCell; cy <= inside.maxY / kClearCell; ++cy)
            for (int cx = inside.minX / kClearCell; cx <= inside.maxX / kClearCell; ++cx)
                std::atomic_ref<std::uint8_t>(cellHoldsClear_[static_cast<std::size_t>(cy) * across + cx])
                    .store(0, std::memory_order_relaxed);
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
