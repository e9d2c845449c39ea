// A point light exactly at a vertex (lighting.h's lightVector): the vertex reaches eye space a few
// float steps away from the light's own eye-space position, and that rounding must not become a
// direction. L = 0 there, in float (the rasterizer, whose flat and Gouraud shading light the vertex
// itself), in eight lanes, and in double (the reference); a point measurably away keeps a unit L.
#include <cmath>

#include <gtest/gtest.h>

#include "shading/lighting.h"

namespace facet {
namespace {

// A light at a cube corner seen from the camera, in eye space: numbers of the size of the scene.
LightParams pointLightAt(vec3 position) {
    LightParams light;
    light.kind = LightKind::Point;
    light.position = position;
    return light;
}

// The position `steps` float steps from `p` in every coordinate, towards +∞: what rounding the
// vertex's view transform in float leaves (facet step showed d = 1.49e-8 for a unit cube's corner).
vec3 roundedAway(vec3 p, int steps) {
    for (int i = 0; i < steps; ++i)
        p = vec3(std::nextafter(p.x, INFINITY), std::nextafter(p.y, INFINITY), std::nextafter(p.z, INFINITY));
    return p;
}

// Catches: the rounding between a vertex and a light placed on it normalised into a unit L (N·L = 0.9
// lit the faces around the vertex under flat and Gouraud shading, where L = 0 is documented).
TEST(LightAtVertex, RoundingBetweenLightAndVertexGivesNoDirection) {
    const vec3 corner(0.341f, -0.2787f, -3.6055f);
    const LightParams light = pointLightAt(corner);
    for (int steps : {1, 2, 4}) {
        const vec3 vertex = roundedAway(corner, steps);
        ASSERT_NE(vertex, corner);
        EXPECT_EQ(lightVector<float>(light, vertex).L, vec3(0.0f)) << steps << " steps";
        // The reference shades in double at the vertex's exact position: the light is still rounded.
        const glm::dvec3 exact = glm::dvec3(vertex) + glm::dvec3(1e-9, -2e-9, 0.5e-9);
        EXPECT_EQ(lightVector<double>(light, exact).L, glm::dvec3(0.0)) << steps << " steps";
        // Eight lanes decide as one.
        Vec3x8 lanesOf;
        for (int i = 0; i < 8; ++i) {
            lanesOf.x[i] = vertex.x;
            lanesOf.y[i] = vertex.y;
            lanesOf.z[i] = vertex.z;
        }
        const Vec3x8 L = lightVector<Float8>(light, lanesOf).L;
        EXPECT_EQ(vec3(L.x[3], L.y[3], L.z[3]), vec3(0.0f)) << steps << " steps";
    }
}

// Catches: an "at the light" distance so generous that a point plainly apart from the light loses it
// (a thousandth of its distance from the eye is a visible offset: it must still be lit, L unit).
TEST(LightAtVertex, APointMeasurablyAwayKeepsAUnitDirection) {
    const vec3 corner(0.341f, -0.2787f, -3.6055f);
    const LightParams light = pointLightAt(corner);
    const float apart = 1e-3f * glm::length(corner);
    const LightVector<float> toLight = lightVector<float>(light, corner + vec3(0.0f, 0.0f, apart));
    EXPECT_NEAR(glm::length(toLight.L), 1.0f, 1e-5f);
    EXPECT_NEAR(toLight.L.z, -1.0f, 1e-5f);
    EXPECT_NEAR(toLight.distance, apart, 1e-6f * glm::length(corner));
}

}  // namespace
}  // namespace facet
