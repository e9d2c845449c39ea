#include "bench/chart.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <sstream>
#include <utility>

#include "pipeline/color.h"

namespace facet {

namespace {

using glm::dvec2;

struct Glyph {
    char c;
    std::array<std::uint8_t, 7> rows;  // top to bottom, bit 4 is the leftmost column
};

// The classic 5×7 character-LCD shapes: digits, capitals and a little punctuation (lower case is drawn
// as upper case).
constexpr Glyph kFont[] = {
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}}, {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}}, {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}}, {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}}, {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}}, {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'A', {0x0E, 0x11, 0x11, 0x11, 0x1F, 0x11, 0x11}}, {'B', {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E}},
    {'C', {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}}, {'D', {0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C}},
    {'E', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}}, {'F', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10}},
    {'G', {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}}, {'H', {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
    {'I', {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}}, {'J', {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C}},
    {'K', {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}}, {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F}},
    {'M', {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}}, {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}},
    {'O', {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}}, {'P', {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10}},
    {'Q', {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}}, {'R', {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11}},
    {'S', {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}}, {'T', {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
    {'U', {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}}, {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04}},
    {'W', {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}}, {'X', {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11}},
    {'Y', {0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04}}, {'Z', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}}, {',', {0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08}},
    {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}}, {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}},
    {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}}, {'/', {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00}},
    {':', {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}}, {'%', {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}},
    {'=', {0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00}}, {'<', {0x02, 0x04, 0x08, 0x10, 0x08, 0x04, 0x02}},
    {'>', {0x08, 0x04, 0x02, 0x01, 0x02, 0x04, 0x08}}, {'+', {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}},
    {'_', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F}}, {'|', {0x04, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
};

// 1, 2 or 5 times a power of ten, about range / ticks.
double niceStep(double range, int ticks) {
    const double raw = range / ticks;
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    const double normal = raw / magnitude;
    return (normal <= 1.0 ? 1.0 : normal <= 2.0 ? 2.0 : normal <= 5.0 ? 5.0 : 10.0) * magnitude;
}

std::string formatTick(double value, double step) {
    const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
    std::ostringstream text;
    text << std::fixed << std::setprecision(decimals) << value;
    return text.str();
}

std::string formatCount(double value) {  // 1000 → "1K", 1000000 → "1M"
    if (value >= 1e6) return formatTick(value / 1e6, 1.0) + "M";
    if (value >= 1e3) return formatTick(value / 1e3, 1.0) + "K";
    return formatTick(value, 1.0);
}

}  // namespace

vec4 srgb8(int r, int g, int b) {
    return vec4(srgbToLinear(r / 255.0f), srgbToLinear(g / 255.0f), srgbToLinear(b / 255.0f), 1.0f);
}

void Canvas::text(int x, int y, std::string_view text, int scale, vec4 color) {
    for (const char raw : text) {
        const char c = static_cast<char>(std::toupper(static_cast<unsigned char>(raw)));
        for (const Glyph& glyph : kFont) {
            if (glyph.c != c) continue;
            for (int row = 0; row < 7; ++row)
                for (int column = 0; column < 5; ++column)
                    if (glyph.rows[row] & (0x10 >> column))
                        fillRect(x + column * scale, y + row * scale, x + (column + 1) * scale,
                                 y + (row + 1) * scale, color);
        }
        x += 6 * scale;
    }
}

