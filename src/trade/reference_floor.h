// The reference's own error (its floor): the reference is a Monte Carlo estimate of each pixel (N×N
// jittered rays), exact wherever a pixel is one colour and off by a little where it is not (an edge, a
// shadow's border, texture detail). The trade scores every setting against it, so no error difference
// smaller than the reference's own error says anything. Estimated by tracing the pixels where the
// reference's rays disagree again with four times the rays (2N×2N) and scoring the reference against
// itself with those pixels replaced, in the trade's own error (1 − SSIM of the 8-bit image); the
// reference is rendered again with more rays until its floor is small beside the errors it must tell apart.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "reference/reference.h"
#include "trade/trade.h"

namespace facet {

// A pixel is unsettled when two of its rays differ by more than this in some channel (linear light;
// with one ray a pixel: when it differs so from a neighbour): one 8-bit step of a linear encoding, and
// less than a step of sRGB's above its darkest tenth, so that every pixel that can be off by a step is
// looked at.
inline constexpr float kUnsettledSpread = 1.0f / 255.0f;
// At most this share of the image's pixels is traced again (with 4× the rays: at most a quarter of the
// reference's own rays); more unsettled pixels than that and an even sample of them is.
inline constexpr std::size_t kFloorPixelShareDivisor = 16;
// The floor has to be at most this share of the smallest error the trade will score (the smaller of
// the baseline's and the best preset's, one frame of each): every setting's score carries the
// reference's own error besides its own, so that the most accurate setting's score is then within a
// tenth of what a perfect reference would give it.
inline constexpr double kFloorShareOfSmallestError = 0.1;
// The reference is not rendered again when the next render is expected to take longer than this (its
// time grows with the rays: four times for twice N).
inline constexpr double kReferenceTimeBoundMs = 120000.0;

struct ReferenceFloor {
    int samples = 0;            // N: the reference's N×N rays per pixel
    int checkSamples = 0;       // 2N: the unsettled pixels traced again with 2N×2N rays
    std::size_t unsettled = 0;  // pixels whose rays disagree (kUnsettledSpread)
    std::size_t checked = 0;    // of them, traced again: all, or an even sample of at most the budget
    // 1 − SSIM of the 8-bit reference against itself with the checked pixels replaced by their 2N×2N
    // colours, times unsettled / checked when only a sample was checked (sparse changes add up in SSIM's
    // mean over windows, so the sample's share of the error scales with its share of the pixels).
    double error = 0;
    double offShare = 0;  // of the checked pixels, the share more than 1/255 off (8-bit: two codes or more)
};

// The unsettled pixels, row by row: rays' disagreement `raySpread` (renderReference's, per pixel) above
// kUnsettledSpread; with one ray a pixel (samples 1, raySpread all 0) the largest difference from one
// of its eight neighbours instead.
std::vector<glm::ivec2> unsettledPixels(const LinearImage& reference, const std::vector<float>& raySpread,
                                        int samples);

// The floor of `reference`, rendered from `prepared` with `options` (samples N), raySpread its rays'
// disagreement; at most `budget` pixels traced again (0: the image's pixels / kFloorPixelShareDivisor),
// with checkSamples × checkSamples rays (0: 2N; more, to measure how good the estimate is).
ReferenceFloor estimateReferenceFloor(const PreparedScene& prepared, const ReferenceOptions& options,
                                      const LinearImage& reference, const std::vector<float>& raySpread,
                                      ThreadPool& pool, std::size_t budget = 0, int checkSamples = 0);

// What settleReference aims at and may spend (the constants above; a test lowers them).
struct FloorGoal {
    double shareOfSmallestError = kFloorShareOfSmallestError;
    int maxSamples = kMaxReferenceSamples;
    double timeBoundMs = kReferenceTimeBoundMs;
};

// The trade's reference made good enough: its floor estimated, and while the floor is above the goal's
// share of the smallest error to score (1 − SSIM of one frame of the baseline and one of the best
// preset against the reference, the smaller), the reference
// rendered again with twice N (up to goal.maxSamples, while the next render is expected within
// goal.timeBoundMs; renderMs: how long the first took). `reference`, `options.samples` and raySpread
// become the final render's; result's referenceSamples, referenceFloor, warnings and referenceMs (the
// time spent here: two readings of `now`) are filled. `progress` gets one line per estimate.
void settleReference(const SceneWithWords& sceneWithWords, const PreparedScene& prepared,
                     ReferenceOptions& options, LinearImage& reference, std::vector<float>& raySpread,
                     double renderMs, DrawContext& context, const std::function<double()>& now,
                     const std::function<void(const std::string&)>& progress, TradeResult& result,
                     const FloorGoal& goal = {});

// Marks the rows (the baseline first) whose error differs from the baseline's by less than `floor`; not
// the baseline itself, nor a row without effect (the same image: nothing to judge).
void markWithinReferenceFloor(std::vector<TradeRow>& rows, double floor);

}  // namespace facet
