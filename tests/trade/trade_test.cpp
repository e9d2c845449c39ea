// facet trade: its knob table speaks the render command's language, its CSV is whole and finite, a knob
// that changes the image is scored as such, and the Pareto front and the metrics mean what they say.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "cli/render_command.h"
#include "cli/trade_command.h"
#include "reference/reference.h"
#include "support/bundled_models.h"
#include "support/sanitizers.h"
#include "support/temp_folder.h"
#include "support/user_shader_files.h"
#include "trade/knobs.h"
#include "trade/metrics.h"
#include "trade/pareto.h"
#include "trade/presets.h"
#include "trade/time_verdicts.h"
#include "trade/trade.h"

namespace facet {
namespace {

using testing_support::kSpot;

std::vector<std::string> splitCsvLine(const std::string& line) {  // the trade's CSV quotes no number
    std::vector<std::string> fields;
    std::string field;
    bool quoted = false;
    for (const char c : line) {
        if (c == '"')
            quoted = !quoted;
        else if (c == ',' && !quoted) {
            fields.push_back(field);
            field.clear();
        } else
            field += c;
    }
    fields.push_back(field);
    return fields;
}

// `facet trade spot.obj --knobs shading,transparency --frames 3 --rounds 2 ...` on a tiny image, parsed by
// the command's own parser and run once for the suite; its CSV read back, one map per row, and its
// progress lines kept.
class TradeRun : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        // The suite's folder (ctest runs each test in its own process, two at a time); the trade makes
        // its output folder in it.
        folder_ = std::make_unique<testing_support::TempFolder>();
        dir_ = folder_->path() / "trade";
        CLI::App app;
        cli::TradeArgs args;
        cli::addTradeCommand(app, args);
        // clang-format off
        const std::vector<std::string> words = {"trade", kSpot, "--knobs", "shading,transparency",
                                                "--frames", "3", "--rounds", "2", "--reference-samples", "1",
                                                "--width", "48", "--height", "36", "--threads", "1",
                                                "-o", dir_.string()};
        // clang-format on
        app.parse(std::vector<std::string>(words.rbegin(), words.rend()));
        ::testing::internal::CaptureStderr();
        const int status = cli::trade(args);
        progress_ = ::testing::internal::GetCapturedStderr();
        ASSERT_EQ(status, 0);
        std::ifstream csv(dir_ / "trade.csv");
        std::string line;
        std::getline(csv, line);
        header_ = splitCsvLine(line);
        while (std::getline(csv, line)) {
            const std::vector<std::string> fields = splitCsvLine(line);
            ASSERT_EQ(fields.size(), header_.size()) << line;
            std::map<std::string, std::string> row;
            for (std::size_t k = 0; k < fields.size(); ++k)
                row[header_[k]] = fields[k];
            rows_.push_back(row);
        }
    }
    static void TearDownTestSuite() { folder_.reset(); }
    static const std::map<std::string, std::string>* row(const std::string& flags) {
        for (const auto& r : rows_)
            if (r.at("flags") == flags) return &r;
        return nullptr;
    }
    static double number(const std::map<std::string, std::string>& row, const std::string& column) {
        return std::stod(row.at(column));
    }
    static inline std::unique_ptr<testing_support::TempFolder> folder_;
    static inline std::filesystem::path dir_;
    static inline std::vector<std::string> header_;
    static inline std::vector<std::map<std::string, std::string>> rows_;
    static inline std::string progress_;
};

// --frames 3 over --rounds 2: every setting is timed in both rounds, in turn (round 1 of every setting
// before round 2 of any), and gets all three frames (2 + 1); the presets are timed after the knobs
// (they are chosen from the knobs' measurements), in rounds of their own alongside the baseline, whose
// frames of both phases count (6). Which presets are timed depends on the run's own times (a preset no
// knob went into is not), so the counts follow the progress lines of the presets' phase. Catches: the
// rounds ignored (one round), a later round's frames not added to the first's (2 frames), the
// remainder of frames / rounds dropped, or the presets timed among the knobs.
TEST_F(TradeRun, EverySettingIsTimedInEveryRoundWithAllItsFrames) {
    auto count = [&](const std::string& text) {
        std::size_t n = 0;
        for (std::size_t at = progress_.find(text); at != std::string::npos;
             at = progress_.find(text, at + 1))
            ++n;
        return n;
    };
    const std::size_t knobRows = 5;  // the baseline, flat, Gouraud, unsorted, exact
    EXPECT_EQ(count("[round 1/2, "), knobRows) << progress_;
    EXPECT_EQ(count("[round 2/2, "), knobRows) << progress_;
    const std::size_t presetPhase = count("[presets, round 2/2, ");  // the presets timed, and the baseline
    EXPECT_EQ(count("[presets, round 1/2, "), presetPhase) << progress_;
    EXPECT_NE(presetPhase, 1u) << progress_;  // never the baseline alone
    for (const auto& r : rows_)
        EXPECT_EQ(r.at("frames"), r.at("knob") == "baseline" && presetPhase > 0 ? "6" : "3") << r.at("flags");
    EXPECT_LT(progress_.rfind("[round 1/2, "), progress_.find("[round 2/2, "));
    if (presetPhase > 0) {
        EXPECT_LT(progress_.rfind("[round 2/2, "), progress_.find("[presets, round 1/2, "));
    }
}

