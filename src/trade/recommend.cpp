#include "trade/recommend.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "trade/knobs.h"

namespace facet {

namespace {

// "1.7" below ten, "16" from ten on: two figures, as much as a noisy time or an error supports.
std::string figures(double ratio) {
    char text[32];
    std::snprintf(text, sizeof text, ratio < 9.95 ? "%.1f" : "%.0f", ratio);
    return text;
}
std::string times(double ratio) {
    return figures(ratio) + "×";
}

// The error of a row against the baseline's, as a noun: "half the error", "37% less error", "84% less
// error", "16× the error". Only for rows whose difference lies outside the reference's own error.
std::string errorChange(double baselineError, double error) {
    if (!(baselineError > 0.0)) return error > baselineError ? "more error" : "the same error";
    const double ratio = error / baselineError;
    if (ratio < 1.0) {
        if (ratio > 0.5) {
            const long percent = std::lround(100.0 * (1.0 - ratio));
            return percent < 1 ? "under 1% less error" : std::to_string(percent) + "% less error";
        }
        if (!(error > 0.0)) return "no error left";
        const double divisor = 1.0 / ratio;  // the error divided by this
        // Plain fractions where the divisor is within 5% of one.
        const char* fractions[] = {"half the error", "a third of the error", "a quarter of the error"};
        for (int n = 2; n <= 4; ++n)
            if (std::abs(divisor - n) <= 0.05 * n) return fractions[n - 2];
        // Otherwise the share taken away: "84% less error" reads at a glance where "1/6.3" does not.
        const long percent = std::min(99L, std::lround(100.0 * (1.0 - ratio)));
        return std::to_string(percent) + "% less error";
    }
    if (ratio == 1.0) return "the same error";
    if (ratio < 2.0) {
        const long percent = std::lround(100.0 * (ratio - 1.0));
        return percent < 1 ? "under 1% more error" : std::to_string(percent) + "% more error";
    }
    return times(ratio) + " the error";
}

// What a row's time verdict allows to be said, with the ratio of the medians where there is a verdict.
struct TimeWords {
    TimeVerdict verdict;
    double ratio;  // row's time / baseline's; 0 when a median is missing
};

TimeWords timeWords(const TradeRow& baseline, const TradeRow& row) {
    // CPU time where both have it (what a busy machine disturbs least), else wall time.
    const bool cpu = baseline.cpuMsMedian > 0.0 && row.cpuMsMedian > 0.0;
    const double base = cpu ? baseline.cpuMsMedian : baseline.msMedian;
    const double own = cpu ? row.cpuMsMedian : row.msMedian;
    return {row.timeVerdict, base > 0.0 && own > 0.0 ? own / base : 0.0};
}

std::string faster(const TimeWords& time) {
    return time.ratio > 0.0 ? times(1.0 / time.ratio) + " faster" : "faster";
}
std::string slower(const TimeWords& time) {
    return time.ratio > 0.0 ? times(time.ratio) + " slower" : "slower";
}

const char* kNoTime = "no measurable difference in time";
// The most time a value recommended by "use" may take, whatever the noise: 1.15× the baseline's.
constexpr double kUseAtMostTimes = 1.15;

// One value's clause, for a row that changed the image and drew the scene as it is.
std::string valueClause(const TradeRow& baseline, const TradeRow& row) {
    const std::string& value = row.setting.value;
    const TimeWords time = timeWords(baseline, row);
    if (row.withinReferenceFloor) {
        const std::string same = value + " makes no difference in error beyond the reference's own";
        if (time.verdict == TimeVerdict::Faster) return same + ", " + faster(time);
        if (time.verdict == TimeVerdict::Slower) return same + ", " + slower(time);
        return same + ", " + kNoTime;
    }
    const double baseError = tradeError(baseline), error = tradeError(row);
    const std::string change = errorChange(baseError, error);
    if (error < baseError) {
        if (time.verdict == TimeVerdict::Slower)
            return value + " gives " + change + " for " +
                   (time.ratio > 0.0 ? times(time.ratio) + " the time" : std::string("more time"));
        if (time.verdict == TimeVerdict::Faster)
            return value + " gives " + change + " and is " + faster(time);
        return value + " gives " + change + ", " + kNoTime;
    }
    if (time.verdict == TimeVerdict::Faster) return value + " is " + faster(time) + " for " + change;
    if (time.verdict == TimeVerdict::Slower) return value + " is " + slower(time) + " and gives " + change;
    return value + " gives " + change + ", " + kNoTime;
}

// "a", "a and b", "a, b and c".
std::string listed(const std::vector<std::string>& items) {
    std::string text;
    for (std::size_t i = 0; i < items.size(); ++i) {
        if (i > 0) text += i + 1 == items.size() ? " and " : ", ";
        text += items[i];
    }
    return text;
}

// The knob's value in the baseline, when the trade skipped it as "the baseline's own"; empty otherwise.
std::string baselineValue(const Knob* knob, const TradeResult& result) {
    if (!knob) return "";
    for (const std::string& value : knob->values) {
        const std::string own = knobSetting(*knob, value).label() + " (the baseline's own)";
        if (std::find(result.skipped.begin(), result.skipped.end(), own) != result.skipped.end())
            return value;
    }
    return "";
}

std::string knobLine(const TradeResult& result, const std::string& name,
                     const std::vector<const TradeRow*>& rows) {
    const TradeRow& baseline = result.rows.front();
    const Knob* knob = nullptr;
    for (const Knob& entry : knobTable())
        if (entry.name == name) knob = &entry;
    const std::string flag = knob ? knob->flag : "--" + name;

    std::vector<std::string> unchanged, content, blank, clauses;
    // Of the values with a clause: those on the Pareto front and the others, for a knob of many values.
    std::vector<std::string> frontClauses, offFront;
    bool allWithinFloor = true;  // every row changed nothing, or nothing beyond the reference's own error
    bool anyWithinFloor = false;
    const TradeRow* use = nullptr;  // the most accurate value that is more accurate and not slower
    bool anyWorse = false, anyBetter = false, anyFaster = false;
    for (const TradeRow* row : rows) {
        const std::string& value = row->setting.value;
        if (row->noEffect) {
            unchanged.push_back(value);
            continue;
        }
        allWithinFloor = allWithinFloor && row->withinReferenceFloor && !row->blank && !row->changesContent &&
                         row->timeVerdict == TimeVerdict::WithinNoise;
        if (row->blank) {
            blank.push_back(value);
            continue;
        }
        if (row->changesContent) {
            content.push_back(value);
            continue;
        }
        clauses.push_back(valueClause(baseline, *row));
        (row->pareto ? frontClauses : offFront).push_back(row->pareto ? clauses.back() : value);
        anyFaster = anyFaster || row->timeVerdict == TimeVerdict::Faster;
        if (row->withinReferenceFloor) {
            anyWithinFloor = true;
            continue;
        }
        const bool better = tradeError(*row) < tradeError(baseline);
        anyBetter = anyBetter || better;
        anyWorse = anyWorse || !better;
        // "Use" only what costs no measurable time: not judged slower, and its median within
        // kUseAtMostTimes of the baseline's, since on a busy run the noise's margin is wide.
        const TimeWords time = timeWords(baseline, *row);
        if (better && time.verdict != TimeVerdict::Slower && time.ratio <= kUseAtMostTimes &&
            (!use || tradeError(*row) < tradeError(*use)))
            use = row;
    }

    const std::string head = flag + ": ";
    if (unchanged.size() == rows.size()) return head + "no effect on this scene";
    if (content.size() == rows.size()) return head + "changes what the scene shows, not how exactly";
    if (allWithinFloor && anyWithinFloor) return head + "no difference beyond the reference's own error";

    std::vector<std::string> parts;
    if (!blank.empty())
        parts.push_back(listed(blank) + " drew nothing or nearly nothing of the scene: not a setting to use");
    // One line per knob: a knob of many values (the anti-aliasing modes) names those on the front, and
    // the rest in a word: another value gives as much for less time, or more for the same.
    if (clauses.size() > 3 && !frontClauses.empty() && !offFront.empty()) {
        parts.insert(parts.end(), frontClauses.begin(), frontClauses.end());
        parts.push_back(listed(offFront) +
                        ": off the front (another setting is faster for the same error, or " +
                        "more accurate for the same time)");
    } else {
        parts.insert(parts.end(), clauses.begin(), clauses.end());
    }
    if (!content.empty())
        parts.push_back(listed(content) + (content.size() == 1 ? " changes" : " change") +
                        " what the scene shows, not how exactly");
    if (!unchanged.empty())
        parts.push_back(listed(unchanged) + (unchanged.size() == 1 ? " changes" : " change") + " nothing");
    std::string line = head;
    for (std::size_t i = 0; i < parts.size(); ++i)
        line += (i ? "; " : "") + parts[i];

    // Advice only where the verdicts settle it: a value more accurate at no measurable cost, or every
    // value less accurate (or no more) and none faster.
    if (use) {
        line += ": use " + use->setting.value;
    } else if (anyWorse && !anyBetter && !anyFaster) {
        const std::string own = baselineValue(knob, result);
        line += ": keep " + (own.empty() ? std::string("the scene's own") : own);
    }
    return line;
}

}  // namespace

std::vector<std::string> tradeRecommendations(const TradeResult& result) {
    std::vector<std::string> lines;
    if (result.rows.empty()) return lines;
    std::vector<std::string> names;  // in the order the knobs ran
    std::vector<std::vector<const TradeRow*>> rowsOf;
    for (const TradeRow& row : result.rows) {
        if (row.setting.knob == "baseline" || row.setting.knob == "preset") continue;
        const auto at = std::find(names.begin(), names.end(), row.setting.knob);
        if (at == names.end()) {
            names.push_back(row.setting.knob);
            rowsOf.push_back({&row});
        } else {
            rowsOf[std::size_t(at - names.begin())].push_back(&row);
        }
    }
    for (std::size_t k = 0; k < names.size(); ++k)
        lines.push_back(knobLine(result, names[k], rowsOf[k]));
    return lines;
}

}  // namespace facet
