// The trade's fast and best presets, made from the run's own measurements and checked against them:
// fast is never slower than the baseline, best never less accurate than the most accurate single
// setting. A preset sets only the knobs traded in the run (--knobs): a knob never timed or scored here
// is left as the scene has it.
#pragma once

#include <string>
#include <vector>

#include "trade/knobs.h"
#include "trade/trade.h"

namespace facet {

// The names of the knobs not in `traded`: what every preset leaves as the scene has it.
std::vector<std::string> knobsNotTraded(const std::vector<const Knob*>& traded);

// Preset `name` ("fast" or "best") from the knobs' rows (`measured`: the baseline first, timeVerdict
// and error filled): a traded knob gets its fast value only where that row measured Faster, its best
// value only where that row measured more accurate than the baseline (and not within the reference's
// own error); never from a row without effect, a blank one or one that changes the scene's content.
// `notes` gets a line for each traded knob left out, saying why. A knob whose preset value the
// baseline already has (no row) is left out silently: the scene has it.
TradeSetting choosePreset(const std::string& name, const std::vector<TradeRow>& measured,
                          const std::vector<const Knob*>& traded, std::vector<std::string>& notes);

// Checks the timed presets against the single settings (result.rows with final verdicts): a fast
// preset not measured Faster than the baseline becomes the fastest single setting measured Faster (its
// row's numbers), or is dropped when there is none; a best preset less accurate than the most accurate
// single setting becomes that setting, or is dropped when that is the baseline. A preset row whose
// setting has no words (no knob chose it) is dropped. Last, a preset that a single setting beats on
// both counts (as fast within 1 + 2·timeNoise, as accurate within referenceFloor, better in one)
// becomes that setting: fast the fastest such, best the most accurate. Each change gets a note.
void keepPresetPromises(TradeResult& result);

}  // namespace facet
