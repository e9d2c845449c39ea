// The Pareto front of a speed–accuracy trade: the settings no other setting beats on both counts.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace facet {

// Indices of the points (x = time, y = error; less is better in both) that no other point dominates,
// i.e. no other point is at least as fast and at least as accurate and better in one of the two; in
// order of x (then y). Points with a NaN coordinate are never on the front. Equal points are all on it.
std::vector<std::size_t> paretoFront(const std::vector<glm::dvec2>& points);

// The same with differences too small to measure ignored: x within a factor 1 + xRelative of the other's
// (time noise) and y within yAbsolute of the other's (the reference's own error) count as equal, so a
// point dominates another only where it is not measurably worse in either and measurably better in one.
// The relation stays acyclic (a cycle would need y equal all round and x growing all round), so the
// front is never empty. Both margins 0: paretoFront(points).
std::vector<std::size_t> paretoFront(const std::vector<glm::dvec2>& points, double xRelative,
                                     double yAbsolute);

}  // namespace facet
