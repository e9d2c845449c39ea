// Exact transparency: per-pixel fragment lists (an A-buffer; Carpenter 1984, and on GPUs the
// "per-pixel linked lists" of Yang et al. 2010). A draw whose DrawState::output is AppendToLists does
// not blend: every fragment that passes the depth test is appended to its pixel's list (colour as the
// shader wrote it, window depth, the draw's BlendMode; submission order is the order of the list).
// After the transparent draws, resolveFragmentLists() sorts each pixel's list by depth, farthest first
// (equal depths in submission order), and composites it over the framebuffer's colour, each fragment
// with its own blend mode (blend.h). Intersecting transparent surfaces come out right at every pixel,
// which no order of whole triangles can do.
//
// A frame, step by step (the context's pool does the parallel parts):
//   1. target.clear(colour, depth, context.pool): colour and depth, and the lists emptied (memory kept);
//   2. opaque draws as usual (FragmentOutput::Blend, depth writes on);
//   3. transparent draws with DrawState::output = FragmentOutput::AppendToLists, DrawState::blend their
//      mode, the depth test on and depth writes off, in any order;
//   4. resolveFragmentLists(target, context.pool) composites them into target's colour and returns
//      FragmentListStats (fragments, longest list, bytes held).
// All AppendToLists draws between a clear and the resolve use one tile size (one DrawContext).
//
// Where the lists live: in the Framebuffer, as an attachment next to colour and depth
// (Framebuffer::fragmentLists()). They are per-pixel data of one render target, exactly like the depth
// buffer: sized with it, cleared with it (Framebuffer::clear), composited into its colour, and kept by
// the caller across frames with it, so their memory is reused from frame to frame. The DrawContext is
// not the owner because it is scratch shared by every target a caller draws into (of any size), and a
// separate object would have to be threaded through every draw() call and kept paired with the right
// framebuffer by hand. A framebuffer that never sees an AppendToLists draw allocates nothing for them.
//
// Layout: a head per pixel (the index of its newest fragment) and one node pool per screen tile of the
// back end (tiles sit on multiples of the tile size in the framebuffer, bin.h). The back end draws each
// tile on one thread, its triangles in submission order, so appending takes no lock, and every pool
// holds the same nodes in the same order for any number of threads: the resolved image is the same
// bytes for any thread count. Pools keep their capacity when cleared (amortised growth, nothing
// allocated per fragment once warmed up); clearing resets the heads of the tiles that hold fragments
// and the pools' sizes.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <vector>

#include "glsl.h"
#include "state.h"
#include "types.h"

namespace facet {

class Framebuffer;
class ThreadPool;

// What the lists held at a resolve, and what they cost.
struct FragmentListStats {
    std::uint64_t fragments = 0;    // fragments stored in all lists
    std::uint64_t pixels = 0;       // pixels whose list is not empty
    std::uint32_t longestList = 0;  // fragments in the longest list
    std::uint64_t dropped = 0;      // fragments refused because their tile's pool was full (see below)
    std::size_t bytesHeld = 0;      // capacity held: heads, node pools, resolve scratch
};

std::ostream& operator<<(std::ostream& os, const FragmentListStats& stats);

class FragmentLists {
  public:
    // One stored fragment, 24 bytes.
    struct Node {
        vec4 color;          // the fragment shader's output
        float depth = 0.0f;  // window depth
        // Bits 0..28: the index, in the same tile pool, of the pixel's previous (older) fragment, or
        // kEnd for its first; bits 29..31: the draw's BlendMode.
        std::uint32_t link = 0;

        std::uint32_t previous() const { return link & kIndexMask; }
        BlendMode blend() const { return static_cast<BlendMode>(link >> kIndexBits); }
    };
    static constexpr int kIndexBits = 29;
    static constexpr std::uint32_t kIndexMask = (std::uint32_t{1} << kIndexBits) - 1;
    static constexpr std::uint32_t kEnd = kIndexMask;  // "no fragment", in heads and links
    // A pool holds at most this many nodes (12.9 GB of them, for one tile); a fragment beyond it is not
    // stored but counted (FragmentListStats::dropped, FragmentFate::Dropped).
    static constexpr std::uint32_t kMaxNodesPerTile = kEnd;

  private:
    // A tile's nodes, on a cache line of its own: the threads drawing neighbouring tiles append at once.
    struct alignas(64) TilePool {
        std::vector<Node> nodes;
        std::uint64_t dropped = 0;
    };

  public:
    // Appends to the lists of one tile's pixels. The back end makes one for each tile it draws.
    class TileWriter {
      public:
        TileWriter() = default;
        // False when the tile's pool is full (the fragment is counted as dropped).
        bool append(int x, int y, const vec4& color, float depth, BlendMode mode) {
            std::vector<Node>& nodes = pool_->nodes;
            const std::size_t index = nodes.size();
            if (index >= kMaxNodesPerTile) [[unlikely]] {
                ++pool_->dropped;
                return false;
            }
            if (index == nodes.capacity() && !lists_->grow(nodes)) [[unlikely]] {
                ++pool_->dropped;  // past the memory limit: the renderer refuses the frame after it
                return false;
            }
            std::uint32_t& head = heads_[static_cast<std::size_t>(y) * width_ + x];
            nodes.push_back(Node{color, depth, head | (static_cast<std::uint32_t>(mode) << kIndexBits)});
            head = static_cast<std::uint32_t>(index);
            return true;
        }

      private:
        friend class FragmentLists;
        TilePool* pool_ = nullptr;
        FragmentLists* lists_ = nullptr;
        std::uint32_t* heads_ = nullptr;
        int width_ = 0;
    };

