// The render target: a linear floating-point colour buffer and a depth buffer of the same size, and
// the per-pixel fragment lists of exact transparency (fragment_lists.h), allocated on first use.
#pragma once

#include <atomic>
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

    // The bytes a width x height framebuffer holds with `samples` samples per pixel (useSamples): its
    // colour and depth planes, the sample planes when samples > 1, and the per-cell clear state. The
    // renderer's memory estimate (src/render/memory_estimate.h) uses this; bytesHeld() counts the same
    // planes as allocated, and a test checks that they agree. Not the fragment lists (they grow with
    // the fragments drawn). Saturates instead of wrapping.
    static std::uint64_t bytesFor(int width, int height, int samples);
    std::uint64_t bytesHeld() const;

    void clearColor(vec4 color);
    void clearDepth(DepthFormat::Stored depth = DepthFormat::kClear);
    // Colour and depth at once (and every sample's, when multisampled), and the fragment lists emptied
    // (their memory kept for the next frame). A 1080p float buffer is 41 MB to write, a 4K one 166 MB:
    // more than a small frame's drawing. So the framebuffer keeps a state per cell (kClearCell pixels
    // square), and
    // - a cell that still holds these very values (bit for bit), untouched since the last clear, needs
    //   no writes: a frame that covers a tenth of the screen clears a tenth of it after the first (what
    //   a GPU's fast-clear metadata does);
    // - the others are only marked pending here: a draw writes the clear values into a pending cell
    //   when its tile first asks for the cell's pixels (planesToDraw), just before drawing into them,
    //   so the cell is written once into cache instead of once to memory by the clear and read back by
    //   the draw; finishClear() writes the cells no draw reached (the renderer calls it after a frame's
    //   draws, over the pool's threads). Every accessor of pixels below writes any pending cells first,
    //   so no caller can see one: the clear's effect is as if every pixel had been written here.
    // Returns the number of cells marked (to be written).
    std::size_t clear(vec4 color, DepthFormat::Stored depth, ThreadPool& pool);
    // Writes the clear values into every cell still pending, bands of cells spread over the pool.
    void finishClear(ThreadPool& pool);
    // The cells marked by a clear and not written yet.
    std::size_t pendingCells() const {
        return std::atomic_ref<std::size_t>(const_cast<std::size_t&>(pendingCells_))
            .load(std::memory_order_acquire);
    }

    // Pixels, to read or to write. Writing through these (rather than a draw's planesToDraw) leaves the
    // framebuffer no memory of which cells hold the clear values: the next clear() writes every pixel.
    vec4& color(int x, int y) {
        settleClear();
        forgetClearedCells();
        return color_[index(x, y)];
    }
    const vec4& color(int x, int y) const {
        settleClear();
        return color_[index(x, y)];
    }
    DepthFormat::Stored& depth(int x, int y) {
        settleClear();
        forgetClearedCells();
        return depth_[index(x, y)];
    }
    DepthFormat::Stored depth(int x, int y) const {
        settleClear();
        return depth_[index(x, y)];
    }

    // The planes for a draw (or a resolve) that writes pixels only inside `area`: the cells `area`
    // overlaps get the clear values first if they are pending, then no longer hold them. Safe to call
    // from several threads at once, also for areas that share a cell.
    FramebufferPlanes planesToDraw(const PixelRect& area);
    static constexpr int kClearCell = 64;

    // Multisampling: per-sample colour and depth planes of `samples` samples per pixel (a pixel's samples
    // contiguous, in the standard pattern's order), allocated here and cleared by clear() from then on;
    // 1 releases them, and a framebuffer at one sample allocates and clears nothing more.
    void useSamples(int samples);
    int samples() const { return samples_; }
    vec4* sampleColors(int x, int y) {
        settleClear();
        forgetClearedCells();
        return sampleColor_.data() + sampleIndex(x, y);
    }
    DepthFormat::Stored* sampleDepths(int x, int y) {
        settleClear();
        forgetClearedCells();
        return sampleDepth_.data() + sampleIndex(x, y);
    }
    // The box filter of multisampling: each pixel's colour becomes the average of its samples in linear
    // light, summed pairwise in sample order (so a pixel whose samples are equal keeps their exact
    // value), rounded as `format` stores it; its depth becomes its first sample's. Rows spread over the
    // pool: the same bytes for any thread count.
    void resolveSamples(ColorBufferFormat format, ThreadPool& pool);

    // Row-major, row 0 at the top of the image: in place, and as copies (for comparisons).
    std::span<const vec4> colorSpan() const {
        settleClear();
        return color_;
    }
    std::span<const DepthFormat::Stored> depthSpan() const {
        settleClear();
        return depth_;
    }
    // The colour plane in place, to write every pixel of (a resolve): what color(x, y) does for each
    // pixel, done once on the calling thread, so that a pool's threads may then write rows of it
    // without touching the framebuffer's own state.
    std::span<vec4> colorSpanToWrite() {
        settleClear();
        forgetClearedCells();
        return {color_.data(), color_.size()};
    }
    std::vector<vec4> colorPixels() const {
        settleClear();
        return {color_.begin(), color_.end()};
    }
    std::vector<DepthFormat::Stored> depthPixels() const {
        settleClear();
        return {depth_.begin(), depth_.end()};
    }

    // Where AppendToLists draws put their fragments, until resolveFragmentLists() composites them.
    FragmentLists& fragmentLists() { return lists_; }
    const FragmentLists& fragmentLists() const { return lists_; }

  private:
    std::size_t index(int x, int y) const { return static_cast<std::size_t>(y) * width_ + x; }
    std::size_t sampleIndex(int x, int y) const { return index(x, y) * static_cast<std::size_t>(samples_); }
    void forgetClearedCells() { clearedCellsKnown_ = false; }
    // Writes the pending cells before any pixel is handed out or read (one load when none is pending).
    // A const accessor may write them too: a pending cell already holds the clear values as far as any
    // caller can tell, so writing them out changes nothing a caller sees.
    void settleClear() const {
        if (pendingCells() != 0) const_cast<Framebuffer*>(this)->settleAllCells();
    }
    void settleAllCells();
    // Writes the clear values into cell `cell` if it is pending, or waits while another thread does;
    // safe to call from several threads at once (a draw's tiles may share a cell).
    void settleCell(std::size_t cell);
    void writeClearValues(std::size_t cell);
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
    // Per cell, row-major, a CellState (framebuffer.cpp): whether it holds clearedColor_ and
    // clearedDepth_ in every plane (and every sample) untouched since the last clear, was drawn into
    // since, or is still to be written (pending). Meaningful only while clearedCellsKnown_; read and
    // written through std::atomic_ref where draws' tiles may reach it from several threads.
    std::vector<std::uint8_t> cellState_;
    std::size_t pendingCells_ = 0;  // cells in the pending state (through std::atomic_ref)
    bool clearedCellsKnown_ = false;
    vec4 clearedColor_{0.0f};
    DepthFormat::Stored clearedDepth_{};
};

}  // namespace facet
