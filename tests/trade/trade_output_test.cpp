// facet trade's output: the table keeps its columns apart and its labels whole, shows every verdict and
// flag, sets apart the settings that change the scene; the CSV has the verdicts' columns; the chart's
// points say what they are; the progress estimates the time left from the times measured so far.
#include <algorithm>
#include <cstdio>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "trade/progress.h"
#include "trade/report.h"
#include "trade/trade.h"

namespace facet {
namespace {

std::vector<std::string> linesOf(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        lines.push_back(line);
    return lines;
}

std::size_t codePoints(const std::string& text) {
    return static_cast<std::size_t>(std::count_if(
        text.begin(), text.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

// The cells of a table line: its text split where two or more spaces separate it.
std::vector<std::string> cellsOf(const std::string& line) {
    std::vector<std::string> cells;
    const std::regex gap(" {2,}");
    for (std::sregex_token_iterator it(line.begin(), line.end(), gap, -1), end; it != end; ++it)
        if (!it->str().empty()) cells.push_back(*it);
    return cells;
}

TradeRow makeRow(const std::string& knob, const std::string& value, double cpuMs, double ssim) {
    TradeRow row;
    if (knob == "baseline")
        row.setting = TradeSetting{"baseline", "", {}};
    else if (knob == "preset")
        row.setting = presetSetting(value);
    else
        row.setting = knobSetting(knobNamed(knob), value);
    row.cpuMsMedian = cpuMs;
    row.cpuMsMin = 0.98 * cpuMs;
    row.cpuMsMax = 1.03 * cpuMs;
    row.msMedian = 1.1 * cpuMs;
    row.msMin = row.msMedian - 1;
    row.msMax = row.msMedian + 1;
    row.frames = 9;
    row.error.encoded.ssim = row.error.linear.ssim = ssim;
    row.error.encoded.psnr = row.error.linear.psnr = 41.25;
    row.error.encoded.over1 = 0.125;
    return row;
}

// A made-up result with every kind of row: times of four digits side by side (the "2443.421006.54" of a
// table whose columns ran together), a label far longer than the others, every flag and verdict.
TradeResult syntheticResult() {
    TradeResult result;
    result.rows.push_back(makeRow("baseline", "", 2443.42, 0.99));
    result.rows.push_back(makeRow("shading", "flat", 1006.54, 0.95));
    result.rows.back().timeVerdict = TimeVerdict::Faster;
    result.rows.back().pareto = true;
    result.rows.push_back(makeRow("shadow-map-size", "4096", 9876.54, 0.99));
    result.rows.back().timeVerdict = TimeVerdict::Slower;
    result.rows.back().withinReferenceFloor = true;
    result.rows.push_back(makeRow("transparency", "exact", 2450.00, 0.99));
    result.rows.back().noEffect = true;
    result.rows.push_back(makeRow("depth", "unorm16", 401.00, 0.20));
    result.rows.back().timeVerdict = TimeVerdict::Faster;
    result.rows.back().blank = true;
    result.rows.push_back(makeRow("textures", "off", 2000.00, 0.90));
    result.rows.back().timeVerdict = TimeVerdict::Faster;
    result.rows.back().changesContent = true;
    result.rows.push_back(makeRow("preset", "fast", 900.00, 0.94));
    result.rows.back().timeVerdict = TimeVerdict::Faster;
    result.rows.back().pareto = true;
    result.timeNoise = 0.04;
    result.referenceSamples = 8;
    result.referenceFloor = 0.00023;
    result.warnings = {"the machine was busy: 40% of the frames waited for a CPU"};
    result.notes = {"preset fast keeps the scene's --shading"};
    result.skipped = {"--shading phong (the baseline's own)"};
    result.recommendations = {"--aa msaa2: half the edge error for 1.7× the time",
                              "--shading flat: faster, 5 times the error"};
    return result;
}

std::string labelOf(const TradeRow& row) {
    return row.setting.knob == "preset" ? "preset " + row.setting.value : row.setting.label();
}

// Catches: columns that run together when a number fills its width ("2443.421006.54"), a label longer
// than the label column wrapped onto a line of its own or cut, a cell out of its column, or a table
// wider than 100 columns.
TEST(TradeTable, ColumnsStayApartAndLabelsWhole) {
    const TradeResult result = syntheticResult();
    std::ostringstream out;
    printTradeTable(result, out);
    const std::vector<std::string> lines = linesOf(out.str());
    for (const std::string& line : lines)
        EXPECT_LE(codePoints(line), 100u) << line;
    // Each row appears twice (time, then error), whole on one line, its cells apart.
    for (const TradeRow& row : result.rows) {
        const std::string label = labelOf(row);
        std::vector<std::string> mine;
        for (const std::string& line : lines)
            if (line.rfind(label + "  ", 0) == 0) mine.push_back(line);
        ASSERT_EQ(mine.size(), 2u) << label << "\n" << out.str();
        const std::vector<std::string> time = cellsOf(mine[0]);
        ASSERT_GE(time.size(), 5u) << mine[0];
        char median[32];
        std::snprintf(median, sizeof median, "%.2f", row.cpuMsMedian);
        EXPECT_EQ(time[0], label);
        EXPECT_EQ(time[1], median) << mine[0];
        const std::vector<std::string> error = cellsOf(mine[1]);
        ASSERT_GE(error.size(), 7u) << mine[1];
        EXPECT_EQ(error[0], label);
    }
    // The numbers of a column end where its heading ends: right-aligned under it.
    const auto heading = std::find_if(lines.begin(), lines.end(),
                                      [](const std::string& l) { return l.rfind("setting ", 0) == 0; });
    ASSERT_NE(heading, lines.end());
    const std::size_t medianEnd = heading->find("median") + 6;
    for (const TradeRow& row : result.rows) {
        char median[32];
        std::snprintf(median, sizeof median, "%.2f", row.cpuMsMedian);
        const auto line = std::find_if(lines.begin(), lines.end(), [&](const std::string& l) {
            return l.rfind(labelOf(row) + "  ", 0) == 0;
        });
        EXPECT_EQ(line->find(std::string(median) + "  ") + std::string(median).size(), medianEnd) << *line;
    }
}

// Catches: a verdict, a ratio or a flag not shown (the time verdict, × baseline by CPU time, BLANK, within
// floor, NO EFFECT, front), the baseline given a verdict against itself, or one of the lines under the
// table (noise, the reference's rays and floor, warnings, notes, skipped, recommendations) missing.
TEST(TradeTable, ShowsTheVerdictsFlagsAndTheLinesUnder) {
    const TradeResult result = syntheticResult();
    std::ostringstream out;
    printTradeTable(result, out);
    const std::string text = out.str();
    const std::vector<std::string> lines = linesOf(text);
    auto rowLines = [&](const std::string& label) {
        std::vector<std::vector<std::string>> found;
        for (const std::string& line : lines)
            if (line.rfind(label + "  ", 0) == 0) found.push_back(cellsOf(line));
        return found;
    };
    // Time: median, spread, wall, × baseline (CPU medians: 1006.54 / 2443.42 = 0.41), verdict.
    const auto flat = rowLines("--shading flat");
    ASSERT_EQ(flat.size(), 2u);
    EXPECT_EQ(flat[0],
              (std::vector<std::string>{"--shading flat", "1006.54", "50.33", "1107.19", "0.41×", "faster"}));
    EXPECT_EQ(flat[1].back(), "front");
    EXPECT_EQ(rowLines("baseline")[0].size(), 5u);  // no verdict against itself
    EXPECT_EQ(rowLines("baseline")[0][4], "1.00×");
    EXPECT_EQ(rowLines("--transparency exact")[0].back(), "within noise");
    EXPECT_EQ(rowLines("--transparency exact")[1].back(), "NO EFFECT");
    EXPECT_EQ(rowLines("--shadows map --shadow-map-size 4096")[0].back(), "slower");
    EXPECT_EQ(rowLines("--shadows map --shadow-map-size 4096")[1].back(), "within floor");
    EXPECT_EQ(rowLines("--depth unorm16")[1].back(), "BLANK");
    EXPECT_EQ(rowLines("preset fast")[1].back(), "front");
    for (const char* expected :
         {"noise: ±4.0%", "8×8 rays per pixel", "1 - SSIM 0.00023",
          "warning: the machine was busy: 40% of the frames waited for a CPU",
          "preset fast keeps the scene's --shading", "skipped: --shading phong (the baseline's own)"})
        EXPECT_NE(text.find(expected), std::string::npos) << expected << "\n" << text;
    for (const std::string& recommendation : result.recommendations)
        EXPECT_NE(std::find(lines.begin(), lines.end(), "  " + recommendation), lines.end())
            << recommendation;
}

// Catches: a setting that changes what the scene shows (--textures off) ranked among the accuracy knobs
// instead of after them under its own heading, in either table.
TEST(TradeTable, ContentChangingSettingsComeLastUnderTheirOwnHeading) {
    std::ostringstream out;
    printTradeTable(syntheticResult(), out);
    const std::vector<std::string> lines = linesOf(out.str());
    std::vector<std::size_t> headings, textures, presets;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (lines[i].rfind("Settings that change what the scene shows", 0) == 0) headings.push_back(i);
        if (lines[i].rfind("--textures off  ", 0) == 0) textures.push_back(i);
        if (lines[i].rfind("preset fast  ", 0) == 0) presets.push_back(i);
    }
    ASSERT_EQ(headings.size(), 2u);
    ASSERT_EQ(textures.size(), 2u);
    ASSERT_EQ(presets.size(), 2u);
    for (int table = 0; table < 2; ++table) {
        EXPECT_LT(presets[table], headings[table]);  // the last accuracy row before the heading
        EXPECT_EQ(textures[table], headings[table] + 1);
    }
}

// Catches: the CSV's earlier columns moved or renamed (a reader by position or name breaks), a new
// column missing, or its value not the row's (verdict words, flags, CPU times).
TEST(TradeCsv, KeepsItsColumnsAndAddsTheVerdicts) {
    const TradeResult result = syntheticResult();
    std::ostringstream out;
    writeTradeCsv(result, out);
    const std::vector<std::string> lines = linesOf(out.str());
    ASSERT_EQ(lines.size(), result.rows.size() + 1);
    const std::string earlier =
        "knob,value,flags,frames,ms_median,ms_min,ms_max,ms_shadow_setup,linear_psnr_db,linear_ssim,"
        "linear_mean_abs,linear_max_abs,linear_over_1_255,linear_over_2_255,output8_psnr_db,output8_ssim,"
        "output8_mean_abs,output8_max_abs,output8_over_1_255,output8_over_2_255,no_effect,pareto,image,"
        "error_image";
    EXPECT_EQ(lines[0], earlier +
                            ",cpu_ms_median,cpu_ms_min,cpu_ms_max,time_verdict,blank,changes_content,"
                            "within_reference_floor,scores_meaningful");
    auto tail = [&](std::size_t row) {  // the last eight fields (no field of these rows is quoted)
        std::vector<std::string> fields;
        std::stringstream in(lines[row + 1]);
        for (std::string field; std::getline(in, field, ',');)
            fields.push_back(field);
        if (lines[row + 1].back() == ',') fields.push_back("");
        return std::vector<std::string>(fields.end() - 8, fields.end());
    };
    EXPECT_EQ(tail(0),
              (std::vector<std::string>{"2443.42", "2394.5516", "2516.7226", "", "0", "0", "0", "1"}));
    EXPECT_EQ(tail(1)[3], "faster");
    EXPECT_EQ(tail(2)[3], "slower");
    EXPECT_EQ(tail(2)[6], "1");
    EXPECT_EQ(tail(3)[3], "within noise");
    EXPECT_EQ(tail(4)[4], "1");
    EXPECT_EQ(tail(4)[7], "0");  // a blank row's scores are an empty image's
    EXPECT_EQ(tail(5)[5], "1");
}

// Catches: a setting without effect labelled or drawn in a strong colour (even on the front), a blank or
// content-changing setting drawn like the others, the baseline not placed first, or the chart's x not
// the CPU time with its fastest and slowest frame.
TEST(TradeChart, PointsSayWhatTheyAre) {
    TradeResult result = syntheticResult();
    result.rows[3].pareto = true;  // without effect, yet on the front
    std::vector<std::size_t> rowOf;
    const std::vector<LabelledPoint> points = chartPoints(result, rowOf);
    ASSERT_EQ(points.size(), result.rows.size());
    EXPECT_EQ(rowOf[0], 0u);
    EXPECT_EQ(points[0].label, "baseline");
    for (std::size_t i = 0; i < points.size(); ++i) {
        const TradeRow& row = result.rows[rowOf[i]];
        SCOPED_TRACE(labelOf(row));
        EXPECT_DOUBLE_EQ(points[i].point.x, row.cpuMsMedian);
        EXPECT_DOUBLE_EQ(points[i].spread.x, row.cpuMsMin);
        EXPECT_DOUBLE_EQ(points[i].spread.y, row.cpuMsMax);
        EXPECT_EQ(points[i].hollow, row.blank || row.changesContent);
        if (row.noEffect) {
            EXPECT_TRUE(points[i].label.empty());
            EXPECT_GT(points[i].color.r, 0.5f);  // pale
            EXPECT_EQ(i, points.size() - 1);     // drawn first, under the others, labelled last
        } else {
            EXPECT_FALSE(points[i].label.empty());
        }
    }
}

// The estimate of the time left, on a clock the test moves: the plan is the baseline (0) and two
// settings in two rounds. The baseline's first run takes 10 s of frames and 2 s of scoring: setting 1,
// not yet run, is estimated as that (12 s), and round 2's runs from each setting's own frames.
// Catches: an estimate that counts the scoring in later rounds, ignores a setting's own time for its
// later runs, keeps the first scoring (which loads the comparison's library) for every setting, or
// counts the run just finished.
TEST(TradeProgressEstimate, LaterRunsFromTheirOwnFirstAndTheRestFromTheBaseline) {
    double now = 0;
    std::ostringstream log;
    TradeProgress progress(log, true, [&] { return now; });
    progress.plan({0, 1, 2, 0, 1, 2});
    EXPECT_TRUE(std::isnan(progress.msLeft()));
    EXPECT_EQ(progress.leftSuffix(), "");
    auto run = [&](std::size_t setting, double framesMs, double scoringMs) {
        progress.runStarted(setting);
        now += framesMs;
        progress.framesTimed(setting);
        now += scoringMs;
        progress.runFinished(setting);
    };
    run(0, 10000, 2000);
    // Left: 1 and 2 unseen (12 s each, scored), then 0, 1, 2 again (10 s each, frames only).
    EXPECT_DOUBLE_EQ(progress.msLeft(), 2 * 12000 + 3 * 10000);
    EXPECT_EQ(progress.leftSuffix(), "");  // not printed yet: one scoring, which loads the comparison
    run(1, 40000, 1000);
    // Setting 2's first run now from the last scoring (1 s) rather than the baseline's first (2 s).
    EXPECT_DOUBLE_EQ(progress.msLeft(), 11000 + 10000 + 40000 + 10000);
    EXPECT_EQ(progress.leftSuffix(), "; about 1 min 10 s left");
    run(2, 5000, 1000);
    EXPECT_DOUBLE_EQ(progress.msLeft(), 10000 + 40000 + 5000);
    run(0, 11000, 0);  // a later run: its new time predicts the next
    run(1, 30000, 0);
    EXPECT_DOUBLE_EQ(progress.msLeft(), 5000);
    EXPECT_EQ(progress.leftSuffix(), "; about 5 s left");
    run(2, 5000, 0);
    EXPECT_DOUBLE_EQ(progress.msLeft(), 0);
    EXPECT_EQ(progress.leftSuffix(), "");  // the last line says nothing is left
}

// Catches: the reference's progress printed more than once a second (a line per row), its estimate not
// the time so far scaled by the rows still to trace, a line at 100% (the trade prints the finished
// reference), or anything printed under -q.
TEST(TradeProgressEstimate, TheReferenceAtMostOnceASecond) {
    double now = 0;
    std::ostringstream log;
    TradeProgress progress(log, true, [&] { return now; });
    progress.referenceStarted(now);
    for (int row = 1; row <= 100; ++row) {
        now += 50;  // 5 s for 100 rows
        progress.referenceRows(row, 100);
    }
    // Lines at 1, 2, 3 and 4 s: 20% (4 s left), 40% (3 s), 60% (2 s), 80% (1 s).
    EXPECT_EQ(log.str(),
              "reference: 20%, about 4 s left\nreference: 40%, about 3 s left\n"
              "reference: 60%, about 2 s left\nreference: 80%, about 1 s left\n");
    std::ostringstream quiet;
    TradeProgress silent(quiet, false, [&] { return now; });
    silent.referenceStarted(now);
    now += 5000;
    silent.referenceRows(50, 100);
    EXPECT_EQ(quiet.str(), "");
}

// Catches: minutes and seconds mixed up, an estimate past a minute given to the second (a count-down
// that a noisy machine makes jump), or a zero-second estimate.
TEST(TradeProgressEstimate, TimeLeftInWords) {
    EXPECT_EQ(timeLeftText(0.2), "under a second left");
    EXPECT_EQ(timeLeftText(6.4), "about 6 s left");
    EXPECT_EQ(timeLeftText(59.0), "about 59 s left");
    EXPECT_EQ(timeLeftText(130.0), "about 2 min 10 s left");
    EXPECT_EQ(timeLeftText(133.0), "about 2 min 10 s left");
    EXPECT_EQ(timeLeftText(178.0), "about 3 min left");
}

}  // namespace
}  // namespace facet
