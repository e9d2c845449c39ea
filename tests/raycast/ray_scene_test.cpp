// RayScene (raycast/ray_scene.h) on hand-built triangles: shadow rays (occluded, occluded8) see exactly
// the opaque triangles inside their range, never trace a non-finite ray, and the eight-lane query agrees
// with the one-lane one; camera rays (nearestOpaque8, allTransparent) name the right mesh and triangle,
// cull by winding as OpenGL does and list a shared edge once; triangles Embree must not see (a
// non-finite corner, an index out of range) are counted and left out.
#include "raycast/ray_scene.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace facet {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// One mesh that owns its arrays (RayMesh only views them).
struct OwnedMesh {
    std::vector<vec3> positions;
    std::vector<std::uint32_t> indices;
    bool opaque = true;
    RayMesh view() const { return {positions, indices, opaque}; }
};

// Adds triangle a, b, c (its own three vertices) to `mesh`.
void addTriangle(OwnedMesh& mesh, vec3 a, vec3 b, vec3 c) {
    for (const vec3& p : {a, b, c}) {
        mesh.indices.push_back(static_cast<std::uint32_t>(mesh.positions.size()));
        mesh.positions.push_back(p);
    }
}

// The triangle (−1,−1), (1,−1), (0,1) in the plane z = `z`: counter-clockwise seen from +z.
void addCounterClockwise(OwnedMesh& mesh, float z) {
    addTriangle(mesh, {-1, -1, z}, {1, -1, z}, {0, 1, z});
}
void addClockwise(OwnedMesh& mesh, float z) {
    addTriangle(mesh, {-1, -1, z}, {0, 1, z}, {1, -1, z});
}

RayScene sceneOf(const std::vector<OwnedMesh>& meshes) {
    std::vector<RayMesh> views;
    for (const OwnedMesh& m : meshes)
        views.push_back(m.view());
    return RayScene(views);
}

const vec3 kAbove(0, 0, 5);  // 5 above the triangle at z = 0, looking down
const vec3 kDown(0, 0, -1);

// ---- occluded -------------------------------------------------------------------------------------

// A ray down through the triangle at z = 0 (t = 5) is blocked; one beside it is not. Breaks if the
// query traces the wrong scene or reads the answer wrongly (Embree sets tfar to −inf when occluded).
TEST(RayScene, OccludedInsideTheTriangleAndFreeBesideIt) {
    OwnedMesh mesh;
    addCounterClockwise(mesh, 0);
    const RayScene scene = sceneOf({mesh});
    EXPECT_TRUE(scene.occluded(kAbove, kDown, 0, kInf));
    EXPECT_TRUE(scene.occluded(vec3(0.5f, -0.5f, 5), kDown, 0, kInf));
    EXPECT_FALSE(scene.occluded(vec3(3, 0, 5), kDown, 0, kInf));
    EXPECT_FALSE(scene.occluded(vec3(0, 0, -5), kDown, 0, kInf));  // below, looking away
    EXPECT_TRUE(scene.occluded(vec3(0, 0, -5), -kDown, 0, kInf));  // back faces block light too
}

// The segment is (tnear, tfar): a triangle at t = 5 blocks (0, 5.1) but neither (0, 4.9) — the light
// is in front of it — nor (5.5, ∞). Breaks if tfar or tnear is not handed to Embree (e.g. tfar = ∞
// always: everything beyond a point light would shadow it).
TEST(RayScene, OccludedOnlyWithinTheRange) {
    OwnedMesh mesh;
    addCounterClockwise(mesh, 0);
    const RayScene scene = sceneOf({mesh});
    EXPECT_TRUE(scene.occluded(kAbove, kDown, 0, 5.1f));
    EXPECT_FALSE(scene.occluded(kAbove, kDown, 0, 4.9f));
    EXPECT_FALSE(scene.occluded(kAbove, kDown, 5.5f, kInf));
    EXPECT_TRUE(scene.occluded(kAbove, kDown, 4.5f, 5.5f));
}