// Every progress line of a setting but the first (whose scoring loads the comparison) and the last says
// how long the trade still needs. Catches: the estimate dropped from the lines, or printed after the
// last run.
TEST_F(TradeRun, ProgressLinesEstimateTheTimeLeft) {
    std::vector<std::string> lines;
    std::istringstream in(progress_);
    for (std::string line; std::getline(in, line);)
        if (line.rfind("[", 0) == 0 && line.rfind("[0/", 0) != 0)
            lines.push_back(line);  // not the reference's
    ASSERT_GT(lines.size(), 3u) << progress_;
    const std::regex estimate("; (about [0-9]+ (min( [0-9]+ s)?|s)|under a second) left$");
    // None on the first line (nothing measured yet); on every other but the last; none on the last when
    // it is a preset's. When the presets take no knob (decided after the knobs' last line, which counted
    // on them), the knobs' last line is the last and may carry an estimate.
    for (std::size_t i = 0; i + 1 < lines.size(); ++i)
        EXPECT_EQ(std::regex_search(lines[i], estimate), i > 0) << lines[i];
    if (lines.back().rfind("[presets", 0) == 0) {
        EXPECT_FALSE(std::regex_search(lines.back(), estimate)) << lines.back();
    }
}

TEST_F(TradeRun, CsvHoldsARowPerSettingWithFiniteNumbers) {
    // The baseline (Phong shading, sorted transparency), flat, Gouraud, unsorted, exact, then the fast
    // and best presets where a knob went into them (by the run's own numbers); the default preset,
    // --shading phong and --transparency sorted are the baseline's own settings, skipped.
    ASSERT_GE(rows_.size(), 5u);
    ASSERT_LE(rows_.size(), 7u);
    for (std::size_t k = 5; k < rows_.size(); ++k)
        EXPECT_EQ(rows_[k].at("knob"), "preset");
    EXPECT_EQ(rows_[0].at("knob"), "baseline");
    EXPECT_NE(row("--shading flat"), nullptr);
    EXPECT_NE(row("--shading gouraud"), nullptr);
    EXPECT_EQ(row("--shading phong"), nullptr);
    std::size_t numbers = 0;
    for (const auto& r : rows_)
        for (const std::string& column : header_) {
            if (column.rfind("ms_", 0) != 0 && column.rfind("cpu_ms_", 0) != 0 &&
                column.rfind("linear_", 0) != 0 && column.rfind("output8_", 0) != 0)
                continue;
            SCOPED_TRACE(r.at("flags") + " " + column);
            const double value = number(r, column);
            EXPECT_TRUE(std::isfinite(value)) << r.at(column);
            ++numbers;
        }
    // 4 wall-clock times, 3 CPU times, 6 metrics in linear light and in 8 bits
    EXPECT_EQ(numbers, rows_.size() * 19);
    for (const auto& r : rows_) {
        EXPECT_TRUE(std::filesystem::exists(dir_ / r.at("image")));
        EXPECT_TRUE(std::filesystem::exists(dir_ / r.at("error_image")));
    }
    EXPECT_TRUE(std::filesystem::exists(dir_ / "reference.png"));
    EXPECT_TRUE(std::filesystem::exists(dir_ / "chart.png"));
}

TEST_F(TradeRun, FlatShadingIsFartherFromTheReferenceAndHasAnEffect) {
    const auto* flat = row("--shading flat");
    ASSERT_NE(flat, nullptr);
    EXPECT_EQ(flat->at("no_effect"), "0");
    EXPECT_LT(number(*flat, "output8_ssim"), number(rows_[0], "output8_ssim"));
    EXPECT_GT(number(*flat, "linear_mean_abs"), number(rows_[0], "linear_mean_abs"));
    EXPECT_LT(number(*flat, "linear_psnr_db"), number(rows_[0], "linear_psnr_db"));
}

// The cow is opaque: no transparency mode changes a pixel, and the trade says so.
TEST_F(TradeRun, ASettingThatChangesNothingIsFlagged) {
    for (const char* flags : {"--transparency unsorted", "--transparency exact"}) {
        SCOPED_TRACE(flags);
        const auto* r = row(flags);
        ASSERT_NE(r, nullptr);
        EXPECT_EQ(r->at("no_effect"), "1");
        EXPECT_EQ(r->at("output8_ssim"), rows_[0].at("output8_ssim"));
    }
    EXPECT_EQ(rows_[0].at("no_effect"), "0");  // the baseline is not compared with itself
}

