#include "trade/reference_floor.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "base/errors.h"
#include "render/renderer.h"
#include "trade/metrics.h"
#include "trade/report.h"

namespace facet {

namespace {

std::string raysWords(int n) {
    return std::to_string(n) + "x" + std::to_string(n) + " rays per pixel";
}

// One frame of a setting (its words), as the trade's first frame of it is drawn, scored as the trade
// scores it.
double settingError(const SceneWithWords& sceneWithWords, const std::vector<std::string>& words,
                    const PreparedScene& referenceScene, const LinearImage& reference, DrawContext& context) {
    PreparedScene prepared = prepareScene(sceneWithWords(words), referenceScene.assets);
    Framebuffer framebuffer(prepared.scene.width, prepared.scene.height);
    FrameMemory memory;
    prepareShadows(prepared);
    renderFrame(prepared, framebuffer, context, memory);
    TradeRow row;
    row.error = measureError(toImage(framebuffer), reference, referenceScene.encoding);
    return tradeError(row);
}

// The smaller of the baseline's error and the best preset's (every knob at its most accurate value):
// about the smallest error the trade will have to score. The best preset's words refused by the scene
// (a knob its own shader does not take): the baseline's alone.
double smallestError(const SceneWithWords& sceneWithWords, const PreparedScene& referenceScene,
                     const LinearImage& reference, DrawContext& context) {
    const double baseline = settingError(sceneWithWords, {}, referenceScene, reference, context);
    try {
        return std::min(baseline, settingError(sceneWithWords, presetSetting("best").words, referenceScene,
                                               reference, context));
    } catch (const InputError&) {
        return baseline;
    }
}

}  // namespace

std::vector<glm::ivec2> unsettledPixels(const LinearImage& reference, const std::vector<float>& raySpread,
                                        int samples) {
    const int width = reference.width, height = reference.height;
    std::vector<glm::ivec2> pixels;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float spread = 0.0f;
            if (samples > 1) {
                spread = raySpread.at(static_cast<std::size_t>(y) * width + x);
            } else {
                // One ray a pixel cannot disagree with itself: how far the pixel's footprint is from one
                // colour is then judged by its neighbours.
                const vec4 c = reference.at(x, y);
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int nx = x + dx, ny = y + dy;
                        if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
                        const vec4 d = glm::abs(reference.at(nx, ny) - c);
                        spread = std::max({spread, d.r, d.g, d.b});
                    }
            }
            if (spread > kUnsettledSpread) pixels.push_back({x, y});
        }
    return pixels;
}

ReferenceFloor estimateReferenceFloor(const PreparedScene& prepared, const ReferenceOptions& options,
                                      const LinearImage& reference, const std::vector<float>& raySpread,
                                      ThreadPool& pool, std::size_t budget, int checkSamples) {
    ReferenceFloor floor;
    floor.samples = std::clamp(options.samples, 1, kMaxReferenceSamples);
    floor.checkSamples =
        std::min(checkSamples > 0 ? checkSamples : 2 * floor.samples, kMaxReferencePixelSamples);
    const std::vector<glm::ivec2> unsettled = unsettledPixels(reference, raySpread, floor.samples);
    floor.unsettled = unsettled.size();
    if (unsettled.empty()) return floor;
    if (budget == 0) budget = std::max<std::size_t>(1, reference.pixels.size() / kFloorPixelShareDivisor);
    // All of them, or an even sample in row order: the k-th of `budget` at k·unsettled / budget.
    std::vector<glm::ivec2> checked;
    if (unsettled.size() <= budget) {
        checked = unsettled;
    } else {
        for (std::size_t k = 0; k < budget; ++k)
            checked.push_back(unsettled[k * unsettled.size() / budget]);
    }
    floor.checked = checked.size();

    ReferenceOptions better = options;
    better.samples = floor.checkSamples;
    better.raySpread = nullptr;
    better.nearestSurfaces = nullptr;
    const std::vector<vec4> colors = renderReferencePixels(prepared, better, checked, pool);
    LinearImage improved = reference;
    for (std::size_t k = 0; k < checked.size(); ++k)
        improved.at(checked[k].x, checked[k].y) = colors[k];

    const std::vector<float> before = encodedPlanes(reference, prepared.encoding);
    const std::vector<float> after = encodedPlanes(improved, prepared.encoding);
    const ErrorMetrics metrics = measurePlanes(before, after, reference.width, reference.height);
    floor.error = std::max(0.0, 1.0 - metrics.ssim) * double(floor.unsettled) / double(floor.checked);
    // More than 1/255 off, as the metrics' over_1_255 counts it (a hair above: one code may round over).
    std::size_t off = 0;
    for (const glm::ivec2 p : checked) {
        const std::size_t at = 3 * (static_cast<std::size_t>(p.y) * reference.width + p.x);
        for (std::size_t channel = 0; channel < 3; ++channel)
            if (std::abs(before[at + channel] - after[at + channel]) > 1.0f / 255.0f * 1.0001f) {
                ++off;
                break;
            }
    }
    floor.offShare = double(off) / double(floor.checked);
    return floor;
}

