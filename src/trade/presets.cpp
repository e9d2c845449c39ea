#include "trade/presets.h"

#include <algorithm>
#include <cstdio>

#include "trade/time_verdicts.h"

namespace facet {

namespace {

std::string ms(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f ms", value);
    return text;
}

std::string errorText(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", value);
    return text;
}

bool isSingleKnob(const TradeRow& row) {
    return row.setting.knob != "baseline" && row.setting.knob != "preset";
}

// The row of the preset `name`, or end.
std::vector<TradeRow>::iterator presetRow(std::vector<TradeRow>& rows, const std::string& name) {
    return std::find_if(rows.begin(), rows.end(), [&](const TradeRow& row) {
        return row.setting.knob == "preset" && row.setting.value == name;
    });
}

// The preset's row becomes `chosen`'s numbers and words: the single setting whose measurements keep
// the preset's promise.
void replaceWith(TradeRow& preset, const TradeRow& chosen) {
    TradeSetting setting = preset.setting;
    setting.words = chosen.setting.words;
    preset = chosen;
    preset.setting = setting;
}

}  // namespace

std::vector<std::string> knobsNotTraded(const std::vector<const Knob*>& traded) {
    std::vector<std::string> names;
    for (const Knob& knob : knobTable())
        if (std::find(traded.begin(), traded.end(), &knob) == traded.end()) names.push_back(knob.name);
    return names;
}

TradeSetting choosePreset(const std::string& name, const std::vector<TradeRow>& measured,
                          const std::vector<const Knob*>& traded, std::vector<std::string>& notes) {
    const bool fast = name == "fast";
    std::vector<std::string> leftAsTheScene = knobsNotTraded(traded);
    if (measured.empty() || measured.front().setting.knob != "baseline")
        return presetSetting(name, leftAsTheScene);
    const TradeRow& baseline = measured.front();
    auto rowOf = [&](const TradeSetting& setting) -> const TradeRow* {
        for (const TradeRow& row : measured)
            if (isSingleKnob(row) && row.setting.words == setting.words) return &row;
        return nullptr;
    };
    const TradeSetting unchecked = presetSetting(name, leftAsTheScene);
    for (const Knob* knob : traded) {
        const std::string& value = fast ? knob->fastValue : knob->bestValue;
        if (value.empty()) continue;
        // A knob acting under another's value the preset does not set is not in the preset anyway.
        const TradeSetting setting = knobSetting(*knob, value);
        if (std::find(unchecked.words.begin(), unchecked.words.end(), knob->flag) == unchecked.words.end())
            continue;
        const TradeRow* row = rowOf(setting);
        std::string why;
        if (!row)
            why = "";  // the baseline's own value: nothing to set
        else if (row->blank)
            why = "it draws nothing or nearly nothing";
        else if (row->changesContent)
            why = "it changes what the scene shows";
        else if (row->noEffect)
            why = "it changes nothing in this scene";
        else if (fast && row->timeVerdict == TimeVerdict::Slower)
            why = "it measured slower (CPU " + ms(row->cpuMsMedian) + " a frame, the baseline " +
                  ms(baseline.cpuMsMedian) + ")";
        else if (fast && row->timeVerdict == TimeVerdict::WithinNoise)
            why = "it was not measurably faster (CPU " + ms(row->cpuMsMedian) + " a frame, the baseline " +
                  ms(baseline.cpuMsMedian) + ", within the noise)";
        else if (!fast && row->withinReferenceFloor)
            why = "its error differs from the baseline's by less than the reference's own error";
        else if (!fast && !(tradeError(*row) < tradeError(baseline)))
            why = "it was not more accurate (1 - SSIM " + errorText(tradeError(*row)) + ", the baseline " +
                  errorText(tradeError(baseline)) + ")";
        else
            continue;  // measured faster (more accurate): in the preset
        leftAsTheScene.push_back(knob->name);
        if (row)
            notes.push_back("preset " + name + " leaves " + knob->flag +
                            " as the scene has it: " + setting.label() + ": " + why);
    }
    return presetSetting(name, leftAsTheScene);
}

void keepPresetPromises(TradeResult& result) {
    std::vector<TradeRow>& rows = result.rows;
    if (rows.empty()) return;
    // A preset no knob chose is the baseline itself: not timed, not listed.
    for (const char* name : {"fast", "best"}) {
        const auto preset = presetRow(rows, name);
        if (preset != rows.end() && preset->setting.words.empty()) {
            result.notes.push_back(
                std::string("preset ") + name + ": no traded knob " +
                (name == std::string("fast") ? "measured faster than" : "measured more accurate than") +
                " the baseline, so it is the scene as given");
            rows.erase(preset);
        }
    }
    // fast: never slower than the baseline on this run's numbers.
    if (const auto fast = presetRow(rows, "fast");
        fast != rows.end() && fast->timeVerdict != TimeVerdict::Faster) {
        const TradeRow* fastest = nullptr;
        for (const TradeRow& row : rows)
            if (isSingleKnob(row) && row.timeVerdict == TimeVerdict::Faster && !row.blank &&
                !row.changesContent && (!fastest || row.cpuMsMedian < fastest->cpuMsMedian))
                fastest = &row;
        std::string note = "preset fast measured " + ms(fast->cpuMsMedian) +
                           " of CPU a frame, not faster than " + "the baseline's " +
                           ms(rows.front().cpuMsMedian) + " beyond the noise: ";
        if (fastest) {
            note += "fast is " + fastest->setting.label() + " alone, the fastest setting measured (" +
                    ms(fastest->cpuMsMedian) + ")";
            replaceWith(*fast, *fastest);
        } else {
            note += "no setting measured faster, so fast is the scene as given";
            rows.erase(fast);
        }
        result.notes.push_back(note);
    }
    // best: never less accurate than the most accurate single setting (or the baseline).
    if (const auto best = presetRow(rows, "best"); best != rows.end()) {
        const TradeRow* accurate = &rows.front();
        for (const TradeRow& row : rows)
            if (isSingleKnob(row) && !row.blank && !row.changesContent &&
                tradeError(row) < tradeError(*accurate))
                accurate = &row;
        if (tradeError(*best) > tradeError(*accurate)) {
            std::string note =
                "preset best scored 1 - SSIM " + errorText(tradeError(*best)) + ", worse than " +
                (accurate == &rows.front() ? std::string("the baseline") : accurate->setting.label()) +
                " alone (" + errorText(tradeError(*accurate)) + "): ";
            if (accurate == &rows.front()) {
                note += "best is the scene as given";
                rows.erase(best);
            } else {
                note += "best is that setting";
                replaceWith(*best, *accurate);
            }
            result.notes.push_back(note);
        }
    }
    // Neither preset is beaten by a single setting on both counts, by the run's own margins (times
    // within 1 + 2·noise and errors within the reference's own error are equal): a preset that takes
    // ssaa16 where ssaa8 scores the same within the floor at half the time, or a fast preset no faster
    // than flat shading alone and less accurate, would sit off the front the trade draws.
    const double timeMargin = 1.0 + kVerdictNoiseFactor * result.timeNoise;
    const double floor = result.referenceFloor;
    for (const char* name : {"fast", "best"}) {
        const auto preset = presetRow(rows, name);
        if (preset == rows.end()) continue;
        const TradeRow* better = nullptr;
        for (const TradeRow& row : rows) {
            if (!isSingleKnob(row) || row.blank || row.changesContent || row.noEffect) continue;
            const bool asFast = row.cpuMsMedian <= preset->cpuMsMedian * timeMargin;
            const bool asAccurate = tradeError(row) <= tradeError(*preset) + floor;
            const bool faster = row.cpuMsMedian * timeMargin < preset->cpuMsMedian;
            const bool moreAccurate = tradeError(row) + floor < tradeError(*preset);
            if (!(asFast && asAccurate && (faster || moreAccurate))) continue;
            // fast: the fastest such setting; best: the most accurate.
            if (!better || (name == std::string("fast") ? row.cpuMsMedian < better->cpuMsMedian
                                                        : tradeError(row) < tradeError(*better)))
                better = &row;
        }
        if (!better) continue;
        result.notes.push_back(std::string("preset ") + name + ": " + better->setting.label() + " alone (" +
                               ms(better->cpuMsMedian) + ", 1 - SSIM " + errorText(tradeError(*better)) +
                               ") is as fast and as accurate and better in one, within the run's noise and " +
                               "the reference's own error: " + name + " is that setting");
        replaceWith(*preset, *better);
    }
}

}  // namespace facet