// tnear > tfar is an empty range, not a range to be put in order. Breaks if the query swaps them
// (std::min/std::max of the two), which would find the triangle at t = 5 in "(10, 1)".
TEST(RayScene, EmptyRangeIsNeverOccluded) {
    OwnedMesh mesh;
    addCounterClockwise(mesh, 0);
    const RayScene scene = sceneOf({mesh});
    EXPECT_FALSE(scene.occluded(kAbove, kDown, 10.0f, 1.0f));
    const Vec3x8 origin(kAbove), direction(kDown);
    EXPECT_EQ(scene.occluded8(origin, direction, splat(10.0f), splat(1.0f), 0xffu), 0u);
}

// A NaN or infinite origin, direction or range is never traced and reports "not occluded" (a dead lane
// of an eight-lane batch carries such values; shadowing it would darken nothing, tracing it would hand
// Embree a NaN). Breaks if the guard answers "occluded" for such rays, or the eight-lane query traces
// them (its answer for the NaN lanes would then be Embree's, whatever it is).
TEST(RayScene, NonFiniteRaysAreNeverTracedAndNeverOccluded) {
    OwnedMesh mesh;
    addCounterClockwise(mesh, 0);
    const RayScene scene = sceneOf({mesh});
    EXPECT_FALSE(scene.occluded(vec3(kNaN, 0, 5), kDown, 0, kInf));
    EXPECT_FALSE(scene.occluded(vec3(0, 0, kInf), kDown, 0, kInf));
    EXPECT_FALSE(scene.occluded(kAbove, vec3(0, kNaN, -1), 0, kInf));
    EXPECT_FALSE(scene.occluded(kAbove, vec3(0, 0, -kInf), 0, kInf));
    EXPECT_FALSE(scene.occluded(kAbove, kDown, kNaN, kInf));
    EXPECT_FALSE(scene.occluded(kAbove, kDown, 0, kNaN));
    EXPECT_FALSE(scene.occluded(kAbove, kDown, -kInf, kInf));

    // Lane 0 is a good ray (blocked); lanes 1–5 each carry one non-finite value.
    Vec3x8 origin(kAbove), direction(kDown);
    Float8 tnear = splat(0.0f), tfar = splat(kInf);
    origin.x[1] = kNaN;
    origin.z[2] = kInf;
    direction.y[3] = kNaN;
    tnear[4] = kNaN;
    tfar[5] = kNaN;
    EXPECT_EQ(scene.occluded8(origin, direction, tnear, tfar, 0b111111u), 1u);
}

// A uniform float in [lo, hi) from the generator's bits (the same on every standard library, unlike
// std::uniform_real_distribution).
float uniform(std::mt19937& random, float lo, float hi) {
    return lo + (hi - lo) * float(random() >> 8) * (1.0f / 16777216.0f);
}
vec3 uniformVec3(std::mt19937& random, float lo, float hi) {
    const float x = uniform(random, lo, hi), y = uniform(random, lo, hi);
    return {x, y, uniform(random, lo, hi)};
}

// Random triangles and random rays (fixed seed): the eight-lane query answers each traced lane as the
// one-lane query does, and never reports a lane outside the mask. Breaks if occluded8 ignores the lane
// mask (traces every lane), or reads lane i's answer from another lane, or drops tnear/tfar per lane.
TEST(RayScene, OccludedEightAgreesWithOneLaneByLane) {
    std::mt19937 random(20261130);
    OwnedMesh mesh;
    for (int t = 0; t < 60; ++t) {
        const vec3 centre = uniformVec3(random, -3, 3);
        addTriangle(mesh, centre + uniformVec3(random, -1.5f, 1.5f),
                    centre + uniformVec3(random, -1.5f, 1.5f), centre + uniformVec3(random, -1.5f, 1.5f));
    }
    const RayScene scene = sceneOf({mesh});
    int occludedCount = 0, freeCount = 0;
    for (int batch = 0; batch < 200; ++batch) {
        Vec3x8 origin, direction;
        Float8 tnear, tfar;
        for (int i = 0; i < 8; ++i) {
            // From anywhere around the triangles towards a point among them, so that about half are blocked.
            const vec3 o = uniformVec3(random, -6, 6), d = uniformVec3(random, -3, 3) - o;
            origin.x[i] = o.x, origin.y[i] = o.y, origin.z[i] = o.z;
            direction.x[i] = d.x, direction.y[i] = d.y, direction.z[i] = d.z;
            tnear[i] = uniform(random, 0, 0.3f);
            tfar[i] = (random() % 4 == 0) ? kInf : uniform(random, 0.3f, 1.5f);
        }
        const unsigned lanes = random() & 0xffu;
        const unsigned occludedLanes = scene.occluded8(origin, direction, tnear, tfar, lanes);
        EXPECT_EQ(occludedLanes & ~lanes, 0u) << "batch " << batch << ": a lane outside the mask";
        for (int i = 0; i < 8; ++i) {
            if (!((lanes >> i) & 1)) continue;
            const bool one =
                scene.occluded(vec3(origin.x[i], origin.y[i], origin.z[i]),
                               vec3(direction.x[i], direction.y[i], direction.z[i]), tnear[i], tfar[i]);
            EXPECT_EQ(bool((occludedLanes >> i) & 1), one) << "batch " << batch << " lane " << i;
            (one ? occludedCount : freeCount) += 1;
        }
    }
    // The rays are a mix of both answers (else the comparison says little).
    EXPECT_GT(occludedCount, 100);
    EXPECT_GT(freeCount, 100);
}