void settleReference(const SceneWithWords& sceneWithWords, const PreparedScene& prepared,
                     ReferenceOptions& options, LinearImage& reference, std::vector<float>& raySpread,
                     double renderMs, DrawContext& context, const std::function<double()>& now,
                     const std::function<void(const std::string&)>& progress, TradeResult& result,
                     const FloorGoal& goal) {
    const double start = now();
    const int maxSamples = std::clamp(goal.maxSamples, 1, kMaxReferenceSamples);
    options.raySpread = &raySpread;
    ReferenceFloor floor;
    double target = 0;
    for (;;) {
        const auto estimateStart = std::chrono::steady_clock::now();
        floor = estimateReferenceFloor(prepared, options, reference, raySpread, context.pool);
        target = goal.shareOfSmallestError * smallestError(sceneWithWords, prepared, reference, context);
        const double estimateMs =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - estimateStart)
                .count();
        progress("reference's own error at " + std::to_string(floor.samples) + "x" +
                 std::to_string(floor.samples) + " rays: 1 - SSIM " + number(floor.error, 5) +
                 ", aim below " + number(target, 5) + " (" + std::to_string(floor.checked) + " of " +
                 std::to_string(floor.unsettled) + " pixels whose rays disagree, at " +
                 std::to_string(floor.checkSamples) + "x" + std::to_string(floor.checkSamples) + ", " +
                 number(100.0 * floor.offShare, 0) + "% of them over 1/255 off): " + number(estimateMs, 0) +
                 " ms");
        if (floor.error <= target) break;
        const std::string notBelow = "the reference's own error (1 - SSIM " + number(floor.error, 5) +
                                     " at " + raysWords(floor.samples) + ") is not below " +
                                     number(target, 5) + " (" + number(100.0 * goal.shareOfSmallestError, 0) +
                                     "% of the smallest error to judge)";
        if (floor.samples >= maxSamples) {
            result.warnings.push_back(notBelow + ": " + raysWords(maxSamples) +
                                      " is the most; error differences below it are no verdict");
            break;
        }
        const int next = std::min(2 * floor.samples, maxSamples);
        const double expectedMs = renderMs * double(next * next) / double(floor.samples * floor.samples);
        if (expectedMs > goal.timeBoundMs) {
            result.warnings.push_back(notBelow + ": " + raysWords(next) + " would take about " +
                                      number(expectedMs / 1000.0, 0) +
                                      " s; error differences below it are no verdict");
            break;
        }
        options.samples = next;
        ReferenceStats stats;
        reference = renderReference(prepared, options, context.pool, &stats);
        renderMs = stats.buildMilliseconds + stats.renderMilliseconds;
    }
    options.raySpread = nullptr;
    result.referenceSamples = floor.samples;
    result.referenceFloor = floor.error;
    result.referenceMs += now() - start;
}

void markWithinReferenceFloor(std::vector<TradeRow>& rows, double floor) {
    if (rows.empty()) return;
    const double baseline = tradeError(rows.front());
    // A row without effect has the baseline's image: nothing to judge, and its flag says so already.
    for (std::size_t k = 1; k < rows.size(); ++k)
        rows[k].withinReferenceFloor = !rows[k].noEffect && std::abs(tradeError(rows[k]) - baseline) < floor;
}

}  // namespace facet
