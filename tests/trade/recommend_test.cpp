// facet trade's line per knob, from synthetic results: the words follow the verdicts (time, reference
// floor, no effect, blank, content) and nothing else.
#include "trade/recommend.h"

#include <string>

#include <gtest/gtest.h>

namespace facet {
namespace {

TradeRow row(const std::string& knob, const std::string& value, double error, double cpuMs,
             TimeVerdict verdict = TimeVerdict::WithinNoise) {
    TradeRow row;
    row.setting = {knob, value, {"--" + knob, value}};
    row.error.encoded.ssim = 1.0 - error;
    row.cpuMsMedian = cpuMs;
    row.msMedian = cpuMs * 1.3;  // wall time: what a busy machine adds; the lines use CPU time
    row.timeVerdict = verdict;
    return row;
}

// The baseline: 1 − SSIM 0.02 at 10 ms of CPU time per frame; then `rows`; then a preset, which is no knob.
TradeResult resultWith(std::vector<TradeRow> rows) {
    TradeResult result;
    result.rows.push_back(row("baseline", "", 0.02, 10.0));
    result.rows.insert(result.rows.end(), rows.begin(), rows.end());
    result.rows.push_back(row("preset", "fast", 0.05, 5.0, TimeVerdict::Faster));
    return result;
}

bool has(const std::string& line, const std::string& part) {
    return line.find(part) != std::string::npos;
}

// msaa2 at 0.01 is half the baseline's 0.02, at 17/10 of its CPU time; ssaa4 at 0.005 a quarter, 42/10.
// Catches: wall time used where CPU time is known, the error's ratio inverted, or a preset given a line.
TEST(TradeRecommend, AntialiasingNamesTheErrorItSavesAndTheTimeItCosts) {
    const TradeResult result = resultWith({row("aa", "msaa2", 0.01, 17.0, TimeVerdict::Slower),
                                           row("aa", "ssaa4", 0.005, 42.0, TimeVerdict::Slower)});
    const std::vector<std::string> lines = tradeRecommendations(result);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_EQ(
        lines[0],
        "--aa: msaa2 gives half the error for 1.7× the time; ssaa4 gives a quarter of the error for 4.2× "
        "the time");
}

// A knob of many values names those on the Pareto front and the others in one clause; a reduction that
// is no plain fraction reads as a percentage (0.02 → 0.0032: 84% less). Catches: a line listing every
// anti-aliasing mode (eight clauses), the off-front values dropped without a word, or "1/6.3 of the error".
TEST(TradeRecommend, ManyValuesNameTheFrontAndTheRestInAWord) {
    TradeRow msaa2 = row("aa", "msaa2", 0.01, 17.0, TimeVerdict::Slower);
    TradeRow ssaa4 = row("aa", "ssaa4", 0.0032, 42.0, TimeVerdict::Slower);
    msaa2.pareto = ssaa4.pareto = true;
    const TradeResult result = resultWith({msaa2, row("aa", "ssaa2", 0.01, 22.0, TimeVerdict::Slower),
                                           row("aa", "msaa4", 0.009, 45.0, TimeVerdict::Slower), ssaa4});
    EXPECT_EQ(tradeRecommendations(result)[0],
              "--aa: msaa2 gives half the error for 1.7× the time; ssaa4 gives 84% less error for 4.2× the "
              "time; ssaa2 and msaa4: off the front (another setting is faster for the same error, or more "
              "accurate for the same time)");
}

// Without CPU times (cpuMsMedian 0) the wall times decide the ratio: 26/13 = 2.0×.
// Catches: a zero CPU time divided into a ratio (inf or 0×) instead of falling back to wall time.
TEST(TradeRecommend, WallTimeWhenThereIsNoCpuTime) {
    TradeResult result = resultWith({row("aa", "msaa4", 0.01, 20.0, TimeVerdict::Slower)});
    for (TradeRow& r : result.rows)
        r.cpuMsMedian = 0.0;
    EXPECT_EQ(tradeRecommendations(result)[0], "--aa: msaa4 gives half the error for 2.0× the time");
}

// Trilinear at 0.0126 is 37% less than 0.02; its CPU time reads 1.1× (then 1.5× on a noisier run) but the
// verdict is within the noise. Catches: a time difference claimed from a ratio the noise does not
// support, or "use" given to a value whose median is half again the baseline's because a busy run's
// noise was wide enough to call it within noise.
TEST(TradeRecommend, TimeWithinTheNoiseIsNeverCalledFasterOrSlower) {
    const std::string line =
        tradeRecommendations(resultWith({row("texture-filter", "trilinear", 0.0126, 11.0)}))[0];
    EXPECT_EQ(line,
              "--texture-filter: trilinear gives 37% less error, no measurable difference in time: use "
              "trilinear");
    EXPECT_FALSE(has(line, "×")) << line;
    const std::string noisy =
        tradeRecommendations(resultWith({row("texture-filter", "trilinear", 0.0126, 15.0)}))[0];
    EXPECT_EQ(noisy, "--texture-filter: trilinear gives 37% less error, no measurable difference in time");
}

// Depth formats whose errors differ from the baseline's by less than the reference's own error.
// Catches: "less error" claimed for a difference the reference cannot tell, or a floor row's speed dropped.
TEST(TradeRecommend, WithinTheReferenceFloorNeverClaimsAccuracy) {
    TradeRow unorm24 = row("depth", "unorm24", 0.0199999, 10.2);
    TradeRow reversed = row("depth", "reversed-float", 0.0199998, 9.9);
    unorm24.withinReferenceFloor = reversed.withinReferenceFloor = true;
    EXPECT_EQ(tradeRecommendations(resultWith({unorm24, reversed}))[0],
              "--depth: no difference beyond the reference's own error");

    reversed.timeVerdict = TimeVerdict::Faster;
    reversed.cpuMsMedian = 5.0;  // 10/5: twice as fast
    const std::string line = tradeRecommendations(resultWith({unorm24, reversed}))[0];
    EXPECT_TRUE(
        has(line, "reversed-float makes no difference in error beyond the reference's own, 2.0× faster"))
        << line;
    EXPECT_FALSE(has(line, "less error")) << line;
    EXPECT_FALSE(has(line, "use")) << line;
}

// Catches: a knob without effect or one that changes the scene's content ranked as an accuracy trade
// (textures off is faster and, against a textured reference, scored here as less error).
TEST(TradeRecommend, NoEffectAndContentChangesAreSaidAsSuch) {
    TradeRow sorted = row("transparency", "sorted", 0.02, 10.0),
             exact = row("transparency", "exact", 0.02, 10.0);
    sorted.noEffect = exact.noEffect = true;
    TradeRow off = row("textures", "off", 0.01, 5.0, TimeVerdict::Faster);
    off.changesContent = true;
    const std::vector<std::string> lines = tradeRecommendations(resultWith({sorted, exact, off}));
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_EQ(lines[0], "--transparency: no effect on this scene");
    EXPECT_EQ(lines[1], "--textures: changes what the scene shows, not how exactly");
}

// Flat at 0.32 is 16× the baseline's 0.02 and 12/10 slower; gouraud 0.03 is 50% more, within the noise.
// Catches: the advice to keep the scene's value missing, or naming another value than the baseline's.
TEST(TradeRecommend, WorseAndNotFasterKeepsTheBaselinesValue) {
    TradeResult result = resultWith(
        {row("shading", "flat", 0.32, 12.0, TimeVerdict::Slower), row("shading", "gouraud", 0.03, 10.5)});
    result.skipped = {"--shading phong (the baseline's own)"};
    EXPECT_EQ(tradeRecommendations(result)[0],
              "--shading: flat is 1.2× slower and gives 16× the error; gouraud gives 50% more error, no "
              "measurable difference in time: keep phong");
    // Flat measured faster: a trade-off, no advice either way.
    result.rows[1] = row("shading", "flat", 0.32, 5.0, TimeVerdict::Faster);
    const std::string line = tradeRecommendations(result)[0];
    EXPECT_TRUE(has(line, "flat is 2.0× faster for 16× the error")) << line;
    EXPECT_FALSE(has(line, "keep")) << line;
}

// A blank image is fast and, on a dark scene, may score well: it is named as blank, with no time.
// Catches: "faster" or "use" said of a setting that drew nothing.
TEST(TradeRecommend, BlankImageIsNeverRecommended) {
    TradeRow unorm16 = row("depth", "unorm16", 0.01, 10.0 / 5.7, TimeVerdict::Faster);
    unorm16.blank = true;
    const std::string line = tradeRecommendations(resultWith({unorm16}))[0];
    EXPECT_TRUE(has(line, "unorm16 drew nothing")) << line;
    EXPECT_FALSE(has(line, "faster")) << line;
    EXPECT_FALSE(has(line, "use unorm16")) << line;
}

// Catches: lines out of the knobs' order, or one line per value instead of per knob.
TEST(TradeRecommend, OneLinePerKnobInTheOrderRun) {
    const std::vector<std::string> lines = tradeRecommendations(resultWith(
        {row("shading", "flat", 0.32, 12.0, TimeVerdict::Slower), row("shading", "gouraud", 0.03, 10.5),
         row("aa", "msaa2", 0.01, 17.0, TimeVerdict::Slower)}));
    ASSERT_EQ(lines.size(), 2u);
    EXPECT_EQ(lines[0].rfind("--shading: ", 0), 0u) << lines[0];
    EXPECT_EQ(lines[1].rfind("--aa: ", 0), 0u) << lines[1];
    EXPECT_TRUE(has(lines[0], "keep the scene's own")) << lines[0];  // no "(the baseline's own)" entry
}

}  // namespace
}  // namespace facet
