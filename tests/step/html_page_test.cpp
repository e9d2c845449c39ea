#include "step/html_page.h"

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

// The object trace-data.js assigns to window.facetStepTrace.
json readTraceData(const fs::path& dir) {
    const std::string script = readFile(dir / kHtmlDataFile);
    const std::string assignment = "window.facetStepTrace = ";
    const std::size_t begin = script.find(assignment);
    const std::size_t end = script.rfind(';');
    EXPECT_NE(begin, std::string::npos) << script.substr(0, 200);
    if (begin == std::string::npos || end == std::string::npos) return json();
    return json::parse(script.substr(begin + assignment.size(), end - begin - assignment.size()));
}

// A walk as the page's script rebuilds it from the numbered strings and screens.
struct PageWalk {
    int x = 0, y = 0;
    std::optional<std::uint32_t> triangle;
    std::string heading;  // what --print writes above the screens
    std::vector<Screen> screens;
};

std::vector<PageWalk> walksFromData(const json& data) {
    const auto text = [&](const json& number) { return data["strings"].at(number.get<std::size_t>()); };
    std::vector<PageWalk> walks;
    for (const json& row : data["walks"]) {
        PageWalk walk;
        walk.x = row.at(0);
        walk.y = row.at(1);
        if (!row.at(2).is_null()) walk.triangle = row.at(2).get<std::uint32_t>();
        walk.heading = text(row.at(3));
        for (const json& number : row.at(4)) {
            const json& screen = data["screens"].at(number.get<std::size_t>());
            walk.screens.push_back({text(screen.at(0)), text(screen.at(1)), text(screen.at(2))});
        }
        walks.push_back(std::move(walk));
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

TEST_F(HtmlPageTest, TheDataFileGivesBackEveryWalkAndStage) {
    const HtmlPage page = twoWalkPage();
    writeHtmlPage(folder_, page);
    const json data = readTraceData(folder_);
    EXPECT_EQ(data["width"], 4);
    EXPECT_EQ(data["height"], 3);
    EXPECT_EQ(data["title"], page.title);
    EXPECT_EQ(data["commandLine"], page.commandLine);
    EXPECT_EQ(data["gridStep"], 2);
    EXPECT_EQ(data["firstWalk"], 1);
    ASSERT_EQ(data["stages"].size(), 2u);
    EXPECT_EQ(data["stages"][1]["id"], "final");
    EXPECT_EQ(data["stages"][1]["file"], "stage-02-final.png");
    EXPECT_EQ(data["stages"][0]["title"], "Clipping");
    EXPECT_EQ(data["stages"][0]["description"], page.stages[0].description);

    const std::vector<PageWalk> walks = walksFromData(data);
    ASSERT_EQ(walks.size(), page.walks.size());
    for (std::size_t n = 0; n < walks.size(); ++n) {
        SCOPED_TRACE("walk " + std::to_string(n));
        expectSameWalk(walks[n], page.walks[n]);
    }
}

TEST_F(HtmlPageTest, EachDistinctScreenIsStoredOnce) {
    HtmlPage page = twoWalkPage();
    // Three more pixels of triangle 7 (its clipping screen again, each with its own shading) and two more
    // background pixels (the same screen as the first).
    for (int x = 0; x < 3; ++x) {
        Walk walk = page.walks[0];
        walk.x = x;
        walk.screens[1].text = "shading of pixel " + std::to_string(x) + "\n";
        page.walks.push_back(walk);
    }
    page.walks.push_back(page.walks[1]);
    page.walks.push_back(page.walks[1]);
    writeHtmlPage(folder_, page);
    const json data = readTraceData(folder_);

    // Distinct screens: the clipping, four shadings, the background history.
    EXPECT_EQ(data["screens"].size(), 6u);
    std::multiset<std::string> strings;
    for (const json& text : data["strings"])
        strings.insert(text.get<std::string>());
    EXPECT_EQ(strings.size(), data["strings"].size());
    EXPECT_EQ(strings.count(triangleScreen().text), 1u);
    EXPECT_EQ(strings.count("no triangle's box holds the pixel\n"), 1u);
    EXPECT_EQ(strings.count(walksFromData(data)[1].heading), 1u);  // three background walks at (0, 0)
    // And still every walk gets its own screens back.
    const std::vector<PageWalk> walks = walksFromData(data);
    ASSERT_EQ(walks.size(), page.walks.size());
    for (std::size_t n = 0; n < walks.size(); ++n) {
        SCOPED_TRACE("walk " + std::to_string(n));
        expectSameWalk(walks[n], page.walks[n]);
    }
}

TEST_F(HtmlPageTest, WritesThePageAndItsDataAndNothingElse) {
    writeHtmlPage(folder_ / "page", twoWalkPage());
    std::set<std::string> files;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder_ / "page"))
        files.insert(entry.path().filename().string());
    EXPECT_EQ(files, (std::set<std::string>{"index.html", "trace-data.js"}));  // no temporary left behind

    const std::string html = readFile(folder_ / "page" / kHtmlPageFile);
    EXPECT_NE(html.find("<script src=\"" + std::string(kHtmlDataFile) + "\"></script>"), std::string::npos);
    // Offline: nothing fetched from a server, no CDN, no web font.
    for (const std::string& file : {html, readFile(folder_ / "page" / kHtmlDataFile)}) {
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
    EXPECT_EQ(files, (std::set<std::string>{"index.html", "trace-data.js"}));
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