// Each row's times are its own setting's frames: a clock of the test's (TradeOptions::clockMs) advances
// by a step of each setting's own at every reading, so a frame of setting k (from before its shadows'
// rebuild to after the draw: two readings after the start) takes 2·step_k ms and the rebuild step_k,
// in every round and both phases; the CPU clock (TradeOptions::cpuClockMs, read at a frame's start and
// end) advances by a CPU step of each setting's own, so a frame's CPU time is that step. Catches: every
// row given the baseline's times (median(frameMs[0])), a row's min, max or shadow time taken from
// another setting's frames, the CPU time read from the wall clock or from another setting, or either
// clock option ignored.
TEST(TradeTimes, EachRowReportsItsOwnSettingsFrames) {
    const testing_support::TempFolder folder;
    const std::filesystem::path dir = folder.path() / "trade";
    cli::SceneArgs args;
    args.input = kSpot;
    args.width = 32;
    args.height = 24;
    // A distinct step for each setting's words, in the order the trade first asks for them.
    std::map<std::vector<std::string>, double> steps;
    std::vector<std::string> current;
    auto stepOf = [&](const std::vector<std::string>& words) {
        return steps.emplace(words, 0.5 * double(steps.size() + 1)).first->second;
    };
    // CPU steps: flat clearly faster than the baseline (so the fast preset is timed), Gouraud slower.
    const std::map<std::vector<std::string>, double> cpuSteps = {
        {{}, 10.0}, {{"--shading", "flat"}, 6.0}, {{"--shading", "gouraud"}, 13.0}};
    double now = 1000.0, cpuNow = 50.0;
    TradeOptions options;
    options.knobs = "shading";
    options.frames = 3;
    options.rounds = 2;
    options.threads = 1;
    options.referenceSamples = 1;
    options.outputDir = dir;
    options.progress = false;
    options.clockMs = [&] {
        const double reading = now;
        now += stepOf(current);
        return reading;
    };
    options.cpuClockMs = [&] {
        const double reading = cpuNow;
        cpuNow += cpuSteps.at(current);
        return reading;
    };
    std::ostringstream log;
    const TradeResult result = runTrade(
        [&](const std::vector<std::string>& words) {
            current = words;
            return cli::sceneWithWords(args, words);
        },
        options, log);
    // The baseline, flat, Gouraud and the fast preset, which is --shading flat again (the only knob
    // traded); phong, and with it the best and default presets, are the baseline's own.
    ASSERT_EQ(result.rows.size(), 4u);
    std::vector<double> medians;
    for (const TradeRow& row : result.rows) {
        SCOPED_TRACE(row.setting.knob + " " + row.setting.value);
        ASSERT_EQ(steps.count(row.setting.words), 1u);
        const double step = steps.at(row.setting.words);
        EXPECT_DOUBLE_EQ(row.msMedian, 2.0 * step);
        EXPECT_DOUBLE_EQ(row.msMin, 2.0 * step);
        EXPECT_DOUBLE_EQ(row.msMax, 2.0 * step);
        EXPECT_DOUBLE_EQ(row.msShadows, step);
        EXPECT_DOUBLE_EQ(row.cpuMsMedian, cpuSteps.at(row.setting.words));
        EXPECT_DOUBLE_EQ(row.cpuMsMin, cpuSteps.at(row.setting.words));
        EXPECT_DOUBLE_EQ(row.cpuMsMax, cpuSteps.at(row.setting.words));
        if (row.setting.knob != "preset") medians.push_back(row.msMedian);
    }
    std::sort(medians.begin(), medians.end());
    EXPECT_EQ(std::unique(medians.begin(), medians.end()), medians.end());  // three different times
    EXPECT_EQ(result.rows[3].setting.knob, "preset");
    EXPECT_EQ(result.rows[3].frames, 3);  // the fast preset was timed in its own phase
    // The reference: its render and then its floor's estimate (with any render again), each timed by two
    // readings, the baseline's step each.
    EXPECT_DOUBLE_EQ(result.referenceMs, 2.0 * steps.at({}));
}

// Every knob's every value is a command line `facet render` accepts (a renamed flag or value fails
// here), and reaches the scene so that the knob reads it back (what the trade's skipping relies on).
TEST(TradeKnobs, EverySettingIsAcceptedByTheRenderParserAndReachesTheScene) {
    for (const Knob& knob : knobTable())
        for (const std::string& value : knob.values) {
            const TradeSetting setting = knobSetting(knob, value);
            SCOPED_TRACE(setting.label());
            CLI::App app;
            cli::RenderArgs args;
            cli::addRenderCommand(app, args);
            std::vector<std::string> words = {"render", kSpot, "-o", "out.png"};
            words.insert(words.end(), setting.words.begin(), setting.words.end());
            EXPECT_NO_THROW(app.parse(std::vector<std::string>(words.rbegin(), words.rend())));
            Scene scene = sceneForModel(kSpot);
            cli::applyLightingOptions(args, scene);
            EXPECT_TRUE(sceneHasSetting(scene, setting));
        }
    for (const std::string& preset : kPresetNames) {
        SCOPED_TRACE(preset);
        cli::SceneArgs args;
        args.input = kSpot;
        EXPECT_TRUE(
            sceneHasSetting(cli::sceneWithWords(args, presetSetting(preset).words), presetSetting(preset)));
    }
}

// A row of a knob at a value (or the baseline) with a CPU median, a time verdict and an error (1 − SSIM).
TradeRow measuredRow(const std::string& knob, const std::string& value, double cpuMs, TimeVerdict verdict,
                     double error) {
    TradeRow row;
    row.setting = knob == "baseline" ? TradeSetting{"baseline", "", {}} : knobSetting(knobNamed(knob), value);
    row.cpuMsMedian = cpuMs;
    row.timeVerdict = verdict;
    row.error.encoded.ssim = 1.0 - error;
    return row;
}

bool hasWords(const TradeSetting& setting, const std::string& flag, const std::string& value) {
    for (std::size_t k = 0; k + 1 < setting.words.size(); ++k)
        if (setting.words[k] == flag && setting.words[k + 1] == value) return true;
    return false;
}

bool mentions(const std::vector<std::string>& notes, const std::string& text) {
    return std::any_of(notes.begin(), notes.end(),
                       [&](const std::string& note) { return note.find(text) != std::string::npos; });
}

