#include "trade/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <utility>

#include "trade/blank.h"

namespace facet {

namespace {

// Enough digits for a CSV: a metric of 0.9999987 keeps its distance from 1.
std::string csvNumber(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", value);
    return text;
}

std::string csvField(const std::string& text) {  // quoted when it holds a comma or a quote
    if (text.find_first_of(",\"") == std::string::npos) return text;
    std::string quoted = "\"";
    for (const char c : text) {
        if (c == '"') quoted += '"';
        quoted += c;
    }
    quoted += '"';
    return quoted;
}

// Columns on a terminal count characters, not bytes ("×" is two bytes of UTF-8).
std::size_t codePoints(const std::string& text) {
    return static_cast<std::size_t>(std::count_if(
        text.begin(), text.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

// A table for the terminal: each column as wide as its widest cell, two spaces between columns, so that
// no two cells ever touch whatever their length; the first column (the labels) and the last (words) left-
// aligned, the numbers between right-aligned. Heading lines may span columns; a line of text of its own
// (a section's title) may come between rows.
class TextTable {
  public:
    explicit TextTable(std::size_t columns) : widths_(columns, 0) {}

    // A heading line of spans: (first column, text), each over the columns up to the next span's first.
    void spans(std::vector<std::pair<std::size_t, std::string>> spans) {
        lines_.push_back({Kind::Spans, {}, std::move(spans), {}});
    }
    void row(std::vector<std::string> cells) {
        cells.resize(widths_.size());
        for (std::size_t c = 0; c < cells.size(); ++c)
            widths_[c] = std::max(widths_[c], codePoints(cells[c]));
        lines_.push_back({Kind::Row, std::move(cells), {}, {}});
    }
    void text(std::string line) { lines_.push_back({Kind::Text, {}, {}, std::move(line)}); }

    void print(std::ostream& out) const {
        std::vector<std::size_t> widths = widths_;
        // A span's text wider than its columns widens its last column.
        for (const Line& line : lines_)
            for (std::size_t s = 0; s < line.spans.size(); ++s) {
                const std::size_t first = line.spans[s].first;
                const std::size_t end = s + 1 < line.spans.size() ? line.spans[s + 1].first : widths.size();
                const std::size_t text = codePoints(line.spans[s].second);
                if (text > spanWidth(widths, first, end))
                    widths[end - 1] += text - spanWidth(widths, first, end);
            }
        for (const Line& line : lines_) {
            std::string printed;
            if (line.kind == Kind::Text) {
                printed = line.text;
            } else if (line.kind == Kind::Row) {
                for (std::size_t c = 0; c < widths.size(); ++c) {
                    const std::string pad(widths[c] - codePoints(line.cells[c]), ' ');
                    if (c > 0) printed += "  ";
                    const bool left = c == 0 || c + 1 == widths.size();
                    printed += left ? line.cells[c] + pad : pad + line.cells[c];
                }
            } else {
                // Each span's text right-aligned over its columns (the numbers under it are).
                for (std::size_t s = 0; s < line.spans.size(); ++s) {
                    const std::size_t first = line.spans[s].first;
                    const std::size_t end =
                        s + 1 < line.spans.size() ? line.spans[s + 1].first : widths.size();
                    if (s == 0 && first > 0) printed += std::string(spanWidth(widths, 0, first) + 2, ' ');
                    const std::string& text = line.spans[s].second;
                    printed += std::string(spanWidth(widths, first, end) - codePoints(text), ' ') + text;
                    if (end < widths.size()) printed += "  ";
                }
            }
            while (!printed.empty() && printed.back() == ' ')
                printed.pop_back();
            out << printed << "\n";
        }
    }

  private:
    enum class Kind { Row, Spans, Text };
    struct Line {
        Kind kind;
        std::vector<std::string> cells;
        std::vector<std::pair<std::size_t, std::string>> spans;
        std::string text;
    };
    static std::size_t spanWidth(const std::vector<std::size_t>& widths, std::size_t first, std::size_t end) {
        std::size_t width = 0;
        for (std::size_t c = first; c < end; ++c)
            width += widths[c] + (c > first ? 2 : 0);
        return width;
    }
    std::vector<std::size_t> widths_;
    std::vector<Line> lines_;
};

// The rows in the table's order: the accuracy knobs and presets as measured, then those that change
// what the scene shows, in a section of their own.
template <class Print>
void forEachRowBySection(const TradeResult& result, TextTable& table, const Print& print) {
    for (const TradeRow& row : result.rows)
        if (!row.changesContent) print(row);
    bool first = true;
    for (const TradeRow& row : result.rows) {
        if (!row.changesContent) continue;
        if (first) table.text("Settings that change what the scene shows (not ranked with the knobs above):");
        first = false;
        print(row);
    }
}

std::string flagsOf(const TradeRow& row) {
    std::string flags;
    auto add = [&](const char* flag) { flags += (flags.empty() ? "" : ", ") + std::string(flag); };
    if (row.pareto) add("front");
    if (row.noEffect) add("NO EFFECT");
    if (row.blank) add("BLANK");
    if (row.withinReferenceFloor) add("within floor");
    return flags;
}

// The chart's label of a row: the knob's own words (its prerequisite's are in the CSV), "preset fast".
std::string chartLabel(const TradeSetting& setting) {
    if (setting.knob == "baseline") return "baseline";
    if (setting.knob == "preset") return "preset " + setting.value;
    return setting.words[setting.words.size() - 2] + " " + setting.words.back();
}

bool measuredCpu(const TradeResult& result) {
    return !result.rows.empty() && std::all_of(result.rows.begin(), result.rows.end(),
                                               [](const TradeRow& r) { return r.cpuMsMedian > 0; });
}

}  // namespace

std::string number(double value, int decimals) {
    char text[32];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    return text;
}

std::string tradeRowLabel(const TradeSetting& setting) {
    return setting.knob == "preset" ? "preset " + setting.value : setting.label();
}

const char* timeVerdictWords(TimeVerdict verdict) {
    switch (verdict) {
        case TimeVerdict::Faster:
            return "faster";
        case TimeVerdict::Slower:
            return "slower";
        case TimeVerdict::WithinNoise:
            break;
    }
    return "within noise";
}

ChartTime chartTime(const TradeResult& result, const TradeRow& row) {
    if (measuredCpu(result)) return {row.cpuMsMedian, row.cpuMsMin, row.cpuMsMax};
    return {row.msMedian, row.msMin, row.msMax};
}

std::vector<LabelledPoint> chartPoints(const TradeResult& result, std::vector<std::size_t>& rowOfPoint) {
    // Drawn and labelled in this order of importance: the baseline (labelled first, so that no other
    // label covers it, and drawn on top), the front, the presets, the other settings, those set apart
    // (blank images, changed scenes), and last the settings without effect: they sit on the baseline's
    // error, pale and unlabelled (even on the front), so that the cluster around the baseline does not
    // bury the labels of the settings that matter.
    enum Group { Baseline, Front, Preset, Other, Apart, NoEffect };
    auto groupOf = [](const TradeRow& row) {
        if (row.setting.knob == "baseline") return Baseline;
        if (row.noEffect) return NoEffect;
        if (row.blank || row.changesContent) return Apart;
        if (row.pareto) return Front;
        return row.setting.knob == "preset" ? Preset : Other;
    };
    rowOfPoint.clear();
    for (const Group group : {Baseline, Front, Preset, Other, Apart, NoEffect})
        for (std::size_t k = 0; k < result.rows.size(); ++k)
            if (groupOf(result.rows[k]) == group) rowOfPoint.push_back(k);
    std::vector<LabelledPoint> points;
    for (const std::size_t k : rowOfPoint) {
        const TradeRow& row = result.rows[k];
        const ChartTime time = chartTime(result, row);
        LabelledPoint point{chartLabel(row.setting), {time.median, tradeError(row)}, srgb8(150, 150, 150)};
        point.spread = {time.fastest, time.slowest};
        switch (groupOf(row)) {
            case Baseline:
                point.color = srgb8(20, 20, 20);
                break;
            case Front:
                point.color = srgb8(30, 100, 200);
                break;
            case Preset:
                point.color = srgb8(230, 120, 20);
                break;
            case Other:
                break;
            case Apart:
                point.hollow = true;
                point.color = row.blank ? srgb8(210, 40, 40) : srgb8(140, 60, 170);
                if (row.blank) point.label += " (BLANK)";
                break;
            case NoEffect:
                point.color = srgb8(210, 210, 210);
                point.label.clear();
                break;
        }
        points.push_back(std::move(point));
    }
    return points;
}

void writeTradeChart(const TradeResult& result, const std::string& title, const std::filesystem::path& path) {
    std::vector<std::size_t> rowOfPoint;
    const std::vector<LabelledPoint> points = chartPoints(result, rowOfPoint);
    // The front joined from the fastest to the slowest.
    std::vector<std::size_t> front;
    for (std::size_t i = 0; i < points.size(); ++i)
        if (result.rows[rowOfPoint[i]].pareto) front.push_back(i);
    std::sort(front.begin(), front.end(),
              [&](std::size_t a, std::size_t b) { return points[a].point.x < points[b].point.x; });
    Canvas canvas(1200, 800, vec4(1.0f));
    drawScatter(canvas, 0, 0, 1200, 800, title,
                measuredCpu(result) ? "CPU MS PER FRAME (MEDIAN)" : "MS PER FRAME (MEDIAN, WALL CLOCK)",
                "1 - SSIM OF THE 8-BIT IMAGE (LOG)",
                "BLUE: PARETO FRONT, ORANGE: PRESET, PALE: NO EFFECT, RED RING: BLANK IMAGE, PURPLE RING: "
                "CHANGES WHAT THE SCENE SHOWS, BAR: FASTEST TO SLOWEST FRAME",
                true, points, front);
    writeImage(path, canvas.image());
}

void writeTradeCsv(const TradeResult& result, std::ostream& out) {
    out << "knob,value,flags,frames,ms_median,ms_min,ms_max,ms_shadow_setup";
    for (const char* space : {"linear", "output8"})
        for (const char* metric : {"psnr_db", "ssim", "mean_abs", "max_abs", "over_1_255", "over_2_255"})
            out << "," << space << "_" << metric;
    out << ",no_effect,pareto,image,error_image";
    out << ",cpu_ms_median,cpu_ms_min,cpu_ms_max,time_verdict,blank,changes_content,within_reference_floor";
    out << ",scores_meaningful\n";
    for (const TradeRow& row : result.rows) {
        out << csvField(row.setting.knob) << "," << csvField(row.setting.value) << ","
            << csvField(row.setting.words.empty() ? "" : row.setting.label()) << "," << row.frames << ","
            << csvNumber(row.msMedian) << "," << csvNumber(row.msMin) << "," << csvNumber(row.msMax) << ","
            << csvNumber(row.msShadows);
        for (const ErrorMetrics* m : {&row.error.linear, &row.error.encoded})
            for (const double value : {m->psnr, m->ssim, m->meanAbs, m->maxAbs, m->over1, m->over2})
                out << "," << csvNumber(value);
        out << "," << row.noEffect << "," << row.pareto << "," << csvField(row.image) << ","
            << csvField(row.errorImage);
        // The baseline's verdict is empty: it is what the others are compared with.
        out << "," << csvNumber(row.cpuMsMedian) << "," << csvNumber(row.cpuMsMin) << ","
            << csvNumber(row.cpuMsMax) << ","
            << (row.setting.knob == "baseline" ? "" : timeVerdictWords(row.timeVerdict)) << "," << row.blank
            << "," << row.changesContent << "," << row.withinReferenceFloor << ","
            << scoresMeaningful(result, row) << "\n";
    }
}

void printTradeTable(const TradeResult& result, std::ostream& out) {
    const TradeRow* baseline = !result.rows.empty() && result.rows.front().setting.knob == "baseline"
                                   ? &result.rows.front()
                                   : nullptr;

    // The time per frame.
    TextTable time(6);
    time.spans({{1, "CPU ms per frame"}, {3, "wall ms"}, {4, "× baseline"}, {5, ""}});
    time.row({"setting", "median", "spread", "median", "(CPU)", "time"});
    forEachRowBySection(result, time, [&](const TradeRow& row) {
        const bool isBaseline = &row == baseline;
        const std::string ratio = baseline && baseline->cpuMsMedian > 0
                                      ? number(row.cpuMsMedian / baseline->cpuMsMedian, 2) + "×"
                                      : "-";
        time.row({tradeRowLabel(row.setting), number(row.cpuMsMedian, 2),
                  number(row.cpuMsMax - row.cpuMsMin, 2), number(row.msMedian, 2), ratio,
                  isBaseline ? "" : timeVerdictWords(row.timeVerdict)});
    });
    time.print(out);
    out << "CPU ms: CPU time of every render thread per frame, less disturbed by other work on the machine\n"
           "than the wall clock; spread: slowest minus fastest frame; time: against the baseline, judged\n"
           "against the noise below (within noise: no verdict, and nothing is decided from it).\n"
        << "noise: ±" << number(100.0 * result.timeNoise, 1)
        << "% (how far frame times of identical work differ in this run: the repeated baseline and\n"
           "the settings without effect)\n\n";

    // The error against the reference.
    // The 8-bit image only (what the chart and the front use): the linear-light metrics are in the CSV.
    TextTable error(8);
    error.spans({{1, "8-bit output against the reference"}, {7, ""}});
    error.row({"setting", "PSNR", "SSIM", "mean", "max", ">1/255", ">2/255", "flags"});
    forEachRowBySection(result, error, [&](const TradeRow& row) {
        const ErrorMetrics& enc = row.error.encoded;
        error.row({tradeRowLabel(row.setting), number(enc.psnr, 1), number(enc.ssim, 4),
                   number(255.0 * enc.meanAbs, 2), std::to_string(std::lround(255.0 * enc.maxAbs)),
                   number(100.0 * enc.over1, 1) + "%", number(100.0 * enc.over2, 1) + "%", flagsOf(row)});
    });
    error.print(out);
    out << "PSNR in dB; mean and max in code steps (the metrics in linear light are in trade.csv).\n"
           "front: on the Pareto front (none faster and more accurate, by 1 - SSIM of the 8-bit image);\n"
           "NO EFFECT: the same 8-bit image as the baseline; BLANK: nothing or nearly nothing drawn where\n"
           "the reference shows the scene; within floor: its error differs from the baseline's by less\n"
           "than the reference's own error (no verdict on accuracy).\n";
    out << "reference: ";
    if (result.referenceSamples > 0)
        out << result.referenceSamples << "×" << result.referenceSamples << " rays per pixel; ";
    char floor[32];
    std::snprintf(floor, sizeof floor, "%.2g", result.referenceFloor);
    out << "its own error (the floor) 1 - SSIM " << floor << "\n";

    for (const std::string& warning : result.warnings)
        out << "warning: " << warning << "\n";
    for (const std::string& note : result.notes)
        out << note << "\n";
    for (const std::string& skipped : result.skipped)
        out << "skipped: " << skipped << "\n";
    if (!result.recommendations.empty()) out << "\nIn short, knob by knob:\n";
    for (const std::string& recommendation : result.recommendations)
        out << "  " << recommendation << "\n";
}

}  // namespace facet
