// The render target: a linear floating-point colour buffer and a depth buffer of the same size, and
// the per-pixel fragment lists of exact transparency (fragment_lists.h), allocated on first use.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "depth_format.h"
#include "fragment_lists.h"
#include "glsl.h"
#include "large_buffer.h"

namespace facet {

class ThreadPool;

class Framebuffer {
  public:
    Framebuffer() = default;
    Framebuffer(int width, int height);

    int width() const { return width_; }
    int height() const { return height_; }

    void clearColor(vec4 color);
    void clearDepth(DepthFormat::Stored depth = DepthFormat::kClear);
    // Colour and depth at once, rows spread over the pool's threads (a 1080p float buffer is 41 MB to
    // write), and the fragment lists emptied (their memory kept for the next frame).
    void clear(vec4 color, DepthFormat::Stored depth, ThreadPool& pool);

    vec4& color(int x, int y) { return color_[index(x, y)]; }
    const vec4& color(int x, int y) const { return color_[index(x, y)]; }
    DepthFormat::Stored& depth(int x, int y) { return depth_[index(x, y)]; }
    DepthFormat::Stored depth(int x, int y) const { return depth_[index(x, y)]; }

    // Multisampling: per-sample colour and depth planes of `samples` samples per pixel (a pixel's samples
    // contiguous, in the standard pattern's order), allocated here and cleared by clear() from then on;
    // 1 releases them, and a framebuffer at one sample allocates and clears nothing more.
    void useSamples(int samples);
    int samples() const { return samples_; }
    vec4* sampleColors(int x, int y) { return sampleColor_.data() + sampleIndex(x, y); }
    DepthFormat::Stored* sampleDepths(int x, int y) { return sampleDepth_.data() + sampleIndex(x, y); }
    // The box filter of multisampling: each pixel's colour becomes the average of its samples in linear
    // light, summed pairwise in sample order (so a pixel whose samples are equal keeps their exact
    // value), rounded as `format` stores it; its depth becomes its first sample's. Rows spread over the
    // pool: the same bytes for any thread count.
    void resolveSamples(ColorBufferFormat format, ThreadPool& pool);

    // Row-major, row 0 at the top of the image: in place, and as copies (for comparisons).
    std::span<const vec4> colorSpan() const { return color_; }
    std::span<const DepthFormat::Stored> depthSpan() const { return depth_; }
    std::vector<vec4> colorPixels() const { return {color_.begin(), color_.end()}; }
    std::vector<DepthFormat::Stored> depthPixels() const { return {depth_.begin(), depth_.end()}; }

    // Where AppendToLists draws put their fragments, until resolveFragmentLists() composites them.
    FragmentLists& fragmentLists() { return lists_; }
    const FragmentLists& fragmentLists() const { return lists_; }

  private:
    std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width_ + x; }
    std::size_t sampleIndex(int x, int y) const { return index(x, y) * static_cast<std::size_t>(samples_); }

    int width_ = 0;
    int height_ = 0;
    LargeBuffer<vec4> color_;                 // linear RGBA
    LargeBuffer<DepthFormat::Stored> depth_;  // window depth as DepthFormat stores it
    FragmentLists lists_;                     // empty (no memory) until an AppendToLists draw
    int samples_ = 1;
    LargeBuffer<vec4> sampleColor_;                 // multisampling only: samples_ per pixel
    LargeBuffer<DepthFormat::Stored> sampleDepth_;  // likewise
};

}  // namespace facet
