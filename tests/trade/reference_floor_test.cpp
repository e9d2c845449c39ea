// The reference's own error in the trade (trade/reference_floor.h): measured where the reference's
// rays disagree, smaller with more rays, the reference rendered again until the floor is small or the
// rays are at their most, and the rows whose error is within it marked.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli/trade_command.h"
#include "reference/reference.h"
#include "render/renderer.h"
#include "support/bundled_models.h"
#include "trade/reference_floor.h"
#include "trade/trade.h"

namespace facet {
namespace {

using testing_support::kSpot;

cli::SceneArgs spotArgs() {
    cli::SceneArgs args;
    args.input = kSpot;
    args.width = 64;
    args.height = 48;
    return args;
}

struct Rendered {
    LinearImage image;
    std::vector<float> spread;
};

Rendered renderAt(const PreparedScene& prepared, int n, ThreadPool& pool) {
    Rendered out;
    ReferenceOptions options;
    options.samples = n;
    options.raySpread = &out.spread;
    out.image = renderReference(prepared, options, pool);
    return out;
}

// The cow's outline against the background: a reference with 2×2 rays a pixel is off there (floor
// above 0, some of its checked pixels more than a step off), one with 8×8 much less so (stratified
// jittered sampling's error at an edge falls faster than 1/N). Catches a floor taken from the pixels
// traced again at the same N (always 0), no pixel found unsettled, or a floor that does not fall.
TEST(ReferenceFloor, IsPositiveAtEdgesAndFallsWhenTheRaysRise) {
    const PreparedScene prepared = prepareScene(cli::sceneWithWords(spotArgs(), {}));
    ThreadPool pool(2);
    ReferenceFloor floors[2];
    int i = 0;
    for (const int n : {2, 8}) {
        const Rendered reference = renderAt(prepared, n, pool);
        ReferenceOptions options;
        options.samples = n;
        floors[i] = estimateReferenceFloor(prepared, options, reference.image, reference.spread, pool,
                                           reference.image.pixels.size());  // a budget of every pixel
        EXPECT_EQ(floors[i].samples, n);
        EXPECT_EQ(floors[i].checkSamples, 2 * n);
        EXPECT_GT(floors[i].unsettled, 0u);
        EXPECT_EQ(floors[i].checked, floors[i].unsettled);  // all of them: under the budget
        ++i;
    }
    EXPECT_GT(floors[0].error, 0.0);
    EXPECT_GT(floors[0].offShare, 0.0);
    EXPECT_LT(floors[1].error, floors[0].error);
}

// With one ray a pixel the rays cannot disagree; the pixels that differ from a neighbour are checked
// instead. Catches a one-ray reference declared exact (floor 0) because its spread is all zero.
TEST(ReferenceFloor, OneRayAPixelIsJudgedByItsNeighbours) {
    const PreparedScene prepared = prepareScene(cli::sceneWithWords(spotArgs(), {}));
    ThreadPool pool(2);
    const Rendered reference = renderAt(prepared, 1, pool);
    ReferenceOptions options;
    options.samples = 1;
    const ReferenceFloor floor =
        estimateReferenceFloor(prepared, options, reference.image, reference.spread, pool);
    EXPECT_GT(floor.unsettled, 0u);
    EXPECT_GT(floor.error, 0.0);
}

// Over the budget, an even sample is traced again and its error scaled up by unsettled / checked: the
// estimate from half the pixels lies near the one from all (within a factor of two: the changes are
// sparse, and SSIM's loss adds up over them). Catches the sample's error left unscaled (about half)
// or the budget ignored.
TEST(ReferenceFloor, ASampleOfThePixelsIsScaledToAll) {
    const PreparedScene prepared = prepareScene(cli::sceneWithWords(spotArgs(), {}));
    ThreadPool pool(2);
    const Rendered reference = renderAt(prepared, 2, pool);
    ReferenceOptions options;
    options.samples = 2;
    const ReferenceFloor all =
        estimateReferenceFloor(prepared, options, reference.image, reference.spread, pool);
    ASSERT_GT(all.unsettled, 20u);
    const ReferenceFloor half =
        estimateReferenceFloor(prepared, options, reference.image, reference.spread, pool, all.unsettled / 2);
    EXPECT_EQ(half.unsettled, all.unsettled);
    EXPECT_EQ(half.checked, all.unsettled / 2);
    EXPECT_GT(half.error, all.error / 2.0);
    EXPECT_LT(half.error, all.error * 2.0);
}

struct Settled {
    TradeResult result;
    LinearImage reference;
    int samples = 0;
    std::vector<std::string> progress;
};

Settled settle(int start, const FloorGoal& goal) {
    const cli::SceneArgs args = spotArgs();
    const SceneWithWords words = [&](const std::vector<std::string>& w) {
        return cli::sceneWithWords(args, w);
    };
    const PreparedScene prepared = prepareScene(words({}));
    DrawContext context(2);
    Settled out;
    ReferenceOptions options;
    options.samples = start;
    std::vector<float> spread;
    options.raySpread = &spread;
    out.reference = renderReference(prepared, options, context.pool);
    double clock = 0;
    settleReference(
        words, prepared, options, out.reference, spread, 1.0, context, [&] { return clock += 10.0; },
        [&](const std::string& line) { out.progress.push_back(line); }, out.result, goal);
    out.samples = options.samples;
    return out;
}

// A goal no reference meets (a floor of 0 beside a cow's outline): the rays double from 1 to 2 to 4,
// the most allowed, and stop there with a warning; the reference handed back is the 4×4 one. Catches a
// loop that runs past the cap, stops without saying so, or keeps the first reference.
TEST(ReferenceFloor, RaisingStopsAtTheMostRaysWithAWarning) {
    FloorGoal goal;
    goal.shareOfSmallestError = 0.0;
    goal.maxSamples = 4;
    const Settled settled = settle(1, goal);
    EXPECT_EQ(settled.result.referenceSamples, 4);
    EXPECT_EQ(settled.samples, 4);
    EXPECT_EQ(settled.progress.size(), 3u);  // an estimate at 1, 2 and 4
    ASSERT_EQ(settled.result.warnings.size(), 1u);
    EXPECT_NE(settled.result.warnings[0].find("4x4 rays per pixel is the most"), std::string::npos)
        << settled.result.warnings[0];
    EXPECT_GT(settled.result.referenceFloor, 0.0);
    EXPECT_DOUBLE_EQ(settled.result.referenceMs, 10.0);  // two readings of the clock around it all
    ThreadPool pool(1);
    ReferenceOptions four;
    four.samples = 4;
    const LinearImage expected =
        renderReference(prepareScene(cli::sceneWithWords(spotArgs(), {})), four, pool);
    EXPECT_TRUE(settled.reference.pixels == expected.pixels);
}

// A goal met at once (the floor below any share this large of the smallest error): one estimate, the
// user's rays kept, no warning. Catches a reference raised whatever its floor.
TEST(ReferenceFloor, AFloorBelowTheGoalKeepsTheUsersRays) {
    FloorGoal goal;
    goal.shareOfSmallestError = 1e6;
    const Settled settled = settle(2, goal);
    EXPECT_EQ(settled.result.referenceSamples, 2);
    EXPECT_EQ(settled.progress.size(), 1u);
    EXPECT_TRUE(settled.result.warnings.empty());
    EXPECT_GT(settled.result.referenceFloor, 0.0);
}

// The next render expected to take longer than allowed (the first took 1 ms; 2×2 rays would take 4):
// no raise, and a warning that says why. Catches the time bound ignored.
TEST(ReferenceFloor, RaisingStopsAtTheTimeBound) {
    FloorGoal goal;
    goal.shareOfSmallestError = 0.0;
    goal.timeBoundMs = 3.0;
    const Settled settled = settle(1, goal);
    EXPECT_EQ(settled.result.referenceSamples, 1);
    ASSERT_EQ(settled.result.warnings.size(), 1u);
    EXPECT_NE(settled.result.warnings[0].find("would take"), std::string::npos) << settled.result.warnings[0];
}

TradeRow rowWithError(double error) {
    TradeRow row;
    row.error.encoded.ssim = 1.0 - error;
    return row;
}

// Rows 0.0004 from the baseline's error (either side) are within a floor of 0.001, rows 0.002 away
// and more are not; the baseline itself is never marked. Catches the difference taken without its
// sign, the comparison made against the error itself rather than the difference, or the baseline marked.
TEST(ReferenceFloor, RowsWithinTheFloorOfTheBaselineAreMarked) {
    std::vector<TradeRow> rows = {rowWithError(0.010), rowWithError(0.0104), rowWithError(0.0096),
                                  rowWithError(0.012), rowWithError(0.004),  rowWithError(0.0005)};
    markWithinReferenceFloor(rows, 0.001);
    EXPECT_FALSE(rows[0].withinReferenceFloor);
    EXPECT_TRUE(rows[1].withinReferenceFloor);
    EXPECT_TRUE(rows[2].withinReferenceFloor);
    EXPECT_FALSE(rows[3].withinReferenceFloor);
    EXPECT_FALSE(rows[4].withinReferenceFloor);
    EXPECT_FALSE(rows[5].withinReferenceFloor);
    markWithinReferenceFloor(rows, 0.0);  // no floor: nothing is within it
    for (const TradeRow& row : rows)
        EXPECT_FALSE(row.withinReferenceFloor);
}

}  // namespace
}  // namespace facet
