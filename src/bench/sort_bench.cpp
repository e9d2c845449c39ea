// facet bench --sort: the transparency sorter on a turntable, insertion sort with memory against sorting
// from scratch.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <ostream>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "base/errors.h"
#include "bench/bench.h"
#include "bench/process_stats.h"
#include "render/renderer.h"
#include "render/transparency_sort.h"

namespace facet {

namespace {

constexpr std::size_t kSortMinTriangles = 50000;
constexpr double kSortStepsDegrees[] = {6.0, 1.0, 0.3, 0.1, 0.03, 0.01};
constexpr double kSortStepBudgetMs = 5000.0;  // timed sorting per step, after at least kSortMinFrames
constexpr int kSortMinFrames = 5;
constexpr double kSortKeyStepDegrees = 1.0;  // the step of the "sort key" comparison
constexpr int kSortKeyFrames = 20;

// The model on a turntable: each frame it turns about the vertical axis (the camera's up) through the
// centre of its bounding box, in world space, and the camera stays where prepareScene framed it.
class Turntable {
  public:
    explicit Turntable(const PreparedScene& prepared) : prepared_(prepared) {
        const mat4 worldFromView = inverse(prepared.camera.viewFromWorld);
        Bounds bounds{vec3(std::numeric_limits<float>::max()), vec3(-std::numeric_limits<float>::max())};
        for (const PreparedDraw& draw : prepared.draws) {
            worldFromObject_.push_back(worldFromView * draw.uniforms.viewFromObject);
            for (const MeshVertex& vertex : draw.vertices) {
                const vec3 p(worldFromObject_.back() * vec4(vertex.position, 1.0f));
                bounds.min = glm::min(bounds.min, p);
                bounds.max = glm::max(bounds.max, p);
            }
            triangles_ += draw.indices.size() / 3;
        }
        centre_ = bounds.centre();
        axis_ = normalize(prepared.camera.up);
    }

    std::size_t triangles() const { return triangles_; }

    // One key per triangle, draw after draw: −z_view of its centroid (the mean of its corners' depths,
    // as the view transform is affine) or of its farthest corner. Larger is farther.
    void keys(double angleDegrees, SortKey kind, std::vector<float>& keys) {
        const mat4 turn = prepared_.camera.viewFromWorld * glm::translate(mat4(1.0f), centre_) *
                          glm::rotate(mat4(1.0f), static_cast<float>(glm::radians(angleDegrees)), axis_) *
                          glm::translate(mat4(1.0f), -centre_);
        keys.resize(triangles_);
        std::size_t k = 0;
        for (std::size_t d = 0; d < prepared_.draws.size(); ++d) {
            const PreparedDraw& draw = prepared_.draws[d];
            const mat4 viewFromObject = turn * worldFromObject_[d];
            const vec4 depthRow(viewFromObject[0][2], viewFromObject[1][2], viewFromObject[2][2],
                                viewFromObject[3][2]);
            depth_.resize(draw.vertices.size());
            for (std::size_t v = 0; v < draw.vertices.size(); ++v) {
                const vec3& p = draw.vertices[v].position;
                depth_[v] = depthRow.x * p.x + depthRow.y * p.y + depthRow.z * p.z + depthRow.w;
            }
            const std::uint32_t* index = draw.indices.data();
            const std::size_t count = draw.indices.size() / 3;
            if (kind == SortKey::Centroid)
                for (std::size_t t = 0; t < count; ++t, index += 3)
                    keys[k++] = -(depth_[index[0]] + depth_[index[1]] + depth_[index[2]]) * (1.0f / 3.0f);
            else
                for (std::size_t t = 0; t < count; ++t, index += 3)
                    keys[k++] = -std::min({depth_[index[0]], depth_[index[1]], depth_[index[2]]});
        }
    }

