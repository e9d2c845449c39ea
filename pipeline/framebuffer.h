// The render target: a linear floating-point colour buffer and a depth buffer of the same size, and
// the per-pixel fragment lists of exact transparency (fragment_lists.h), allocated on first use.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "depth_format.h"
#include "fragment_lists.h"
#include "glsl.h"
#include "large_buffer.h"

namespace facet {

class ThreadPool;

// The planes of a framebuffer as a draw writes them: what the back end and the fragment lists' resolve
// are handed for the pixels they were given (Framebuffer::planesToDraw), with the framebuffer's own
// names. Plain pointers: copying one is free, and reaching a pixel through one costs what it costs
// through the framebuffer.
class FramebufferPlanes {
  public:
    int width() const { return width_; }
    vec4& color(int x, int y) const { return color_[index(x, y)]; }
    DepthFormat::Stored& depth(int x, int y) const { return depth_[index(x, y)]; }
    vec4* sampleColors(int x, int y) const { return sampleColor_ + index(x, y) * samples_; }
    DepthFormat::Stored* sampleDepths(int x, int y) const { return sampleDepth_ + index(x, y) * samples_; }
    FragmentLists& fragmentLists() const { return *lists_; }

  private:
    friend class Framebuffer;
    std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width_ + x; }

    int width_ = 0;
    std::size_t samples_ = 1;
    vec4* color_ = nullptr;
    DepthFormat::Stored* depth_ = nullptr;
    vec4* sampleColor_ = nullptr;
    DepthFormat::Stored* sampleDepth_ = nullptr;
    FragmentLists* lists_ = nullptr;
};

class Framebuffer {
  public:
    Framebuffer() = default;
    Framebuffer(int width, int height);

    int width() const { return width_; }
    int height() const { return height_; }

    void clearColor(vec4 color);
    void clearDepth(DepthFormat::Stored depth = DepthFormat::kClear);
    // Colour and depth at once (and every sample's, when multisampled), bands of rows spread over the
    // pool's threads, and the fragment lists emptied (their memory kept for the next frame).
    // A 1080p float buffer is 41 MB to write, a 4K one 166 MB: more than a small frame's drawing. So
    // the framebuffer remembers which cells (kClearCell pixels square) still hold the values of the
    // last clear, untouched since, and a clear to the same values writes only the others: a frame
    // that covers a tenth of the screen clears a tenth of it after the first (what a GPU's fast-clear
    // metadata does). Returns the number of cells written.
    std::size_t clear(vec4 color, DepthFormat::Stored depth, ThreadPool& pool);

    // Pixels, to read or to write. Writing through these (rather than a draw's planesToDraw) leaves the
    // framebuffer no memory of which cells hold the clear values: the next clear() writes every pixel.
    vec4& color(int x, int y) {
        forgetClearedCells();
        return color_[index(x, y)];
    }
    const vec4& color(int x, int y) const { return color_[index(x, y)]; }
    DepthFormat::Stored& depth(int x, int y) {
        forgetClearedCells();
        return depth_[index(x, y)];
    }
    DepthFormat::Stored depth(int x, int y) const { return depth_[index(x, y)]; }

    // The planes for a draw (or a resolve) that writes pixels only inside `area`: the cells `area`
    // overlaps no longer hold the clear values. Safe to call from several threads at once.
    FramebufferPlanes planesToDraw(const PixelRect& area);
    static constexpr int kClearCell = 64;

    // Multisampling: per-sample colour and depth planes of `samples` samples per pixel (a pixel's samples
    // contiguous, in the standard pattern's order), allocated here and cleared by clear() from then on;
    // 1 releases them, and a framebuffer at one sample allocates and clears nothing more.
    void useSamples(int samples);
    int samples() const { return samples_; }
    vec4* sampleColors(int x, int y) {
        forgetClearedCells();
        return sampleColor_.data() + sampleIndex(x, y);
    }
    DepthFormat::Stored* sampleDepths(int x, int y) {
        forgetClearedCells();
        return sampleDepth_.data() + sampleIndex(x, y);
    }
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
    void forgetClearedCells() { clearedCellsKnown_ = false; }
    int cellsAcross() const { return (width_ + kClearCell - 1) / kClearCell; }
    int cellsDown() const { return (height_ + kClearCell - 1) / kClearCell; }

    int width_ = 0;
    int height_ = 0;
    LargeBuffer<vec4> color_;                 // linear RGBA
    LargeBuffer<DepthFormat::Stored> depth_;  // window depth as DepthFormat stores it
    FragmentLists lists_;                     // empty (no memory) until an AppendToLists draw
    int samples_ = 1;
    LargeBuffer<vec4> sampleColor_;                 // multisampling only: samples_ per pixel
    LargeBuffer<DepthFormat::Stored> sampleDepth_;  // likewise
    // Per cell, row-major: 1 while it holds clearedColor_ and clearedDepth_ in every plane (and every
    // sample), untouched since the last clear. Meaningful only while clearedCellsKnown_.
    std::vector<std::uint8_t> cellHoldsClear_;
    bool clearedCellsKnown_ = false;
    vec4 clearedColor_{0.0f};
    DepthFormat::Stored clearedDepth_{};
};

}  // namespace facet
