// What facet trade shows of its result: the table for the terminal, the CSV and the chart (the table's
// and the CSV's declarations are in trade.h).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "bench/chart.h"
#include "trade/trade.h"

namespace facet {

// A row's name in the table and the progress: its command-line words, "preset fast", "baseline".
std::string tradeRowLabel(const TradeSetting& setting);

// `value` with `decimals` digits after the point ("%.*f"): the trade's tables, notes and progress lines.
std::string number(double value, int decimals);

// The words of a time verdict, as the table and the CSV write them: "faster", "slower", "within noise".
const char* timeVerdictWords(TimeVerdict verdict);

// The chart's x: CPU ms per frame when the run measured CPU time (every row has some), else the wall
// clock's; with the fastest and slowest frame of the same clock.
struct ChartTime {
    double median, fastest, slowest;
};
ChartTime chartTime(const TradeResult& result, const TradeRow& row);

// The chart's points, the most important first (the baseline, the front, the others, the settings
// without effect last), and each one's row.
std::vector<LabelledPoint> chartPoints(const TradeResult& result, std::vector<std::size_t>& rowOfPoint);

// chart.png: time against error, the Pareto front joined (see docs/trade.md).
void writeTradeChart(const TradeResult& result, const std::string& title, const std::filesystem::path& path);

}  // namespace facet