  private:
    const PreparedScene& prepared_;
    std::vector<mat4> worldFromObject_;  // per draw
    vec3 centre_{0.0f}, axis_{0.0f, 1.0f, 0.0f};
    std::size_t triangles_ = 0;
    std::vector<float> depth_;  // view-space z per vertex of the current draw
};

bool backToFront(std::span<const std::uint32_t> order, const std::vector<float>& keys) {
    for (std::size_t i = 1; i < order.size(); ++i)
        if (keys[order[i - 1]] < keys[order[i]]) return false;  // the model's keys are never NaN
    return true;
}

struct SortStep {
    double degrees = 0.0;
    int frames = 0;
    double keyMs = 0.0, insertionMs = 0.0, scratchMs = 0.0, radixMs = 0.0;
    double insertionComparisons = 0.0, insertionMoves = 0.0, scratchComparisons = 0.0;
    bool sorted = true;  // every order came out back to front
};

// Turns the model by `degrees` per frame from 0: one untimed warm-up frame (the insertion sorter's
// first, from scratch), then up to `frames` timed frames, the two sorts alternating which goes first.
SortStep timeSortStep(Turntable& turntable, double degrees, int frames) {
    SortStep step;
    step.degrees = degrees;
    TransparencySorter insertion, scratch, radix;
    SortStats stats;
    std::vector<float> keys;
    turntable.keys(0.0, SortKey::Centroid, keys);
    insertion.sort(keys, SortAlgorithm::InsertionWithMemory, stats);
    scratch.sort(keys, SortAlgorithm::FromScratch, stats);
    radix.sort(keys, SortAlgorithm::RadixFromScratch, stats);

    std::vector<double> keyMs, insertionMs, scratchMs, radixMs, insertionComparisons, insertionMoves,
        scratchComparisons;
    double spentMs = 0.0;
    for (int frame = 1; frame <= frames; ++frame) {
        const double keyStart = threadCpuMs();
        turntable.keys(frame * degrees, SortKey::Centroid, keys);
        keyMs.push_back(threadCpuMs() - keyStart);

        auto timeInsertion = [&] {
            const double start = threadCpuMs();
            const auto order = insertion.sort(keys, SortAlgorithm::InsertionWithMemory, stats);
            insertionMs.push_back(threadCpuMs() - start);
            insertionComparisons.push_back(static_cast<double>(stats.comparisons));
            insertionMoves.push_back(static_cast<double>(stats.moves));
            step.sorted = step.sorted && !stats.fromScratch && backToFront(order, keys);
        };
        auto timeScratch = [&] {
            const double start = threadCpuMs();
            const auto order = scratch.sort(keys, SortAlgorithm::FromScratch, stats);
            scratchMs.push_back(threadCpuMs() - start);
            scratchComparisons.push_back(static_cast<double>(stats.comparisons));
            step.sorted = step.sorted && backToFront(order, keys);
        };
        auto timeRadix = [&] {
            const double start = threadCpuMs();
            const auto order = radix.sort(keys, SortAlgorithm::RadixFromScratch, stats);
            radixMs.push_back(threadCpuMs() - start);
            step.sorted = step.sorted && backToFront(order, keys);
        };
        switch (frame % 3) {  // each goes first in turn
            case 0:
                timeInsertion();
                timeScratch();
                timeRadix();
                break;
            case 1:
                timeScratch();
                timeRadix();
                timeInsertion();
                break;
            default:
                timeRadix();
                timeInsertion();
                timeScratch();
                break;
        }
        step.frames = frame;
        spentMs += insertionMs.back() + scratchMs.back() + radixMs.back();
        if (spentMs > kSortStepBudgetMs && frame >= kSortMinFrames) break;
    }
    step.keyMs = median(keyMs);
    step.insertionMs = median(insertionMs);
    step.scratchMs = median(scratchMs);
    step.radixMs = median(radixMs);
    step.insertionComparisons = median(insertionComparisons);
    step.insertionMoves = median(insertionMoves);
    step.scratchComparisons = median(scratchComparisons);
    return step;
}

std::string degreesText(double degrees) {
    std::ostringstream text;
    text << degrees << " deg";
    return text.str();
}

// "12.3 M", "45.6 k", "789": a count per frame, short.
std::string countText(double count) {
    std::ostringstream text;
    text << std::fixed << std::setprecision(count >= 1e5 ? 1 : 0);
    if (count >= 1e6)
        text << count / 1e6 << " M";
    else if (count >= 1e5)
        text << count / 1e3 << " k";
    else
        text << count;
    return text.str();
}

}  // namespace

void runSortBench(const BenchOptions& options, std::ostream& out) {
    if (options.frames < 1) throw InputError("--frames must be at least 1");
    const PreparedScene prepared = prepareScene(loadSceneOrModel(options.model));
    Turntable turntable(prepared);
    const std::size_t n = turntable.triangles();
    if (n < kSortMinTriangles)
        throw InputError(options.model.string() + " has " + std::to_string(n) +
                         " triangles; bench --sort needs a model with at least " +
                         std::to_string(kSortMinTriangles) + " (the Stanford bunny has 69451)");

    out << "Per frame of a turntable, every triangle's back-to-front order (key: view-space depth of its "
           "centroid)\nby insertion sort from the previous frame's order, by std::sort from scratch and by a "
           "radix sort from scratch;\none thread, medians.\n";
    out << std::fixed << std::setprecision(2);
    out << "model      " << options.model.string() << "\n";
    out << "triangles  " << n << ", all treated as transparent (one key each)\n";
    out << "turntable  about the vertical axis through the bounding box's centre, camera as facet render "
           "frames it\n";
    out << "frames     " << options.frames << " timed per step after 1 warm-up (fewer where a step's "
        << kSortStepBudgetMs / 1000.0 << " s budget runs out); sorts alternate going first\n";
    out << "times      ms of CPU time of the thread (time slices taken by other processes do not count); "
           "each "
           "sort's ms\n           include turning the keys into (key, index) pairs and writing the order "
           "out; "
           "keys ms is\n           computing the keys (vertex depths, then centroids), paid once for both\n";
    out << "moves      insertion sort's shifts (= inversions of the previous order); std::sort's element "
           "moves are\n           swaps inside partitions, not comparable, not counted\n\n";

    out << "  step/frame  frames  keys ms   insertion ms   std::sort ms   faster               "
           "insertion compares    moves   std::sort compares   radix ms\n";
    std::vector<SortStep> steps;
    for (const double degrees : kSortStepsDegrees) {
        const SortStep step = timeSortStep(turntable, degrees, options.frames);
        steps.push_back(step);
        const bool insertionWins = step.insertionMs < step.scratchMs;
        std::ostringstream faster;
        faster << std::fixed << std::setprecision(1) << (insertionWins ? "insertion " : "std::sort ")
               << (insertionWins ? step.scratchMs / step.insertionMs : step.insertionMs / step.scratchMs)
               << "x";
        out << std::setprecision(2) << std::setw(12) << degreesText(degrees) << std::setw(8) << step.frames
            << std::setw(9) << step.keyMs << std::setw(15) << step.insertionMs << std::setw(15)
            << step.scratchMs << "   " << std::left << std::setw(18) << faster.str() << std::right
            << std::setw(20) << countText(step.insertionComparisons) << std::setw(9)
            << countText(step.insertionMoves) << std::setw(21) << countText(step.scratchComparisons)
            << std::setw(11) << step.radixMs << (step.sorted ? "" : "   ORDER NOT BACK TO FRONT")
            << std::endl;
    }

    // Where the two cross: the ratio of the times interpolated in log-log between the two steps around 1.
    for (std::size_t i = 1; i < steps.size(); ++i) {
        const double a = std::log(steps[i - 1].insertionMs / steps[i - 1].scratchMs);
        const double b = std::log(steps[i].insertionMs / steps[i].scratchMs);
        if (a >= 0.0 && b < 0.0) {
            const double t = a / (a - b);
            const double degrees =
                std::exp(std::log(steps[i - 1].degrees) +
                         t * (std::log(steps[i].degrees) - std::log(steps[i - 1].degrees)));
            out << "break-even insertion with memory is the faster below about " << std::setprecision(2)
                << degrees << " deg per frame (interpolated)\n";
            break;
        }
    }

    // The other usual key: the farthest corner. What it costs, and how much its order differs: the pairs
    // the two keys put the other way round are the moves of an insertion sort that starts from the
    // centroid order and is given the farthest-vertex keys.
    std::vector<float> centroidKeys, farthestKeys;
    TransparencySorter centroidSorter, farthestSorter, crossSorter;
    SortStats stats;
    turntable.keys(0.0, SortKey::Centroid, centroidKeys);
    turntable.keys(0.0, SortKey::FarthestVertex, farthestKeys);
    centroidSorter.sort(centroidKeys, SortAlgorithm::InsertionWithMemory, stats);
    farthestSorter.sort(farthestKeys, SortAlgorithm::InsertionWithMemory, stats);
    std::vector<double> centroidKeyMs, farthestKeyMs, centroidMoves, farthestMoves, disagreeing;
    for (int frame = 1; frame <= std::min(options.frames, kSortKeyFrames); ++frame) {
        const double angle = frame * kSortKeyStepDegrees;
        for (int k = 0; k < 2; ++k) {  // alternating which goes first
            const bool centroid = (k + frame) % 2 == 0;
            const double start = threadCpuMs();
            turntable.keys(angle, centroid ? SortKey::Centroid : SortKey::FarthestVertex,
                           centroid ? centroidKeys : farthestKeys);
            (centroid ? centroidKeyMs : farthestKeyMs).push_back(threadCpuMs() - start);
        }
        centroidSorter.sort(centroidKeys, SortAlgorithm::InsertionWithMemory, stats);
        centroidMoves.push_back(static_cast<double>(stats.moves));
        farthestSorter.sort(farthestKeys, SortAlgorithm::InsertionWithMemory, stats);
        farthestMoves.push_back(static_cast<double>(stats.moves));
        crossSorter.forget();
        crossSorter.sort(centroidKeys, SortAlgorithm::InsertionWithMemory, stats);
        crossSorter.sort(farthestKeys, SortAlgorithm::InsertionWithMemory, stats);
        disagreeing.push_back(static_cast<double>(stats.moves));
    }
    const double pairs = 0.5 * static_cast<double>(n) * static_cast<double>(n - 1);
    out << "sort key   at " << degreesText(kSortKeyStepDegrees) << " per frame: centroid keys "
        << median(centroidKeyMs) << " ms, " << countText(median(centroidMoves))
        << " moves; farthest vertex keys " << median(farthestKeyMs) << " ms, "
        << countText(median(farthestMoves)) << " moves; the two keys order " << countText(median(disagreeing))
        << " pairs differently (" << std::setprecision(3) << 100.0 * median(disagreeing) / pairs
        << "% of all pairs)\n";
}

}  // namespace facet