// Lanes outside the mask are not reported even when their rays would be blocked. Breaks if occluded8
// traces every lane (valid = −1 for all).
TEST(RayScene, OccludedEightReportsNoLaneOutsideTheMask) {
    OwnedMesh mesh;
    addCounterClockwise(mesh, 0);
    const RayScene scene = sceneOf({mesh});
    const Vec3x8 origin(kAbove), direction(kDown);  // every lane blocked
    EXPECT_EQ(scene.occluded8(origin, direction, splat(0.0f), splat(kInf), 0b10100101u), 0b10100101u);
    EXPECT_EQ(scene.occluded8(origin, direction, splat(0.0f), splat(kInf), 0u), 0u);
}

// ---- camera rays ----------------------------------------------------------------------------------

// Traces one ray (lane 0 of a packet) for the nearest opaque triangle.
RayHit nearest(const RayScene& scene, glm::dvec3 origin, glm::dvec3 direction, RayScene::Culling culling = {},
               double tnear = 0, double tfar = 1e30) {
    glm::dvec3 origins[8], directions[8];
    double tnears[8], tfars[8];
    RayHit hits[8];
    for (int i = 0; i < 8; ++i)
        origins[i] = origin, directions[i] = direction, tnears[i] = tnear, tfars[i] = tfar;
    scene.nearestOpaque8(origins, directions, tnears, tfars, 1u, culling, hits);
    for (int i = 1; i < 8; ++i)
        EXPECT_FALSE(hits[i].hit()) << "lane " << i << " was not traced";
    return hits[0];
}

// Mesh 0 is see-through (not in the opaque BVH); mesh 1 begins with two NaN triangles, then one at
// z = 0; mesh 2 holds one at z = −1, a NaN one and one at z = 1. The nearest hit from above is mesh 2's
// triangle 2 at t = 4; from z = 0.5, mesh 1's triangle 2 at t = 0.5; tnear beyond both finds mesh 2's
// triangle 0. Breaks if the hit reports Embree's geometry number (geometries are numbered per BVH, so
// mesh 1 is geometry 0) or its primitive number (the NaN triangles are skipped, so triangle 2 is
// primitive 0 or 1), or the farther triangle.
TEST(RayScene, NearestOpaqueNamesTheMeshAndItsOwnTriangleNumber) {
    std::vector<OwnedMesh> meshes(3);
    meshes[0].opaque = false;
    addCounterClockwise(meshes[0], 2);
    addTriangle(meshes[1], {kNaN, 0, 0}, {1, 0, 0}, {0, 1, 0});
    addTriangle(meshes[1], {0, 0, 0}, {kInf, 0, 0}, {0, 1, 0});
    addCounterClockwise(meshes[1], 0);
    addCounterClockwise(meshes[2], -1);
    addTriangle(meshes[2], {0, 0, 0}, {1, 0, 0}, {0, kNaN, 0});
    addCounterClockwise(meshes[2], 1);
    const RayScene scene = sceneOf(meshes);

    const RayHit fromAbove = nearest(scene, {0, 0, 5}, {0, 0, -1});
    EXPECT_EQ(fromAbove.mesh, 2u);
    EXPECT_EQ(fromAbove.triangle, 2u);
    EXPECT_FLOAT_EQ(fromAbove.t, 4.0f);

    const RayHit between = nearest(scene, {0, 0, 0.5}, {0, 0, -1});
    EXPECT_EQ(between.mesh, 1u);
    EXPECT_EQ(between.triangle, 2u);
    EXPECT_FLOAT_EQ(between.t, 0.5f);

    const RayHit beyond = nearest(scene, {0, 0, 5}, {0, 0, -1}, {}, 5.5);
    EXPECT_EQ(beyond.mesh, 2u);
    EXPECT_EQ(beyond.triangle, 0u);
    EXPECT_FLOAT_EQ(beyond.t, 6.0f);

    EXPECT_FALSE(nearest(scene, {3, 0, 5}, {0, 0, -1}).hit());
}

