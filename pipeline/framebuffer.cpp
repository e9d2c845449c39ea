#include "framebuffer.h"

#include <algorithm>

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
    });
    lists_.clear(pool);
}

}  // namespace facet