void drawPanel(Canvas& canvas, int left, int top, int width, int height, const std::string& title,
               const std::string& xLabel, bool logX, const std::vector<Series>& series) {
    const vec4 ink = srgb8(20, 20, 20), grid = srgb8(225, 225, 225);
    const int plotLeft = left + 80, plotRight = left + width - 40;
    const int plotTop = top + 40, plotBottom = top + height - 60;
    canvas.text(left + (width - Canvas::textWidth(title, 2)) / 2, top + 8, title, 2, ink);

    // Ranges and ticks.
    double maxX = 0.0, minX = std::numeric_limits<double>::max(), maxY = 0.0;
    for (const Series& s : series)
        for (const dvec2& p : s.points) {
            if (std::isnan(p.y)) continue;
            maxX = std::max(maxX, p.x);
            minX = std::min(minX, p.x);
            maxY = std::max(maxY, p.y);
        }
    if (maxY <= 0.0 || maxX <= 0.0) return;
    const double yStep = niceStep(1.05 * maxY, 5);
    const double yMax = std::ceil(1.05 * maxY / yStep) * yStep;
    double xLow = 0.0, xHigh = 0.0, xStep = 0.0;
    if (logX) {
        xLow = std::log10(minX) - 0.15;
        xHigh = std::log10(maxX) + 0.15;
    } else {
        xStep = niceStep(maxX, 5);
        xHigh = std::ceil(1.02 * maxX / xStep) * xStep;
    }
    auto toPixel = [&](dvec2 p) {
        const double x = logX ? std::log10(p.x) : p.x;
        return vec2(static_cast<float>(plotLeft + (x - xLow) / (xHigh - xLow) * (plotRight - plotLeft)),
                    static_cast<float>(plotBottom - p.y / yMax * (plotBottom - plotTop)));
    };

    // Grid, axes and tick labels.
    for (double y = 0.0; y <= yMax + 0.5 * yStep; y += yStep) {
        const int py = static_cast<int>(std::lround(toPixel({logX ? 1.0 : 0.0, y}).y));
        canvas.fillRect(plotLeft, py, plotRight, py + 1, grid);
        const std::string label = formatTick(y, yStep);
        canvas.text(plotLeft - 10 - Canvas::textWidth(label, 2), py - 7, label, 2, ink);
    }
    std::vector<std::pair<double, std::string>> xTicks;
    if (logX) {
        for (int decade = static_cast<int>(std::ceil(xLow)); decade <= xHigh; ++decade)
            xTicks.emplace_back(std::pow(10.0, decade), formatCount(std::pow(10.0, decade)));
    } else {
        for (double x = 0.0; x <= xHigh + 0.5 * xStep; x += xStep)
            xTicks.emplace_back(x, formatTick(x, xStep));
    }
    for (const auto& [x, label] : xTicks) {
        const int px = static_cast<int>(std::lround(toPixel({x, 0.0}).x));
        canvas.fillRect(px, plotTop, px + 1, plotBottom, grid);
        canvas.fillRect(px, plotBottom, px + 1, plotBottom + 6, ink);
        canvas.text(px - Canvas::textWidth(label, 2) / 2, plotBottom + 12, label, 2, ink);
    }
    canvas.fillRect(plotLeft, plotTop, plotLeft + 2, plotBottom + 1, ink);
    canvas.fillRect(plotLeft, plotBottom, plotRight, plotBottom + 2, ink);
    canvas.text(plotLeft + (plotRight - plotLeft - Canvas::textWidth(xLabel, 2)) / 2, plotBottom + 36, xLabel,
                2, ink);
    canvas.text(left + 4, plotTop - 22, "MS", 2, ink);

    // Series, then the legend.
    int legendY = plotTop + 12;
    for (const Series& s : series) {
        std::vector<vec2> pixels;
        for (const dvec2& p : s.points)
            if (!std::isnan(p.y)) pixels.push_back(toPixel(p));
        if (pixels.empty()) continue;
        for (std::size_t i = 1; i < pixels.size(); ++i)
            canvas.line(pixels[i - 1], pixels[i], 3.0f, s.color);
        for (const vec2& p : pixels)
            canvas.disc(p, 6.0f, s.color);
        canvas.line(vec2(plotLeft + 16, legendY + 7), vec2(plotLeft + 56, legendY + 7), 3.0f, s.color);
        canvas.disc(vec2(plotLeft + 36, legendY + 7), 6.0f, s.color);
        canvas.text(plotLeft + 68, legendY, s.name, 2, ink);
        legendY += 26;
    }
}

