#include "framebuffer.h"

#include <algorithm>

namespace facet {

Framebuffer::Framebuffer(int width, int height)
    : width_(width),
      height_(height),
      color_(static_cast<std::size_t>(width) * height, vec4(0.0f)),
      depth_(static_cast<std::size_t>(width) * height, 1.0f) {}

void Framebuffer::clearColor(vec4 color) {
    std::fill(color_.begin(), color_.end(), color);
}

void Framebuffer::clearDepth(float depth) {
    std::fill(depth_.begin(), depth_.end(), depth);
}

}  // namespace facet
