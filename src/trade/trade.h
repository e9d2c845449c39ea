// facet trade: the speed–accuracy trade of a scene. The scene as given (the baseline), then each knob
// setting alone on top of it, then the presets, each timed over frames and scored against one image of
// the exact reference renderer; a table, a CSV, images and a chart of time against error.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "trade/knobs.h"
#include "trade/metrics.h"

namespace facet {

struct TradeOptions {
    std::string knobs;  // --knobs: comma-separated names; empty: every knob
    int frames = 9;     // timed frames per setting, split over the rounds
    // The settings are timed in rounds: each round renders every setting (a warm-up frame, then its
    // share of the frames) before the next round starts, so that a slow spell of a shared machine falls
    // on every setting alike instead of on the few timed during it. Capped at `frames`.
    int rounds = 3;
    int threads = 0;
    // N×N rays per pixel of the reference to start with (the reference renderer's default), so that the
    // reference shows the edges as they truly are and the rasterizer's one sample per pixel is charged
    // for its aliasing alike in every setting; doubled while the reference's own estimated error is not
    // small beside the baseline's (trade/reference_floor.h).
    int referenceSamples = 4;
    std::filesystem::path outputDir;
    bool progress = true;  // "[3/17] --shading gouraud: 12.3 ms" lines on `log`
    bool presets = true;   // false (--no-presets): no preset rows, only the baseline and the knobs
    // The clock the reference and the frames are timed with: milliseconds since any fixed moment. Empty:
    // the steady clock. A test gives each setting known durations through it.
    std::function<double()> clockMs;
    // The CPU time the frames are also timed with, and the trade's decisions use: milliseconds of CPU
    // of the whole process (every render thread) since any fixed moment. Empty: processCpuMs(). A test
    // gives each setting known CPU times through it.
    std::function<double()> cpuClockMs;
};
inline constexpr int kMaxTradeFrames = 1000;
inline constexpr int kMaxTradeRounds = 100;

// The scene with the command-line words of a setting applied over the user's own, through the render
// command's parser (the cli layer provides it). Throws InputError for words it refuses.
using SceneWithWords = std::function<Scene(const std::vector<std::string>& words)>;

// How a setting's frame time compares with the baseline's, judged against the run's own measured noise:
// a difference within the noise is no verdict, and the trade takes no decision from it.
enum class TimeVerdict { WithinNoise, Faster, Slower };

struct TradeRow {
    TradeSetting setting;
    // Per frame of the scene in motion: its shadows' maps and BVH rebuilt, then clearing, sorting and
    // drawing. msShadows: the rebuild's median alone (what a static scene would not pay every frame).
    double msMedian = 0, msMin = 0, msMax = 0, msShadows = 0;
    int frames = 0;         // frames timed, over every round
    ImageError error;       // against the reference
    bool noEffect = false;  // the 8-bit image is the baseline's, byte for byte: the knob changed nothing
    bool pareto = false;  // no other row is both faster and more accurate (by 1 − SSIM of the 8-bit image)
    // CPU time of the process per frame (every render thread), which other processes on a shared machine
    // disturb far less than wall time: median, fastest and slowest frame.
    double cpuMsMedian = 0, cpuMsMin = 0, cpuMsMax = 0;
    TimeVerdict timeVerdict =
        TimeVerdict::WithinNoise;  // against the baseline; the baseline's own: WithinNoise
    bool blank =
        false;  // nothing or nearly nothing drawn where the reference shows the scene: never on the front
    // The knob changes what the scene shows (textures off, another reflection model, shadows the scene
    // does not have) rather than how exactly it is drawn: listed apart, never on the front.
    bool changesContent = false;
    // Its error differs from the baseline's by less than the reference's own error: no verdict on accuracy.
    bool withinReferenceFloor = false;
    std::string image, errorImage;  // file names in the output folder
};

struct TradeResult {
    std::vector<TradeRow> rows;        // the baseline first
    std::vector<std::string> skipped;  // settings the baseline already has, by label
    std::vector<std::string> notes;    // what the run decided from its own measurements (the presets)
    double referenceMs = 0;
    int width = 0, height = 0;
    int referenceSamples = 0;  // N×N rays per pixel the reference was finally made with
    double referenceFloor = 0;  // the reference's own estimated error, in the chart's error (1 − SSIM, 8-bit)
    double timeNoise = 0;       // relative noise of the frame times (0.1: ±10%), from the repeated baseline
                                // and the rows without effect
    // The reference is brighter than kPlainLinearPeak (2) somewhere: the linear metrics compare the
    // images after the tone map x / (1 + x) (trade/metrics.h), and `notes` says so.
    bool linearToneMapped = false;
    std::vector<std::string> warnings;         // the machine was busy, a blank image, ...
    std::vector<std::string> recommendations;  // one line per knob ("--aa msaa2: half the edge error ...")
};

// Runs the trade of `baseline` (the scene as the user gave it): renders, writes the images, trade.csv
// and chart.png into options.outputDir, reports progress on `log`. Throws InputError for a bad option or
// unusable scene.
TradeResult runTrade(const SceneWithWords& sceneWithWords, const TradeOptions& options, std::ostream& log);

// The rows as CSV (a header, then one line per row) and as an aligned table for the terminal.
void writeTradeCsv(const TradeResult& result, std::ostream& out);
void printTradeTable(const TradeResult& result, std::ostream& out);

// The y of the chart and of the Pareto front: 1 − SSIM of the 8-bit image.
inline double tradeError(const TradeRow& row) {
    return 1.0 - row.error.encoded.ssim;
}

// File name for a setting: "03-shading-flat" (its number, then its words without dashes).
std::string settingFileStem(int number, const TradeSetting& setting);

}  // namespace facet