// The fast preset takes a traded knob's fast value only where its row measured Faster: never a Slower
// row, one within the noise, one without effect, a blank one or one that changes the scene's content,
// each left out with a note; and never a knob not traded (--knobs aa: no flat shading, never timed).
// Catches: the presets built from every knob of the table (flat shading in a --knobs aa run), a Slower
// or WithinNoise fast value kept, a blank or content-changing row trusted for its time, a left-out knob
// without its note.
TEST(TradePresets, TheFastPresetTakesOnlyKnobsMeasuredFasterAmongThoseTraded) {
    const std::vector<const Knob*> traded =
        selectKnobs("shading,normalize,transparency,aa,interpolation,fresnel");
    const std::vector<TradeRow> measured = {
        measuredRow("baseline", "", 10.0, TimeVerdict::WithinNoise, 0.02),
        measuredRow("shading", "flat", 16.0, TimeVerdict::Slower, 0.05),
        measuredRow("normalize", "fast", 9.9, TimeVerdict::WithinNoise, 0.02),
        [] {
            TradeRow r = measuredRow("transparency", "unsorted", 10.0, TimeVerdict::WithinNoise, 0.02);
            r.noEffect = true;
            return r;
        }(),
        [] {
            TradeRow r = measuredRow("interpolation", "affine", 2.0, TimeVerdict::Faster, 0.9);
            r.blank = true;
            return r;
        }(),
        [] {
            TradeRow r = measuredRow("fresnel", "schlick", 7.0, TimeVerdict::Faster, 0.3);
            r.changesContent = true;
            return r;
        }(),
        measuredRow("aa", "msaa4", 20.0, TimeVerdict::Slower, 0.01),  // not aa's fast value: not a reason
    };
    std::vector<std::string> notes;
    TradeSetting fast = choosePreset("fast", measured, traded, notes);
    EXPECT_TRUE(fast.words.empty()) << fast.label();  // nothing measured faster; aa's fast is the scene's
    EXPECT_EQ(notes.size(), 5u);
    for (const char* flag : {"--shading", "--normalize", "--transparency", "--interpolation", "--fresnel"})
        EXPECT_TRUE(mentions(notes, std::string("leaves ") + flag)) << flag;
    EXPECT_TRUE(mentions(notes, "--shading flat: it measured slower"));
    EXPECT_TRUE(mentions(notes, "--normalize fast: it was not measurably faster"));

    // Normalize measured Faster: it goes in, and only it (interpolation, never traded, stays out).
    std::vector<TradeRow> faster = measured;
    faster[2].timeVerdict = TimeVerdict::Faster;
    notes.clear();
    fast = choosePreset("fast", faster, traded, notes);
    EXPECT_EQ(fast.words, (std::vector<std::string>{"--normalize", "fast"}));
    EXPECT_EQ(notes.size(), 4u);

    // --knobs aa alone: the preset holds no other knob, whatever the table's fast values.
    notes.clear();
    const TradeSetting aaOnly = choosePreset("fast", {measured[0]}, selectKnobs("aa"), notes);
    EXPECT_FALSE(hasWords(aaOnly, "--shading", "flat")) << aaOnly.label();
    EXPECT_TRUE(aaOnly.words.empty() || aaOnly.words.front() == "--aa") << aaOnly.label();
}

// The best preset takes a traded knob's best value only where its row scored more accurate than the
// baseline beyond the reference's own error. Catches: a best value taken on the table's word alone (one
// that scored worse), a difference within the reference's floor taken as a gain, a note missing.
TEST(TradePresets, TheBestPresetTakesOnlyKnobsMeasuredMoreAccurate) {
    const std::vector<const Knob*> traded = selectKnobs("aa,depth,normalize");
    std::vector<TradeRow> measured = {
        measuredRow("baseline", "", 10.0, TimeVerdict::WithinNoise, 0.02),
        measuredRow("aa", "ssaa16", 90.0, TimeVerdict::Slower, 0.01),  // more accurate: in
        measuredRow("depth", "reversed-float", 10.0, TimeVerdict::WithinNoise, 0.0199999),  // floor
        measuredRow("normalize", "exact", 11.0, TimeVerdict::Slower, 0.021),  // less accurate: out
    };
    measured[2].withinReferenceFloor = true;
    std::vector<std::string> notes;
    const TradeSetting best = choosePreset("best", measured, traded, notes);
    EXPECT_EQ(best.words, (std::vector<std::string>{"--aa", "ssaa16"}));
    EXPECT_EQ(notes.size(), 2u);
    EXPECT_TRUE(mentions(notes, "leaves --depth as the scene has it"));
    EXPECT_TRUE(mentions(notes, "--normalize exact: it was not more accurate"));
}

// After the presets are timed and scored: fast that did not measure Faster than the baseline becomes
// the fastest single setting measured Faster (its numbers; a note says so), or goes when there is none;
// best that scored worse than the most accurate single setting becomes it, or goes when that is the
// baseline; a preset no knob went into goes. Catches: a slower fast preset reported as it is, the
// fallback chosen by wall time or from a Slower row, best left worse than a single knob, a missing note.
TEST(TradePresets, FastIsNeverSlowerThanTheBaselineAndBestNeverWorseThanASingleKnob) {
    auto preset = [](const std::string& name, std::vector<std::string> words, double cpuMs,
                     TimeVerdict verdict, double error) {
        TradeRow row = measuredRow("baseline", "", cpuMs, verdict, error);
        row.setting = TradeSetting{"preset", name, std::move(words)};
        return row;
    };
    TradeResult result;
    result.rows = {
        measuredRow("baseline", "", 10.0, TimeVerdict::WithinNoise, 0.02),
        measuredRow("shading", "flat", 7.0, TimeVerdict::Faster, 0.05),
        measuredRow("shading", "gouraud", 8.0, TimeVerdict::Faster, 0.03),
        measuredRow("aa", "ssaa16", 90.0, TimeVerdict::Slower, 0.010),
        measuredRow("aa", "msaa8", 40.0, TimeVerdict::Slower, 0.012),
        preset("fast", {"--shading", "flat", "--aa", "none"}, 10.5, TimeVerdict::WithinNoise, 0.05),
        preset("best", {"--shading", "phong", "--aa", "ssaa16"}, 95.0, TimeVerdict::Slower, 0.0132),
    };
    result.rows[1].msMedian = 30.0;  // its wall time is not what decides
    keepPresetPromises(result);
    ASSERT_EQ(result.rows.size(), 7u);
    const TradeRow& fast = result.rows[5];
    EXPECT_EQ(fast.setting.knob, "preset");
    EXPECT_EQ(fast.setting.value, "fast");
    EXPECT_EQ(fast.setting.words, (std::vector<std::string>{"--shading", "flat"}));
    EXPECT_EQ(fast.cpuMsMedian, 7.0);
    EXPECT_EQ(fast.timeVerdict, TimeVerdict::Faster);
    const TradeRow& best = result.rows[6];
    EXPECT_EQ(best.setting.words, (std::vector<std::string>{"--aa", "ssaa16"}));
    EXPECT_NEAR(tradeError(best), 0.010, 1e-12);
    EXPECT_EQ(result.notes.size(), 2u);
    EXPECT_TRUE(mentions(result.notes, "fast is --shading flat alone"));
    EXPECT_TRUE(mentions(result.notes, "best is that setting"));

    // Nothing measured faster, nothing more accurate than the baseline: both presets go, with notes;
    // a preset that kept its promise stays as measured.
    TradeResult none;
    none.rows = {measuredRow("baseline", "", 10.0, TimeVerdict::WithinNoise, 0.02),
                 measuredRow("aa", "msaa8", 40.0, TimeVerdict::Slower, 0.025),
                 preset("fast", {"--aa", "msaa8"}, 12.0, TimeVerdict::Slower, 0.02),
                 preset("best", {"--aa", "msaa8"}, 40.0, TimeVerdict::Slower, 0.025),
                 preset("default", {"--aa", "none"}, 10.0, TimeVerdict::WithinNoise, 0.02)};
    keepPresetPromises(none);
    ASSERT_EQ(none.rows.size(), 3u);
    EXPECT_EQ(none.rows[2].setting.value, "default");
    EXPECT_EQ(none.notes.size(), 2u);
    TradeResult kept;
    kept.rows = {measuredRow("baseline", "", 10.0, TimeVerdict::WithinNoise, 0.02),
                 measuredRow("shading", "flat", 7.0, TimeVerdict::Faster, 0.05),
                 preset("fast", {"--shading", "flat", "--normalize", "fast"}, 6.0, TimeVerdict::Faster, 0.05),
                 preset("best", {}, 0.0, TimeVerdict::Faster, 0.0)};  // no knob went in: never timed
    keepPresetPromises(kept);
    ASSERT_EQ(kept.rows.size(), 3u);
    EXPECT_EQ(kept.rows[2].cpuMsMedian, 6.0);
    EXPECT_EQ(kept.notes.size(), 1u);  // best, untimed, is the scene as given
}

