// One pixel under two settings (facet step --versus): the two walks side by side, screen by screen,
// lines matched by a longest common subsequence, and the first line where they part marked.
#pragma once

#include <string>

#include "step/screens.h"

namespace facet::step {

// The two walks, `nameA` the left and `nameB` the right, stacked within 80 columns: each screen's lines
// under a gutter, blank for a line both have, '<' for the left's and '>' for the right's (a changed line
// shows both, the left's first); the first difference is marked '*' and named in the heading.
std::string sideBySide(const Walk& a, const std::string& nameA, const Walk& b, const std::string& nameB);

}  // namespace facet::step
