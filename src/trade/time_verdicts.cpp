#include "trade/time_verdicts.h"

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "trade/pareto.h"

namespace facet {

namespace {

// The q-quantile of `values` by nearest rank (the smallest value with at least q of them at or below);
// 0 for none.
double quantile(std::vector<double> values, double q) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
    return values[std::clamp<std::size_t>(rank, 1, values.size()) - 1];
}

}  // namespace

double estimateTimeNoise(const std::vector<TradeRow>& rows, const std::vector<std::vector<double>>& roundMs) {
    if (rows.empty() || !(rows.front().cpuMsMedian > 0)) return kTimeNoiseFloor;
    std::vector<double> repeats, withoutEffect;
    for (std::size_t k = 0; k < rows.size() && k < roundMs.size(); ++k)
        if (roundMs[k].size() >= 2 && rows[k].cpuMsMedian > 0)
            for (const double ms : roundMs[k])
                repeats.push_back(std::abs(ms / rows[k].cpuMsMedian - 1.0));
    for (const TradeRow& row : rows)
        if (row.noEffect) withoutEffect.push_back(std::abs(row.cpuMsMedian / rows.front().cpuMsMedian - 1.0));
    return std::max({kTimeNoiseFloor, quantile(repeats, kRepeatQuantile), quantile(withoutEffect, 0.5)});
}

TimeVerdict judgeTime(double ms, double baselineMs, double noise) {
    const double margin = 1.0 + kVerdictNoiseFactor * noise;
    if (ms * margin < baselineMs) return TimeVerdict::Faster;
    if (ms > baselineMs * margin) return TimeVerdict::Slower;
    return TimeVerdict::WithinNoise;
}

void judgeTimes(TradeResult& result, const std::vector<std::vector<double>>& roundMs) {
    if (result.rows.empty()) return;
    const double baselineMs = result.rows.front().cpuMsMedian;
    result.timeNoise = estimateTimeNoise(result.rows, roundMs);
    for (std::size_t k = 0; k < result.rows.size(); ++k) {
        TradeRow& row = result.rows[k];
        row.timeVerdict = k == 0 || row.noEffect ? TimeVerdict::WithinNoise
                                                 : judgeTime(row.cpuMsMedian, baselineMs, result.timeNoise);
    }
}

void markParetoFront(std::vector<TradeRow>& rows, double timeNoise, double referenceFloor) {
    if (rows.empty()) return;
    const TradeRow& baseline = rows.front();
    std::vector<glm::dvec2> points;
    for (std::size_t k = 0; k < rows.size(); ++k) {
        const TradeRow& row = rows[k];
        const bool eligible = k == 0 || !(row.noEffect || row.blank || row.changesContent);
        const double x = row.timeVerdict == TimeVerdict::WithinNoise ? baseline.cpuMsMedian : row.cpuMsMedian;
        const double y = row.withinReferenceFloor ? tradeError(baseline) : tradeError(row);
        points.push_back(eligible ? glm::dvec2(x, y) : glm::dvec2(std::nan(""), std::nan("")));
        rows[k].pareto = false;
    }
    for (const std::size_t k : paretoFront(points, kVerdictNoiseFactor * timeNoise, referenceFloor))
        rows[k].pareto = true;
}

namespace {

bool allowedCpus(cpu_set_t& set) {
    CPU_ZERO(&set);
    return ::sched_getaffinity(0, sizeof set, &set) == 0;
}

}  // namespace

int allowedCpuCount() {
    cpu_set_t set;
    return allowedCpus(set) ? CPU_COUNT(&set) : 0;
}

double allowedCpusBusyMs() {
    cpu_set_t set;
    std::ifstream stat("/proc/stat");
    if (!allowedCpus(set) || !stat) return -1.0;
    const long ticksPerSecond = ::sysconf(_SC_CLK_TCK);
    if (ticksPerSecond <= 0) return -1.0;
    double busyTicks = 0;
    bool any = false;
    std::string line;
    while (std::getline(stat, line)) {
        // "cpu3 user nice system idle iowait irq softirq steal ...": the per-CPU lines (not "cpu ").
        int cpu = -1;
        unsigned long long user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0,
                           steal = 0;
        if (std::sscanf(line.c_str(), "cpu%d %llu %llu %llu %llu %llu %llu %llu %llu", &cpu, &user, &nice,
                        &system, &idle, &iowait, &irq, &softirq, &steal) < 8 ||
            cpu < 0 || cpu >= CPU_SETSIZE || !CPU_ISSET(cpu, &set))
            continue;
        busyTicks += static_cast<double>(user + nice + system + irq + softirq + steal);
        any = true;
    }
    return any ? busyTicks * 1000.0 / static_cast<double>(ticksPerSecond) : -1.0;
}

std::string busyMachineWarning(double othersCpus, int allowedCpus, int threads, double noise) {
    char text[400];
    if (allowedCpus > 0 && othersCpus > 0.25 && allowedCpus - othersCpus < threads - 0.25) {
        std::snprintf(text, sizeof text,
                      "the machine was busy: other processes kept %.1f of the %d CPUs this trade "
                      "may use busy while it timed %d render thread%s; wall-clock times are inflated and "
                      "uneven, so decisions use CPU time, and differences within the noise (±%.1f%%) "
                      "decide nothing",
                      othersCpus, allowedCpus, threads, threads == 1 ? "" : "s", 100.0 * noise);
        return text;
    }
    if (noise > kBusyNoise) {
        std::snprintf(text, sizeof text,
                      "the machine was busy or its speed changed: repeats of the same work (the "
                      "baseline again, settings that change nothing) differed by up to %.0f%% in CPU time; "
                      "only differences beyond %.0f%% are judged faster or slower",
                      100.0 * noise, 100.0 * kVerdictNoiseFactor * noise);
        return text;
    }
    return "";
}

}  // namespace facet