// A preset beaten on both counts by a single setting, within the run's margins, becomes that setting:
// best = ssaa16 when ssaa8 scores the same within the reference's floor at half the time; fast = flat
// plus shadows off when flat alone is as fast within the noise and more accurate beyond the floor.
// Catches: a preset left off the front the trade draws, the margins ignored (ssaa8 is 0.000006 worse:
// not "less accurate" under a floor of 0.000015; flat alone is 1% slower: not "slower" under ±5% noise),
// or the replacement taken from a row without effect.
TEST(TradePresets, NoSingleSettingBeatsAPresetOnBothCounts) {
    auto preset = [](const std::string& name, std::vector<std::string> words, double cpuMs,
                     TimeVerdict verdict, double error) {
        TradeRow row = measuredRow("baseline", "", cpuMs, verdict, error);
        row.setting = TradeSetting{"preset", name, std::move(words)};
        return row;
    };
    TradeRow sameImage = measuredRow("depth", "unorm24", 0.5, TimeVerdict::WithinNoise, 0.02);
    sameImage.noEffect = true;  // its time is noise: never a preset
    TradeResult result;
    result.timeNoise = 0.05;
    result.referenceFloor = 0.000015;
    result.rows = {
        measuredRow("baseline", "", 6.0, TimeVerdict::WithinNoise, 0.0026),
        measuredRow("shading", "flat", 0.82, TimeVerdict::Faster, 0.087),
        measuredRow("aa", "ssaa8", 60.0, TimeVerdict::Slower, 0.000384),
        measuredRow("aa", "ssaa16", 120.0, TimeVerdict::Slower, 0.000378),
        sameImage,
        preset("fast", {"--shading", "flat", "--shadows", "none"}, 0.81, TimeVerdict::Faster, 0.116),
        preset("best", {"--aa", "ssaa16"}, 121.0, TimeVerdict::Slower, 0.000378),
    };
    keepPresetPromises(result);
    ASSERT_EQ(result.rows.size(), 7u);
    EXPECT_EQ(result.rows[5].setting.value, "fast");
    EXPECT_EQ(result.rows[5].setting.words, (std::vector<std::string>{"--shading", "flat"}));
    EXPECT_EQ(result.rows[6].setting.value, "best");
    EXPECT_EQ(result.rows[6].setting.words, (std::vector<std::string>{"--aa", "ssaa8"}));
    EXPECT_EQ(result.rows[6].cpuMsMedian, 60.0);
    EXPECT_TRUE(mentions(result.notes, "preset fast: --shading flat alone"));
    EXPECT_TRUE(mentions(result.notes, "preset best: --aa ssaa8 alone"));
}

