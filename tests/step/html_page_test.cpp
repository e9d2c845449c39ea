#include "step/html_page.h"

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "base/errors.h"
#include "step/notation.h"
#include "support/temp_folder.h"

namespace facet::step {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// The object a script of the page passes on: what follows `marker` up to the script's last `end`.
json scriptObject(const fs::path& file, const std::string& marker, char end) {
    const std::string script = readFile(file);
    const std::size_t begin = script.find(marker);
    const std::size_t stop = script.rfind(end);
    EXPECT_NE(begin, std::string::npos) << file << ": " << script.substr(0, 200);
    if (begin == std::string::npos || stop == std::string::npos) return json();
    return json::parse(script.substr(begin + marker.size(), stop - begin - marker.size()));
}

// The object trace-data.js assigns to window.facetStepTrace: the index.
json readTraceData(const fs::path& dir) {
    return scriptObject(dir / kHtmlDataFile, "window.facetStepTrace = ", ';');
}

// The tile trace-tiles/tile-C-R.js passes to facetStepTile.
json readTile(const fs::path& dir, int column, int row) {
    const std::string key = std::to_string(column) + "," + std::to_string(row);
    return scriptObject(
        dir / kHtmlTileFolder / ("tile-" + std::to_string(column) + "-" + std::to_string(row) + ".js"),
        "facetStepTile(\"" + key + "\", ", ')');
}

// A walk as the page's script rebuilds it from the index and a tile.
struct PageWalk {
    int x = 0, y = 0;
    std::optional<std::uint32_t> triangle;
    std::string heading;  // what --print writes above the screens
    std::vector<Screen> screens;
};

// Every walk of the page, the tiles in the index's order, each tile's walks in its order. Numbers below
// the index's count are the index's lines and screens, the others the tile's.
std::vector<PageWalk> walksFromPage(const fs::path& dir) {
    const json index = readTraceData(dir);
    std::vector<PageWalk> walks;
    for (const json& place : index["tiles"]) {
        const json tile = readTile(dir, place.at(0), place.at(1));
        const std::size_t sharedLines = index["lines"].size(), sharedScreens = index["screens"].size();
        const auto line = [&](const json& number) -> std::string {
            const std::size_t n = number.get<std::size_t>();
            return n < sharedLines ? index["lines"].at(n) : tile["lines"].at(n - sharedLines);
        };
        const auto screen = [&](const json& number) -> Screen {
            const std::size_t n = number.get<std::size_t>();
            const json& entry =
                n < sharedScreens ? index["screens"].at(n) : tile["screens"].at(n - sharedScreens);
            std::string text;
            for (std::size_t k = 0; k < entry.at(2).size(); ++k) {
                if (k) text += '\n';
                text += line(entry.at(2).at(k));
            }
            return {line(entry.at(0)), line(entry.at(1)), text};
        };
        for (const json& row : tile["walks"]) {
            PageWalk walk;
            walk.x = row.at(0);
            walk.y = row.at(1);
            if (!row.at(2).is_null()) walk.triangle = row.at(2).get<std::uint32_t>();
            walk.heading = screen(row.at(3)).text;
            for (const json& number : row.at(4))
                walk.screens.push_back(screen(number));
            walks.push_back(std::move(walk));
        }
    }
    return walks;
}

// The page shows what --print writes: the heading, then each screen's title and text.
void expectSameWalk(const PageWalk& shown, const Walk& walk) {
    EXPECT_EQ(shown.x, walk.x);
    EXPECT_EQ(shown.y, walk.y);
    EXPECT_EQ(shown.triangle, walk.triangle ? std::optional(walk.triangle->number) : std::nullopt);
    Walk withoutScreens = walk;
    withoutScreens.screens.clear();
    EXPECT_EQ(shown.heading, printWalk(withoutScreens));
    ASSERT_EQ(shown.screens.size(), walk.screens.size());
    for (std::size_t k = 0; k < walk.screens.size(); ++k) {
        EXPECT_EQ(shown.screens[k].id, walk.screens[k].id) << "screen " << k;
        EXPECT_EQ(shown.screens[k].title, walk.screens[k].title) << "screen " << k;
        EXPECT_EQ(shown.screens[k].text, walk.screens[k].text) << "screen " << k;
    }
}

Screen triangleScreen() {
    return {"clip", "Clipping: no plane cuts the triangle", "w = 1.5 > 0 at every vertex\n"};
}

HtmlPage twoWalkPage() {
    HtmlPage page;
    page.width = 4;
    page.height = 3;
    page.title = "tiny.obj";
    page.commandLine = "facet step tiny.obj --html out/page";
    page.stages = {
        {"clip", "Clipping", "stage-01-clip.png", "Every triangle, cut by the frustum."},
        {"final", "The final image", "stage-02-final.png", "The frame as facet render writes it."}};
    page.gridStep = 2;
    page.firstWalk = 1;
    Walk covered;
    covered.x = 2;
    covered.y = 1;
    covered.triangle = TriangleRef{7, 0, 7};
    covered.verdict = "triangle 7 wrote \"its\" colour";
    // Everything JSON or a script could trip on: quotes, backslashes, a closing script tag, U+2028,
    // the lecture's symbols.
    covered.screens = {triangleScreen(),
                       {"shade", "Shading: c = a⊗m + max(N·L, 0)",
                        "\"quoted\" \\ back\\slash </script> line\u2028separator\n\tα = 0.5, d² = 4\n"}};
    Walk background;
    background.x = 0;
    background.y = 0;
    background.verdict = "no triangle covers the pixel: the clear colour";
    background.screens = {{"history", "Pixel history", "no triangle's box holds the pixel\n"}};
    page.walks = {covered, background};
    return page;
}

class HtmlPageTest : public testing_support::TempFolderTest {};

// Catches: a field of the index, a stage, or any text of a walk (quotes, backslashes, </script>, U+2028)
// lost or changed between the walks given and what the page's script rebuilds from its files.
TEST_F(HtmlPageTest, TheFilesGiveBackEveryWalkAndStage) {
    HtmlPage page = twoWalkPage();
    page.region = PixelRect{1, 0, 2, 2};
    writeHtmlPage(folder_, page);
    const json data = readTraceData(folder_);
    EXPECT_EQ(data["width"], 4);
    EXPECT_EQ(data["height"], 3);
    EXPECT_EQ(data["title"], page.title);
    EXPECT_EQ(data["commandLine"], page.commandLine);
    EXPECT_EQ(data["gridStep"], 2);
    EXPECT_EQ(data["region"], json::parse("[1, 0, 2, 2]"));
    EXPECT_EQ(data["opening"], json::parse("[0, 0, 1]"));  // walk 1, the second of tile 0,0
    ASSERT_EQ(data["stages"].size(), 2u);
    EXPECT_EQ(data["stages"][1]["id"], "final");
    EXPECT_EQ(data["stages"][1]["file"], "stage-02-final.png");
    EXPECT_EQ(data["stages"][0]["title"], "Clipping");
    EXPECT_EQ(data["stages"][0]["description"], page.stages[0].description);

    const std::vector<PageWalk> walks = walksFromPage(folder_);
    ASSERT_EQ(walks.size(), page.walks.size());
    for (std::size_t n = 0; n < walks.size(); ++n) {
        SCOPED_TRACE("walk " + std::to_string(n));
        expectSameWalk(walks[n], page.walks[n]);
    }
}

// Catches: the traced triangle's window-space pieces (the outline the page draws) dropped, moved or
// keyed by the wrong triangle.
TEST_F(HtmlPageTest, TheIndexOutlinesEachTracedTriangle) {
    HtmlPage page = twoWalkPage();
    page.walks[0].windowPieces = {{{{0.5, 0.25}, {3.75, 1.0}, {1.0, 2.5}}},
                                  {{{1.0, 2.5}, {3.75, 1.0}, {4.0, 3.0}}}};
    writeHtmlPage(folder_, page);
    const json outlines = readTraceData(folder_)["outlines"];
    ASSERT_EQ(outlines.size(), 1u) << outlines;  // the background walk has no triangle
    EXPECT_EQ(outlines["7"],
              json::parse("[[[0.5, 0.25], [3.75, 1.0], [1.0, 2.5]], [[1.0, 2.5], [3.75, 1.0], [4.0, 3.0]]]"));
}

// Catches: a screen or a line of text stored again for each walk that shows it (the page's files growing
// with the walks' printed text), or a walk given back another walk's screens.
TEST_F(HtmlPageTest, EachDistinctScreenAndLineIsStoredOnce) {
    HtmlPage page = twoWalkPage();
    // Three more pixels of triangle 7 (its clipping screen again, each with its own shading) and two more
    // background pixels (the same screen as the first).
    for (int x = 0; x < 3; ++x) {
        Walk walk = page.walks[0];
        walk.x = x;
        walk.screens[1].text = "shading of pixel " + std::to_string(x) + "\nthe same second line\n";
        page.walks.push_back(walk);
    }
    page.walks.push_back(page.walks[1]);
    page.walks.push_back(page.walks[1]);
    writeHtmlPage(folder_, page);
    const json data = readTraceData(folder_);
    const json tile = readTile(folder_, 0, 0);  // the whole 4x3 image is one tile

    // Distinct screens: the clipping, four shadings, the background history, and the headings of the
    // four distinct pixels; every screen and line in the tile, since no other tile uses them.
    EXPECT_EQ(data["screens"].size() + tile["screens"].size(), 10u);
    EXPECT_TRUE(data["lines"].empty()) << data["lines"];
    std::multiset<std::string> lines;
    for (const json& text : tile["lines"])
        lines.insert(text.get<std::string>());
    EXPECT_EQ(lines.size(), tile["lines"].size());
    EXPECT_EQ(lines.count("the same second line"), 1u);
    EXPECT_EQ(lines.count("no triangle's box holds the pixel"), 1u);
    // And still every walk gets its own screens back.
    const std::vector<PageWalk> walks = walksFromPage(folder_);
    ASSERT_EQ(walks.size(), page.walks.size());
    for (std::size_t n = 0; n < walks.size(); ++n) {
        SCOPED_TRACE("walk " + std::to_string(n));
        expectSameWalk(walks[n], page.walks[n]);
    }
}

// Walks in two tiles: what both show is in the index once, what one shows only in its tile. Catches: the
// shared text written into every tile (the folder growing with the tiles), a tile's own text put in the
// index (which the page loads whole at once), or numbers into the two tables mixed up.
TEST_F(HtmlPageTest, WhatTwoTilesShareIsInTheIndexOnce) {
    HtmlPage page = twoWalkPage();
    page.width = 70;
    page.height = 40;
    Walk far = page.walks[0];  // triangle 7 again, at the next tile to the right, with its own shading
    far.x = 40;
    far.y = 33;
    far.screens[1].text = "only in tile 1,1\n";
    page.walks.push_back(far);
    writeHtmlPage(folder_, page);
    const json data = readTraceData(folder_);
    EXPECT_EQ(data["tileSize"], 32);
    EXPECT_EQ(data["tiles"], json::parse("[[0, 0], [1, 1]]"));
    const auto has = [](const json& lines, const std::string& line) {
        return std::find(lines.begin(), lines.end(), json(line)) != lines.end();
    };
    EXPECT_TRUE(has(data["lines"], "w = 1.5 > 0 at every vertex"));  // the clipping screen, in both tiles
    ASSERT_EQ(data["screens"].size(), 1u);                           // and that screen itself
    const json near = readTile(folder_, 0, 0), other = readTile(folder_, 1, 1);
    EXPECT_FALSE(has(near["lines"], "w = 1.5 > 0 at every vertex"));
    EXPECT_TRUE(has(other["lines"], "only in tile 1,1"));
    EXPECT_FALSE(has(data["lines"], "only in tile 1,1"));
    EXPECT_FALSE(has(near["lines"], "only in tile 1,1"));
    const std::vector<PageWalk> walks = walksFromPage(folder_);
    ASSERT_EQ(walks.size(), 3u);
    expectSameWalk(walks[0], page.walks[0]);
    expectSameWalk(walks[1], page.walks[1]);
    expectSameWalk(walks[2], far);
}

TEST_F(HtmlPageTest, WritesThePageAndItsDataAndNothingElse) {
    writeHtmlPage(folder_ / "page", twoWalkPage());
    std::set<std::string> files;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder_ / "page"))
        files.insert(entry.path().filename().string());
    EXPECT_EQ(files, (std::set<std::string>{"index.html", "trace-data.js", "trace-tiles"}));  // no temporary
    std::set<std::string> tiles;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder_ / "page" / kHtmlTileFolder))
        tiles.insert(entry.path().filename().string());
    EXPECT_EQ(tiles, (std::set<std::string>{"tile-0-0.js"}));

    const std::string html = readFile(folder_ / "page" / kHtmlPageFile);
    EXPECT_NE(html.find("<script src=\"" + std::string(kHtmlDataFile) + "\"></script>"), std::string::npos);
    // Offline: nothing fetched from a server, no CDN, no web font.
    for (const std::string& file : {html, readFile(folder_ / "page" / kHtmlDataFile),
                                    readFile(folder_ / "page" / kHtmlTileFolder / "tile-0-0.js")}) {
        EXPECT_EQ(file.find("http:"), std::string::npos);
        EXPECT_EQ(file.find("https:"), std::string::npos);
        EXPECT_EQ(file.find("@import"), std::string::npos);
        EXPECT_EQ(file.find("@font-face"), std::string::npos);
    }
}

