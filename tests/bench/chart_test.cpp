// The scatter chart (facet trade's chart.png): its labels never cover one another nor the first point,
// unlabelled points stay so, a point's spread is drawn as a bar, a hollow point as a ring.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/chart.h"

namespace facet {
namespace {

bool overlap(const ScatterMark& a, const ScatterMark& b) {
    return std::min(a.x1, b.x1) > std::max(a.x0, b.x0) && std::min(a.y1, b.y1) > std::max(a.y0, b.y0);
}

// Thirty labelled points piled on and around the first (a trade's settings whose time and error are
// the baseline's), a few far away. Catches: a label written over another label when no free place is
// left (it must be left out instead), a label over the first point, the first point's label not placed
// first, or an unlabelled point given a label.
TEST(ChartScatter, LabelsNeverCoverOneAnotherNorTheFirstPoint) {
    Canvas canvas(1200, 800, vec4(1.0f));
    std::vector<LabelledPoint> points;
    points.push_back({"baseline", {10.0, 0.01}, srgb8(20, 20, 20)});
    for (int k = 0; k < 30; ++k)
        points.push_back({"--setting number " + std::to_string(k),
                          {10.0 + 0.02 * (k % 5), 0.01 * (1.0 + 0.01 * k)},
                          srgb8(150, 150, 150)});
    points.push_back({"", {10.01, 0.01}, srgb8(210, 210, 210)});  // unlabelled
    points.push_back({"far away", {40.0, 0.001}, srgb8(30, 100, 200)});
    const std::vector<ScatterMark> marks =
        drawScatter(canvas, 0, 0, 1200, 800, "TITLE", "X", "Y", "KEY", true, points, {});
    ASSERT_EQ(marks.size(), points.size());
    EXPECT_TRUE(marks[0].labelled);
    EXPECT_TRUE(marks.back().labelled);
    EXPECT_FALSE(marks[points.size() - 2].labelled);
    ScatterMark firstDisc = marks[0];  // the first point's disc as a box
    firstDisc.x0 = static_cast<int>(marks[0].centre.x) - 5;
    firstDisc.x1 = static_cast<int>(marks[0].centre.x) + 6;
    firstDisc.y0 = static_cast<int>(marks[0].centre.y) - 5;
    firstDisc.y1 = static_cast<int>(marks[0].centre.y) + 6;
    int labelled = 0;
    for (std::size_t i = 0; i < marks.size(); ++i) {
        if (!marks[i].labelled) continue;
        ++labelled;
        if (i > 0) {
            EXPECT_FALSE(overlap(marks[i], firstDisc)) << points[i].label;
        }
        for (std::size_t j = i + 1; j < marks.size(); ++j)
            if (marks[j].labelled) {
                EXPECT_FALSE(overlap(marks[i], marks[j])) << points[i].label << " / " << points[j].label;
            }
    }
    EXPECT_GT(labelled, 5);   // the pile still gets the labels there is room for
    EXPECT_LT(labelled, 31);  // and not all of them
}

// Catches: a point's spread (its fastest to its slowest frame) not drawn, drawn off the point's height,
// or left out of the x range (cut at the plot's edge); a hollow point drawn as a disc.
TEST(ChartScatter, SpreadBarsAndRings) {
    const vec4 paper(1.0f), red = srgb8(210, 40, 40);
    Canvas canvas(1200, 800, paper);
    std::vector<LabelledPoint> points = {{"wide", {10.0, 0.01}, red}, {"ring", {12.0, 0.1}, red}};
    points[0].spread = {5.0, 20.0};  // past every other x: the axis must reach it
    points[1].hollow = true;
    const std::vector<ScatterMark> marks =
        drawScatter(canvas, 0, 0, 1200, 800, "TITLE", "X", "Y", "", true, points, {});
    const ScatterMark& wide = marks[0];
    EXPECT_LT(wide.spreadLeft, wide.centre.x - 20);
    EXPECT_GT(wide.spreadRight, wide.centre.x + 20);
    EXPECT_GT(wide.spreadLeft, 90);     // inside the plot (its left edge is 90 pixels in)
    EXPECT_LT(wide.spreadRight, 1170);  // and its right edge 30 from the image's
    const int y = static_cast<int>(wide.centre.y);
    for (const float x : {wide.spreadLeft + 2, 0.5f * (wide.spreadLeft + wide.centre.x),
                          0.5f * (wide.centre.x + wide.spreadRight), wide.spreadRight - 2})
        EXPECT_EQ(canvas.image().at(static_cast<int>(x), y), red) << x;
    EXPECT_NE(canvas.image().at(static_cast<int>(wide.centre.x), y - 20), red);  // a bar, not a band
    const ScatterMark& ring = marks[1];
    EXPECT_EQ(canvas.image().at(static_cast<int>(ring.centre.x), static_cast<int>(ring.centre.y)), paper);
    EXPECT_EQ(canvas.image().at(static_cast<int>(ring.centre.x) + 4, static_cast<int>(ring.centre.y)), red);
}

}  // namespace
}  // namespace facet
