// facet trade on a view whose baseline draws nothing of the scene: its scores are marked meaningless
// and nothing is judged against it (no "NO EFFECT", no time verdict, not on the front).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli/trade_command.h"
#include "quick_trade.h"
#include "support/bundled_models.h"
#include "support/temp_folder.h"
#include "trade/blank.h"
#include "trade/trade.h"

namespace facet {
namespace {

using testing_support::kModels;
using testing_support::quickTrade;

// The camera inside the cow's bounds with a near plane of 1e-6 and a 16-bit unorm depth buffer: every
// depth, 1 - near/z, rounds to the far plane and fails the depth test, so the scene as given draws
// nothing while the reference (and --depth float) shows the cow.
std::filesystem::path blankBaselineScene(const std::filesystem::path& folder) {
    const std::filesystem::path path = folder / "near16.json";
    std::ofstream(path) << R"({"width": 48, "height": 36,
        "camera": {"eye": [0.1, 0.3, 0.5], "target": [0, 0.2, 0], "near": 1e-6},
        "pipeline": {"depth": "unorm16"},
        "objects": [{"model": ")"
                        << kModels.string() << R"(/spot/spot_triangulated.obj"}]})";
    return path;
}

// Catches: a blank baseline reported with "NO EFFECT" for every knob that also draws nothing (the
// issue's "PSNR 100, SSIM 1.0, NO EFFECT"), with time verdicts against an empty image, on the front,
// without the warning that the scores are meaningless, or with knob advice drawn from it.
TEST(TradeBlankView, ABlankBaselineMarksEveryScoreMeaningless) {
    const testing_support::TempFolder folder;
    const TradeResult result =
        quickTrade(blankBaselineScene(folder.path()), "depth,shading", folder.path() / "t", false);
    ASSERT_FALSE(result.rows.empty());
    ASSERT_TRUE(result.rows.front().blank);
    bool anyDraws = false;  // --depth float draws the cow: the reference does show the scene
    for (const TradeRow& row : result.rows) {
        SCOPED_TRACE(row.setting.label());
        EXPECT_FALSE(row.noEffect);  // --shading flat draws nothing too, which says nothing of the knob
        EXPECT_EQ(row.timeVerdict, TimeVerdict::WithinNoise);
        EXPECT_FALSE(row.withinReferenceFloor);
        EXPECT_FALSE(scoresMeaningful(result, row));
        anyDraws = anyDraws || !row.blank;
    }
    EXPECT_TRUE(anyDraws);
    EXPECT_FALSE(result.rows.front().pareto);
    ASSERT_FALSE(result.warnings.empty());
    EXPECT_NE(result.warnings.front().find("the scores are meaningless"), std::string::npos);
    ASSERT_EQ(result.recommendations.size(), 1u);
    EXPECT_NE(result.recommendations.front().find("draws nothing"), std::string::npos);

    // The CSV says it on every row: the last column, scores_meaningful, is 0.
    std::ifstream csv(folder.path() / "t" / "trade.csv");
    std::string line;
    std::getline(csv, line);
    ASSERT_EQ(line.substr(line.rfind(',') + 1), "scores_meaningful");
    int rows = 0;
    while (std::getline(csv, line)) {
        ++rows;
        EXPECT_EQ(line.substr(line.rfind(',') + 1), "0") << line;
    }
    EXPECT_EQ(rows, static_cast<int>(result.rows.size()));
}

// The same scene with 32-bit float depth as given draws the cow: nothing is marked meaningless.
// Catches: markBlankBaseline acting on a baseline that draws (every verdict of a good trade erased).
TEST(TradeBlankView, ABaselineThatDrawsKeepsItsScores) {
    const testing_support::TempFolder folder;
    std::filesystem::path scene = blankBaselineScene(folder.path());
    {
        std::stringstream text;
        text << std::ifstream(scene).rdbuf();
        std::string s = text.str();
        s.replace(s.find("unorm16"), 7, "float");
        std::ofstream(scene) << s;
    }
    const TradeResult result = quickTrade(scene, "shading", folder.path() / "t", false);
    ASSERT_FALSE(result.rows.empty());
    EXPECT_FALSE(result.rows.front().blank);
    EXPECT_TRUE(scoresMeaningful(result, result.rows.front()));
    for (const std::string& warning : result.warnings)
        EXPECT_EQ(warning.find("meaningless"), std::string::npos) << warning;
}

}  // namespace
}  // namespace facet