// The noise is the larger of how far each setting's round medians read from its own median (their 90th
// percentile) and the median distance of the rows without effect from the baseline, never below the
// floor; a verdict needs a difference beyond twice the noise. Catches: one row without effect that does
// more work (--cull none) swamping the estimate, the noise taken from rows that change the image (real
// differences read as noise), the rounds' repeats ignored, the floor dropped (a 1% difference judged on a
// quiet run), the factor of two dropped or the comparison reversed, a row without effect given a verdict.
TEST(TradeVerdicts, DifferencesWithinTwiceTheNoiseDecideNothing) {
    const TradeRow baseline = measuredRow("baseline", "", 10.0, TimeVerdict::Slower, 0.02);
    TradeRow same = measuredRow("transparency", "unsorted", 11.0, TimeVerdict::Faster, 0.02);
    same.noEffect = true;
    TradeRow cullNone = measuredRow("cull", "none", 20.0, TimeVerdict::Faster, 0.02);
    cullNone.noEffect = true;  // the same image for twice the work
    const TradeRow flat = measuredRow("shading", "flat", 5.0, TimeVerdict::WithinNoise, 0.05);
    EXPECT_DOUBLE_EQ(estimateTimeNoise({baseline, flat}, {{10.0, 10.2, 9.9}, {5.0, 5.0, 5.1}}),
                     kTimeNoiseFloor);
    EXPECT_NEAR(estimateTimeNoise({baseline, flat}, {{10.0, 9.5}, {5.0, 5.0}}), 0.05, 1e-12);
    EXPECT_NEAR(estimateTimeNoise({baseline, flat}, {{10.0, 10.0}, {5.0, 5.4}}), 0.08, 1e-12);  // any row's
    EXPECT_NEAR(estimateTimeNoise({baseline, flat, same}, {{10.0, 9.5}, {5.0, 5.0}}), 0.10, 1e-12);
    // The median of the rows without effect (4%, 10% and 100% off): the middle one, not the largest.
    TradeRow same2 = same;
    same2.cpuMsMedian = 10.4;
    EXPECT_NEAR(estimateTimeNoise({baseline, flat, same, same2, cullNone}, {{10.0, 10.0}}), 0.10, 1e-12);

    EXPECT_EQ(judgeTime(10.5, 10.0, 0.03), TimeVerdict::WithinNoise);
    EXPECT_EQ(judgeTime(10.7, 10.0, 0.03), TimeVerdict::Slower);
    EXPECT_EQ(judgeTime(9.5, 10.0, 0.03), TimeVerdict::WithinNoise);
    EXPECT_EQ(judgeTime(9.3, 10.0, 0.03), TimeVerdict::Faster);  // 9.3 · 1.06 < 10
    EXPECT_EQ(judgeTime(8.5, 10.0, 0.10), TimeVerdict::WithinNoise);

    TradeResult result;
    result.rows = {measuredRow("baseline", "", 10.0, TimeVerdict::Slower, 0.02), same, flat,
                   measuredRow("shading", "gouraud", 10.9, TimeVerdict::Faster, 0.03)};
    judgeTimes(result, {{10.0, 9.8}});
    EXPECT_NEAR(result.timeNoise, 0.10, 1e-12);  // the row without effect read 10% slower
    EXPECT_EQ(result.rows[0].timeVerdict, TimeVerdict::WithinNoise);
    EXPECT_EQ(result.rows[1].timeVerdict, TimeVerdict::WithinNoise);
    EXPECT_EQ(result.rows[2].timeVerdict, TimeVerdict::Faster);
    EXPECT_EQ(result.rows[3].timeVerdict, TimeVerdict::WithinNoise);
}

// The front takes no decision from noise: a row without effect never pushes the baseline off however
// fast it timed, a row within the noise counts at the baseline's time, a row within the reference's
// floor at the baseline's error; blank and content-changing rows are never on it. Catches: the front
// built on raw times or on wall times, a NO EFFECT, blank or content-changing row on it, a difference
// within the reference's floor pushing a row off, a setting timed twice pushing its twin off.
TEST(TradePareto, TheFrontTakesNoDecisionFromNoise) {
    std::vector<TradeRow> rows = {
        measuredRow("baseline", "", 10.0, TimeVerdict::WithinNoise, 0.02),
        measuredRow("transparency", "unsorted", 6.0, TimeVerdict::WithinNoise, 0.02),  // 0-1: no effect
        measuredRow("normalize", "fast", 9.0, TimeVerdict::WithinNoise, 0.02),  // 2: the baseline's time
        measuredRow("depth", "unorm16", 2.0, TimeVerdict::Faster, 0.5),         // 3: blank
        measuredRow("textures", "off", 3.0, TimeVerdict::Faster, 0.001),        // 4: other content
        measuredRow("shading", "flat", 5.0, TimeVerdict::Faster, 0.05),         // 5: on the front
        measuredRow("color-buffer", "float", 10.4, TimeVerdict::WithinNoise,
                    0.0199999),                                        // 6: within the floor
        measuredRow("aa", "ssaa16", 90.0, TimeVerdict::Slower, 0.01),  // 7: on the front
        measuredRow("aa", "ssaa16", 92.0, TimeVerdict::Slower, 0.01),  // 8: its twin (a preset) timed again
    };
    rows[1].noEffect = true;
    rows[3].blank = true;
    rows[4].changesContent = true;
    rows[6].withinReferenceFloor = true;
    rows[0].msMedian = 50.0;  // wall time: not the front's
    markParetoFront(rows, 0.03, 0.0);
    std::vector<bool> front;
    for (const TradeRow& row : rows)
        front.push_back(row.pareto);
    EXPECT_EQ(front, (std::vector<bool>{true, false, true, false, false, true, true, true, true}));
}

// What a trade decided: each row's time verdict and front membership, and the presets' settings.
std::vector<std::string> decisionsOf(const TradeResult& result) {
    auto verdict = [](TimeVerdict v) {
        return v == TimeVerdict::Faster ? "faster" : v == TimeVerdict::Slower ? "slower" : "within noise";
    };
    std::vector<std::string> decisions;
    for (std::size_t i = 0; i < result.rows.size(); ++i) {
        const TradeRow& row = result.rows[i];
        // A row that changes the image really costs what it costs: a colour buffer of 8 or 16 bits sits
        // near the margin (1 + 2 x noise) and reads "slower" in one run and "within noise" in the next on
        // a loaded machine, and with its verdict goes its place on the front (read faster by chance, the
        // less accurate row joins it). Only the baseline's and the no-effect rows' verdicts and places
        // are fixed by design.
        const bool verdictFixed = i == 0 || row.noEffect;
        decisions.push_back(row.setting.knob + " " + row.setting.value + " [" + row.setting.label() +
                            "]: " + (verdictFixed ? verdict(row.timeVerdict) : "any verdict") +
                            (row.pareto && verdictFixed ? ", front" : "") +
                            (row.noEffect ? ", no effect" : ""));
    }
    return decisions;
}

