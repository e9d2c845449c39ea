// The two-sided test (shading/two_sided.h), which the rasterizer runs in float (one lane and eight) and
// the reference in double: at N·V near 0 all three give the same answer for the same normal and point,
// and the answer is the sign of N·V.
#include "shading/two_sided.h"

#include <cmath>

#include <gtest/gtest.h>

#include "pipeline/wide.h"

namespace facet {
namespace {

// A unit normal at angle acos(nDotV) to V, V pointing from P = −3·V (3 units in front of the eye)
// towards the eye; the normal turned about the axis perpendicular to V.
struct Case {
    glm::dvec3 normal, point;
};
Case caseAt(double nDotV) {
    const glm::dvec3 view = glm::normalize(glm::dvec3(0.3, -0.2, 1.0));  // towards the eye
    const glm::dvec3 across = glm::normalize(glm::cross(view, glm::dvec3(0, 1, 0)));
    const double sine = std::sqrt(1.0 - nDotV * nDotV);
    return {nDotV * view + sine * across, -3.0 * view};
}

// Catches: the rasterizer's and the reference's flip decided differently near N·V = 0 (a margin, or a
// normalised N·V in one path and not the other), or the eight-lane form disagreeing with one lane; the
// test's sign reversed (the lit side turned away from the viewer).
TEST(TwoSided, FloatEightLanesAndDoubleAgreeNearGrazing) {
    // +0.0043: the pixel where the two renderers once disagreed by 111/255; the others down to where
    // float still resolves N·V from its rounding (about 1e-6 here).
    for (const double nDotV : {0.5, 0.0043, 1e-3, 1e-4, 1e-5, -1e-5, -1e-4, -1e-3, -0.0043, -0.5}) {
        SCOPED_TRACE(nDotV);
        const Case c = caseAt(nDotV);
        const bool underside = nDotV < 0.0;
        EXPECT_EQ(seesUnderside(c.normal, c.point), underside);  // the reference: double
        const glm::vec3 n(c.normal), p(c.point);
        EXPECT_EQ(seesUnderside(n, p), underside);  // the rasterizer: one lane
        Vec3x8 n8(n), p8(p);
        const unsigned lanes = signMask(seesUnderside(n8, p8));  // eight lanes
        EXPECT_EQ(lanes, underside ? 0xFFu : 0u);
        // Scaling either vector (an interpolated normal is not unit length) does not change the answer.
        EXPECT_EQ(seesUnderside(glm::vec3(7.0f * n), glm::vec3(0.25f * p)), underside);
    }
}

}  // namespace
}  // namespace facet
