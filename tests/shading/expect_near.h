// Component-wise closeness of two vectors, for the tests of the lighting formulas.
#pragma once

#include <gtest/gtest.h>
#include <glm/glm.hpp>

namespace facet::testing_shading {

inline void expectVec3Near(const glm::vec3& actual, const glm::vec3& expected, float tolerance = 1e-6f) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

}  // namespace facet::testing_shading