// The same small trade run twice in one test agrees on every decision: the time verdicts, the front and
// the presets' knobs. Its knobs cost the baseline's time or nearly (no transparency mode or depth format
// changes the opaque cow; the colour buffers of 8 and 16 bits change it, and their verdicts and places
// on the front are left out of the comparison), so that on a loaded machine any raw difference between their
// times is noise: with CPU time and the noise margin no verdict comes from it. (Anti-aliasing is left out:
// settings such as ssaa2 and msaa2 cost within a few per cent of each other, and which of the two a front
// keeps then depends on the margin of that run.) Catches: verdicts, front or presets taken from the raw times
// (the rows without effect then read faster or slower by chance and push the baseline off the front), a row
// without effect given a verdict.
TEST(TradeRepeat, TheSameTradeTwiceAgreesOnEveryVerdict) {
#if defined(FACET_TEST_ADDRESS_SANITIZER)
    // What this test checks is how the trade reads times, and instrumented code's times are not a
    // program's: the release suite runs it. The trade's code runs under the sanitizers in TradeRun.* and
    // the other tests here (this one, two whole trades of nine frames a setting and three rounds, was the
    // sanitized suite's longest test).
    GTEST_SKIP() << "the trade's verdicts on times are checked in an uninstrumented build";
#endif
    const testing_support::TempFolder folder;
    cli::SceneArgs args;
    args.input = kSpot;
    args.width = 160;
    args.height = 120;
    auto run = [&](const std::string& name) {
        TradeOptions options;
        options.knobs = "transparency,depth,color-buffer";
        options.frames = 9;
        options.rounds = 3;
        options.threads = 1;
        options.referenceSamples = 2;
        options.outputDir = folder.path() / name;
        options.progress = false;
        std::ostringstream log;
        return runTrade(
            [&](const std::vector<std::string>& words) { return cli::sceneWithWords(args, words); }, options,
            log);
    };
    const TradeResult first = run("first"), second = run("second");
    EXPECT_EQ(decisionsOf(first), decisionsOf(second))
        << "noise " << first.timeNoise << " and " << second.timeNoise;
    for (const TradeRow& row : first.rows)
        if (row.noEffect) {
            EXPECT_EQ(row.timeVerdict, TimeVerdict::WithinNoise) << row.setting.label();
        }
}

// --no-presets: the baseline and the knobs only. Catches: the flag not parsed, or parsed and not passed
// to the run (the fast, default and best rows back in the CSV).
TEST(TradeCommand, NoPresetsLeavesThePresetsOut) {
    const testing_support::TempFolder folder;
    CLI::App app;
    cli::TradeArgs args;
    cli::addTradeCommand(app, args);
    // clang-format off
    const std::vector<std::string> words = {"trade", kSpot, "--knobs", "shading", "--no-presets", "--frames", "1",
                                            "--rounds", "1", "--reference-samples", "1", "--width", "32",
                                            "--height", "24", "--threads", "1", "-q",
                                            "-o", (folder.path() / "trade").string()};
    // clang-format on
    app.parse(std::vector<std::string>(words.rbegin(), words.rend()));
    ASSERT_EQ(cli::trade(args), 0);
    std::ifstream csv(folder.path() / "trade" / "trade.csv");
    std::string line;
    std::size_t rows = 0;
    std::getline(csv, line);
    while (std::getline(csv, line)) {
        ++rows;
        EXPECT_NE(line.rfind("preset,", 0), 0u) << line;
    }
    EXPECT_EQ(rows, 3u);  // the baseline, flat, Gouraud
}

// The busy warning: other processes left fewer free CPUs than the render threads, or the repeats
// spread by more than 10%. Catches: a warning on a quiet machine, none when the other processes took
// the CPUs the threads needed, the noise criterion dropped.
TEST(TradeVerdicts, TheBusyWarningSaysWhatWasSeen) {
    EXPECT_EQ(busyMachineWarning(0.1, 2, 2, 0.03), "");
    EXPECT_EQ(busyMachineWarning(1.5, 8, 2, 0.03), "");  // six CPUs left for two threads
    const std::string others = busyMachineWarning(1.4, 2, 2, 0.03);
    EXPECT_NE(others.find("other processes kept 1.4 of the 2 CPUs"), std::string::npos) << others;
    EXPECT_EQ(others.find('\n'), std::string::npos);
    const std::string noise = busyMachineWarning(0.0, 2, 1, 0.15);
    EXPECT_NE(noise.find("up to 15%"), std::string::npos) << noise;
}

