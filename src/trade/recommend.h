// facet trade's one line per knob: what each of the knob's values did to the error and the time of a
// finished trade, in words taken from the run's own verdicts only ("--aa: msaa2 gives half the error
// for 1.7× the time; ..."), and what to do about it where the verdicts decide it ("keep phong").
#pragma once

#include <string>
#include <vector>

#include "trade/trade.h"

namespace facet {

// One line per knob traded in `result` (rows of the baseline and the presets are not knobs), in the
// order the knobs were run. A time is named only with a Faster or Slower verdict (never within the
// noise); an error is named better or worse only outside the reference's own error; a blank image, a
// content-changing value and a value without effect are said as such, never ranked.
std::vector<std::string> tradeRecommendations(const TradeResult& result);

}  // namespace facet
