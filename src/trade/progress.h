// What facet trade prints while it runs (on standard error): how far the reference image is, then a line
// per setting timed, each with an estimate of the time the trade still needs.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <ostream>
#include <set>
#include <string>
#include <vector>

namespace facet {

// "about 6 s left", "about 2 min 10 s left", "under a second left".
std::string timeLeftText(double seconds);

class TradeProgress {
  public:
    // `clockMs`: milliseconds since any fixed moment. Nothing is printed unless `enabled` (-q); the
    // estimates are kept either way.
    TradeProgress(std::ostream& log, bool enabled, std::function<double()> clockMs);

    // The reference: its rows traced so far (ReferenceOptions::onRows). At most one line a second,
    // "reference: 40%, about 6 s left", the time left the time so far scaled by the rows still to trace.
    void referenceStarted(double startMs);  // when it began, by the clock
    void referenceRows(int rowsDone, int rows);

    // The settings' runs in the order they will come (a setting's index once for each round and phase it
    // is timed in). Its first run also scores it (its image compared and written): that part is counted
    // once.
    void plan(std::vector<std::size_t> runs);
    // The runs after those done so far, when the run decides them late (the presets, chosen from the
    // knobs' numbers: a preset no knob went into is not timed).
    void replanRest(std::vector<std::size_t> runs);
    // A run of `setting` begins; its frames are timed (what follows is the scoring); it ends.
    void runStarted(std::size_t setting);
    void framesTimed(std::size_t setting);
    void runFinished(std::size_t setting);

    // The runs still to come, estimated from those measured: each setting's later runs from its last
    // one (without the scoring), a setting not yet run from the plan's first (the baseline's) and the
    // last scoring measured. NaN before anything is measured.
    double msLeft() const;
    // "; about 2 min 10 s left" for a progress line; empty after the last run, and until two settings
    // are scored (the first scoring also loads what the comparison needs).
    std::string leftSuffix() const;

  private:
    std::ostream& log_;
    bool enabled_;
    std::function<double()> clockMs_;
    double referenceStart_ = 0, referencePrinted_ = 0;

    std::vector<std::size_t> runs_;
    std::size_t next_ = 0;  // the index in runs_ of the run now going on or next to start
    double runStart_ = 0, framesEnd_ = 0;
    bool framesMarked_ = false;
    std::map<std::size_t, double> framesMs_;  // per setting: its last run, without the scoring
    std::set<std::size_t> scored_;            // the settings whose first run is over
    double lastScoringMs_ = 0;                // the scoring of the last first run
};

}  // namespace facet