// Facing as OpenGL sees it: a triangle whose corners run counter-clockwise seen from the ray's origin is
// a front face. cullBack keeps it and drops the clockwise one; cullFront the reverse; no culling keeps
// both. Breaks if the sign of the facing test is flipped (n·d > 0 taken as front).
TEST(RayScene, CullingFollowsTheWindingSeenFromTheRayOrigin) {
    OwnedMesh counterClockwise, clockwise;
    addCounterClockwise(counterClockwise, 0);
    addClockwise(clockwise, 0);
    const RayScene ccwScene = sceneOf({counterClockwise});
    const RayScene cwScene = sceneOf({clockwise});
    const RayScene::Culling none{}, back{true, false}, front{false, true};
    EXPECT_TRUE(nearest(ccwScene, {0, 0, 5}, {0, 0, -1}, none).hit());
    EXPECT_TRUE(nearest(ccwScene, {0, 0, 5}, {0, 0, -1}, back).hit());
    EXPECT_FALSE(nearest(ccwScene, {0, 0, 5}, {0, 0, -1}, front).hit());
    EXPECT_TRUE(nearest(cwScene, {0, 0, 5}, {0, 0, -1}, none).hit());
    EXPECT_FALSE(nearest(cwScene, {0, 0, 5}, {0, 0, -1}, back).hit());
    EXPECT_TRUE(nearest(cwScene, {0, 0, 5}, {0, 0, -1}, front).hit());
    // Seen from below, the same triangle runs the other way round.
    EXPECT_FALSE(nearest(ccwScene, {0, 0, -5}, {0, 0, 1}, back).hit());
    EXPECT_TRUE(nearest(cwScene, {0, 0, -5}, {0, 0, 1}, back).hit());
    // A culled face lets the ray on to the next one: the clockwise one above a front face below.
    OwnedMesh stacked;
    addClockwise(stacked, 1);
    addCounterClockwise(stacked, 0);
    const RayScene stackedScene = sceneOf({stacked});
    const RayHit behind = nearest(stackedScene, {0, 0, 5}, {0, 0, -1}, back);
    EXPECT_EQ(behind.triangle, 1u);
    EXPECT_FLOAT_EQ(behind.t, 5.0f);
}

// Every see-through triangle on the ray, nearest first, with its mesh and own triangle number; the
// opaque ones are not listed (they are nearestOpaque8's). Breaks if the list is not sorted by t, or
// stops at the first hit (the filter accepting it instead of rejecting it to go on).
TEST(RayScene, AllTransparentListsEveryTriangleNearestFirst) {
    std::vector<OwnedMesh> meshes(3);
    meshes[0].opaque = false;
    addCounterClockwise(meshes[0], -2);  // t = 7
    addCounterClockwise(meshes[0], 1);   // t = 4
    meshes[1].opaque = true;
    addCounterClockwise(meshes[1], 0);  // opaque: not listed
    meshes[2].opaque = false;
    addTriangle(meshes[2], {kNaN, 0, 0}, {1, 0, 0}, {0, 1, 0});  // skipped: numbering goes on
    addCounterClockwise(meshes[2], 3);                           // t = 2
    addCounterClockwise(meshes[2], -1);                          // t = 6
    const RayScene scene = sceneOf(meshes);
    EXPECT_TRUE(scene.hasTransparent());

    std::vector<RayHit> hits;
    scene.allTransparent({0, 0, 5}, {0, 0, -1}, 0, 1e30, {}, hits);
    ASSERT_EQ(hits.size(), 4u);
    const std::uint32_t mesh[] = {2, 0, 2, 0}, triangle[] = {1, 1, 2, 0};
    const float t[] = {2, 4, 6, 7};
    for (std::size_t i = 0; i < hits.size(); ++i) {
        SCOPED_TRACE(i);
        EXPECT_EQ(hits[i].mesh, mesh[i]);
        EXPECT_EQ(hits[i].triangle, triangle[i]);
        EXPECT_FLOAT_EQ(hits[i].t, t[i]);
    }
    // The range bounds the list; culling drops faces as for nearestOpaque8.
    scene.allTransparent({0, 0, 5}, {0, 0, -1}, 3, 6.5, {}, hits);
    ASSERT_EQ(hits.size(), 2u);
    EXPECT_FLOAT_EQ(hits[0].t, 4.0f);
    EXPECT_FLOAT_EQ(hits[1].t, 6.0f);
    scene.allTransparent({0, 0, 5}, {0, 0, -1}, 0, 1e30, {false, true}, hits);
    EXPECT_TRUE(hits.empty());
}

