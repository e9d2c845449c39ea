// One pixel under two settings (facet step --versus): the two walks side by side, screen by screen,
// lines matched by a longest common subsequence, and the first line where they part marked.
#pragma once

#include <string>

#include "step/screens.h"

namespace facet::step {

// Two columns, `nameA` on the left and `nameB` on the right, each as wide as its longest line. The
// gutter between them: ' ' the same line, '|' a changed line, '<' a line only on the left, '>' only on
// the right; the first difference is marked '*' and named in the heading.
std::string sideBySide(const Walk& a, const std::string& nameA, const Walk& b, const std::string& nameB);

}  // namespace facet::step