TEST_F(HtmlPageTest, TextThatIsNotUtf8IsWrittenWithReplacementCharacters) {
    HtmlPage page = twoWalkPage();
    page.title = "caf\xe9.obj";  // a Latin-1 file name from the command line
    writeHtmlPage(folder_, page);
    EXPECT_EQ(readTraceData(folder_)["title"], "caf\uFFFD.obj");
}

TEST_F(HtmlPageTest, AFolderInTheWayIsAnInputErrorNamingTheFileAndLeavesNoTemporary) {
    fs::create_directories(folder_ / kHtmlPageFile / "something");
    try {
        writeHtmlPage(folder_, twoWalkPage());
        FAIL() << "expected an InputError";
    } catch (const InputError& error) {
        EXPECT_NE(std::string(error.what()).find((folder_ / kHtmlPageFile).string() + ": cannot write: "),
                  std::string::npos)
            << error.what();
    }
    std::set<std::string> files;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder_))
        files.insert(entry.path().filename().string());
    EXPECT_EQ(files, (std::set<std::string>{"index.html", "trace-data.js", "trace-tiles"}));
}

// Catches: the page's notation legend with no rows (the data without the table) or rows out of step
// with the notation the terminal shows, or the page without the legend's element.
TEST(HtmlPage, TheLegendListsTheNotation) {
    testing_support::TempFolder dir;
    HtmlPage page;
    page.width = page.height = 1;
    page.walks = {Walk{}};
    writeHtmlPage(dir.path(), page);
    const json data = readTraceData(dir.path());
    ASSERT_EQ(data["notation"].size(), notation().size());
    std::size_t row = 0;
    for (const Symbol& s : notation()) {
        EXPECT_EQ(data["notation"][row],
                  json::array({std::string(s.symbol), std::string(s.meaning), std::string(s.where)}));
        ++row;
    }
    EXPECT_NE(readFile(dir.path() / kHtmlPageFile).find("<details id=\"notation\""), std::string::npos);
}

}  // namespace
}  // namespace facet::step