// A ray through the shared edge of two see-through triangles of one surface (a square cut along its
// diagonal) meets the surface once: it is listed once, or a pane would be blended twice along its
// diagonal. Robust mode reports both triangles there. Breaks if the duplicate is not removed.
TEST(RayScene, AllTransparentListsASharedEdgeOnce) {
    OwnedMesh square;
    square.opaque = false;
    square.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    square.indices = {0, 1, 2, 0, 2, 3};
    const RayScene scene = sceneOf({square});
    std::vector<RayHit> hits;
    for (const float s : {-0.5f, 0.0f, 0.25f, 0.7f}) {
        SCOPED_TRACE(s);
        scene.allTransparent({s, s, 5}, {0, 0, -1}, 0, 1e30, {}, hits);  // on the diagonal
        EXPECT_EQ(hits.size(), 1u);
    }
    scene.allTransparent({0, 0, 5}, {0.1, 0.1, -1}, 0, 1e30, {}, hits);  // slanted, through the centre
    EXPECT_EQ(hits.size(), 1u);
    scene.allTransparent({0.5, -0.5, 5}, {0, 0, -1}, 0, 1e30, {}, hits);  // inside one triangle
    ASSERT_EQ(hits.size(), 1u);
    EXPECT_EQ(hits[0].triangle, 0u);
}

// A fan of six triangles around one vertex of a tilted plane: a ray through the vertex lists the fan
// once. Two coincident panes of different meshes (two objects) are two surfaces: both listed. Breaks if
// the duplicates around a vertex are kept, or if coincident hits of different meshes are merged.
TEST(RayScene, AllTransparentListsASharedVertexOnceAndEachMesh) {
    OwnedMesh fan;
    fan.opaque = false;
    const vec3 centre(0.3f, -0.2f, 0.1f), u = normalize(vec3(1, 0, 0.4f)), v = normalize(vec3(0, 1, -0.3f));
    fan.positions.push_back(centre);
    for (int k = 0; k < 6; ++k) {
        const float angle = float(k) * 1.04719755f;
        fan.positions.push_back(centre + std::cos(angle) * u + std::sin(angle) * v);
        fan.indices.insert(fan.indices.end(), {0, std::uint32_t(1 + k), std::uint32_t(1 + (k + 1) % 6)});
    }
    const RayScene scene = sceneOf({fan, fan});
    std::vector<RayHit> hits;
    const glm::dvec3 eye(1, 2, 6);
    scene.allTransparent(eye, glm::dvec3(centre) - eye, 0, 1e30, {}, hits);
    ASSERT_EQ(hits.size(), 2u);
    EXPECT_EQ(hits[0].mesh, 0u);
    EXPECT_EQ(hits[1].mesh, 1u);
}

// A scene without see-through meshes answers allTransparent with nothing.
TEST(RayScene, AllTransparentOfAnOpaqueSceneIsEmpty) {
    OwnedMesh mesh;
    addCounterClockwise(mesh, 0);
    const RayScene scene = sceneOf({mesh});
    EXPECT_FALSE(scene.hasTransparent());
    std::vector<RayHit> hits = {RayHit{0, 0, 1}};
    scene.allTransparent({0, 0, 5}, {0, 0, -1}, 0, 1e30, {}, hits);
    EXPECT_TRUE(hits.empty());
}

// ---- what Embree is handed ------------------------------------------------------------------------

