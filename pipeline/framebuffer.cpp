#include "framebuffer.h"

#include <algorithm>

#include "blend.h"
#include "thread_pool.h"

namespace facet {

Framebuffer::Framebuffer(int width, int height)
    : width_(width),
      height_(height),
      color_(static_cast<std::size_t>(width) * height, vec4(0.0f)),
      depth_(static_cast<std::size_t>(width) * height, DepthFormat::kClear) {}

void Framebuffer::clearColor(vec4 color) {
    std::fill(color_.begin(), color_.end(), color);
}

void Framebuffer::clearDepth(DepthFormat::Stored depth) {
    std::fill(depth_.begin(), depth_.end(), depth);
}

void Framebuffer::clear(vec4 color, DepthFormat::Stored depth, ThreadPool& pool) {
    constexpr int kRowsPerItem = 32;
    const int items = (height_ + kRowsPerItem - 1) / kRowsPerItem;
    pool.parallelFor(static_cast<std::size_t>(items), [&](std::size_t item, int) {
        const std::size_t first = index(0, static_cast<int>(item) * kRowsPerItem);
        const std::size_t last = index(0, std::min(height_, (static_cast<int>(item) + 1) * kRowsPerItem));
        std::fill(color_.begin() + first, color_.begin() + last, color);
        std::fill(depth_.begin() + first, depth_.begin() + last, depth);
        if (samples_ > 1) {
            const auto samples = static_cast<std::size_t>(samples_);
            std::fill(sampleColor_.begin() + first * samples, sampleColor_.begin() + last * samples, color);
            std::fill(sampleDepth_.begin() + first * samples, sampleDepth_.begin() + last * samples, depth);
        }
    });
    lists_.clear(pool);
}

void Framebuffer::useSamples(int samples) {
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