    // Makes the lists ready for draws on a width × height target whose back end uses `tileSize`
    // (draw() calls it for every AppendToLists draw; it allocates only the first time, or when the
    // size changes). Throws std::invalid_argument when the lists hold fragments and the size or the
    // tile size differs from theirs: clear the lists first.
    void prepare(int width, int height, int tileSize);

    // The depth and colour buffer formats of the draws that append (draw() sets them with prepare()):
    // the resolve sorts farthest first in the depth format's direction and rounds each composited
    // colour as the colour buffer stores it.
    void useFormats(DepthBufferFormat depth, ColorBufferFormat color) {
        depthFormat_ = depth;
        colorBuffer_ = color;
    }

    // The memory the node pools may hold together (the memory limit less what the frame's other
    // buffers take; unlimited unless set): a pool that would grow past it does not, the fragment is
    // dropped and overBudget() says so, for the renderer to refuse the frame with a message instead of
    // running out of memory (1,000 layers at 640x480 are 7.4 GB of nodes). Kept until set again.
    void setByteBudget(std::uint64_t bytes) { byteBudget_ = bytes; }
    bool overBudget() const { return bytesRefused() != 0; }
    // The node memory a refused growth would have brought the pools to (0 when none was refused).
    std::uint64_t bytesRefused() const {
        return std::atomic_ref<std::uint64_t>(const_cast<std::uint64_t&>(refusedBytes_))
            .load(std::memory_order_relaxed);
    }
    // The bytes of nodes a pool of `capacity` holds, and its next capacity: the one rule grow() and the
    // estimate in tests use.
    static std::uint64_t nodeBytes(std::size_t capacity) { return std::uint64_t(capacity) * sizeof(Node); }
    static std::size_t nextCapacity(std::size_t capacity) { return capacity < 64 ? 64 : 2 * capacity; }

    // The writer for the tile holding pixel (x, y): the back end passes its tile's top-left pixel.
    TileWriter writer(int x, int y);

    // Empties every list, on the pool's threads: the heads of tiles that hold fragments are reset and
    // the pools' sizes set to zero; their capacity stays for the next frame.
    void clear(ThreadPool& pool);

    bool allocated() const { return !heads_.empty(); }
    int tileSize() const { return tileSize_; }
    std::uint64_t size() const;  // fragments stored
    bool empty() const { return size() == 0 && dropped() == 0; }
    std::uint64_t dropped() const;
    std::size_t bytesHeld() const;  // capacity of heads, pools and resolve scratch

    // The fragments of pixel (x, y) in submission order, oldest first (tests, the step mode).
    std::vector<Node> fragmentsAt(int x, int y) const;

    // resolveFragmentLists() for the lists of `target` (which must be this object's framebuffer),
    // telling the observer how each pixel was composited (fragment_lists_resolve.h defines it).
    template <class Observer>
    FragmentListStats resolve(Framebuffer& target, ThreadPool& pool, Observer& observer);

  private:
    // One fragment of the list being resolved: its sort key (depth, farthest first, then submission
    // order) and where its node is.
    struct Entry {
        std::uint64_t key;
        std::uint32_t node;
    };
    struct alignas(64) ResolveScratch {
        std::vector<Entry> entries;
        FragmentListStats stats;
    };

    std::size_t pixelIndex(int x, int y) const { return static_cast<std::size_t>(y) * width_ + x; }
    PixelRect tileRect(int tile) const;
    template <bool kLessIsNearer, ColorBufferFormat kColor, class Observer>
    void resolveTile(int tile, Framebuffer& target, ResolveScratch& scratch, Observer& observer) const;
    template <bool kLessIsNearer, ColorBufferFormat kColor, class Observer>
    void resolvePixel(int x, int y, const Node* nodes, std::uint32_t head, vec4& color,
                      ResolveScratch& scratch, std::vector<ResolvedFragment>& observed,
                      Observer& observer) const;
    template <bool kLessIsNearer, ColorBufferFormat kColor, class Observer>
    void resolveTiles(Framebuffer& target, ThreadPool& pool, Observer& observer);

    // Grows a full pool to nextCapacity() when the budget allows; false (and bytesRefused set) when not.
    bool grow(std::vector<Node>& nodes);

    std::uint64_t byteBudget_ = ~std::uint64_t{0};
    // Written by the threads of a draw at once: through std::atomic_ref.
    std::uint64_t nodeBytesHeld_ = 0;  // the pools' capacity, in bytes
    std::uint64_t refusedBytes_ = 0;
    int width_ = 0, height_ = 0;
    int tileSize_ = 0;
    int columns_ = 0, rows_ = 0;           // tiles across and down the framebuffer
    std::vector<std::uint32_t> heads_;     // per pixel, row-major: newest node in its tile's pool, or kEnd
    std::vector<TilePool> pools_;          // per tile, row-major
    std::vector<ResolveScratch> scratch_;  // per resolving thread
    DepthBufferFormat depthFormat_ = DepthBufferFormat::Float;
    ColorBufferFormat colorBuffer_ = ColorBufferFormat::Float;
};

// Composites every pixel's list over target's colour, tiles in parallel on the pool's threads: the list
// is sorted by window depth, largest (farthest, the Framebuffer's convention) first, equal depths in
// submission order, and each fragment is blended with its own mode: c = blend(mode, fragment, c).
// The lists are left as they are (clear them, or the framebuffer, before the next frame: resolving
// twice composites twice). Returns what the lists held and the memory they hold.
// resolveFragmentLists(target, pool, observer) (fragment_lists_resolve.h) does the same on the calling
// thread and shows every pixel's resolve to the observer (Observer::onResolve).
FragmentListStats resolveFragmentLists(Framebuffer& target, ThreadPool& pool);

}  // namespace facet
