// The interactive terminal walk of facet step: one screen per stage, paged to the terminal's height,
// moved through with keys typed at a prompt. Keys are read a line at a time (each key, then Enter), so
// the walk needs no raw mode and works the same over ssh, in tmux and from a script.
//
// The walk is recorded once; going back and forth only redraws. A new pixel or triangle asks the
// command for a new walk (Retrace), which renders the frame again.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "step/screens.h"

namespace facet::step {

// What the user asked to trace next. `p X,Y` gives the pixel and no triangle (the command traces the
// triangle in front at that pixel, as `facet step --pixel X,Y` does); `t N` gives the triangle and the
// walk's current pixel (as `facet step --pixel X,Y --triangle N`).
struct WalkRequest {
    std::optional<std::pair<int, int>> pixel;
    std::optional<std::uint32_t> triangle;
};

// A new walk for another pixel or triangle (recorded afresh); throws facet::InputError with a
// message for the status line when the request is refused (pixel outside the image, no such triangle).
using Retrace = std::function<Walk(const WalkRequest&)>;

struct TerminalSize {
    int columns = 80, rows = 24;
};

// Shows the walk on `out` and reads keys from `in` until `q` or the end of the input; returns the
// program's exit status (0).
int runTerminalWalk(Walk walk, const Retrace& retrace, std::istream& in, std::ostream& out,
                    TerminalSize size);

// The size of the terminal on standard output, or 80×24 when it is not a terminal.
TerminalSize terminalSize();

// Whether standard input and standard output are both terminals, so that a walk can be interactive.
bool isInteractive();

// ---- The walk's state and its key handling, separate from the terminal so that tests can drive them.

// A view laid over the stage, closed by Enter.
enum class Overlay { none, stageList, help, notation };

struct WalkState {
    Walk walk;
    std::size_t stage = 0;  // index into walk.screens
    int page = 0;           // page of the stage's text shown, when it is longer than the terminal
    Overlay overlay = Overlay::none;
    int overlayPage = 0;
    std::string status;  // one line for the status bar, set by the last key; empty shows the verdict
    bool quit = false;
};

// Applies one line the user typed (without its newline). Calls `retrace` once for `p` or `t`; when it
// refuses (facet::InputError) the walk stays as it was and its message goes to the status line.
void applyKeys(WalkState& state, std::string_view line, const Retrace& retrace, TerminalSize size);

// The whole terminal frame for the state: clear the screen, the header (stage, pixel, triangle), the
// page of text, the status line, the keys and the prompt.
std::string drawFrame(const WalkState& state, TerminalSize size);

}  // namespace facet::step