TEST(TradeKnobs, AnUnknownNameIsOneLineListingTheValidOnes) {
    try {
        selectKnobs("shading,shadwos");
        FAIL() << "no error";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("--knobs: unknown knob \"shadwos\""), std::string::npos) << message;
        EXPECT_NE(message.find("shading, interpolation, shadows"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    EXPECT_THROW(selectKnobs("shading,"), InputError);
    EXPECT_EQ(selectKnobs("shadows,shading").size(), 2u);
}

TEST(TradePareto, TheFrontIsThePointsNoneBeatsOnBothCounts) {
    // x: ms, y: error.
    const std::vector<glm::dvec2> points = {
        {10, 0.5},   // 0: on the front (fastest)
        {20, 0.1},   // 1: on the front
        {15, 0.6},   // 2: slower and worse than 0
        {30, 0.01},  // 3: on the front (most accurate)
        {30, 0.1},   // 4: as accurate as 1, slower
        {20, 0.1},   // 5: equal to 1: not beaten, on the front
        {40, 0.02},  // 6: slower and worse than 3
    };
    EXPECT_EQ(paretoFront(points), (std::vector<std::size_t>{0, 1, 5, 3}));
    EXPECT_EQ(paretoFront({{1, std::nan("")}, {2, 1}}), (std::vector<std::size_t>{1}));
}

// With margins, differences too small to measure decide nothing: times within a factor 1.06 and errors
// within 0.001 count as equal. Catches: the margins ignored (a twin timed 4% slower pushed off, a
// 1e-4 better error taking the front), or applied the wrong way (a point measurably faster and as
// accurate within the margin left beside the point it beats).
TEST(TradePareto, DifferencesWithinTheMarginsCountAsEqual) {
    EXPECT_EQ(paretoFront({{10, 0.5}, {10.4, 0.5}}), (std::vector<std::size_t>{0}));
    EXPECT_EQ(paretoFront({{10, 0.5}, {10.4, 0.5}}, 0.06, 0.001), (std::vector<std::size_t>{0, 1}));
    EXPECT_EQ(paretoFront({{10, 0.5}, {10, 0.4999}}), (std::vector<std::size_t>{1}));
    EXPECT_EQ(paretoFront({{10, 0.5}, {10, 0.4999}}, 0.06, 0.001), (std::vector<std::size_t>{1, 0}));
    EXPECT_EQ(paretoFront({{10, 0.5}, {12, 0.4999}}), (std::vector<std::size_t>{0, 1}));
    EXPECT_EQ(paretoFront({{10, 0.5}, {12, 0.4999}}, 0.06, 0.001), (std::vector<std::size_t>{0}));
}

TEST(TradeMetrics, IdenticalImagesHaveTheCappedPsnrAndAnSsimOfOne) {
    LinearImage image;
    image.width = 24;
    image.height = 16;
    for (int k = 0; k < image.width * image.height; ++k)
        image.pixels.push_back(glm::vec4(0.01f * (k % 97), 0.3f, 0.002f * (k % 13), 1.0f));
    const ImageError same = measureError(image, image, kSrgbEncoding);
    for (const ErrorMetrics* m : {&same.linear, &same.encoded}) {
        EXPECT_EQ(m->psnr, kMaxPsnr);
        EXPECT_DOUBLE_EQ(m->ssim, 1.0);
        EXPECT_EQ(m->meanAbs, 0.0);
        EXPECT_EQ(m->over1, 0.0);
    }
    // One pixel's red two codes off in the 8-bit image: above 1/255, not above 2/255.
    LinearImage other = image;
    other.pixels[5] = glm::vec4(0.5f, 0.3f, 0.0f, 1.0f);
    image.pixels[5] =
        glm::vec4(srgbToLinear((encodeChannel(0.5f, kSrgbEncoding) + 2) / 255.0f), 0.3f, 0.0f, 1.0f);
    const ImageError two = measureError(image, other, kSrgbEncoding);
    EXPECT_DOUBLE_EQ(two.encoded.over1, 1.0 / (24 * 16));
    EXPECT_EQ(two.encoded.over2, 0.0);
    EXPECT_NEAR(two.encoded.maxAbs, 2.0 / 255.0, 1e-6);
    EXPECT_LT(two.encoded.psnr, kMaxPsnr);
    EXPECT_LT(two.encoded.ssim, 1.0);
}

// facet trade --shader: the knobs timed and scored with a shader of one's own, against the reference
// traced with it (displace_cutout.cpp, its vertices moved along the normal), the shader compiled once for
// every setting. Breaks caught: the shader compiled for the first setting and again for the next; the trade's
// settings parsed onto a fresh scene that drops --shader or --uniform (the rows drawn with the built-in
// shader, far from the reference); the reference traced with the built-in shader or at the mesh's own
// positions (its image the built-in's, the rows far from it).
TEST(TradeWithShader, TheKnobsAreScoredAgainstTheReferenceOfTheShader) {
    const testing_support::TempFolder folder;
    // A cache of its own: the compile is seen (a shared cache may hold the modules already).
    ::setenv("FACET_SHADER_CACHE", (folder.path() / "cache").c_str(), 1);
    CLI::App app;
    cli::TradeArgs args;
    cli::addTradeCommand(app, args);
    const std::string shader = (testing_support::kUserShaders / "displace_cutout.cpp").string();
    // clang-format off
    const std::vector<std::string> words = {"trade", kSpot, "--shader", shader, "--uniform", "displacement=0.04",
                                            "--knobs", "depth", "--frames", "1", "--rounds", "1",
                                            "--reference-samples", "1", "--width", "48", "--height", "36",
                                            "--threads", "1", "-q", "-o", (folder.path() / "trade").string()};
    // clang-format on
    app.parse(std::vector<std::string>(words.rbegin(), words.rend()));
    TradeOptions options;
    options.knobs = args.knobs;
    selectKnobs(options.knobs);
    options.frames = args.frames;
    options.rounds = args.rounds;
    options.threads = 1;
    options.referenceSamples = args.referenceSamples;
    options.progress = false;
    options.outputDir = folder.path() / "trade";
    std::ostringstream log;
    ::testing::internal::CaptureStderr();
    const TradeResult result = runTrade(
        [&](const std::vector<std::string>& settingWords) {
            return cli::sceneWithWords(args.scene, settingWords);
        },
        options, log);
    const std::string messages = ::testing::internal::GetCapturedStderr();
    ::unsetenv("FACET_SHADER_CACHE");
    // The depth formats are several kinds of draw: the shader compiled once for all of them.
    EXPECT_EQ(messages.find(" again, for "), std::string::npos) << messages;
    ASSERT_GE(result.rows.size(), 2u);
    // The baseline (the shader as given) is close to the shader's reference.
    EXPECT_EQ(result.rows[0].setting.knob, "baseline");
    EXPECT_GT(result.rows[0].error.encoded.ssim, 0.95) << result.rows[0].image;
    // That reference is not the built-in shader's: the built-in's own reference image differs from it.
    Scene builtIn = loadSceneOrModel(kSpot);
    builtIn.width = 48;
    builtIn.height = 36;
    ReferenceOptions referenceOptions;
    referenceOptions.samples = 1;
    ThreadPool pool(1);
    const LinearImage builtInReference = renderReference(prepareScene(builtIn), referenceOptions, pool);
    const LinearImage reference = readImage(options.outputDir / "reference.png");
    const ImageError error = measureError(reference, builtInReference, kSrgbEncoding);
    EXPECT_LT(error.encoded.ssim, 0.9) << error.encoded.ssim;
}

}  // namespace
}  // namespace facet
