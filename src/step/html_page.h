// The web page of the step-through teaching mode (facet step --html DIR): the images of the frame after
// each stage beside the history of any pixel the student clicks, offline, in one folder.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "step/screens.h"

namespace facet::step {

// A rectangle of pixels: x, y its top-left pixel (y down), width × height pixels.
struct PixelRect {
    int x = 0, y = 0, width = 0, height = 0;
    bool contains(int px, int py) const { return px >= x && py >= y && px < x + width && py < y + height; }
};

struct HtmlPage;

// The walks of a page, held compactly while they are added: each distinct line of text once, each
// distinct screen once, each walk as numbers into them. A page of 100 000 walks (whose text would be
// gigabytes) thus fits in memory; add() copies what it needs, so a Walk can be dropped after it.
class PageWalks {
  public:
    // Walks of an image `imageWidth` pixels wide, written to one file per tileSize × tileSize pixels.
    explicit PageWalks(int imageWidth, int tileSize = 32)
        : tileSize_(tileSize), tileColumns_((imageWidth + tileSize - 1) / tileSize) {}
    void add(const Walk& walk);
    std::size_t size() const { return places_.size(); }
    int tileSize() const { return tileSize_; }

  private:
    friend class PageWriter;
    friend void writeHtmlPage(const std::filesystem::path&, const HtmlPage&, const PageWalks&);
    struct CompactWalk {
        int x = 0, y = 0;
        std::optional<std::uint32_t> triangle;
        std::size_t heading = 0;           // a screen number: the lines --print writes above the screens
        std::vector<std::size_t> screens;  // screen numbers
    };
    struct Usage {  // in which tiles an item is used: one, or more than one (then it goes to the index)
        std::int64_t lastTile = -1;
        bool shared = false;
        bool use(std::int64_t tile);  // true the first time in this tile
    };
    std::size_t lineNumber(std::string_view line);
    std::size_t screenNumber(const std::string& id, const std::string& title, const std::string& text);
    void useScreen(std::size_t screen, std::int64_t tile);

    int tileSize_;
    int tileColumns_;
    std::deque<std::string> lines_;  // owns the text the map's keys view
    std::unordered_map<std::string_view, std::size_t> lineNumbers_;
    std::vector<Usage> lineUsage_;
    std::vector<std::vector<std::size_t>> screens_;  // [id line, title line, text lines...]
    std::map<std::vector<std::size_t>, std::size_t> screenNumbers_;
    std::vector<Usage> screenUsage_;
    std::map<std::int64_t, std::vector<CompactWalk>> tiles_;    // tile number (row-major) → its walks
    std::vector<std::pair<std::int64_t, std::size_t>> places_;  // walk number → tile, index in the tile
    std::map<std::uint32_t, std::vector<std::array<std::array<double, 2>, 3>>> outlines_;  // per triangle
};

// What the page shows. The stage images are already in the folder (facet step --stages writes them);
// the page refers to them by file name.
struct HtmlPage {
    int width = 0, height = 0;        // the frame's size in pixels: a click on the image maps to a pixel
    std::string title;                // one line, the page's heading, like "spot_triangulated.obj"
    std::string commandLine;          // the command that made the page, shown so it can be run again
    std::vector<StageImage> stages;   // files already in the folder, pipeline order; id "final": the frame
    int gridStep = 1;                 // pixels traced every gridStep in x and y from gridStep/2 (1: all)
    std::optional<PixelRect> region;  // traced in full besides the grid (--html-region)
    std::vector<Walk> walks;          // the traced pixels: the grid's in row order, then the region's
    std::size_t firstWalk = 0;        // index into walks: the one shown when the page opens
};

// The names of what writeHtmlPage writes into the folder: the page, its index of the trace, and the
// folder of the trace's tiles.
inline constexpr const char* kHtmlPageFile = "index.html";
inline constexpr const char* kHtmlDataFile = "trace-data.js";
inline constexpr const char* kHtmlTileFolder = "trace-tiles";

// Writes DIR/index.html (the page, the same bytes for every trace: markup, CSS and script),
// DIR/trace-tiles/tile-TX-TY.js (the walks of the pixels of one tile, which the page loads when a pixel
// of it is clicked) and DIR/trace-data.js (the index: the stages, which pixels are traced, and the lines
// and screens more than one tile uses). The files are scripts, since a page opened from file:// cannot
// fetch JSON; nothing is loaded from the network. index.html describes the format. Each file goes to a
// temporary name beside it and is renamed into place (writeTextFile), the tiles first and the page last:
// an open page never sees half a file. Creates DIR if needed. Throws InputError ("out/page/index.html:
// cannot write: ...") when the folder refuses the files.
void writeHtmlPage(const std::filesystem::path& dir, const HtmlPage& page);

// The same with the walks already added to `walks` (page.walks is ignored; page.firstWalk numbers the
// walks in the order they were added): what facet step uses, tracing a batch of pixels at a time.
void writeHtmlPage(const std::filesystem::path& dir, const HtmlPage& page, const PageWalks& walks);

}  // namespace facet::step
