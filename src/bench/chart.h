// Charts drawn by hand into a LinearImage: lines, discs, rectangles and a 5×7 bitmap font, and a panel
// of line series with axes, ticks and a legend (facet bench --vs-mesa; any command that charts).
#pragma once

#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "io/image_io.h"
#include "pipeline/glsl.h"

namespace facet {

// A colour given as 8-bit sRGB, as a colour picker shows it, in the image's linear light.
vec4 srgb8(int r, int g, int b);

class Canvas {
  public:
    Canvas(int width, int height, vec4 background) {
        image_.width = width;
        image_.height = height;
        image_.pixels.assign(static_cast<std::size_t>(width) * height, background);
    }
    const LinearImage& image() const { return image_; }

    void fillRect(int x0, int y0, int x1, int y1, vec4 color) {  // [x0, x1) × [y0, y1)
        for (int y = std::max(y0, 0); y < std::min(y1, image_.height); ++y)
            for (int x = std::max(x0, 0); x < std::min(x1, image_.width); ++x)
                image_.at(x, y) = color;
    }
    void disc(vec2 centre, float radius, vec4 color) {
        for (int y = static_cast<int>(std::floor(centre.y - radius)); y <= centre.y + radius; ++y)
            for (int x = static_cast<int>(std::floor(centre.x - radius)); x <= centre.x + radius; ++x) {
                const vec2 d = vec2(x + 0.5f, y + 0.5f) - centre;
                if (dot(d, d) <= radius * radius) fillRect(x, y, x + 1, y + 1, color);
            }
    }
    void line(vec2 a, vec2 b, float width, vec4 color) {  // discs stamped every half pixel
        const int steps = std::max(1, static_cast<int>(std::ceil(2.0f * length(b - a))));
        for (int i = 0; i <= steps; ++i)
            disc(mix(a, b, static_cast<float>(i) / steps), 0.5f * width, color);
    }
    static int textWidth(std::string_view text, int scale) {
        return static_cast<int>(text.size()) * 6 * scale;
    }
    void text(int x, int y, std::string_view text, int scale, vec4 color);  // (x, y): top left

  private:
    LinearImage image_;
};

struct Series {
    std::string name;
    vec4 color;
    std::vector<glm::dvec2> points;  // data units
};

// One panel: y = ms from 0, x linear from 0 or logarithmic over decades; a line with point markers per
// series, grid lines at the ticks, a legend in the top-left corner of the plot.
void drawPanel(Canvas& canvas, int left, int top, int width, int height, const std::string& title,
               const std::string& xLabel, bool logX, const std::vector<Series>& series);

struct LabelledPoint {
    std::string label;  // empty: unlabelled
    glm::dvec2 point;   // data units
    vec4 color;
    // An x range drawn as a horizontal bar through the point (facet trade: its fastest to its slowest
    // frame); NaN: none.
    glm::dvec2 spread{std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN()};
    bool hollow = false;  // a ring instead of a disc: a point set apart from the others
};

// Where drawScatter put a point and its label, in pixels.
struct ScatterMark {
    vec2 centre;
    float spreadLeft = 0, spreadRight = 0;  // the spread bar's ends (the centre's x without a bar)
    bool labelled = false;                  // false: no label, or no room for it clear of the others
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;     // the label's box [x0, x1) × [y0, y1) when labelled
};

// One scatter panel (facet trade): x linear from a round value below the smallest (logarithmic when
// the values span more than a decade), y linear from 0 or
// logarithmic (then values at or below 0 sit on the axis's floor, a decade below the smallest positive);
// the points `joined` (indices, in order) linked by a line, drawn first; then each point's spread bar,
// then the points as discs (or rings), the first drawn last so that it lies on top; then the labels in
// the points' order (the most important first), each beside, above or below its point where it covers
// as little of the points and then of the bars as possible, never another label nor the first point: a label
// with no such place is left out. `key`: a line of small text under the y axis's title (what the colours
// mean).
std::vector<ScatterMark> drawScatter(Canvas& canvas, int left, int top, int width, int height,
                                     const std::string& title, const std::string& xLabel,
                                     const std::string& yLabel, const std::string& key, bool logY,
                                     const std::vector<LabelledPoint>& points,
                                     const std::vector<std::size_t>& joined);

}  // namespace facet
