#include "step/terminal_walk.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <istream>
#include <ostream>
#include <vector>

#include "base/errors.h"
#include "step/notation.h"

namespace facet::step {
namespace {

// Plain ANSI (ECMA-48) control sequences, which every terminal and tmux understand.
constexpr std::string_view clearAndHome = "\x1b[2J\x1b[H";
constexpr std::string_view bold = "\x1b[1m";
constexpr std::string_view reverseVideo = "\x1b[7m";
constexpr std::string_view plain = "\x1b[0m";

// The frame around the text: the title (a line, or more when it is long), the pixel line and a rule
// above it; the status (a line or more: a message is wrapped, never cut), the keys and the prompt
// below it.
constexpr int fewestTextRows = 3;

// Columns a line takes on the terminal: one per UTF-8 code point (the screens use symbols like · and
// ≤, each one column wide), i.e. every byte that is not a continuation byte 10xxxxxx.
int displayWidth(std::string_view line) {
    return static_cast<int>(std::count_if(
        line.begin(), line.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

// Terminal rows a line fills: a line wider than the terminal wraps onto the next row.
int rowsOf(std::string_view line, int columns) {
    return std::max(1, (displayWidth(line) + columns - 1) / std::max(1, columns));
}

// A message as lines of at most `columns` code points, words kept whole (a word wider than the
// terminal split across lines): nothing of it is cut.
std::vector<std::string> wrappedLines(const std::string& message, int columns) {
    const std::size_t width = static_cast<std::size_t>(std::max(1, columns));
    std::vector<std::string> lines;
    const std::string wrapped = wrapText(message, width, 0);
    std::string_view rest = wrapped;
    while (!rest.empty()) {
        const std::size_t end = rest.find('\n');
        std::string_view line = rest.substr(0, end);
        rest = end == std::string_view::npos ? std::string_view() : rest.substr(end + 1);
        do {  // a word wider than the terminal: its pieces one after another
            std::size_t cut = line.size(), seen = 0;
            for (std::size_t i = 0; i < line.size(); ++i)
                if ((static_cast<unsigned char>(line[i]) & 0xC0) != 0x80 && seen++ == width) {
                    cut = i;
                    break;
                }
            lines.emplace_back(line.substr(0, cut));
            line.remove_prefix(cut);
        } while (!line.empty());
    }
    return lines;
}

// The line cut to at most `columns` code points, for the lines the walk writes itself.
std::string fitted(std::string_view line, int columns) {
    int width = 0;
    for (std::size_t i = 0; i < line.size(); ++i) {
        if ((static_cast<unsigned char>(line[i]) & 0xC0) != 0x80 && ++width > columns) {
            return std::string(line.substr(0, i));
        }
    }
    return std::string(line);
}

// The text cut into pages of whole lines that each fit in `rows` terminal rows (a single line taller
// than that is a page of its own). Always at least one page, empty for an empty text.
std::vector<std::vector<std::string_view>> pagesOf(std::string_view text, TerminalSize size, int rows) {
    std::vector<std::vector<std::string_view>> pages(1);
    int used = 0;
    for (std::string_view line : linesOf(text)) {
        const int needed = rowsOf(line, size.columns);
        if (used + needed > rows && !pages.back().empty()) {
            pages.emplace_back();
            used = 0;
        }
        pages.back().push_back(line);
        used += needed;
    }
    return pages;
}

std::string stageRange(const Walk& walk) {
    return "1-" + std::to_string(walk.screens.size());
}

std::string stageListText(const WalkState& state) {
    std::string text =
        "The stages of this walk, in pipeline order (> marks the one you are at).\n"
        "Type a stage's number or its short name in [ ] to go there.\n\n";
    for (std::size_t k = 0; k < state.walk.screens.size(); ++k) {
        const Screen& screen = state.walk.screens[k];
        text += (k == state.stage ? " > " : "   ") + std::to_string(k + 1) + ". " + screen.title + "  [" +
                screen.id + "]\n";
    }
    return text;
}

constexpr std::string_view helpText =
    "Type a key, then Enter.\n"
    "\n"
    "  Enter or n   the next page of this stage, or the next stage\n"
    "  b            back: the previous page, or the previous stage\n"
    "  3            stage 3 (any stage's number)\n"
    "  clip         the stage with that short name (l shows them in [ ])\n"
    "  l            the list of stages\n"
    "  p X,Y        trace another pixel, e.g. p 120,84: X counts columns from the\n"
    "               left, Y rows from the top; the triangle in front there is traced\n"
    "  t N          trace triangle N (numbered across the whole scene) at this pixel\n"
    "  ?            this help\n"
    "  ??           the notation: every symbol the screens print, what it means\n"
    "               and which screens print it (so does typing notation)\n"
    "  q            quit (so does Ctrl-D)\n"
    "\n"
    "The walk was recorded once, so going back and forth costs nothing; another\n"
    "pixel or triangle renders the frame again, then stays at the same stage.\n";

// The text the frame shows: the stage's, or the list or the help laid over it.
std::string shownText(const WalkState& state) {
    switch (state.overlay) {
        case Overlay::stageList:
            return stageListText(state);
        case Overlay::help:
            return std::string(helpText);
        case Overlay::notation:
            return notationText();
        case Overlay::none:
            break;
    }
    if (state.walk.screens.empty()) return "This trace has no stages to show.\n";
    return state.walk.screens[state.stage].text;
}

std::string titleLine(const WalkState& state);

// The status bar's message: the last key's, else the verdict.
std::string statusMessage(const WalkState& state) {
    return state.status.empty() ? state.walk.verdict : state.status;
}

// The rows of text a page has: the terminal's, less the title's lines, the pixel line, the rule, the
// status's lines, the keys and the prompt.
int textRows(const WalkState& state, TerminalSize size) {
    const int title = static_cast<int>(wrappedLines(titleLine(state), size.columns).size());
    const int status = static_cast<int>(wrappedLines(statusMessage(state), size.columns).size());
    return std::max(fewestTextRows, size.rows - title - 2 - status - 2);
}

int pageCount(const WalkState& state, TerminalSize size) {
    const std::string text = shownText(state);
    return static_cast<int>(pagesOf(text, size, textRows(state, size)).size());
}

int shownPage(const WalkState& state) {
    return state.overlay == Overlay::none ? state.page : state.overlayPage;
}

bool onLastStage(const WalkState& state) {
    return state.stage + 1 >= state.walk.screens.size();
}

std::string_view trimmed(std::string_view text) {
    const auto isSpace = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
    while (!text.empty() && isSpace(text.front()))
        text.remove_prefix(1);
    while (!text.empty() && isSpace(text.back()))
        text.remove_suffix(1);
    return text;
}

// A whole decimal number and nothing else, or none.
template <typename Integer>
std::optional<Integer> wholeNumber(std::string_view text) {
    text = trimmed(text);
    Integer value{};
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return value;
}

// "X,Y", "X, Y" or "X Y".
std::optional<std::pair<int, int>> pixelOf(std::string_view text) {
    text = trimmed(text);
    std::size_t split = text.find(',');
    if (split == std::string_view::npos) split = text.find(' ');
    if (split == std::string_view::npos) return std::nullopt;
    const auto x = wholeNumber<int>(text.substr(0, split));
    const auto y = wholeNumber<int>(text.substr(split + 1));
    if (!x || !y) return std::nullopt;
    return std::pair{*x, *y};
}

void goToStage(WalkState& state, std::size_t stage) {
    state.stage = stage;
    state.page = 0;
    state.overlay = Overlay::none;
}

void next(WalkState& state, TerminalSize size) {
    if (state.overlay != Overlay::none) {
        if (state.overlayPage + 1 < pageCount(state, size)) {
            ++state.overlayPage;
        } else {
            state.overlay = Overlay::none;
        }
    } else if (state.page + 1 < pageCount(state, size)) {
        ++state.page;
    } else if (!onLastStage(state)) {
        goToStage(state, state.stage + 1);
    } else {
        state.status = "This is the last stage: b goes back, a number jumps, q quits.";
    }
}

void back(WalkState& state) {
    if (state.overlay != Overlay::none) {
        state.overlay = Overlay::none;
    } else if (state.page > 0) {
        --state.page;
    } else if (state.stage > 0) {
        goToStage(state, state.stage - 1);
    } else {
        state.status = "This is the first stage: Enter goes on.";
    }
}

void jump(WalkState& state, std::size_t number) {
    if (number >= 1 && number <= state.walk.screens.size()) {
        goToStage(state, number - 1);
    } else {
        state.status = "There is no stage " + std::to_string(number) + ": the stages are " +
                       stageRange(state.walk) + " (l lists them).";
    }
}

// A new walk from `retrace`, at the stage with the same id when the new walk has one.
void retraceWalk(WalkState& state, const WalkRequest& request, const Retrace& retrace) {
    Walk walk;
    try {
        walk = retrace(request);
    } catch (const InputError& refusal) {
        state.status = refusal.what();
        return;
    }
    const std::string stageId = state.walk.screens.empty() ? "" : state.walk.screens[state.stage].id;
    const auto same = std::find_if(walk.screens.begin(), walk.screens.end(),
                                   [&](const Screen& screen) { return screen.id == stageId; });
    const bool hasStage = same != walk.screens.end();
    const auto sameStage = static_cast<std::size_t>(same - walk.screens.begin());
    state.walk = std::move(walk);
    goToStage(state, hasStage ? sameStage : 0);
    if (!hasStage && !stageId.empty()) {
        state.status = "This walk has no stage [" + stageId + "]: here is stage 1.";
    }
}

std::string pixelLine(const WalkState& state, int page, int pages) {
    const Walk& walk = state.walk;
    std::string line = "Pixel (" + std::to_string(walk.x) + ", " + std::to_string(walk.y) + "), ";
    line += walk.triangle ? "triangle " + std::to_string(walk.triangle->number) : "no triangle covers it";
    if (pages > 1) line += "; page " + std::to_string(page + 1) + " of " + std::to_string(pages);
    return line;
}

std::string titleLine(const WalkState& state) {
    switch (state.overlay) {
        case Overlay::stageList:
            return "The stages";
        case Overlay::help:
            return "Keys";
        case Overlay::notation:
            return "Notation: the symbols the screens print";
        case Overlay::none:
            break;
    }
    if (state.walk.screens.empty()) return "No stages";
    return "Stage " + std::to_string(state.stage + 1) + " of " + std::to_string(state.walk.screens.size()) +
           ": " + state.walk.screens[state.stage].title;
}

// The keys that do something now, in the order of the help; when they do not all fit the width, the
// least needed (in `keys`' order, most needed first) are left out.
std::string keysLine(const WalkState& state, bool morePages, TerminalSize size) {
    struct Key {
        int place;  // on the line
        std::string text;
    };
    std::vector<Key> keys;
    if (morePages) {
        keys.push_back({0, state.overlay == Overlay::none ? "Enter more of this stage" : "Enter more"});
    } else if (state.overlay != Overlay::none) {
        keys.push_back({0, "Enter back to stage " + std::to_string(state.stage + 1)});
    } else if (!onLastStage(state)) {
        keys.push_back({0, "Enter next"});
    }
    keys.push_back({8, "q quit"});
    if (state.overlay == Overlay::none) keys.push_back({1, "b back"});
    keys.push_back({2, stageRange(state.walk) + " stage"});
    keys.push_back({6, "? help"});
    keys.push_back({3, "p X,Y pixel"});
    keys.push_back({4, "t N triangle"});
    if (state.overlay != Overlay::stageList) keys.push_back({5, "l list"});
    // The notation is the least needed (the help names it too): shown where the line has room.
    if (state.overlay != Overlay::notation) keys.push_back({7, "?? symbols"});
    std::vector<Key> shown;
    int width = -2;
    for (const Key& key : keys) {
        if (width + 2 + displayWidth(key.text) > size.columns) continue;
        width += 2 + displayWidth(key.text);
        shown.push_back(key);
    }
    std::sort(shown.begin(), shown.end(), [](const Key& a, const Key& b) { return a.place < b.place; });
    std::string line;
    for (const Key& key : shown)
        line += (line.empty() ? "" : "  ") + key.text;
    return line;
}

}  // namespace

void applyKeys(WalkState& state, std::string_view line, const Retrace& retrace, TerminalSize size) {
    state.status.clear();
    line = trimmed(line);
    const std::string_view key = line.substr(0, 1);
    const std::string_view argument = line.empty() ? line : line.substr(1);
    if (line.empty() || line == "n" || line == "N") {
        next(state, size);
    } else if (line == "b" || line == "B") {
        back(state);
    } else if (line == "q" || line == "Q") {
        state.quit = true;
    } else if (line == "l" || line == "L") {
        state.overlay = Overlay::stageList;
        state.overlayPage = 0;
    } else if (line == "?" || line == "h") {
        state.overlay = Overlay::help;
        state.overlayPage = 0;
    } else if (line == "notation" || line == "??") {
        state.overlay = Overlay::notation;
        state.overlayPage = 0;
    } else if (const auto number = wholeNumber<std::size_t>(line)) {
        jump(state, *number);
    } else if (const auto same = std::find_if(state.walk.screens.begin(), state.walk.screens.end(),
                                              [&](const Screen& screen) { return screen.id == line; });
               same != state.walk.screens.end()) {
        goToStage(state, static_cast<std::size_t>(same - state.walk.screens.begin()));
    } else if (key == "p" || key == "P") {
        if (const auto pixel = pixelOf(argument)) {
            retraceWalk(state, WalkRequest{.pixel = pixel, .triangle = std::nullopt}, retrace);
        } else {
            state.status = "Type the pixel as p X,Y, for example p 120,84.";
        }
    } else if (key == "t" || key == "T") {
        if (const auto triangle = wholeNumber<std::uint32_t>(argument)) {
            retraceWalk(state,
                        WalkRequest{.pixel = std::pair{state.walk.x, state.walk.y}, .triangle = triangle},
                        retrace);
        } else {
            state.status = "Type the triangle as t N, for example t 5.";
        }
    } else {
        state.status = std::string(1, '"').append(line).append(
            "\" is not a key: Enter goes on, b back, ? lists the keys.");
    }
}

std::string drawFrame(const WalkState& state, TerminalSize size) {
    const std::string text = shownText(state);
    const int rows = textRows(state, size);
    const auto pages = pagesOf(text, size, rows);
    const int page = std::min(shownPage(state), static_cast<int>(pages.size()) - 1);
    const int pageTotal = static_cast<int>(pages.size());

    std::string frame(clearAndHome);
    for (const std::string& line : wrappedLines(titleLine(state), size.columns))
        frame += std::string(bold) + line + std::string(plain) + "\n";
    frame += fitted(pixelLine(state, page, pageTotal), size.columns) + "\n";
    frame += std::string(static_cast<std::size_t>(std::min(size.columns, 80)), '-') + "\n";
    int used = 0;
    for (std::string_view line : pages[static_cast<std::size_t>(page)]) {
        frame += std::string(line) + "\n";
        used += rowsOf(line, size.columns);
    }
    // Blank rows down to the status line, so that it and the keys stay at the bottom of the terminal.
    for (; used < rows; ++used)
        frame += "\n";
    for (std::string status : wrappedLines(statusMessage(state), size.columns)) {
        status +=
            std::string(static_cast<std::size_t>(std::max(0, size.columns - displayWidth(status))), ' ');
        frame += std::string(reverseVideo) + status + std::string(plain) + "\n";
    }
    frame += keysLine(state, page + 1 < pageTotal, size) + "\n";
    frame += "> ";
    return frame;
}

int runTerminalWalk(Walk walk, const Retrace& retrace, std::istream& in, std::ostream& out,
                    TerminalSize size) {
    WalkState state;
    state.walk = std::move(walk);
    std::string line;
    while (!state.quit) {
        out << drawFrame(state, size) << std::flush;
        if (!std::getline(in, line)) {
            out << "\n";  // the end of the input (Ctrl-D) left the cursor after the prompt
            break;
        }
        applyKeys(state, line, retrace, size);
    }
    return 0;
}

TerminalSize terminalSize() {
    winsize window{};
    if (ioctl(STDOUT_FILENO, TIOCGWINSZ, &window) == 0 && window.ws_col > 0 && window.ws_row > 0) {
        return {.columns = window.ws_col, .rows = window.ws_row};
    }
    return {};
}

bool isInteractive() {
    return isatty(STDIN_FILENO) == 1 && isatty(STDOUT_FILENO) == 1;
}

}  // namespace facet::step
