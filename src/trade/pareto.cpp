#include "trade/pareto.h"

#include <algorithm>
#include <cmath>

namespace facet {

std::vector<std::size_t> paretoFront(const std::vector<glm::dvec2>& points) {
    return paretoFront(points, 0.0, 0.0);
}

std::vector<std::size_t> paretoFront(const std::vector<glm::dvec2>& points, double xRelative,
                                     double yAbsolute) {
    const double xFactor = 1.0 + xRelative;
    auto dominates = [&](glm::dvec2 a, glm::dvec2 b) {  // a at least as good in both, better in one
        const bool asFast = a.x <= b.x * xFactor, asAccurate = a.y <= b.y + yAbsolute;
        const bool faster = a.x * xFactor < b.x, moreAccurate = a.y + yAbsolute < b.y;
        return asFast && asAccurate && (faster || moreAccurate);
    };
    std::vector<std::size_t> front;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (std::isnan(points[i].x) || std::isnan(points[i].y)) continue;
        bool dominated = false;
        for (std::size_t j = 0; j < points.size() && !dominated; ++j)
            dominated = j != i && !std::isnan(points[j].x) && !std::isnan(points[j].y) &&
                        dominates(points[j], points[i]);
        if (!dominated) front.push_back(i);
    }
    std::sort(front.begin(), front.end(), [&](std::size_t a, std::size_t b) {
        return points[a].x != points[b].x ? points[a].x < points[b].x : points[a].y < points[b].y;
    });
    return front;
}

}  // namespace facet