// Triangles with a NaN or infinite corner and triangles with a corner index beyond the positions are
// counted and left out; the good ones are traced. Breaks if a kind is not counted, or is handed over
// (an index out of range would read past the positions).
TEST(RayScene, StatsCountTrianglesLeftOut) {
    OwnedMesh mesh;
    addTriangle(mesh, {kNaN, 0, 0}, {1, 0, 0}, {0, 1, 0});
    addTriangle(mesh, {0, 0, 0}, {1, -kInf, 0}, {0, 1, 0});
    addCounterClockwise(mesh, 0);
    mesh.indices.insert(mesh.indices.end(), {6, 7, 1000});
    mesh.indices.insert(mesh.indices.end(),
                        {1000, 0, 1});  // 0 is the NaN corner: counted once, as out of range
    const RayScene scene = sceneOf({mesh});
    EXPECT_EQ(scene.stats().triangles, 5u);
    EXPECT_EQ(scene.stats().nonFiniteSkipped, 2u);
    EXPECT_EQ(scene.stats().indexOutOfRange, 2u);
    EXPECT_TRUE(scene.occluded(kAbove, kDown, 0, kInf));
    EXPECT_FALSE(scene.occluded(vec3(3, 0, 5), kDown, 0, kInf));
}

// A mesh of NaN positions only (a model scaled past the float range, say) builds: all of it is left out,
// and queries go on working, for the other meshes too. Breaks if a mesh with no usable triangle hands
// Embree an empty buffer (an Embree error and no BVH) or its NaN positions.
TEST(RayScene, MeshOfOnlyNaNPositionsBuildsAndIsLeftOut) {
    OwnedMesh nan;
    for (int t = 0; t < 4; ++t)
        addTriangle(nan, vec3(kNaN), vec3(kNaN), vec3(kNaN));
    {
        const RayScene alone = sceneOf({nan});
        EXPECT_EQ(alone.stats().triangles, 4u);
        EXPECT_EQ(alone.stats().nonFiniteSkipped, 4u);
        EXPECT_FALSE(alone.occluded(kAbove, kDown, 0, kInf));
        EXPECT_FALSE(nearest(alone, {0, 0, 5}, {0, 0, -1}).hit());
    }
    OwnedMesh good;
    addCounterClockwise(good, 0);
    const RayScene both = sceneOf({nan, good});
    EXPECT_EQ(both.stats().nonFiniteSkipped, 4u);
    EXPECT_TRUE(both.occluded(kAbove, kDown, 0, kInf));
    const RayHit hit = nearest(both, {0, 0, 5}, {0, 0, -1});
    EXPECT_EQ(hit.mesh, 1u);
    EXPECT_EQ(hit.triangle, 0u);
}

constexpr float kEmbreeTestInfinity = std::numeric_limits<float>::infinity();

// A ray whose origin or direction is finite but beyond Embree's ±1.844e18 (the dead lanes of a batch of
// fragments hold such garbage) is never handed over: Debian's Embree asserts on it and aborts the process.
// It reports "not occluded"; the other lanes of its packet are traced as usual.
TEST(RaySceneTest, RaysBeyondEmbreesRangeAreNotTraced) {
    const std::vector<vec3> positions = {{-1.0f, -1.0f, -1.0f}, {1.0f, -1.0f, -1.0f}, {0.0f, 1.0f, -1.0f}};
    const std::vector<std::uint32_t> indices = {0, 1, 2};
    const std::vector<RayMesh> meshes = {{positions, indices, true}};
    const RayScene scene(meshes);

    EXPECT_TRUE(scene.occluded({0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 0.0f, kEmbreeTestInfinity));
    EXPECT_FALSE(scene.occluded({-2.8e22f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 0.0f, kEmbreeTestInfinity));
    EXPECT_FALSE(scene.occluded({0.0f, 0.0f, 0.0f}, {1e20f, 0.0f, -1.0f}, 0.0f, kEmbreeTestInfinity));

    Vec3x8 origin(vec3(0.0f)), direction(vec3(0.0f, 0.0f, -1.0f));
    origin.x[1] = -2.8e22f;  // lane 1: the origin
    origin.y[2] = -1.0e29f;  // lane 2: the origin
    direction.x[3] = 1e20f;  // lane 3: the direction
    EXPECT_EQ(scene.occluded8(origin, direction, splat(0.0f), splat(kEmbreeTestInfinity), 0xffu), 0xf1u);
}

}  // namespace
}  // namespace facet
