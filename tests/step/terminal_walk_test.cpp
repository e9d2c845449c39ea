#include "step/terminal_walk.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "base/errors.h"
#include "step/notation.h"

namespace facet::step {
namespace {

constexpr std::string_view clearAndHome = "\x1b[2J\x1b[H";

Walk threeStages() {
    Walk walk;
    walk.x = 3;
    walk.y = 4;
    walk.triangle = TriangleRef{.number = 2, .draw = 0, .triangle = 2};
    walk.verdict = "triangle 2 wrote the colour";
    walk.screens = {{"clip", "Clipping", "no plane cuts it\n"},
                    {"history", "Pixel history", "one triangle\n"},
                    {"shade", "Shading", "the lighting equation\n"}};
    return walk;
}

// The same stages in another order, as a walk for pixel (5, 6) would show them.
Walk reorderedAtFiveSix() {
    Walk walk = threeStages();
    walk.x = 5;
    walk.y = 6;
    walk.verdict = "the background shows";
    std::reverse(walk.screens.begin(), walk.screens.end());  // shade, history, clip
    std::swap(walk.screens[1], walk.screens[2]);             // shade, clip, history
    walk.screens[2].text = "no triangle here\n";
    return walk;
}

struct Session {
    std::vector<std::string> frames;  // every frame drawn, in order
    std::vector<WalkRequest> requests;
    int status = -1;
    const std::string& last() const { return frames.back(); }
};

Session run(Walk walk, const std::string& keys, const Retrace& retrace, TerminalSize size = {}) {
    Session session;
    std::istringstream in(keys);
    std::ostringstream out;
    const Retrace recording = [&](const WalkRequest& request) {
        session.requests.push_back(request);
        return retrace(request);
    };
    session.status = runTerminalWalk(std::move(walk), recording, in, out, size);
    const std::string text = out.str();
    for (std::size_t start = text.find(clearAndHome); start != std::string::npos;) {
        const std::size_t end = text.find(clearAndHome, start + 1);
        session.frames.push_back(text.substr(start, end == std::string::npos ? end : end - start));
        start = end;
    }
    return session;
}

Session run(const std::string& keys, TerminalSize size = {}) {
    return run(
        threeStages(), keys, [](const WalkRequest&) -> Walk { throw std::logic_error("no retrace"); }, size);
}

bool shows(const std::string& frame, std::string_view text) {
    return frame.find(text) != std::string::npos;
}

TEST(TerminalWalk, StartsAtTheFirstStageWithPixelTriangleAndVerdict) {
    const Session session = run("");
    ASSERT_EQ(session.frames.size(), 1u);
    EXPECT_TRUE(shows(session.last(), "Stage 1 of 3: Clipping"));
    EXPECT_TRUE(shows(session.last(), "Pixel (3, 4), triangle 2"));
    EXPECT_TRUE(shows(session.last(), "no plane cuts it\n"));
    EXPECT_TRUE(shows(session.last(), "triangle 2 wrote the colour"));  // the status line
}

TEST(TerminalWalk, EnterAndNGoToTheNextStage) {
    EXPECT_TRUE(shows(run("\n").last(), "Stage 2 of 3: Pixel history"));
    const Session session = run("\nn\n");
    EXPECT_TRUE(shows(session.last(), "Stage 3 of 3: Shading"));
    EXPECT_TRUE(shows(session.last(), "the lighting equation\n"));
}

TEST(TerminalWalk, EnterOnTheLastStageStaysAndSaysSo) {
    const Session session = run("3\n\n");
    EXPECT_TRUE(shows(session.last(), "Stage 3 of 3: Shading"));
    EXPECT_TRUE(shows(session.last(), "This is the last stage"));
}

TEST(TerminalWalk, BackGoesToThePreviousStageAndStopsAtTheFirst) {
    EXPECT_TRUE(shows(run("\n\nb\n").last(), "Stage 2 of 3: Pixel history"));
    const Session session = run("b\n");
    EXPECT_TRUE(shows(session.last(), "Stage 1 of 3: Clipping"));
    EXPECT_TRUE(shows(session.last(), "This is the first stage"));
}

TEST(TerminalWalk, ANumberOrAShortNameJumpsToThatStage) {
    EXPECT_TRUE(shows(run("3\n").last(), "Stage 3 of 3: Shading"));
    EXPECT_TRUE(shows(run("3\nb\n").last(), "Stage 2 of 3: Pixel history"));
    EXPECT_TRUE(shows(run("history\n").last(), "Stage 2 of 3: Pixel history"));
    const Session outside = run("2\n4\n");
    EXPECT_TRUE(shows(outside.last(), "Stage 2 of 3: Pixel history"));
    EXPECT_TRUE(shows(outside.last(), "There is no stage 4: the stages are 1-3"));
}

TEST(TerminalWalk, AnotherPixelRetracesOnceAndKeepsTheStage) {
    const Session session =
        run(threeStages(), "2\np 5,6\nb\n", [](const WalkRequest&) { return reorderedAtFiveSix(); });
    ASSERT_EQ(session.requests.size(), 1u);  // going back and forth afterwards costs no trace
    EXPECT_EQ(session.requests[0].pixel, std::pair(5, 6));
    EXPECT_FALSE(session.requests[0].triangle);
    // The frame right after `p`: the same stage (history), now the new walk's last.
    const std::string& afterPixel = session.frames[2];
    EXPECT_TRUE(shows(afterPixel, "Stage 3 of 3: Pixel history"));
    EXPECT_TRUE(shows(afterPixel, "Pixel (5, 6), triangle 2"));
    EXPECT_TRUE(shows(afterPixel, "no triangle here\n"));
    EXPECT_TRUE(shows(afterPixel, "the background shows"));
    EXPECT_TRUE(shows(session.last(), "Stage 2 of 3: Clipping"));
}

TEST(TerminalWalk, ANewWalkWithoutTheStageStartsAtItsFirst) {
    Walk other = threeStages();
    other.screens.erase(other.screens.begin() + 1);  // no "history"
    const Session session = run(threeStages(), "2\np 5 6\n", [&](const WalkRequest&) { return other; });
    ASSERT_EQ(session.requests.size(), 1u);
    EXPECT_EQ(session.requests[0].pixel, std::pair(5, 6));
    EXPECT_TRUE(shows(session.last(), "Stage 1 of 2: Clipping"));
    EXPECT_TRUE(shows(session.last(), "This walk has no stage [history]"));
}

TEST(TerminalWalk, AnotherTriangleIsTracedAtTheSamePixel) {
    Walk seven = threeStages();
    seven.triangle = TriangleRef{.number = 7, .draw = 1, .triangle = 3};
    const Session session = run(threeStages(), "3\nt 7\n", [&](const WalkRequest&) { return seven; });
    ASSERT_EQ(session.requests.size(), 1u);
    EXPECT_EQ(session.requests[0].triangle, 7u);
    EXPECT_EQ(session.requests[0].pixel, std::pair(3, 4));
    EXPECT_TRUE(shows(session.last(), "Pixel (3, 4), triangle 7"));
    EXPECT_TRUE(shows(session.last(), "Stage 3 of 3: Shading"));
}

TEST(TerminalWalk, ARefusedRequestKeepsTheWalkAndShowsWhy) {
    const Session session = run(threeStages(), "2\np 900,5\n", [](const WalkRequest&) -> Walk {
        throw InputError("pixel (900, 5) is outside the 800x600 image");
    });
    ASSERT_EQ(session.requests.size(), 1u);
    EXPECT_TRUE(shows(session.last(), "\x1b[7mpixel (900, 5) is outside the 800x600 image"));
    EXPECT_TRUE(shows(session.last(), "Stage 2 of 3: Pixel history"));
    EXPECT_TRUE(shows(session.last(), "Pixel (3, 4), triangle 2"));
}

TEST(TerminalWalk, AMalformedPixelOrTriangleAsksForTheFormWithoutRetracing) {
    const Session pixel = run("p 5\n");
    EXPECT_TRUE(pixel.requests.empty());
    EXPECT_TRUE(shows(pixel.last(), "Type the pixel as p X,Y"));
    const Session triangle = run("t x\n");
    EXPECT_TRUE(triangle.requests.empty());
    EXPECT_TRUE(shows(triangle.last(), "Type the triangle as t N"));
}

TEST(TerminalWalk, QuitAndTheEndOfInputEndTheWalk) {
    const Session quit = run("\nq\n\n\n");
    EXPECT_EQ(quit.status, 0);
    EXPECT_EQ(quit.frames.size(), 2u);  // no frame after q, and the Enters after it are not read
    const Session end = run("n");       // a last line without its newline, then the end
    EXPECT_EQ(end.status, 0);
    EXPECT_EQ(end.frames.size(), 2u);
    EXPECT_TRUE(shows(end.last(), "Stage 2 of 3"));
}

TEST(TerminalWalk, UnknownInputGivesAHintAndChangesNothingElse) {
    WalkState state;
    state.walk = threeStages();
    state.stage = 1;
    applyKeys(state, "zz", nullptr, {});
    EXPECT_EQ(state.stage, 1u);
    EXPECT_EQ(state.page, 0);
    EXPECT_EQ(state.overlay, Overlay::none);
    EXPECT_FALSE(state.quit);
    EXPECT_EQ(state.status, "\"zz\" is not a key: Enter goes on, b back, ? lists the keys.");
    // The next key clears the hint.
    applyKeys(state, "b", nullptr, {});
    EXPECT_EQ(state.stage, 0u);
    EXPECT_EQ(state.status, "");
}

Walk withLongFirstScreen(int lines) {
    Walk walk = threeStages();
    walk.screens[0].text.clear();
    for (int line = 1; line <= lines; ++line)
        walk.screens[0].text += "line " + std::to_string(line) + "\n";
    return walk;
}

TEST(TerminalWalk, AScreenTallerThanTheTerminalIsShownInPages) {
    // 24 rows: two header lines and a rule, then 18 rows of text, then status, keys and prompt.
    const Retrace none = [](const WalkRequest&) -> Walk { throw std::logic_error("no retrace"); };
    const Session session = run(withLongFirstScreen(40), "\n\nb\n\n\n\n", none, {.columns = 80, .rows = 24});
    ASSERT_EQ(session.frames.size(), 7u);
    const std::string& first = session.frames[0];
    EXPECT_TRUE(shows(first, "line 18\n"));
    EXPECT_FALSE(shows(first, "line 19\n"));
    EXPECT_TRUE(shows(first, "page 1 of 3"));
    EXPECT_TRUE(shows(first, "Enter more of this stage"));
    const std::string& second = session.frames[1];
    EXPECT_TRUE(shows(second, "Stage 1 of 3: Clipping"));
    EXPECT_TRUE(shows(second, "\nline 19\n"));
    EXPECT_FALSE(shows(second, "line 18\n"));
    EXPECT_TRUE(shows(session.frames[2], "\nline 37\n"));  // page 3
    EXPECT_TRUE(shows(session.frames[3], "\nline 19\n"));  // b: back a page
    EXPECT_TRUE(shows(session.frames[4], "line 40\n"));
    EXPECT_TRUE(shows(session.frames[4], "Enter next"));
    EXPECT_TRUE(shows(session.frames[5], "Stage 2 of 3: Pixel history"));
}

TEST(TerminalWalk, EveryFrameFillsTheTerminalExactly) {
    // A line twice the width takes two rows; the prompt is the last row, without a newline.
    Walk walk = withLongFirstScreen(30);
    walk.screens[0].text = std::string(120, 'x') + "\n" + walk.screens[0].text;
    const Retrace none = [](const WalkRequest&) -> Walk { throw std::logic_error("no retrace"); };
    for (const TerminalSize size : {TerminalSize{80, 24}, TerminalSize{60, 30}, TerminalSize{100, 50}}) {
        const Session session = run(walk, "\n\n\nl\n?\n", none, size);
        for (std::string frame : session.frames) {
            if (frame.ends_with("> \n")) frame.pop_back();  // the newline at the end of the input
            int rows = 1;
            std::size_t start = clearAndHome.size();
            for (std::size_t end; (end = frame.find('\n', start)) != std::string::npos; start = end + 1) {
                std::string line = frame.substr(start, end - start);
                for (const auto code : {"\x1b[1m", "\x1b[7m", "\x1b[0m"}) {
                    for (std::size_t at; (at = line.find(code)) != std::string::npos;)
                        line.erase(at, 4);
                }
                rows += std::max<int>(1, (static_cast<int>(line.size()) + size.columns - 1) / size.columns);
            }
            EXPECT_EQ(rows, size.rows) << frame;
            EXPECT_EQ(frame.substr(frame.size() - 3), "\n> ");
        }
    }
}

// The frame's lines without the colour codes, and the status bar's (reverse video) joined by spaces.
struct FrameLines {
    std::vector<std::string> lines;
    std::string status;
};

FrameLines frameLines(const std::string& frame) {
    FrameLines result;
    std::string_view rest(frame);
    rest.remove_prefix(clearAndHome.size());
    while (!rest.empty()) {
        const std::size_t end = rest.find('\n');
        std::string line(rest.substr(0, end));
        rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
        const bool status = line.starts_with("\x1b[7m");
        for (const auto code : {"\x1b[1m", "\x1b[7m", "\x1b[0m"})
            for (std::size_t at; (at = line.find(code)) != std::string::npos;)
                line.erase(at, 4);
        if (status) {
            const std::size_t last = line.find_last_not_of(' ');
            if (!result.status.empty()) result.status += ' ';
            result.status.append(line, 0, last + 1);
        }
        result.lines.push_back(line);
    }
    return result;
}

// A refusal longer than the terminal is wide, in the status bar: wrapped over as many lines as it
// needs, each within the width, the page shorter by as many, the frame still the terminal's height.
// Catches: the bar cutting its message ("… y from 0 t"), a wrapped bar pushing the frame past the
// terminal's last row.
TEST(TerminalWalk, ALongMessageWrapsInTheStatusBarWithoutBeingCut) {
    // The refusal traceStep (step/walk.h) gives for a pixel outside a 160x120 image.
    const std::string refusal =
        "pixel 99999,5 is outside the image, which is 160x120 (x from 0 to 159, y from 0 to 119, y down)";
    const Retrace refuse = [&](const WalkRequest&) -> Walk { throw InputError(refusal); };
    for (const TerminalSize size : {TerminalSize{80, 24}, TerminalSize{40, 24}, TerminalSize{24, 24}}) {
        SCOPED_TRACE(size.columns);
        const Session session = run(withLongFirstScreen(40), "p 99999,5\n", refuse, size);
        const FrameLines frame = frameLines(session.last());
        EXPECT_EQ(frame.status, refusal);
        for (const std::string& line : frame.lines)
            EXPECT_LE(line.size(), static_cast<std::size_t>(size.columns)) << line;
        EXPECT_EQ(static_cast<int>(frame.lines.size()), size.rows);  // the prompt's row last
        EXPECT_TRUE(frame.lines.back().starts_with("> "));
        // The page gave the status its rows: fewer lines of the stage than under a one-line verdict.
        const FrameLines before = frameLines(session.frames.front());
        const auto stageLines = [](const FrameLines& f) {
            return std::count_if(f.lines.begin(), f.lines.end(),
                                 [](const std::string& l) { return l.starts_with("line "); });
        };
        EXPECT_LT(stageLines(frame), stageLines(before));
    }
}

// A stage's title longer than the terminal is wide is wrapped in the header, not cut. Catches: the
// header cutting the title at the terminal's width.
TEST(TerminalWalk, ALongTitleWrapsInTheHeader) {
    Walk walk = threeStages();
    walk.screens[0].title = "Clipping: left+right+bottom+top+near+w cut the triangle into five pieces";
    const Retrace none = [](const WalkRequest&) -> Walk { throw std::logic_error("no retrace"); };
    const Session session = run(walk, "", none, {.columns = 40, .rows = 24});
    const FrameLines frame = frameLines(session.last());
    std::string header;
    for (std::size_t k = 0; k < frame.lines.size() && !frame.lines[k].starts_with("Pixel ("); ++k)
        header += (header.empty() ? "" : " ") + frame.lines[k];
    EXPECT_EQ(header, "Stage 1 of 3: " + walk.screens[0].title);
    EXPECT_EQ(static_cast<int>(frame.lines.size()), 24);
}

TEST(TerminalWalk, TheListShowsEveryStageAndEnterReturnsToTheSameStage) {
    const Session session = run("2\nl\n\n");
    const std::string& list = session.frames[2];
    EXPECT_TRUE(shows(list, "   1. Clipping  [clip]\n"));
    EXPECT_TRUE(shows(list, " > 2. Pixel history  [history]\n"));
    EXPECT_TRUE(shows(list, "   3. Shading  [shade]\n"));
    EXPECT_TRUE(shows(session.last(), "Stage 2 of 3: Pixel history"));
    EXPECT_TRUE(shows(run("l\n3\n").last(), "Stage 3 of 3: Shading"));
}

TEST(TerminalWalk, HelpNamesEveryKey) {
    const Session session = run("?\n");
    for (const char* key :
         {"\n  Enter or n ", "\n  b ", "\n  3 ", "\n  l ", "\n  p X,Y ", "\n  t N ", "\n  ? ", "\n  q "}) {
        EXPECT_TRUE(shows(session.last(), key)) << key;
    }
    EXPECT_TRUE(shows(run("?\n\n").last(), "Stage 1 of 3: Clipping"));
}

// Catches: the notation unreachable from the walk (?? or notation ignored, or showing other text), a
// symbol of the table missing from it, or the help not naming the key.
TEST(TerminalWalk, DoubleQuestionMarkOrNotationShowsTheNotation) {
    const TerminalSize tall{.columns = 80, .rows = 400};  // the whole notation on one page
    for (const char* key : {"??\n", "notation\n"}) {
        const Session session = run(key, tall);
        EXPECT_TRUE(shows(session.last(), "Notation: the symbols the screens print")) << key;
        for (const Symbol& symbol : notation())
            EXPECT_TRUE(shows(session.last(), "\n  " + std::string(symbol.symbol) + "\n")) << symbol.symbol;
    }
    EXPECT_TRUE(shows(run("?\n").last(), "\n  ??  "));
    EXPECT_TRUE(shows(run("??\n\n", tall).last(), "Stage 1 of 3: Clipping"));
}

}  // namespace
}  // namespace facet::step
