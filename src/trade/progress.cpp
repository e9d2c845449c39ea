#include "trade/progress.h"

#include <algorithm>
#include <cmath>

namespace facet {

std::string timeLeftText(double seconds) {
    if (!(seconds >= 0.5)) return "under a second left";
    std::string text = "about ";
    if (seconds < 59.5) {
        text += std::to_string(std::lround(seconds));
        text += " s left";
        return text;
    }
    // Past a minute, to ten seconds: an estimate, not a count-down.
    const long tens = std::lround(seconds / 10.0);
    text += std::to_string(tens / 6);
    text += " min";
    if (tens % 6 > 0) {
        text += " ";
        text += std::to_string(10 * (tens % 6));
        text += " s";
    }
    text += " left";
    return text;
}

TradeProgress::TradeProgress(std::ostream& log, bool enabled, std::function<double()> clockMs)
    : log_(log), enabled_(enabled), clockMs_(std::move(clockMs)) {}

void TradeProgress::referenceStarted(double startMs) {
    referenceStart_ = referencePrinted_ = startMs;
}

void TradeProgress::referenceRows(int rowsDone, int rows) {
    if (!enabled_ || rowsDone <= 0 || rowsDone >= rows) return;  // the trade prints the finished reference
    constexpr double kEveryMs = 1000.0;
    const double now = clockMs_();
    if (now - referencePrinted_ < kEveryMs) return;
    referencePrinted_ = now;
    const double leftMs = (now - referenceStart_) * (rows - rowsDone) / rowsDone;
    log_ << "reference: " << 100 * rowsDone / rows << "%, " << timeLeftText(leftMs / 1000.0) << "\n"
         << std::flush;
}

void TradeProgress::plan(std::vector<std::size_t> runs) {
    runs_ = std::move(runs);
    next_ = 0;
}

void TradeProgress::replanRest(std::vector<std::size_t> runs) {
    runs_.resize(std::min(next_, runs_.size()));
    runs_.insert(runs_.end(), runs.begin(), runs.end());
}

void TradeProgress::runStarted(std::size_t setting) {
    // Where the run is not the one planned (a plan out of step with the loop), the next run of that
    // setting is taken as this one, so that the estimate recovers.
    const auto at = std::find(runs_.begin() + static_cast<std::ptrdiff_t>(std::min(next_, runs_.size())),
                              runs_.end(), setting);
    if (at != runs_.end()) next_ = static_cast<std::size_t>(at - runs_.begin());
    runStart_ = clockMs_();
    framesMarked_ = false;
}

void TradeProgress::framesTimed(std::size_t setting) {
    framesEnd_ = clockMs_();
    framesMarked_ = true;
    framesMs_[setting] = framesEnd_ - runStart_;
}

void TradeProgress::runFinished(std::size_t setting) {
    const double end = clockMs_();
    if (!framesMarked_) framesMs_[setting] = end - runStart_;
    if (framesMarked_ && !scored_.count(setting)) {
        scored_.insert(setting);
        lastScoringMs_ = end - framesEnd_;
    }
    if (next_ < runs_.size() && runs_[next_] == setting) ++next_;
}

double TradeProgress::msLeft() const {
    if (runs_.empty()) return std::nan("");
    const auto baseline = framesMs_.find(runs_.front());
    if (baseline == framesMs_.end()) return std::nan("");
    double left = 0;
    for (std::size_t i = next_; i < runs_.size(); ++i) {
        const std::size_t setting = runs_[i];
        const auto own = framesMs_.find(setting);
        if (own != framesMs_.end()) {
            left += own->second;
            continue;
        }
        // Not yet run: the baseline's frames, and on its first run the last scoring measured (the same
        // work for every setting: an image of the same size compared and written; the first one also
        // loads what the comparison needs, so the last rather than the baseline's).
        const bool first = std::find(runs_.begin() + static_cast<std::ptrdiff_t>(next_),
                                     runs_.begin() + static_cast<std::ptrdiff_t>(i),
                                     setting) == runs_.begin() + static_cast<std::ptrdiff_t>(i);
        left += baseline->second + (first ? lastScoringMs_ : 0.0);
    }
    return left;
}

std::string TradeProgress::leftSuffix() const {
    // Not after the first run alone: its scoring also loaded what the comparison needs, and would
    // count for every setting.
    if (next_ >= runs_.size() || scored_.size() < 2) return "";
    const double left = msLeft();
    if (std::isnan(left)) return "";
    return "; " + timeLeftText(left / 1000.0);
}

}  // namespace facet
