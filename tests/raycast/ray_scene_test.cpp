// RayScene: what it hands to Embree and what it refuses.
#include <cstdint>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "raycast/ray_scene.h"

namespace facet {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// A ray whose origin or direction is finite but beyond Embree's ±1.844e18 (the dead lanes of a batch of
// fragments hold such garbage) is never handed over: Debian's Embree asserts on it and aborts the process.
// It reports "not occluded"; the other lanes of its packet are traced as usual.
TEST(RaySceneTest, RaysBeyondEmbreesRangeAreNotTraced) {
    const std::vector<vec3> positions = {{-1.0f, -1.0f, -1.0f}, {1.0f, -1.0f, -1.0f}, {0.0f, 1.0f, -1.0f}};
    const std::vector<std::uint32_t> indices = {0, 1, 2};
    const std::vector<RayMesh> meshes = {{positions, indices, true}};
    const RayScene scene(meshes);

    EXPECT_TRUE(scene.occluded({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 0.0f, kInfinity));
    EXPECT_FALSE(scene.occluded({-2.8e22f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 0.0f, kInfinity));
    EXPECT_FALSE(scene.occluded({0.0f, 0.0f, 0.0f}, {1e20f, 0.0f, -1.0f}, 0.0f, kInfinity));

    Vec3x8 origin(vec3(0.0f)), direction(vec3(0.0f, 0.0f, -1.0f));
    origin.x[1] = -2.8e22f;  // lane 1: the origin
    origin.y[2] = -1.0e29f;  // lane 2: the origin
    direction.x[3] = 1e20f;  // lane 3: the direction
    EXPECT_EQ(scene.occluded8(origin, direction, splat(0.0f), splat(kInfinity), 0xffu), 0xf1u);
}

}  // namespace
}  // namespace facet
