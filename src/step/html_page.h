// The web page of the step-through teaching mode (facet step --html DIR): the images of the frame after
// each stage beside the history of any pixel the student clicks, offline, in one folder.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "step/screens.h"

namespace facet::step {

// What the page shows. The stage images are already in the folder (facet step --stages writes them);
// the page refers to them by file name.
struct HtmlPage {
    int width = 0, height = 0;       // the frame's size in pixels: a click on the image maps to a pixel
    std::string title;               // one line, the page's heading, like "spot_triangulated.obj"
    std::string commandLine;         // the command that made the page, shown so it can be run again
    std::vector<StageImage> stages;  // files already in the folder, pipeline order; id "final": the frame
    std::vector<Walk> walks;         // the traced pixels
    int gridStep = 1;                // pixels traced every gridStep in x and y (1: all)
    std::size_t firstWalk = 0;       // index into walks: the one shown when the page opens
};

// The names of the two files writeHtmlPage writes into the folder.
inline constexpr const char* kHtmlPageFile = "index.html";
inline constexpr const char* kHtmlDataFile = "trace-data.js";

// Writes DIR/index.html (the page, the same bytes for every trace: markup, CSS and script) and
// DIR/trace-data.js (the trace: a script assigning the global facetStepTrace, since a page opened from
// file:// cannot fetch JSON). Nothing is loaded from the network. Each distinct string (a screen's id,
// title or text, the heading --print writes above the screens) is stored once, and each distinct screen
// once; walks refer to them by number, so the screens of a triangle shared by many pixels cost their size
// once. Each file goes to a temporary name beside it and is renamed into place (writeTextFile): an open
// page never sees half a file. Creates DIR if needed. Throws InputError ("out/page/index.html: cannot
// write: ...") when the folder refuses the files.
void writeHtmlPage(const std::filesystem::path& dir, const HtmlPage& page);

}  // namespace facet::step