namespace {

// "0.5", "0.001", "1E-5": a log axis's tick, short.
std::string formatLogTick(double value) {
    std::ostringstream text;
    if (value >= 1e-3 && value < 1e5) {
        text << value;
        return text.str();
    }
    const int exponent = static_cast<int>(std::lround(std::log10(value)));
    const double mantissa = value / std::pow(10.0, exponent);
    if (std::abs(mantissa - 1.0) > 1e-9)
        text << std::lround(mantissa);
    else
        text << 1;
    text << "E" << exponent;
    return text.str();
}

struct Box {
    int x0, y0, x1, y1;
    int overlap(const Box& o) const {
        const int w = std::min(x1, o.x1) - std::max(x0, o.x0), h = std::min(y1, o.y1) - std::max(y0, o.y0);
        return w > 0 && h > 0 ? w * h : 0;
    }
};

}  // namespace

std::vector<ScatterMark> drawScatter(Canvas& canvas, int left, int top, int width, int height,
                                     const std::string& title, const std::string& xLabel,
                                     const std::string& yLabel, const std::string& key, bool logY,
                                     const std::vector<LabelledPoint>& points,
                                     const std::vector<std::size_t>& joined) {
    const vec4 ink = srgb8(20, 20, 20), grid = srgb8(225, 225, 225);
    const int plotLeft = left + 90, plotRight = left + width - 30;
    const int plotTop = top + 70, plotBottom = top + height - 60;
    canvas.text(left + (width - Canvas::textWidth(title, 2)) / 2, top + 8, title, 2, ink);
    if (points.empty()) return {};

    // Ranges (x over the spread bars too). x: linear, from a round value below the fastest. y: from 0,
    // or log over the positive values.
    double minX = std::numeric_limits<double>::max(), maxX = 0.0, maxY = 0.0;
    double minPositiveY = std::numeric_limits<double>::max();
    for (const LabelledPoint& p : points) {
        minX = std::min(minX, p.point.x);
        maxX = std::max(maxX, p.point.x);
        if (!std::isnan(p.spread.x)) minX = std::min(minX, p.spread.x);
        if (!std::isnan(p.spread.y)) maxX = std::max(maxX, p.spread.y);
        maxY = std::max(maxY, p.point.y);
        if (p.point.y > 0) minPositiveY = std::min(minPositiveY, p.point.y);
    }
    if (maxX <= minX) maxX = minX + std::max(1e-3, 0.1 * std::abs(minX));
    // Times spanning more than a decade (a shadow map of 4096² beside a plain frame) on a log axis.
    const bool logX = minX > 0.0 && maxX / minX > 10.0;
    double xLow = 0.0, xHigh = 0.0, xStep = 0.0;
    if (logX) {
        const double span = std::log10(maxX) - std::log10(minX);
        xLow = std::log10(minX) - 0.05 * span;
        xHigh = std::log10(maxX) + 0.05 * span;
    } else {
        xStep = niceStep(maxX - minX, 5);
        xLow = std::max(0.0, std::floor((minX - 0.05 * (maxX - minX)) / xStep) * xStep);
        xHigh = std::ceil((maxX + 0.05 * (maxX - minX)) / xStep) * xStep;
    }
    double yLow = 0.0, yHigh = 0.0, yStep = 0.0;
    if (logY) {
        if (maxY <= 0.0) maxY = minPositiveY = 1.0;
        yLow = std::floor(std::log10(minPositiveY)) - (minPositiveY == maxY ? 1.0 : 0.0);
        yHigh = std::ceil(std::log10(maxY) + 1e-9);
        if (yHigh <= yLow) yHigh = yLow + 1.0;
    } else {
        if (maxY <= 0.0) maxY = 1.0;
        yStep = niceStep(1.05 * maxY, 5);
        yHigh = std::ceil(1.05 * maxY / yStep) * yStep;
    }
    auto toPixel = [&](dvec2 p) {
        const double y = logY ? (p.y > 0 ? std::max(std::log10(p.y), yLow) : yLow) : p.y;
        const double x = logX ? std::log10(p.x) : p.x;
        return vec2(static_cast<float>(plotLeft + (x - xLow) / (xHigh - xLow) * (plotRight - plotLeft)),
                    static_cast<float>(plotBottom - (y - yLow) / (yHigh - yLow) * (plotBottom - plotTop)));
    };

    // Grid, axes and tick labels.
    std::vector<std::pair<double, std::string>> yTicks;
    if (logY) {
        const bool fine = yHigh - yLow <= 2.0;  // few decades: 1, 2 and 5 of each
        for (int decade = static_cast<int>(yLow); decade <= yHigh; ++decade)
            for (const double m : {1.0, 2.0, 5.0}) {
                if (m > 1.0 && !fine) continue;
                const double value = m * std::pow(10.0, decade);
                if (std::log10(value) <= yHigh + 1e-9) yTicks.emplace_back(value, formatLogTick(value));
            }
    } else {
        for (double y = 0.0; y <= yHigh + 0.5 * yStep; y += yStep)
            yTicks.emplace_back(y, formatTick(y, yStep));
    }
    for (const auto& [y, label] : yTicks) {
        const int py = static_cast<int>(std::lround(toPixel({minX, y}).y));
        canvas.fillRect(plotLeft, py, plotRight, py + 1, grid);
        canvas.text(plotLeft - 10 - Canvas::textWidth(label, 2), py - 7, label, 2, ink);
    }
    std::vector<std::pair<double, std::string>> xTicks;
    if (logX) {
        for (int decade = static_cast<int>(std::floor(xLow)); decade <= xHigh; ++decade)
            for (const double m : {1.0, 2.0, 5.0}) {
                const double value = m * std::pow(10.0, decade);
                if (std::log10(value) >= xLow && std::log10(value) <= xHigh)
                    xTicks.emplace_back(value, formatLogTick(value));
            }
    } else {
        for (double x = xLow; x <= xHigh + 0.5 * xStep; x += xStep)
            xTicks.emplace_back(x, formatTick(x, xStep));
    }
    for (const auto& [x, label] : xTicks) {
        const int px = static_cast<int>(std::lround(toPixel({x, 0.0}).x));
        canvas.fillRect(px, plotTop, px + 1, plotBottom, grid);
        canvas.fillRect(px, plotBottom, px + 1, plotBottom + 6, ink);
        canvas.text(px - Canvas::textWidth(label, 2) / 2, plotBottom + 12, label, 2, ink);
    }
    canvas.fillRect(plotLeft, plotTop, plotLeft + 2, plotBottom + 1, ink);
    canvas.fillRect(plotLeft, plotBottom, plotRight, plotBottom + 2, ink);
    const std::string xTitle = logX ? xLabel + " (LOG)" : xLabel;
    canvas.text(plotLeft + (plotRight - plotLeft - Canvas::textWidth(xTitle, 2)) / 2, plotBottom + 36, xTitle,
                2, ink);
    canvas.text(left + 4, plotTop - 30, yLabel, 2, ink);
    canvas.text(plotLeft + 10, plotTop - 12, key, 1, ink);  // under it, clear of the ticks' labels

    // The joined points' line, the spread bars, then the points (the first on top), then their labels.
    std::vector<ScatterMark> marks(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        marks[i].centre = toPixel(points[i].point);
        marks[i].spreadLeft = marks[i].spreadRight = marks[i].centre.x;
        if (!std::isnan(points[i].spread.x) && !std::isnan(points[i].spread.y)) {
            marks[i].spreadLeft = toPixel({points[i].spread.x, points[i].point.y}).x;
            marks[i].spreadRight = toPixel({points[i].spread.y, points[i].point.y}).x;
        }
    }
    for (std::size_t i = 1; i < joined.size(); ++i)
        canvas.line(marks[joined[i - 1]].centre, marks[joined[i]].centre, 2.0f, srgb8(120, 170, 230));
    constexpr int kRadius = 5;
    for (std::size_t i = points.size(); i-- > 0;) {
        const ScatterMark& m = marks[i];
        if (m.spreadRight - m.spreadLeft < 1.0f) continue;
        const int y = static_cast<int>(m.centre.y);
        canvas.fillRect(static_cast<int>(m.spreadLeft), y - 1, static_cast<int>(m.spreadRight) + 1, y + 1,
                        points[i].color);
        for (const float end : {m.spreadLeft, m.spreadRight})  // the ends: short upright ticks
            canvas.fillRect(static_cast<int>(end), y - 4, static_cast<int>(end) + 1, y + 4, points[i].color);
    }
    const vec4 paper = canvas.image().pixels.empty() ? vec4(1.0f) : canvas.image().at(0, 0);
    for (std::size_t i = points.size(); i-- > 0;) {
        canvas.disc(marks[i].centre, kRadius, points[i].color);
        if (points[i].hollow) canvas.disc(marks[i].centre, kRadius - 2, paper);
    }
    auto discBox = [&](std::size_t i) {
        const int x = static_cast<int>(marks[i].centre.x), y = static_cast<int>(marks[i].centre.y);
        return Box{x - kRadius, y - kRadius, x + kRadius + 1, y + kRadius + 1};
    };
    std::vector<Box> discs, bars, labels;
    for (std::size_t i = 0; i < points.size(); ++i) {
        discs.push_back(discBox(i));
        const int y = static_cast<int>(marks[i].centre.y);
        if (marks[i].spreadRight - marks[i].spreadLeft >= 1.0f)
            bars.push_back({static_cast<int>(marks[i].spreadLeft), y - 4,
                            static_cast<int>(marks[i].spreadRight) + 1, y + 4});
    }
    const Box plot{plotLeft + 3, plotTop, plotRight, plotBottom};
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (points[i].label.empty()) continue;
        const int w = Canvas::textWidth(points[i].label, 1);
        const int px = static_cast<int>(marks[i].centre.x), py = static_cast<int>(marks[i].centre.y);
        std::vector<Box> candidates;
        for (const int dy : {0, -10, 10, -20, 20, -30, 30, -40, 40}) {
            candidates.push_back({px + 9, py - 3 + dy, px + 9 + w, py + 4 + dy});  // right
            candidates.push_back({px - 9 - w, py - 3 + dy, px - 9, py + 4 + dy});  // left
            if (dy == 0) {
                candidates.push_back({px - w / 2, py - 16, px - w / 2 + w, py - 9});  // above
                candidates.push_back({px - w / 2, py + 9, px - w / 2 + w, py + 16});  // below
            }
        }
        const Box* best = nullptr;
        long bestCost = std::numeric_limits<long>::max();
        for (const Box& c : candidates) {
            // Refused: a label seen in part (outside the plot), over another label, or over the first
            // point (the one the others are read against: the trade's baseline).
            const Box padded{c.x0 - 1, c.y0 - 1, c.x1 + 1, c.y1 + 1};
            if (c.overlap(plot) < (c.x1 - c.x0) * (c.y1 - c.y0)) continue;
            if (std::any_of(labels.begin(), labels.end(),
                            [&](const Box& l) { return padded.overlap(l) > 0; }))
                continue;
            if (i != 0 && padded.overlap(discs[0]) > 0) continue;
            // Least over the points, then over the bars (a label across a bar is hard to read).
            long cost = 0;
            for (const Box& d : discs)
                cost += 4 * c.overlap(d);
            for (const Box& b : bars)
                cost += c.overlap(b);
            if (cost < bestCost) {
                bestCost = cost;
                best = &c;
            }
            if (cost == 0) break;
        }
        if (!best) continue;  // no room: left unlabelled rather than written over another
        canvas.text(best->x0, best->y0, points[i].label, 1, ink);
        labels.push_back(*best);
        marks[i].labelled = true;
        marks[i].x0 = best->x0;
        marks[i].y0 = best->y0;
        marks[i].x1 = best->x1;
        marks[i].y1 = best->y1;
    }
    return marks;
}

}  // namespace facet
