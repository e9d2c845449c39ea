// How the trade judges its own times: the run's noise, measured from what it repeats; each setting's
// verdict against the baseline; the Pareto front built on those verdicts; a warning when the machine
// was busy. Decisions use CPU time (every render thread's), which other work on a shared machine
// disturbs far less than wall-clock time.
#pragma once

#include <string>
#include <vector>

#include "trade/trade.h"

namespace facet {

// The noise never reads below this (±3%): even CPU time moves by a few per cent between repeats on a
// quiet machine (caches, the clock's frequency, where the threads land).
inline constexpr double kTimeNoiseFloor = 0.03;
// A difference counts when the ratio of the medians is beyond twice the noise: both medians carry it.
inline constexpr double kVerdictNoiseFactor = 2.0;
// The noise above which the run warns that the machine was busy (±10%).
inline constexpr double kBusyNoise = 0.10;

// The run's relative noise of a median frame time (0.05: ±5%), from what it repeats; never below
// kTimeNoiseFloor. The larger of
//  (a) how far the same setting reads from round to round: for every row (rows[0]: the baseline) its
//      median of each round (`roundMs[k]`, the baseline's of both phases) against its overall median
//      (cpuMsMedian), the kRepeatQuantile quantile of all those relative distances: one round that a
//      busy spell hit counts, a single outlier among a hundred does not;
//  (b) how far the rows without effect read from the baseline (the same image, usually the same work):
//      the median of their relative distances. The median, because "usually": --cull none on a closed
//      model draws back faces the depth test then hides, the same image for twice the work, and one
//      such row must not make every other difference read as noise.
double estimateTimeNoise(const std::vector<TradeRow>& rows, const std::vector<std::vector<double>>& roundMs);
inline constexpr double kRepeatQuantile = 0.9;

// Faster when ms < baselineMs / (1 + 2·noise), Slower when ms > baselineMs · (1 + 2·noise), else
// WithinNoise (kVerdictNoiseFactor = 2).
TimeVerdict judgeTime(double ms, double baselineMs, double noise);

// result.timeNoise and every row's timeVerdict from the rows' CPU medians (rows[0]: the baseline).
// The baseline and the rows without effect are WithinNoise by definition.
void judgeTimes(TradeResult& result, const std::vector<std::vector<double>>& roundMs);

// Marks the rows on the Pareto front of CPU time against tradeError. No decision comes from noise: a
// row WithinNoise takes the baseline's time, a row withinReferenceFloor the baseline's error, and
// between any two rows, times within the verdicts' margin (1 + 2·timeNoise) and errors within
// `referenceFloor` count as equal (paretoFront's margins): a setting timed twice (a preset that is one
// knob) does not push its twin off. Rows without effect (the baseline stands for them), blank rows and
// rows that change the scene's content are never on it.
void markParetoFront(std::vector<TradeRow>& rows, double timeNoise = 0.0, double referenceFloor = 0.0);

// Busy CPU milliseconds (user, system, interrupts, stolen by the hypervisor) of the CPUs this process
// may run on, summed, from /proc/stat; −1 where unreadable. Its difference over the timed frames, less
// the process's own CPU time, is what other processes took from those CPUs.
double allowedCpusBusyMs();
int allowedCpuCount();

// The busy-machine warning, or "" when there is none: when other processes kept so many of the CPUs
// the process may use busy (`othersCpus`, on average over the timed frames) that fewer than `threads`
// were left, or when the noise is above kBusyNoise.
std::string busyMachineWarning(double othersCpus, int allowedCpus, int threads, double noise);

}  // namespace facet
