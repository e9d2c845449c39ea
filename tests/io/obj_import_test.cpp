// OBJ import tests: hand-computed small files written to a temp folder (welding, area-weighted
// normals, crease angles, fan triangulation, errors with their line), then every bundled model as a
// property check.

#include "io/obj_import.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "support/bundled_models.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

using testing_support::kSharedModels;

// Each test gets its own folder (support/temp_folder.h), so tests may run in parallel (ctest -j)
// without sharing files.
class ObjImport : public ::testing::Test {
  protected:
    // Writes `text` byte for byte (no newline translation), creating folders as needed.
    fs::path write(const std::string& name, const std::string& text) { return folder_.write(name, text); }

    // The InputError message loadObj throws for `path`, or "" if it loads.
    static std::string errorOf(const fs::path& path) {
        try {
            loadObj(path);
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    }

    testing_support::TempFolder folder_;
    const fs::path dir_ = folder_.path();
};

void expectVec3(glm::vec3 actual, glm::vec3 expected, float tolerance = 1e-6f) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// The position triple of triangle t.
std::vector<glm::vec3> triangle(const Mesh& mesh, std::size_t t) {
    return {mesh.vertices[mesh.indices[3 * t]].position, mesh.vertices[mesh.indices[3 * t + 1]].position,
            mesh.vertices[mesh.indices[3 * t + 2]].position};
}

// A unit cube centred on the origin, six outward (counter-clockwise) quads.
const std::string kCubePositions =
    "v -0.5 -0.5 -0.5\n"
    "v  0.5 -0.5 -0.5\n"
    "v  0.5  0.5 -0.5\n"
    "v -0.5  0.5 -0.5\n"
    "v -0.5 -0.5  0.5\n"
    "v  0.5 -0.5  0.5\n"
    "v  0.5  0.5  0.5\n"
    "v -0.5  0.5  0.5\n";
const std::string kCubeFaces =
    "f 1 4 3 2\n"   // -z
    "f 5 6 7 8\n"   // +z
    "f 1 2 6 5\n"   // -y
    "f 4 8 7 3\n"   // +y
    "f 1 5 8 4\n"   // -x
    "f 2 3 7 6\n";  // +x

// ---- Geometry -------------------------------------------------------------------------------------

// Crease angle 180 smooths across every edge: the welded mesh, as before crease angles.
const ObjOptions kSmoothAll{180.0f};

TEST_F(ObjImport, CubeWithoutNormalsWeldsToEightVerticesWithCornerNormals) {
    const Mesh mesh = loadObj(write("cube.obj", kCubePositions + kCubeFaces), kSmoothAll);

    EXPECT_EQ(mesh.stats.facesRead, 6u);
    EXPECT_EQ(mesh.stats.trianglesKept, 12u);
    EXPECT_EQ(mesh.stats.degenerateSkipped, 0u);
    ASSERT_EQ(mesh.indices.size(), 36u);
    ASSERT_EQ(mesh.vertices.size(), 8u);
    EXPECT_EQ(mesh.stats.normalsComputed, 8u);
    EXPECT_EQ(mesh.stats.creaseSplits, 0u);
    EXPECT_FALSE(mesh.hasTexcoords);
    // Each corner touches three equal faces, whichever fan triangles it is in: (±1, ±1, ±1) / √3.
    for (const MeshVertex& v : mesh.vertices) {
        expectVec3(v.normal, glm::sign(v.position) / std::sqrt(3.0f));
        EXPECT_EQ(v.uv, glm::vec2(0.0f));
    }
    // Winding kept: every triangle faces away from the centre.
    for (std::size_t t = 0; t < 12; ++t) {
        const auto p = triangle(mesh, t);
        EXPECT_GT(glm::dot(glm::cross(p[1] - p[0], p[2] - p[0]), p[0] + p[1] + p[2]), 0.0f)
            << "triangle " << t;
    }
    expectVec3(mesh.boundsMin, glm::vec3(-0.5f));
    expectVec3(mesh.boundsMax, glm::vec3(0.5f));
    ASSERT_EQ(mesh.parts.size(), 1u);
    EXPECT_EQ(mesh.parts[0].firstIndex, 0u);
    EXPECT_EQ(mesh.parts[0].indexCount, 36u);
    ASSERT_EQ(mesh.materials.size(), 1u);
    EXPECT_EQ(mesh.materials[0].name, "default");
    EXPECT_EQ(mesh.materials[0].diffuse, glm::vec3(0.8f));
    EXPECT_TRUE(mesh.warnings.empty());
}

TEST_F(ObjImport, CubeWithFaceNormalsHasTwentyFourVertices) {
    // Normals deliberately not unit length: the importer normalises them.
    const std::string normals = "vn 0 0 -2\nvn 0 0 3\nvn 0 -1 0\nvn 0 0.5 0\nvn -4 0 0\nvn 1 0 0\n";
    const std::string faces =
        "f 1//1 4//1 3//1 2//1\n"
        "f 5//2 6//2 7//2 8//2\n"
        "f 1//3 2//3 6//3 5//3\n"
        "f 4//4 8//4 7//4 3//4\n"
        "f 1//5 5//5 8//5 4//5\n"
        "f 2//6 3//6 7//6 6//6\n";
    const Mesh mesh = loadObj(write("cube.obj", kCubePositions + normals + faces));

    EXPECT_EQ(mesh.stats.trianglesKept, 12u);
    EXPECT_EQ(mesh.vertices.size(), 24u);
    EXPECT_EQ(mesh.stats.normalsComputed, 0u);
    for (std::size_t t = 0; t < 12; ++t) {
        const auto p = triangle(mesh, t);
        const glm::vec3 faceNormal = glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
        for (int c = 0; c < 3; ++c)
            expectVec3(mesh.vertices[mesh.indices[3 * t + c]].normal, faceNormal);
    }
}

// Two triangles meeting only at the origin: one in the z = 0 plane with area 2 (cross product
// (0,0,4)), one in the x = 0 plane with area 1/2 (cross product (1,0,0)). The origin's normal is
// (1,0,4)/√17, not the unweighted (1,0,1)/√2 (at 180°: the faces meet at 90°).
const std::string kTwoFaces =
    "v 0 0 0\n"
    "v 2 0 0\n"
    "v 0 2 0\n"
    "v 0 1 0\n"
    "v 0 0 1\n";

TEST_F(ObjImport, NormalsAreAreaWeighted) {
    const Mesh mesh = loadObj(write("two.obj", kTwoFaces + "f 1 2 3\nf 1 4 5\n"), kSmoothAll);

    ASSERT_EQ(mesh.vertices.size(), 5u);
    EXPECT_EQ(mesh.stats.normalsComputed, 5u);
    std::map<std::vector<float>, glm::vec3> normalAt;
    for (const MeshVertex& v : mesh.vertices)
        normalAt[{v.position.x, v.position.y, v.position.z}] = v.normal;
    expectVec3(normalAt[{0, 0, 0}], glm::vec3(1, 0, 4) / std::sqrt(17.0f));
    expectVec3(normalAt[{2, 0, 0}], glm::vec3(0, 0, 1));
    expectVec3(normalAt[{0, 2, 0}], glm::vec3(0, 0, 1));
    expectVec3(normalAt[{0, 1, 0}], glm::vec3(1, 0, 0));
    expectVec3(normalAt[{0, 0, 1}], glm::vec3(1, 0, 0));
}

// The three weightings at the origin, where a 2×1 quad in the z = 0 plane (written from (2,0,0), so
// that the origin is in only its second fan triangle) meets a triangle in the x = 0 plane at 90°:
//   polygon-area:  the quad's vector area (0,0,4) + the triangle's (1,0,0)        → (1,0,4)/√17
//   triangle-area: the fan triangle (2,0,0),(0,1,0),O's cross product (0,0,2) + (1,0,0) → (1,0,2)/√5
//   angle:         (0,0,1)·π/2 + (1,0,0)·π/2                                       → (1,0,1)/√2
const std::string kQuadAndTriangle = kTwoFaces + "v 2 1 0\n" + "f 2 6 4 1\nf 1 4 5\n";

glm::vec3 normalAtOrigin(const Mesh& mesh) {
    for (const MeshVertex& v : mesh.vertices)
        if (v.position == glm::vec3(0.0f)) return v.normal;
    ADD_FAILURE() << "no vertex at the origin";
    return glm::vec3(0.0f);
}

TEST_F(ObjImport, VertexNormalsWeighFacesByPolygonAreaTriangleAreaOrAngle) {
    const fs::path path = write("quad.obj", kQuadAndTriangle);
    const auto normalWith = [&](VertexNormals normals) {
        return normalAtOrigin(loadObj(path, ObjOptions{.creaseAngleDegrees = 180.0f, .normals = normals}));
    };
    expectVec3(normalWith(VertexNormals::PolygonArea), glm::vec3(1, 0, 4) / std::sqrt(17.0f));
    expectVec3(normalWith(VertexNormals::TriangleArea), glm::vec3(1, 0, 2) / std::sqrt(5.0f));
    expectVec3(normalWith(VertexNormals::Angle), glm::vec3(1, 0, 1) / std::sqrt(2.0f));
    // The default is today's polygon-area.
    expectVec3(normalAtOrigin(loadObj(path, kSmoothAll)), glm::vec3(1, 0, 4) / std::sqrt(17.0f));
}

// The same quad as two triangles, split along either diagonal: the origin is in both triangles of the
// split along (0,0,0)–(2,1,0), in one of the other. Angle weighting sees the quad's corner angle π/2
// either way (atan(1/2) + (π/2 − atan(1/2))); triangle-area weighting sees the area of the triangles
// at the origin, (0,0,4) or (0,0,2).
TEST_F(ObjImport, AngleWeightedNormalsDoNotDependOnTheTriangulation) {
    const fs::path throughOrigin = write(
        "a.obj", kQuadAndTriangle.substr(0, kQuadAndTriangle.find('f')) + "f 1 2 6\nf 1 6 4\nf 1 4 5\n");
    const fs::path across = write(
        "b.obj", kQuadAndTriangle.substr(0, kQuadAndTriangle.find('f')) + "f 1 2 4\nf 2 6 4\nf 1 4 5\n");
    const auto normalWith = [&](const fs::path& path, VertexNormals normals) {
        return normalAtOrigin(loadObj(path, ObjOptions{.creaseAngleDegrees = 180.0f, .normals = normals}));
    };
    expectVec3(normalWith(throughOrigin, VertexNormals::Angle), glm::vec3(1, 0, 1) / std::sqrt(2.0f));
    expectVec3(normalWith(across, VertexNormals::Angle), glm::vec3(1, 0, 1) / std::sqrt(2.0f));
    expectVec3(normalWith(throughOrigin, VertexNormals::TriangleArea), glm::vec3(1, 0, 4) / std::sqrt(17.0f));
    expectVec3(normalWith(across, VertexNormals::TriangleArea), glm::vec3(1, 0, 2) / std::sqrt(5.0f));
}

// A reflex corner counts its interior angle, 2π − θ: an L-shaped hexagon in z = 0 whose corner at the
// origin is 270°, beside a triangle in x = 0 with a 90° corner there: (1,0,0)·π/2 + (0,0,1)·3π/2.
TEST_F(ObjImport, AngleWeightedNormalsCountAReflexCornersInteriorAngle) {
    const Mesh mesh = loadObj(write("l.obj",
                                    "v 0 0 0\nv 0 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nv -1 0 0\nv 0 0 1\n"
                                    "f 2 3 4 5 6 1\nf 1 7 2\n"),
                              ObjOptions{.creaseAngleDegrees = 180.0f, .normals = VertexNormals::Angle});
    expectVec3(normalAtOrigin(mesh), glm::vec3(1, 0, 3) / std::sqrt(10.0f));
}

TEST_F(ObjImport, CornersSharingAPositionShareTheSmoothNormal) {
    // The origin has texcoord 1 in one face and 2 in the other: two vertices, one normal.
    const Mesh mesh = loadObj(
        write("two.obj", kTwoFaces + "vt 0.25 0.5\nvt 0.75 1\nf 1/1 2/1 3/1\nf 1/2 4/2 5/2\n"), kSmoothAll);

    ASSERT_EQ(mesh.vertices.size(), 6u);
    EXPECT_TRUE(mesh.hasTexcoords);
    int atOrigin = 0;
    for (const MeshVertex& v : mesh.vertices) {
        if (v.position != glm::vec3(0.0f)) continue;
        ++atOrigin;
        expectVec3(v.normal, glm::vec3(1, 0, 4) / std::sqrt(17.0f));
        EXPECT_TRUE(v.uv == glm::vec2(0.25f, 0.5f) || v.uv == glm::vec2(0.75f, 1.0f));
    }
    EXPECT_EQ(atOrigin, 2);
}

TEST_F(ObjImport, ZeroLengthFileNormalIsComputedInstead) {
    const Mesh mesh = loadObj(write("z.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1\n"));

    ASSERT_EQ(mesh.vertices.size(), 3u);
    EXPECT_EQ(mesh.stats.normalsComputed, 3u);
    for (const MeshVertex& v : mesh.vertices)
        expectVec3(v.normal, glm::vec3(0, 0, 1));
}

TEST_F(ObjImport, CancellingFacesFallBackToTheFaceNormal) {
    // The same triangle twice, once per side: at 180° the sums cancel to zero, so no NaN but a face
    // normal (below 180° the two sides are not smoothed together at all).
    const Mesh mesh =
        loadObj(write("sheet.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 2\n"), kSmoothAll);

    EXPECT_EQ(mesh.stats.trianglesKept, 2u);
    ASSERT_EQ(mesh.vertices.size(), 3u);
    for (const MeshVertex& v : mesh.vertices)
        EXPECT_EQ(v.normal, glm::vec3(0, 0, 1));  // the first triangle's

    const Mesh sides = loadObj(write("sheet.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 2\n"));
    ASSERT_EQ(sides.vertices.size(), 6u);
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(sides.vertices[sides.indices[c]].normal, glm::vec3(0, 0, 1));
        EXPECT_EQ(sides.vertices[sides.indices[3 + c]].normal, glm::vec3(0, 0, -1));
    }
}

// ---- Crease angle ---------------------------------------------------------------------------------

std::string objNumber(double value) {
    std::ostringstream out;
    out << std::setprecision(9) << value;
    return out.str();
}

std::string objVertex(glm::dvec3 p) {
    return "v " + objNumber(p.x) + " " + objNumber(p.y) + " " + objNumber(p.z) + "\n";
}

// The unit normal of triangle t, from its vertices' positions.
glm::vec3 faceNormal(const Mesh& mesh, std::size_t t) {
    const auto p = triangle(mesh, t);
    return glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
}

// How many vertices sit at `position`.
std::size_t verticesAt(const Mesh& mesh, glm::vec3 position) {
    return std::size_t(std::count_if(mesh.vertices.begin(), mesh.vertices.end(),
                                     [&](const MeshVertex& v) { return v.position == position; }));
}

TEST_F(ObjImport, CreaseAngleKeepsTheCubeEdgesHard) {
    const fs::path path = write("cube.obj", kCubePositions + kCubeFaces);
    for (const float crease : {60.0f, 0.0f, 89.0f}) {
        SCOPED_TRACE(crease);
        const Mesh mesh = loadObj(path, ObjOptions{crease});

        EXPECT_EQ(mesh.stats.trianglesKept, 12u);
        ASSERT_EQ(mesh.vertices.size(), 24u);  // each corner once per face: 8 welded + 16 split off
        EXPECT_EQ(mesh.stats.normalsComputed, 24u);
        EXPECT_EQ(mesh.stats.creaseSplits, 16u);
        for (std::size_t t = 0; t < 12; ++t) {
            const glm::vec3 n = faceNormal(mesh, t);
            EXPECT_EQ(glm::abs(n.x) + glm::abs(n.y) + glm::abs(n.z), 1.0f) << "triangle " << t;
            for (int c = 0; c < 3; ++c)
                EXPECT_EQ(mesh.vertices[mesh.indices[3 * t + c]].normal, n) << "triangle " << t;
        }
        for (const MeshVertex& v : mesh.vertices)
            EXPECT_EQ(verticesAt(mesh, v.position), 3u);
    }
    // From 90° on, the three faces at a corner are smoothed together.
    const Mesh smooth = loadObj(path, ObjOptions{90.5f});
    EXPECT_EQ(smooth.vertices.size(), 8u);
    EXPECT_EQ(smooth.stats.creaseSplits, 0u);
    for (const MeshVertex& v : smooth.vertices)
        expectVec3(v.normal, glm::sign(v.position) / std::sqrt(3.0f));
}

// Two triangles of area 1/2 sharing the edge (0,0,0)-(1,0,0), folded so that their normals, (0,0,1)
// and (0, sin 45°, cos 45°), are 45° apart.
const std::string kFold =
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 0.5 1 0\n"
    "v 0.5 -0.707106781 0.707106781\n"
    "f 1 2 3\n"
    "f 2 1 4\n";

TEST_F(ObjImport, FoldIsSmoothOnlyWithinTheCreaseAngle) {
    const fs::path path = write("fold.obj", kFold);
    const glm::vec3 flat(0, 0, 1), folded = glm::normalize(glm::vec3(0, 1, 1));

    const Mesh hard = loadObj(path, ObjOptions{44.0f});
    ASSERT_EQ(hard.vertices.size(), 6u);
    EXPECT_EQ(hard.stats.creaseSplits, 2u);
    for (int c = 0; c < 3; ++c) {
        expectVec3(hard.vertices[hard.indices[c]].normal, flat);
        expectVec3(hard.vertices[hard.indices[3 + c]].normal, folded);
    }

    const Mesh smooth = loadObj(path, ObjOptions{46.0f});
    ASSERT_EQ(smooth.vertices.size(), 4u);
    EXPECT_EQ(smooth.stats.creaseSplits, 0u);
    EXPECT_EQ(smooth.indices[0], smooth.indices[4]);  // the shared edge is welded, both ends
    EXPECT_EQ(smooth.indices[1], smooth.indices[3]);
    const glm::vec3 bisector(0, std::sin(glm::radians(22.5f)), std::cos(glm::radians(22.5f)));
    expectVec3(smooth.vertices[smooth.indices[0]].normal, bisector);
    expectVec3(smooth.vertices[smooth.indices[1]].normal, bisector);
    expectVec3(smooth.vertices[smooth.indices[2]].normal, flat);  // the far corners keep their face's
    expectVec3(smooth.vertices[smooth.indices[5]].normal, folded);
}

// A closed cylinder of radius 1 and height 1 around the z axis: `segments` side quads, caps fanned
// from their centres.
std::string cylinder(int segments) {
    std::string obj;
    for (int z = 0; z < 2; ++z) {
        for (int i = 0; i < segments; ++i) {
            const double angle = 2.0 * std::numbers::pi * i / segments;
            obj += objVertex({std::cos(angle), std::sin(angle), z});
        }
    }
    obj += "v 0 0 0\nv 0 0 1\n";
    const int bottomCentre = 2 * segments + 1, topCentre = 2 * segments + 2;
    for (int i = 0; i < segments; ++i) {
        const int b0 = i + 1, b1 = (i + 1) % segments + 1, t0 = b0 + segments, t1 = b1 + segments;
        obj += "f " + std::to_string(b0) + " " + std::to_string(b1) + " " + std::to_string(t1) + " " +
               std::to_string(t0) + "\n";
        obj += "f " + std::to_string(topCentre) + " " + std::to_string(t0) + " " + std::to_string(t1) + "\n";
        obj +=
            "f " + std::to_string(bottomCentre) + " " + std::to_string(b1) + " " + std::to_string(b0) + "\n";
    }
    return obj;
}

TEST_F(ObjImport, CylinderSideIsSmoothAndItsCapEdgesHard) {
    const int segments = 32;
    const fs::path path = write("cylinder.obj", cylinder(segments));

    const Mesh mesh = loadObj(path);  // the default 60°; neighbouring side quads meet at 11.25°
    EXPECT_EQ(mesh.stats.trianglesKept, 4u * segments);
    // Every rim position twice (side and cap), the cap centres once.
    ASSERT_EQ(mesh.vertices.size(), 4u * segments + 2);
    EXPECT_EQ(mesh.stats.creaseSplits, 2u * segments);
    for (std::size_t t = 0; t < mesh.indices.size() / 3; ++t) {
        const bool cap = std::abs(faceNormal(mesh, t).z) > 0.5f;
        for (int c = 0; c < 3; ++c) {
            const MeshVertex& v = mesh.vertices[mesh.indices[3 * t + c]];
            if (cap)  // flat, up to the rim
                expectVec3(v.normal, glm::vec3(0, 0, v.position.z > 0.5f ? 1 : -1));
            else  // radial: smooth round the side
                expectVec3(v.normal, glm::vec3(v.position.x, v.position.y, 0), 1e-5f);
        }
    }

    const Mesh welded = loadObj(path, kSmoothAll);
    EXPECT_EQ(welded.vertices.size(), 2u * segments + 2);
    EXPECT_EQ(welded.stats.creaseSplits, 0u);
}

TEST_F(ObjImport, FinelyFacetedSphereKeepsOneVertexPerPosition) {
    // A latitude-longitude sphere: quads, triangle fans at the poles; neighbouring faces meet at 15°.
    const int rings = 12, segments = 24;
    std::string obj = "v 0 0 1\nv 0 0 -1\n";
    for (int r = 1; r < rings; ++r) {
        for (int s = 0; s < segments; ++s) {
            const double theta = std::numbers::pi * r / rings, phi = 2.0 * std::numbers::pi * s / segments;
            obj += objVertex(
                {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)});
        }
    }
    const auto at = [&](int r, int s) { return std::to_string(3 + (r - 1) * segments + s % segments); };
    for (int s = 0; s < segments; ++s) {
        obj += "f 1 " + at(1, s) + " " + at(1, s + 1) + "\n";
        obj += "f 2 " + at(rings - 1, s + 1) + " " + at(rings - 1, s) + "\n";
        for (int r = 1; r + 1 < rings; ++r)
            obj += "f " + at(r, s) + " " + at(r + 1, s) + " " + at(r + 1, s + 1) + " " + at(r, s + 1) + "\n";
    }
    const Mesh mesh = loadObj(write("sphere.obj", obj));

    EXPECT_EQ(mesh.vertices.size(), 2u + (rings - 1) * segments);
    EXPECT_EQ(mesh.stats.creaseSplits, 0u);
    for (const MeshVertex& v : mesh.vertices)
        EXPECT_GT(glm::dot(v.normal, v.position), 0.99f);  // area weighting leans a little near the poles
}

TEST_F(ObjImport, CreaseAngleNeverChangesFileNormals) {
    // Every corner of the cube names the same odd normal: nothing is computed, whatever the angle.
    const std::string faces =
        "vn 1 2 3\n"
        "f 1//1 4//1 3//1 2//1\n"
        "f 5//1 6//1 7//1 8//1\n"
        "f 1//1 2//1 6//1 5//1\n"
        "f 4//1 8//1 7//1 3//1\n"
        "f 1//1 5//1 8//1 4//1\n"
        "f 2//1 3//1 7//1 6//1\n";
    const fs::path path = write("cube.obj", kCubePositions + faces);
    for (const float crease : {0.0f, 60.0f, 180.0f}) {
        SCOPED_TRACE(crease);
        const Mesh mesh = loadObj(path, ObjOptions{crease});
        EXPECT_EQ(mesh.vertices.size(), 8u);
        EXPECT_EQ(mesh.stats.normalsComputed, 0u);
        EXPECT_EQ(mesh.stats.creaseSplits, 0u);
        for (const MeshVertex& v : mesh.vertices)
            expectVec3(v.normal, glm::normalize(glm::vec3(1, 2, 3)));
    }

    // Only the -z face has (deliberately wrong) file normals: they stay, while that face still
    // counts in the computed normals around it when it is within the angle (at 180°).
    const std::string mixed =
        "vn 0 1 0\nf 1//1 4//1 3//1 2//1\n" + kCubeFaces.substr(kCubeFaces.find('\n') + 1);
    const fs::path mixedPath = write("mixed.obj", kCubePositions + mixed);
    const Mesh hard = loadObj(mixedPath);
    EXPECT_EQ(hard.vertices.size(), 24u);  // 4 with the file normal, 5 faces × 4 computed
    EXPECT_EQ(hard.stats.normalsComputed, 20u);
    for (std::size_t t = 0; t < 12; ++t) {
        const glm::vec3 expected = t < 2 ? glm::vec3(0, 1, 0) : faceNormal(hard, t);
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(hard.vertices[hard.indices[3 * t + c]].normal, expected) << "triangle " << t;
    }
    const Mesh smooth = loadObj(mixedPath, kSmoothAll);
    EXPECT_EQ(smooth.vertices.size(), 12u);  // 4 with the file normal, 8 computed
    for (std::size_t t = 0; t < 12; ++t) {
        for (int c = 0; c < 3; ++c) {
            const MeshVertex& v = smooth.vertices[smooth.indices[3 * t + c]];
            expectVec3(v.normal, t < 2 ? glm::vec3(0, 1, 0) : glm::sign(v.position) / std::sqrt(3.0f));
        }
    }
}

TEST_F(ObjImport, CreaseAngleZeroStillWeldsCoplanarFaces) {
    // A flat 2×2 grid of quads (8 triangles), tilted so that rounding makes its face normals differ in
    // their last bits: at 0° they still share vertices. Then a ninth triangle folded up by 10°.
    const glm::dvec3 origin(0.1, 0.2, 0.3), u(1.0, 0.3, 0.7), v(-0.2, 1.0, 0.45);
    std::string obj;
    for (int j = 0; j < 3; ++j) {
        for (int i = 0; i < 3; ++i)
            obj += objVertex(origin + double(i) * u + double(j) * v);
    }
    for (int j = 0; j < 2; ++j) {
        for (int i = 0; i < 2; ++i) {
            const int a = 1 + j * 3 + i, b = a + 1, c = a + 4, d = a + 3;
            obj += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(c) + "\n";
            obj += "f " + std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(d) + "\n";
        }
    }
    const glm::dvec3 n = glm::normalize(glm::cross(u, v));
    const glm::dvec3 away = -glm::normalize(glm::cross(n, u));  // in the plane, off the j = 0 edge
    const double tilt = glm::radians(10.0);
    obj += objVertex(origin + 0.5 * u + std::cos(tilt) * away + std::sin(tilt) * n);
    obj += "f 2 1 10\n";
    const fs::path path = write("flat.obj", obj);

    const Mesh mesh = loadObj(path, ObjOptions{0.0f});
    EXPECT_EQ(mesh.stats.trianglesKept, 9u);
    EXPECT_EQ(mesh.vertices.size(), 12u);  // 9 on the grid, the fold's 3 of its own
    EXPECT_EQ(mesh.stats.creaseSplits, 2u);
    for (std::size_t t = 0; t < 8; ++t) {
        for (int c = 0; c < 3; ++c)
            expectVec3(mesh.vertices[mesh.indices[3 * t + c]].normal, glm::vec3(n), 1e-6f);
    }
    const glm::vec3 fold = faceNormal(mesh, 8);
    EXPECT_NEAR(glm::degrees(std::acos(glm::dot(fold, glm::vec3(n)))), 10.0f, 1e-3f);
    for (int c = 0; c < 3; ++c)
        expectVec3(mesh.vertices[mesh.indices[24 + c]].normal, fold, 1e-6f);

    EXPECT_EQ(loadObj(path, ObjOptions{10.5f}).vertices.size(), 10u);
}

TEST_F(ObjImport, CrowdedPositionIsClusteredGreedily) {
    // A cone of 90 triangles (more than the 64 compared pairwise): the apex normals lean 45°, and two
    // are within 60° when their directions round the axis differ by at most 90°. In file order, face 0
    // (at 2°) starts a cluster, faces up to 90° join it; face 23 (94°) starts one, faces up to 182° join;
    // face 46 (186°) starts one, faces up to 270° join; from 274° on they are within 90° of face 0 and
    // join the first cluster. So the apex has three vertices at 60°, where the exact rule gives 90.
    const int segments = 90;
    std::string obj = "v 0 0 1\n";
    for (int i = 0; i < segments; ++i) {
        const double angle = 2.0 * std::numbers::pi * i / segments;
        obj += objVertex({std::cos(angle), std::sin(angle), 0.0});
    }
    for (int i = 0; i < segments; ++i)
        obj += "f 1 " + std::to_string(i + 2) + " " + std::to_string((i + 1) % segments + 2) + "\n";
    const fs::path path = write("cone.obj", obj);

    const Mesh mesh = loadObj(path);
    EXPECT_EQ(verticesAt(mesh, glm::vec3(0, 0, 1)), 3u);
    EXPECT_EQ(mesh.vertices.size(), segments + 3u);  // the rim is smooth (neighbours 4° apart)
    for (std::size_t t = 0; t < std::size_t(segments); ++t) {
        const std::size_t cluster = t <= 22 ? 0 : t <= 45 ? 1 : t <= 67 ? 2 : 0;
        EXPECT_EQ(mesh.indices[3 * t], mesh.indices[3 * (cluster * 23)]) << "triangle " << t;
        EXPECT_GT(glm::dot(mesh.vertices[mesh.indices[3 * t]].normal, faceNormal(mesh, t)), 0.5f);
    }

    const Mesh smooth = loadObj(path, kSmoothAll);
    EXPECT_EQ(smooth.vertices.size(), segments + 1u);
    expectVec3(smooth.vertices[smooth.indices[0]].normal, glm::vec3(0, 0, 1), 1e-5f);
}

TEST_F(ObjImport, CreaseAngleOutsideZeroTo180IsInvalid) {
    const fs::path path = write("cube.obj", kCubePositions + kCubeFaces);
    for (const float crease : {-1.0f, -0.0001f, 180.0001f, 360.0f, std::numeric_limits<float>::infinity(),
                               std::numeric_limits<float>::quiet_NaN()}) {
        EXPECT_THROW(loadObj(path, ObjOptions{crease}), std::invalid_argument) << crease;
    }
    EXPECT_NO_THROW(loadObj(path, ObjOptions{0.0f}));
    EXPECT_NO_THROW(loadObj(path, ObjOptions{180.0f}));
    // Checked before the file is even read.
    EXPECT_THROW(loadObj(dir_ / "missing.obj", ObjOptions{-5.0f}), std::invalid_argument);
}

// ---- Triangulation and indices -------------------------------------------------------------------

TEST_F(ObjImport, PolygonsFanTriangulateFromTheFirstCorner) {
    // A rhombus whose 0-2 diagonal is the longer one: tinyobjloader's own triangulation would cut
    // along 1-3; a fan from corner 0 cuts along 0-2. Then a pentagon: three fan triangles.
    const Mesh mesh = loadObj(write("fan.obj",
                                    "v -2 0 0\nv 0 -1 0\nv 2 0 0\nv 0 1 0\n"
                                    "v 10 0 0\nv 11 0 0\nv 12 1 0\nv 11 2 0\nv 10 1 0\n"
                                    "f 1 2 3 4\nf 5 6 7 8 9\n"));

    ASSERT_EQ(mesh.stats.trianglesKept, 5u);
    const std::vector<std::vector<glm::vec3>> expected = {
        {{-2, 0, 0}, {0, -1, 0}, {2, 0, 0}},  {{-2, 0, 0}, {2, 0, 0}, {0, 1, 0}},
        {{10, 0, 0}, {11, 0, 0}, {12, 1, 0}}, {{10, 0, 0}, {12, 1, 0}, {11, 2, 0}},
        {{10, 0, 0}, {11, 2, 0}, {10, 1, 0}},
    };
    for (std::size_t t = 0; t < expected.size(); ++t)
        EXPECT_EQ(triangle(mesh, t), expected[t]) << "triangle " << t;
}

TEST_F(ObjImport, NegativeIndicesCountBackFromTheirStatement) {
    const Mesh mesh = loadObj(write("rel.obj",
                                    "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5 0.5\nvn 0 0 1\n"
                                    "f -3/-1/-1 -2/-1/-1 -1/-1/-1\n"
                                    "v 5 0 0\nv 6 0 0\nv 5 1 0\n"
                                    "f -3 -2 -1\n"));

    ASSERT_EQ(mesh.stats.trianglesKept, 2u);
    EXPECT_EQ(triangle(mesh, 0), (std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));
    EXPECT_EQ(triangle(mesh, 1), (std::vector<glm::vec3>{{5, 0, 0}, {6, 0, 0}, {5, 1, 0}}));
    EXPECT_EQ(mesh.vertices[mesh.indices[0]].uv, glm::vec2(0.5f));
    EXPECT_EQ(mesh.stats.normalsComputed, 3u);  // only the second face's
}

TEST_F(ObjImport, PositiveIndicesMayReferForward) {
    const Mesh mesh = loadObj(write("fwd.obj", "f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"));
    EXPECT_EQ(mesh.stats.trianglesKept, 1u);
}

TEST_F(ObjImport, HugeFiniteCoordinatesLoad) {
    const Mesh mesh = loadObj(write("huge.obj", "v -1e30 0 0\nv 1e30 0 0\nv 0 1e30 0\nf 1 2 3\n"));

    EXPECT_EQ(mesh.boundsMin, glm::vec3(-1e30f, 0.0f, 0.0f));
    EXPECT_EQ(mesh.boundsMax, glm::vec3(1e30f, 1e30f, 0.0f));
    for (const MeshVertex& v : mesh.vertices)
        expectVec3(v.normal, glm::vec3(0, 0, 1));
}

// Skin weights are not used, and never reach tinyobjloader, which converts a joint id to int unchecked
// (undefined behaviour for 1e999 or 3e9; the fuzz build's seed tests/fuzz/regressions/obj replays it
// under UBSan). Breaks if the importer stops blanking `vw` lines or blanks the line after one.
TEST_F(ObjImport, SkinWeightsAreIgnored) {
    const Mesh mesh =
        loadObj(write("weights.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvw 0 1e999 1\nvw 1 3e9 1\nf 1 2 3\n"));
    EXPECT_EQ(mesh.stats.trianglesKept, 1u);
    EXPECT_EQ(mesh.boundsMax, glm::vec3(1.0f, 1.0f, 0.0f));
}

TEST_F(ObjImport, BoundsCoverOnlyVerticesOfKeptTriangles) {
    const Mesh mesh =
        loadObj(write("b.obj", "v 100 100 100\nv 0 0 0\nv 1 0 0\nv 0 2 0\nv -50 0 0\nf 2 3 4\n"));

    EXPECT_EQ(mesh.vertices.size(), 3u);
    EXPECT_EQ(mesh.boundsMin, glm::vec3(0.0f));
    EXPECT_EQ(mesh.boundsMax, glm::vec3(1.0f, 2.0f, 0.0f));
}

TEST_F(ObjImport, DegenerateTrianglesAndShortFacesAreSkippedAndCounted) {
    const fs::path path = write("degenerate.obj",
                                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\n"
                                "f 1 2 3\n"      // line 5: kept
                                "f 1 1 2\n"      // line 6: repeated corner
                                "f 1 2 4\n"      // line 7: collinear, zero area
                                "f 1 2\n"        // line 8: two corners
                                "f 1 2 3 3\n");  // line 9: second fan triangle repeats corner 3
    const Mesh mesh = loadObj(path);

    EXPECT_EQ(mesh.stats.facesRead, 5u);
    EXPECT_EQ(mesh.stats.trianglesKept, 2u);
    EXPECT_EQ(mesh.stats.degenerateSkipped, 4u);
    EXPECT_EQ(mesh.warnings,
              std::vector<std::string>{path.string() + ":8: 1 face(s) with fewer than 3 corners skipped"});
}

TEST_F(ObjImport, CrlfFileMatchesLf) {
    std::string crlf;
    for (char c : kCubePositions + kCubeFaces)
        crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    const Mesh mesh = loadObj(write("crlf.obj", crlf));
    EXPECT_EQ(mesh.stats.trianglesKept, 12u);
    EXPECT_EQ(mesh.vertices.size(), 24u);  // split at the cube's edges by the default 60°

    // Lines still count right: CRLF, lone CR (old Mac) and LF each end one line.
    const fs::path bad = write("bad.obj", "v 0 0 0\r\nv 1 0 0\rv 0 1 0\n\r\nf 1 2 7\r\n");
    EXPECT_EQ(errorOf(bad), bad.string() + ":5: face index 7 is out of range (the file has 3 vertices)");
}

TEST_F(ObjImport, LineContinuationsAndTrailingCommentsAreUnderstood) {
    const fs::path path = write("cont.obj",
                                "v 0 0 0 # origin\n"
                                "v 1 0 \\\n"
                                "  0\n"
                                "v 0 1 0\n"
                                "f 1 2 \\\n"
                                "  3 # the only face\n");
    const Mesh mesh = loadObj(path);
    EXPECT_EQ(mesh.stats.trianglesKept, 1u);
    EXPECT_EQ(triangle(mesh, 0), (std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));

    // An error in a continued statement names its first line; later lines keep their numbers.
    const fs::path bad = write("bad.obj", "v 0 0 \\\n 0\nv 1 0 0\nv 0 1 0\nf 1 \\\n 2 \\\n 0\nf 1 2 3\n");
    EXPECT_EQ(errorOf(bad), bad.string() + ":5: face index 0 is invalid (OBJ indices start at 1)");
    const fs::path nan = write("nan.obj", "v 0 0 \\\n 0\nv 1 0 0\nv nan 1 0\n");
    EXPECT_EQ(errorOf(nan), nan.string() + ":4: vertex coordinate 'nan' is not a finite number");
}

// ---- Errors ---------------------------------------------------------------------------------------

TEST_F(ObjImport, MissingFileDirectoryAndEmptyFile) {
    const fs::path missing = dir_ / "nope.obj";
    EXPECT_EQ(errorOf(missing), missing.string() + ": no such file");
    EXPECT_EQ(errorOf(dir_), dir_.string() + ": is a directory, not a file");
    const fs::path empty = write("empty.obj", "");
    EXPECT_EQ(errorOf(empty), empty.string() + ": no triangles to draw (the file has no faces)");
    const fs::path binary = write("binary.obj", std::string("v 0 0 0\n\0\x01\x02", 11));
    EXPECT_EQ(errorOf(binary), binary.string() + ": contains NUL bytes: not an OBJ text file");
}

TEST_F(ObjImport, UnreadableFile) {
    if (::geteuid() == 0) GTEST_SKIP() << "root reads any file";
    const fs::path path = write("locked.obj", "v 0 0 0\n");
    fs::permissions(path, fs::perms::none);
    EXPECT_EQ(errorOf(path), path.string() + ": cannot open (Permission denied)");
}

TEST_F(ObjImport, FaceIndexErrorsNameFileAndLine) {
    const std::string header =
        "# three vertices\n\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n";  // lines 1-7
    struct Case {
        std::string face;
        std::string message;
    };
    const std::vector<Case> cases = {
        {"f 1 2 9", ":8: face index 9 is out of range (the file has 3 vertices)"},
        {"f 0 1 2", ":8: face index 0 is invalid (OBJ indices start at 1)"},
        {"f -4 -3 -2", ":8: face index -4 is out of range (3 vertices are defined before this line)"},
        // Texture coordinate and normal indices out of range are dropped with a warning
        // (AttributeIndicesOutOfRangeAreDroppedWithAWarning); 0 is still refused.
        {"f 1/2 2/1 3/1", ""},
        {"f 1//-2 2//1 3//1", ""},
        {"f 1/0/1 2/1/1 3/1/1", ":8: face texture coordinate index 0 is invalid (OBJ indices start at 1)"},
        {"f 1 2 99999999999999999999", ":8: face index '99999999999999999999' is out of range"},
        {"f 1 2 -9223372036854775808",
         ":8: face index -9223372036854775808 is out of range (3 vertices are defined before this line)"},
        {"f 1 2 x", ":8: malformed corner 'x' (expected v, v/vt, v//vn or v/vt/vn with integer indices)"},
        {"f 1 2 3/1/1/1",
         ":8: malformed corner '3/1/1/1' (expected v, v/vt, v//vn or v/vt/vn with integer indices)"},
        {"f 1 2 3/", ":8: malformed corner '3/' (expected v, v/vt, v//vn or v/vt/vn with integer indices)"},
        {"l 1 0", ":8: index 0 is invalid (OBJ indices start at 1)"},
        {"l 1/0 2/1", ":8: index 0 is invalid (OBJ indices start at 1)"},
    };
    for (const Case& c : cases) {
        const fs::path path = write("index.obj", header + c.face + "\nf 1 2 3\n");
        EXPECT_EQ(errorOf(path), c.message.empty() ? "" : path.string() + c.message) << c.face;
    }
}

TEST_F(ObjImport, BadNumbersNameFileAndLine) {
    struct Case {
        std::string statement;
        std::string message;
    };
    const std::vector<Case> cases = {
        {"v nan 0 0", ":2: vertex coordinate 'nan' is not a finite number"},
        {"v 0 -inf 0", ":2: vertex coordinate '-inf' is not a finite number"},
        {"v 0 0 1e39", ":2: vertex coordinate '1e39' is not a finite number"},
        {"v 0 0 1e400", ":2: vertex coordinate '1e400' is not a finite number"},
        {"v 1.#IND 0 0", ":2: vertex coordinate '1.#IND' is not a finite number"},
        {"v 1 abc 3", ":2: vertex coordinate 'abc' is not a number"},
        {"v 1 2,5 3",
         ":2: vertex coordinate '2,5' has a decimal comma; OBJ numbers are written with a point, like '2.5'"},
        {"v 1 2e 3", ":2: vertex coordinate '2e' is not a number"},  // tinyobjloader reads no number either
        {"v 1 . 3", ":2: vertex coordinate '.' is not a number"},
        {"v 1 1e39x 3", ":2: vertex coordinate '1e39x' is not a finite number"},
        {"v 1 2", ":2: a vertex needs 3 coordinates (x y z), found 2"},
        {"vn 0 nan 1", ":2: normal component 'nan' is not a finite number"},
        {"vn 0 1", ":2: a normal needs 3 components (x y z), found 2"},
        {"vt inf 0", ":2: texture coordinate 'inf' is not a finite number"},
        {"vt", ""},  // "vt" without a blank is no statement at all; the file loads
    };
    for (const Case& c : cases) {
        const fs::path path =
            write("num.obj", "v 0 0 0\n" + c.statement + "\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n");
        EXPECT_EQ(errorOf(path), c.message.empty() ? "" : path.string() + c.message) << c.statement;
    }
    // Accepted spellings: a leading '+' or '.', exponents, underflow to zero.
    const fs::path ok = write("ok.obj", "v +1 .5 -.7e+2\nv 1e-400 0 0\nv 0 1E2 0\nf 1 2 3\n");
    EXPECT_EQ(errorOf(ok), "");
}

// A coordinate with stray characters after it is read as its number, as tinyobjloader and Blender read
// it: one warning for the file, at the first, with the count.
TEST_F(ObjImport, NumbersWithStrayCharactersAreReadAsTheNumberWithOneWarning) {
    const fs::path one = write("one.obj", "v 0 0 0\nv 1.5, 0 0\nv 0 1 0\nf 1 2 3\n");
    const Mesh mesh = loadObj(one);
    EXPECT_EQ(mesh.warnings,
              std::vector<std::string>{one.string() +
                                       R"(:2: "1.5," read as 1.5 (stray characters after the number))"});
    EXPECT_EQ(mesh.boundsMax, glm::vec3(1.5f, 1.0f, 0.0f));

    std::string text;
    for (int i = 0; i < 3000; ++i)
        text += "v " + std::to_string(i) + ".0000c 0 0\nv " + std::to_string(i) + " 1 0\nv " +
                std::to_string(i) + " 0 1)\nf -3 -2 -1\n";
    const fs::path many = write("many.obj", text);
    const Mesh manyMesh = loadObj(many);
    EXPECT_EQ(
        manyMesh.warnings,
        std::vector<std::string>{many.string() + R"(:1: "0.0000c" read as 0 (stray characters after the )"
                                                 "number; 6000 numbers in this file have them, the first is "
                                                 "here)"});
    EXPECT_EQ(manyMesh.boundsMax, glm::vec3(2999.0f, 1.0f, 1.0f));

    // vt and vn too; an exponent is part of the number ("1e2x" is 100), "0x1" is 0 as in tinyobjloader.
    const fs::path other =
        write("other.obj", "v 0 0 0\nv 1e2x 0 0\nv 0 1 0\nvt 0x1 0\nvn 0 0 1;\nf 1/1/1 2/1/1 3/1/1\n");
    const Mesh otherMesh = loadObj(other);
    EXPECT_EQ(otherMesh.warnings,
              std::vector<std::string>{other.string() +
                                       R"(:2: "1e2x" read as 100 (stray characters after the )"
                                       "number; 3 numbers in this file have them, the first is here)"});
    EXPECT_EQ(otherMesh.boundsMax, glm::vec3(100.0f, 1.0f, 0.0f));
}

// A clean file (every bundled model below is one too) warns of nothing.
TEST_F(ObjImport, CleanNumbersGiveNoWarning) {
    const fs::path path =
        write("clean.obj", "v +1 .5 -.7e+2\nv 1e-400 0 0\nv 0 1E2 0\nvt 0.5 1.\nf 1/1 2/1 3/1\n");
    EXPECT_TRUE(loadObj(path).warnings.empty());
}

// A texture coordinate or normal index out of range leaves the corner without it (tinyobjloader's
// catmark_torus_creases0.obj and smoothing-group-two-squares.obj name normals they do not have).
TEST_F(ObjImport, AttributeIndicesOutOfRangeAreDroppedWithAWarning) {
    const fs::path path =
        write("n.obj",
              "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1/1 2/1/1 3/1/1\nf 1/2 2/1 3/1\nf 1//-3 3//1 2//1\n");
    const Mesh mesh = loadObj(path);
    EXPECT_EQ(
        mesh.warnings,
        (std::vector<std::string>{
            path.string() + ":6: face texture coordinate index 2 is out of range (the file has 1 texture "
                            "coordinates); the corner is drawn without a texture coordinate",
            path.string() + ":5: face normal index 1 is out of range (the file has 0 normals); the corner "
                            "gets a computed normal (6 such corners in this file)"}));
    EXPECT_EQ(mesh.stats.trianglesKept, 3u);
    for (const MeshVertex& v : mesh.vertices)
        EXPECT_NEAR(std::abs(v.normal.z), 1.0f, 1e-6f);
}

TEST_F(ObjImport, FilesWithoutTrianglesAreRejected) {
    const fs::path points = write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\n");
    EXPECT_EQ(errorOf(points), points.string() + ": no triangles to draw (the file has no faces)");
    const fs::path flat = write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 2\n");
    EXPECT_EQ(
        errorOf(flat),
        flat.string() + ": no triangles to draw (all 2 faces are degenerate or have fewer than 3 corners)");
}

TEST_F(ObjImport, TooManyCornersIsAnError) {
    std::string text, face = "f";
    for (int i = 0; i < 256; ++i) {
        const float a = float(i) / 256.0f * 6.2831853f;
        text += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
        face += ' ';
        face += std::to_string(i + 1);
    }
    const fs::path path = write("big.obj", text + face + "\n");
    EXPECT_EQ(errorOf(path), path.string() + ":257: a face with 256 corners; at most 255 are supported");
}

// ---- Materials ------------------------------------------------------------------------------------

TEST_F(ObjImport, MissingMtlWarnsAndUsesTheDefaultMaterial) {
    const fs::path path =
        write("m.obj", "mtllib nothere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n");
    const Mesh mesh = loadObj(path);

    const std::string file = path.string();
    EXPECT_EQ(
        mesh.warnings,
        (std::vector<std::string>{
            file + ":1: material library 'nothere.mtl': no such file; its materials fall back to the default",
            file + ":5: unknown material 'red'; using the default material"}));
    ASSERT_EQ(mesh.materials.size(), 1u);
    EXPECT_EQ(mesh.materials[0].name, "default");
    EXPECT_EQ(mesh.materials[0].diffuse, glm::vec3(0.8f));
    EXPECT_EQ(mesh.materials[0].opacity, 1.0f);
}

TEST_F(ObjImport, MaterialFieldsAndTrOnlyOpacity) {
    write("glass.mtl",
          "newmtl glass\n"
          "Ka 0.1 0.2 0.3\n"
          "Kd 0.4 0.5 0.6\n"
          "Ks 0.7 0.8 0.9\n"
          "Ns 64\n"
          "Ke 1 0.5 0.25\n"
          "Tr 0.25\n");
    const Mesh mesh =
        loadObj(write("g.obj", "mtllib glass.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl glass\nf 1 2 3\n"));

    EXPECT_TRUE(mesh.warnings.empty());
    ASSERT_EQ(mesh.materials.size(), 1u);
    const Material& m = mesh.materials[0];
    EXPECT_EQ(m.name, "glass");
    EXPECT_EQ(m.ambient, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(m.diffuse, glm::vec3(0.4f, 0.5f, 0.6f));
    EXPECT_EQ(m.specular, glm::vec3(0.7f, 0.8f, 0.9f));
    EXPECT_EQ(m.shininess, 64.0f);
    EXPECT_EQ(m.emission, glm::vec3(1.0f, 0.5f, 0.25f));
    EXPECT_FLOAT_EQ(m.opacity, 0.75f);
    EXPECT_TRUE(m.diffuseTexture.empty());
}

// tinyobjloader reads an MTL number it cannot parse as 0 and 1e39 as infinity; each numeric statement
// is checked first, with its line. A material is optional to the image: a statement whose numbers
// cannot be used is left out with a warning, one out of range is clamped with a warning.
TEST_F(ObjImport, MtlNumbersThatCannotBeUsedWarnAndAreLeftOutOrClamped) {
    struct Case {
        std::string line;
        std::string warning;      // after "m.mtl:3: "; empty for none
        glm::vec3 diffuse{0.5f};  // line 2's Kd, unless line 3 changes it
        float shininess = 1.0f;   // tinyobjloader's default
        float opacity = 1.0f;
        std::string modelWarning{};  // after "m.obj: ", the model's own; empty for none
    };
    const std::string drawnOpaque =
        "every material of the model is fully transparent (d 0, or Tr 1), which "
        "would draw nothing; drawing it opaque (some exporters write Tr as the "
        "opacity)";
    const Case cases[] = {
        {"Kd nan 1 1", R"(Kd expects three finite numbers (got "nan 1 1"); the statement is ignored)",
         glm::vec3(0.5f)},
        {"Kd 1 1", R"(Kd expects three finite numbers (got "1 1"); the statement is ignored)",
         glm::vec3(0.5f)},
        {"Ks 0 inf 0", R"(Ks expects three finite numbers (got "0 inf 0"); the statement is ignored)"},
        {"Kd 0.5 1e39 0.5",
         R"(Kd expects three finite numbers (got "0.5 1e39 0.5"); the statement is ignored)",
         glm::vec3(0.5f)},
        {"Kd 0,5 0,5 0,5", R"(Kd expects three finite numbers (got "0,5 0,5 0,5"); the statement is ignored)",
         glm::vec3(0.5f)},
        {"Ke 3e38 0 0",
         R"(Ke must be from 0 to 1000000 in each component (got "3e38 0 0"); read as 1000000 0 0)"},
        {"Kd -0.5 0.25 0",
         R"(Kd must be from 0 to 1000000 in each component (got "-0.5 0.25 0"); read as 0 0.25 0)",
         glm::vec3(0.0f, 0.25f, 0.0f)},
        {"Tf 0 0 2e6",
         R"(Tf must be from 0 to 1000000 in each component (got "0 0 2e6"); read as 0 0 1000000)"},
        {"Ns -5", R"(Ns must not be negative (got "-5"); read as 0)", glm::vec3(0.5f), 0.0f},
        {"Ns nan", R"(Ns expects a finite number (got "nan"); the statement is ignored)"},
        {"Ni inf", R"(Ni expects a finite number (got "inf"); the statement is ignored)"},
        {"d 1.5", R"(d must be from 0 to 1 (got "1.5"); read as 1)"},
        {"Tr -0.25", R"(Tr must be from 0 to 1 (got "-0.25"); read as 0)"},
        // Clamped to Tr 1, opacity 0: the model's only material would draw nothing, so it is drawn opaque.
        {"Tr 1.25", R"(Tr must be from 0 to 1 (got "1.25"); read as 1)", glm::vec3(0.5f), 1.0f, 1.0f,
         drawnOpaque},
        {"d", ""},  // no blank after the keyword: not a statement, as for LoadMtl
        {"d  ", R"(d expects a finite number (got ""); the statement is ignored)"},
        {"illum two", R"(illum expects a whole number from 0 to 10 (got "two"); the statement is ignored)"},
        {"illum 2.5", R"(illum expects a whole number from 0 to 10 (got "2.5"); the statement is ignored)"},
        {"Pr nan", R"(Pr expects a finite number (got "nan"); the statement is ignored)"},
        // What LoadMtl ignores after the numbers it reads is not checked (cube-mcguire has "Tr 0  illum 2").
        {"Tr 0  illum 2", ""},
        {"Ka 0.63 0.065 0.05 # Red", ""},
        {"Ke 1000000 0 0", ""},
        {"Ns 0", "", glm::vec3(0.5f), 0.0f},
        // The MTL format: "If only r is specified, then g, and b are assumed to be equal to r".
        {"Kd 0.25", "", glm::vec3(0.25f)},
        {"Kd 0.25 # grey", "", glm::vec3(0.25f)},
    };
    const fs::path obj = write("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
    const std::string mtl = (dir_ / "m.mtl").string();
    for (const Case& c : cases) {
        SCOPED_TRACE(c.line);
        write("m.mtl", "newmtl a\nKd 0.5 0.5 0.5\n" + c.line + "\n");
        const Mesh mesh = loadObj(obj);
        std::vector<std::string> expected;
        if (!c.warning.empty()) expected.push_back(mtl + ":3: " + c.warning);
        if (!c.modelWarning.empty()) expected.push_back(obj.string() + ": " + c.modelWarning);
        EXPECT_EQ(mesh.warnings, expected);
        ASSERT_EQ(mesh.materials.size(), 1u);
        EXPECT_EQ(mesh.materials[0].diffuse, c.diffuse);
        EXPECT_EQ(mesh.materials[0].shininess, c.shininess);
        EXPECT_EQ(mesh.materials[0].opacity, c.opacity);
    }
}

// The car of McGuire's archive has "Ka 0.0000 0.0000 0.0000c": a number followed by stray characters is
// read as the number, as tinyobjloader and Blender read it, with one warning naming the file and line.
TEST_F(ObjImport, MtlNumbersWithStrayCharactersAreReadAsTheNumber) {
    const fs::path obj = write("car.obj", "mtllib car.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n");
    write("car.mtl", "newmtl a\nKa 0.0000 0.0000 0.0000c\nKd 0.25 1.5, 2.0)\nNs 12.5abc\nd 0.5x  illum 2\n");
    const Mesh mesh = loadObj(obj);
    EXPECT_EQ(mesh.warnings, std::vector<std::string>{
                                 (dir_ / "car.mtl").string() +
                                 R"(:2: "0.0000c" read as 0 (stray characters after the number; 5 numbers )"
                                 "in this file have them, the first is here)"});
    ASSERT_EQ(mesh.materials.size(), 1u);
    const Material& m = mesh.materials[0];
    EXPECT_EQ(m.ambient, glm::vec3(0.0f));
    EXPECT_EQ(m.diffuse, glm::vec3(0.25f, 1.5f, 2.0f));
    EXPECT_EQ(m.shininess, 12.5f);
    EXPECT_EQ(m.opacity, 0.5f);

    // One such number: the warning has no count.
    write("car.mtl", "newmtl a\nKd 0.5 0.5 0.5\nKa 0.0000 0.0000 0.0000c\n");
    EXPECT_EQ(loadObj(obj).warnings,
              std::vector<std::string>{(dir_ / "car.mtl").string() +
                                       R"(:3: "0.0000c" read as 0 (stray characters after the number))"});
}

// Exporters write MTL file names with blanks ("mtllib My Model.mtl"), which the format splits into
// several names: when the names are not files but the whole is, the whole is read, with a warning.
// Names that are truly missing are still each warned of. (Breaks caught: LibraryReader not trying the
// joined name — the material stays the default; the held warnings not dropped — two extra warnings.)
TEST_F(ObjImport, AnMtlFileNameWithBlanksIsReadAsOneName) {
    const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
    write("My Model.mtl", "newmtl red\nKd 1 0 0\n");
    const fs::path obj = write("spaces.obj", "mtllib My Model.mtl\n" + triangle);
    const Mesh mesh = loadObj(obj);
    EXPECT_EQ(mesh.warnings,
              std::vector<std::string>{obj.string() + ":1: material library 'My Model.mtl' read as one file "
                                                      "name with blanks (mtllib separates file names by "
                                                      "blanks)"});
    ASSERT_EQ(mesh.materials.size(), 1u);
    EXPECT_FALSE(mesh.materials[0].fallback);
    EXPECT_EQ(mesh.materials[0].diffuse, glm::vec3(1.0f, 0.0f, 0.0f));

    const fs::path missing = write("missing.obj", "mtllib Other Model.mtl\n" + triangle);
    const std::vector<std::string> warnings = loadObj(missing).warnings;
    ASSERT_EQ(warnings.size(), 3u);
    EXPECT_NE(warnings[0].find(":1: material library 'Other': "), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[1].find(":1: material library 'Model.mtl': "), std::string::npos) << warnings[1];
    EXPECT_NE(warnings[2].find(":5: unknown material 'red'"), std::string::npos) << warnings[2];
}

// A model whose every material is fully transparent (`d 0`, or `Tr 1`, which some exporters write for
// opaque) would render as an empty image reported as success: it is drawn opaque, with a warning. A
// fully transparent part among visible ones may be meant: it stays invisible and is named. (Breaks
// caught: the opaque fallback removed — opacity stays 0; the check made per part — the glass pane below
// turns opaque.)
TEST_F(ObjImport, AModelWhoseEveryMaterialIsFullyTransparentIsDrawnOpaque) {
    const std::string quad = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
    const fs::path obj =
        write("clear.obj", "mtllib clear.mtl\n" + quad + "usemtl a\nf 1 2 3\nusemtl b\nf 2 4 3\n");
    write("clear.mtl", "newmtl a\nKd 1 0 0\nd 0\nnewmtl b\nKd 0 1 0\nTr 1.000000\n");
    const Mesh all = loadObj(obj);
    EXPECT_EQ(
        all.warnings,
        std::vector<std::string>{
            obj.string() + ": every material of the model is fully transparent (d 0, or Tr 1), which "
                           "would draw nothing; drawing it opaque (some exporters write Tr as the opacity)"});
    ASSERT_EQ(all.materials.size(), 2u);
    EXPECT_EQ(all.materials[0].opacity, 1.0f);
    EXPECT_EQ(all.materials[1].opacity, 1.0f);

    write("clear.mtl", "newmtl a\nKd 1 0 0\nnewmtl b\nKd 0 1 0\nd 0\n");
    const Mesh pane = loadObj(obj);
    EXPECT_EQ(pane.warnings,
              std::vector<std::string>{obj.string() + ": material 'b' is fully transparent (d 0, or Tr 1): 1 "
                                                      "triangle draws nothing"});
    ASSERT_EQ(pane.materials.size(), 2u);
    EXPECT_EQ(pane.materials[0].opacity, 1.0f);
    EXPECT_EQ(pane.materials[1].opacity, 0.0f);
}

// A file with thousands of defects says so in a few lines: statements left out or clamped are warned of
// three times, then counted; numbers with stray characters are one warning with their count.
TEST_F(ObjImport, ManyMtlDefectsGiveAFewWarnings) {
    std::string mtl;
    for (int i = 0; i < 1000; ++i)
        mtl += "newmtl m" + std::to_string(i) + "\nKd 0.5c 0.5 0.5\nNs -1\n";
    write("many.mtl", mtl);
    const fs::path obj =
        write("many.obj", "mtllib many.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m7\nf 1 2 3\n");
    const std::string file = (dir_ / "many.mtl").string();
    const Mesh mesh = loadObj(obj);
    EXPECT_EQ(mesh.warnings,
              (std::vector<std::string>{
                  file + R"(:3: Ns must not be negative (got "-1"); read as 0)",
                  file + R"(:6: Ns must not be negative (got "-1"); read as 0)",
                  file + R"(:9: Ns must not be negative (got "-1"); read as 0)",
                  file + ": 997 more statements with numbers ignored or clamped, like those above",
                  file + R"(:2: "0.5c" read as 0.5 (stray characters after the number; 1000 numbers in this )"
                         "file have them, the first is here)"}));
    ASSERT_EQ(mesh.materials.size(), 1u);
    EXPECT_EQ(mesh.materials[0].diffuse, glm::vec3(0.5f));
}

// A value quoted from an MTL file is cut short and its raw bytes escaped.
TEST_F(ObjImport, MtlValuesInMessagesAreShortAndPrintable) {
    const fs::path obj = write("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    write("m.mtl", "newmtl a\nNs \xFF\x1B[31m" + std::string(100000, '9') + "x\n");
    EXPECT_EQ(loadObj(obj).warnings,
              std::vector<std::string>{(dir_ / "m.mtl").string() +
                                       R"(:2: Ns expects a finite number (got "\xFF\x1B[31m)" +
                                       std::string(34, '9') + "…\"); the statement is ignored"});
}

TEST_F(ObjImport, DWinsOverTrInEitherOrder) {
    // Material.001 has d 0.75 then Tr 0.5; Material.002 the other way round. d wins in both.
    const fs::path path = kSharedModels / "tinyobjloader-tests" / "tr-and-d-issue-43.obj";
    const Mesh mesh = loadObj(path);

    ASSERT_EQ(mesh.materials.size(), 2u);
    EXPECT_EQ(mesh.materials[0].name, "Material.001");
    EXPECT_EQ(mesh.materials[1].name, "Material.002");
    EXPECT_FLOAT_EQ(mesh.materials[0].opacity, 0.75f);
    EXPECT_FLOAT_EQ(mesh.materials[1].opacity, 0.75f);
    const std::string mtl = (kSharedModels / "tinyobjloader-tests" / "tr-and-d-issue-43.mtl").string();
    EXPECT_EQ(
        mesh.warnings,
        (std::vector<std::string>{
            mtl + ":6: material 'Material.001' sets opacity twice, d 0.75 and Tr 0.5 (opacity 0.5); d wins",
            mtl +
                ":13: material 'Material.002' sets opacity twice, d 0.75 and Tr 0.5 (opacity 0.5); d wins"}));
}

TEST_F(ObjImport, AgreeingDAndTrDoNotWarn) {
    write("m.mtl", "newmtl a\nd 1\nTr 0\nnewmtl b\nTr 0.2\nd 0.8\n");
    const Mesh mesh = loadObj(write("m.obj",
                                    "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n"
                                    "usemtl b\nf 1 3 2\n"));
    EXPECT_TRUE(mesh.warnings.empty());
    ASSERT_EQ(mesh.materials.size(), 2u);
    EXPECT_FLOAT_EQ(mesh.materials[0].opacity, 1.0f);
    EXPECT_FLOAT_EQ(mesh.materials[1].opacity, 0.8f);
}

TEST_F(ObjImport, TexturesResolveAgainstTheMtlFolder) {
    write("lib/tex.png", "not really a png");
    write("lib/m.mtl",
          "newmtl found\nKd 1 1 1\nmap_Kd tex.png\n"
          "newmtl lost\nKd 1 1 1\nmap_Kd missing.png\n");
    const fs::path path = write("t.obj",
                                "mtllib lib/m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\n"
                                "usemtl found\nf 1/1 2/1 3/1\nusemtl lost\nf 1/1 3/1 2/1\n");
    const Mesh mesh = loadObj(path);

    ASSERT_EQ(mesh.materials.size(), 2u);
    EXPECT_EQ(mesh.materials[0].diffuseTexture, dir_ / "lib" / "tex.png");
    EXPECT_TRUE(mesh.materials[1].diffuseTexture.empty());
    EXPECT_EQ(mesh.warnings,
              std::vector<std::string>{(dir_ / "lib" / "m.mtl").string() +
                                       ":6: texture 'missing.png' of material 'lost' not found; "
                                       "drawing without it"});
}

// Models made on case-insensitive file systems: Sponza's MTL names "SP_LUK.JPG" for sp_luk.JPG.
TEST_F(ObjImport, TextureNameInAnotherCaseFindsTheFileAndWarns) {
    write("Maps/sp_luk.JPG", "not really a jpeg");
    const fs::path mtl = write("m.mtl", "newmtl wall\nKd 1 1 1\nmap_Kd maps\\SP_LUK.JPG\n");
    const Mesh mesh =
        loadObj(write("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl wall\nf 1 2 3\n"));

    ASSERT_EQ(mesh.materials.size(), 1u);
    EXPECT_EQ(mesh.materials[0].diffuseTexture, dir_ / "Maps" / "sp_luk.JPG");
    EXPECT_EQ(mesh.warnings, std::vector<std::string>{
                                 mtl.string() +
                                 ":3: texture 'maps\\\\SP_LUK.JPG' of material 'wall' not "
                                 "found as written; using '" +
                                 (dir_ / "Maps" / "sp_luk.JPG").string() + "', whose name differs in case"});
}

// Exporters write the path a texture had on the author's machine: not found there, the file name alone
// is looked for beside the MTL file (in any case), with a warning; a name found nowhere still warns
// "not found". (Break caught: the fallback removed — no texture, the plain "not found" warning.)
TEST_F(ObjImport, TextureAtTheAuthorsAbsolutePathIsFoundBesideTheMtl) {
    write("Wood.png", "not really a png");
    const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n";
    for (const std::string written :
         {"C:\\Users\\bob\\textures\\wood.png", "/home/bob/textures/Wood.png", "textures/Wood.png"}) {
        SCOPED_TRACE(written);
        const fs::path mtl = write("m.mtl", "newmtl a\nmap_Kd " + written + "\n");
        const Mesh mesh = loadObj(write("m.obj", "mtllib m.mtl\n" + triangle));
        ASSERT_EQ(mesh.materials.size(), 1u);
        EXPECT_EQ(mesh.materials[0].diffuseTexture, dir_ / "Wood.png");
        std::string quoted = written;
        for (std::size_t at = 0; (at = quoted.find('\\', at)) != std::string::npos; at += 2)
            quoted.insert(at, 1, '\\');  // messages escape a backslash
        EXPECT_EQ(mesh.warnings, std::vector<std::string>{mtl.string() + ":2: texture '" + quoted +
                                                          "' of material 'a' not found as written; using '" +
                                                          (dir_ / "Wood.png").string() +
                                                          "', the file of that name beside the MTL file"});
    }
    const fs::path mtl = write("m.mtl", "newmtl a\nmap_Kd /home/bob/textures/stone.png\n");
    const Mesh none = loadObj(write("m.obj", "mtllib m.mtl\n" + triangle));
    EXPECT_TRUE(none.materials[0].diffuseTexture.empty());
    EXPECT_EQ(none.warnings, std::vector<std::string>{
                                 mtl.string() + ":2: texture '/home/bob/textures/stone.png' of material "
                                                "'a' not found; drawing without it"});
}

// Two files that differ only in case are two candidates: neither is guessed.
TEST_F(ObjImport, TextureNameMatchingSeveralFilesInAnotherCaseWarnsAndUsesNone) {
    write("wood.png", "not really a png");
    write("WOOD.png", "not really a png either");
    const fs::path mtl = write("m.mtl", "newmtl floor\nmap_Kd Wood.png\n");
    const Mesh mesh =
        loadObj(write("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl floor\nf 1 2 3\n"));

    ASSERT_EQ(mesh.materials.size(), 1u);
    EXPECT_TRUE(mesh.materials[0].diffuseTexture.empty());
    ASSERT_EQ(mesh.warnings.size(), 1u);
    const std::string& warning = mesh.warnings[0];
    EXPECT_EQ(
        warning.rfind(mtl.string() + ":2: texture 'Wood.png' of material 'floor' differs only in case from "
                                     "'WOOD.png', 'wood.png'",
                      0),
        0u)
        << warning;
    EXPECT_NE(warning.find("drawing without it"), std::string::npos) << warning;
}

TEST_F(ObjImport, EmissionMapResolvesLikeTheDiffuseMap) {
    write("glow.png", "not really a png");
    write("m.mtl", "newmtl lamp\nKe 1 1 1\nmap_Ke glow.png\n");
    const Mesh mesh =
        loadObj(write("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl lamp\nf 1 2 3\n"));

    ASSERT_EQ(mesh.materials.size(), 1u);
    EXPECT_EQ(mesh.materials[0].emissionTexture, dir_ / "glow.png");
    EXPECT_TRUE(mesh.materials[0].diffuseTexture.empty());
    EXPECT_TRUE(mesh.warnings.empty()) << mesh.warnings.front();
}

// Texture statements Facet does not draw are named once each per file, not ignored in silence.
TEST_F(ObjImport, UnusedTextureMapsWarnOnceEach) {
    const fs::path mtl = write("m.mtl",
                               "newmtl a\nmap_Ks spec.png\nbump normal.png\n"
                               "newmtl b\nmap_Ks spec.png\nmap_d mask.png\n");
    const Mesh mesh = loadObj(write("m.obj",
                                    "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n"
                                    "usemtl b\nf 1 3 2\n"));
    EXPECT_EQ(mesh.warnings,
              (std::vector<std::string>{
                  mtl.string() + ":2: map_Ks is not supported and is ignored (2 times in this file)",
                  mtl.string() + ":3: bump is not supported and is ignored",
                  mtl.string() + ":6: map_d is not supported and is ignored",
              }));
}

TEST_F(ObjImport, TextureNameEatenByAnOptionWarns) {
    // tinyobjloader reads "-o u [v [w]]" greedily, so "tex.png" becomes v and the name is lost.
    write("tex.png", "not really a png");
    const fs::path mtl = write("o.mtl", "newmtl shifted\nmap_Kd -o 0.1 tex.png\n");
    const Mesh mesh =
        loadObj(write("o.obj", "mtllib o.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl shifted\nf 1 2 3\n"));

    ASSERT_EQ(mesh.materials.size(), 1u);
    EXPECT_TRUE(mesh.materials[0].diffuseTexture.empty());
    EXPECT_EQ(mesh.warnings,
              std::vector<std::string>{mtl.string() + ":2: map_Kd of material 'shifted' names no "
                                                      "texture file that could be read; drawing "
                                                      "without it"});
}

TEST_F(ObjImport, PartsGroupMaterialsInFirstUseOrder) {
    write("c.mtl", "newmtl red\nKd 1 0 0\nnewmtl green\nKd 0 1 0\nnewmtl unused\nKd 0 0 1\n");
    const Mesh mesh = loadObj(write("p.obj",
                                    "mtllib c.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n"
                                    "f 1 2 3\n"  // no material yet: default
                                    "usemtl green\nf 2 4 3\n"
                                    "usemtl red\nf 1 2 4\n"
                                    "usemtl green\nf 1 3 4\n"));

    ASSERT_EQ(mesh.materials.size(), 3u);
    EXPECT_EQ(mesh.materials[0].name, "default");
    EXPECT_EQ(mesh.materials[1].name, "green");
    EXPECT_EQ(mesh.materials[2].name, "red");
    ASSERT_EQ(mesh.parts.size(), 3u);
    const std::vector<std::pair<std::uint32_t, std::uint32_t>> ranges = {{0, 3}, {3, 6}, {9, 3}};
    for (std::size_t p = 0; p < 3; ++p) {
        EXPECT_EQ(mesh.parts[p].material, p);
        EXPECT_EQ(mesh.parts[p].firstIndex, ranges[p].first);
        EXPECT_EQ(mesh.parts[p].indexCount, ranges[p].second);
    }
    // The green part holds faces 2 and 4, in file order.
    EXPECT_EQ(triangle(mesh, 1), (std::vector<glm::vec3>{{1, 0, 0}, {1, 1, 0}, {0, 1, 0}}));
    EXPECT_EQ(triangle(mesh, 2), (std::vector<glm::vec3>{{0, 0, 0}, {0, 1, 0}, {1, 1, 0}}));
}

TEST_F(ObjImport, EveryLibraryOnAnMtllibLineIsRead) {
    write("a.mtl", "newmtl a\nKd 1 0 0\n");
    write("b c.mtl", "newmtl b\nKd 0 1 0\n");
    const fs::path path = write("two.obj",
                                "mtllib missing.mtl a.mtl b\\ c.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                                "usemtl a\nf 1 2 3\nusemtl b\nf 1 3 2\n");
    const Mesh mesh = loadObj(path);

    ASSERT_EQ(mesh.materials.size(), 2u);
    EXPECT_EQ(mesh.materials[0].diffuse, glm::vec3(1, 0, 0));
    EXPECT_EQ(mesh.materials[1].diffuse, glm::vec3(0, 1, 0));
    EXPECT_EQ(mesh.warnings, std::vector<std::string>{path.string() +
                                                      ":1: material library 'missing.mtl': no such file; its "
                                                      "materials fall back to the default"});
}

// ---- Bundled models -------------------------------------------------------------------------------

// Every file of tinyobjloader's regression suite either loads or is refused with a one-line message
// naming it. The refused ones were checked by hand against the files (see models/README.md).
TEST(ObjImportModels, TinyobjloaderTestsLoadOrThrowInputError) {
    const std::map<std::string, std::string> expectedRefusals = {
        {"invalid-face-definition.obj",
         ": no triangles to draw (all 2 faces are degenerate or have fewer than 3 corners)"},
        {"invalid-relative-texture-index.obj", ":2: face index 1 is out of range (the file has 0 vertices)"},
        {"invalid-relative-vertex-index.obj",
         ":1: face index -4 is out of range (0 vertices are defined before this line)"},
        {"issue-140-zero-face-idx.obj", ":16: face index 0 is invalid (OBJ indices start at 1)"},
        {"issue-356-leading-spaces-newmtl.obj", ": no triangles to draw (the file has no faces)"},
        {"line-prim.obj", ": no triangles to draw (the file has no faces)"},
        {"points-prim.obj", ": no triangles to draw (the file has no faces)"},
        {"test-nan.obj", ":12: vertex coordinate 'nan' is not a finite number"},
    };
    std::map<std::string, std::string> refusals;
    std::size_t loaded = 0;
    for (const fs::directory_entry& entry : fs::directory_iterator(kSharedModels / "tinyobjloader-tests")) {
        if (entry.path().extension() != ".obj") continue;
        const std::string file = entry.path().string();
        try {
            const Mesh mesh = loadObj(entry.path());
            EXPECT_GT(mesh.stats.trianglesKept, 0u) << file;
            ++loaded;
        } catch (const InputError& e) {
            const std::string message = e.what();
            EXPECT_EQ(message.rfind(file, 0), 0u) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
            refusals[entry.path().filename().string()] =
                message.substr(std::min(file.size(), message.size()));
        }
    }
    EXPECT_EQ(refusals, expectedRefusals);
    EXPECT_EQ(loaded + refusals.size(), 47u);
}

// Every other model loads with the triangle count models/README.md lists (there: n - 2 per face);
// these scans and exports have no degenerate triangles. Plus properties every mesh must have.
TEST(ObjImportModels, BundledModelsLoadWithTheirTriangleCounts) {
    const std::map<std::string, std::size_t> expected = {
        {"stanford-bunny/stanford-bunny.obj", 69451},
        {"utah-teapot/teapot.obj", 6320},
        {"utah-teapot-mcguire/teapot.obj", 15704},
        {"suzanne/suzanne.obj", 968},
        {"spot/spot_control_mesh.obj", 372},
        {"spot/spot_quadrangulated.obj", 5856},
        {"spot/spot_triangulated.obj", 5856},
        {"cornell-box/CornellBox-Empty-CO.obj", 12},
        {"cornell-box/CornellBox-Empty-RG.obj", 12},
        {"cornell-box/CornellBox-Empty-Squashed.obj", 12},
        {"cornell-box/CornellBox-Empty-White.obj", 12},
        {"cornell-box/CornellBox-Glossy-Floor.obj", 1112},
        {"cornell-box/CornellBox-Glossy.obj", 1112},
        {"cornell-box/CornellBox-Mirror.obj", 36},
        {"cornell-box/CornellBox-Original.obj", 36},
        {"cornell-box/CornellBox-Sphere.obj", 2188},
        {"cornell-box/CornellBox-Water.obj", 7088},
        {"cornell-box/water.obj", 4900},
        {"cube-mcguire/cube.obj", 12},
        {"lat-long-sphere/sphere-cylcoords-16k.obj", 15872},
        {"lat-long-sphere/sphere-cylcoords-1k.obj", 960},
        {"lat-long-sphere/sphere-cylcoords-4k.obj", 3968},
        {"scrub-pine/scrubPine.obj", 527},
        {"mori-knob/testObj.obj", 11970},
        {"armadillo/armadillo.obj", 99976},
        {"lucy/lucy.obj", 99970},
        {"lost-empire/lost_empire.obj", 224998},
    };
    // Every .obj outside tinyobjloader-tests/ must be in the table, so a new model cannot be skipped.
    std::set<std::string> found;
    for (const fs::directory_entry& folder : fs::directory_iterator(kSharedModels)) {
        if (!folder.is_directory() || folder.path().filename() == "tinyobjloader-tests") continue;
        for (const fs::directory_entry& entry : fs::directory_iterator(folder.path())) {
            if (entry.path().extension() == ".obj")
                found.insert(fs::relative(entry.path(), kSharedModels).generic_string());
        }
    }
    std::set<std::string> listed;
    for (const auto& [name, count] : expected)
        listed.insert(name);
    EXPECT_EQ(found, listed);

    for (const auto& [name, triangles] : expected) {
        SCOPED_TRACE(name);
        const Mesh mesh = loadObj(kSharedModels / name);
        EXPECT_EQ(mesh.stats.trianglesKept, triangles);
        EXPECT_EQ(mesh.stats.degenerateSkipped, 0u);
        EXPECT_EQ(mesh.indices.size(), 3 * triangles);

        std::size_t covered = 0;
        for (const MeshPart& part : mesh.parts) {
            EXPECT_EQ(part.firstIndex, covered);
            EXPECT_LT(part.material, mesh.materials.size());
            covered += part.indexCount;
        }
        EXPECT_EQ(covered, mesh.indices.size());
        for (std::uint32_t i : mesh.indices)
            ASSERT_LT(i, mesh.vertices.size());
        for (const MeshVertex& v : mesh.vertices) {
            ASSERT_NEAR(glm::length(v.normal), 1.0f, 1e-5f);
            ASSERT_TRUE(glm::all(glm::greaterThanEqual(v.position, mesh.boundsMin)));
            ASSERT_TRUE(glm::all(glm::lessThanEqual(v.position, mesh.boundsMax)));
        }
    }
}

// The bunny (triangles, no normals, one position per vertex line) against a brute-force reading of
// the crease rule: every corner's normal is the normalised sum of the cross products of the triangles
// at its position within 60° of its own, and corners share a vertex exactly when their sets agree.
TEST(ObjImportModels, BunnyNormalsFollowTheCreaseRule) {
    const fs::path path = kSharedModels / "stanford-bunny" / "stanford-bunny.obj";
    const Mesh mesh = loadObj(path);
    const Mesh welded = loadObj(path, kSmoothAll);

    const std::size_t triangles = mesh.indices.size() / 3;
    EXPECT_EQ(triangles, 69451u);
    EXPECT_EQ(welded.indices.size(), mesh.indices.size());
    EXPECT_EQ(welded.stats.creaseSplits, 0u);
    EXPECT_GT(mesh.stats.creaseSplits, 0u);
    EXPECT_EQ(mesh.vertices.size(), welded.vertices.size() + mesh.stats.creaseSplits);
    EXPECT_EQ(mesh.stats.normalsComputed, mesh.vertices.size());

    // A position as a hash key: the bytes of its coordinates, -0 read as 0 (positions compare as values).
    auto positionKey = [](glm::vec3 q) {
        q += glm::vec3(0.0f);
        return std::string(reinterpret_cast<const char*>(&q), sizeof q);
    };
    std::vector<glm::dvec3> cross(triangles), unit(triangles);
    std::unordered_map<std::string, std::vector<std::size_t>> trianglesAt;
    for (std::size_t t = 0; t < triangles; ++t) {
        const auto p = triangle(mesh, t);
        cross[t] = glm::cross(glm::dvec3(p[1]) - glm::dvec3(p[0]), glm::dvec3(p[2]) - glm::dvec3(p[0]));
        unit[t] = cross[t] / glm::length(cross[t]);
        for (const glm::vec3& q : p)
            trianglesAt[positionKey(q)].push_back(t);
    }
    const double limit = std::cos(glm::radians(60.0));
    // A corner's position and the set of triangles its normal sums, as one key.
    std::unordered_map<std::string, std::uint32_t> vertexOfSet;
    std::size_t checked = 0;
    for (std::size_t t = 0; t < triangles; ++t) {
        for (int c = 0; c < 3; ++c) {
            const std::uint32_t index = mesh.indices[3 * t + c];
            const glm::vec3 q = mesh.vertices[index].position;
            std::vector<std::size_t> set;
            glm::dvec3 sum(0.0);
            bool nearTheLimit = false;
            for (const std::size_t other : trianglesAt[positionKey(q)]) {
                const double d = glm::dot(unit[t], unit[other]);
                nearTheLimit = nearTheLimit || std::abs(d - limit) < 1e-9;
                if (d >= limit || other == t) {
                    set.push_back(other);
                    sum += cross[other];
                }
            }
            if (nearTheLimit) continue;  // rounding may decide either way
            ++checked;
            ASSERT_NEAR(glm::distance(glm::dvec3(mesh.vertices[index].normal), sum / glm::length(sum)), 0.0,
                        1e-6)
                << "triangle " << t << " corner " << c;
            std::string key = positionKey(q);
            key.append(reinterpret_cast<const char*>(set.data()), set.size() * sizeof(std::size_t));
            const auto [it, inserted] = vertexOfSet.try_emplace(key, index);
            ASSERT_EQ(it->second, index) << "triangle " << t << " corner " << c;
        }
    }
    EXPECT_GT(checked, 3 * triangles - 100);
    EXPECT_EQ(vertexOfSet.size(), mesh.vertices.size());

    // The same input gives the same bytes.
    const Mesh again = loadObj(path);
    ASSERT_EQ(again.vertices.size(), mesh.vertices.size());
    EXPECT_EQ(
        std::memcmp(again.vertices.data(), mesh.vertices.data(), mesh.vertices.size() * sizeof(MeshVertex)),
        0);
    EXPECT_EQ(again.indices, mesh.indices);
}

TEST(ObjImportModels, CubeMcguireIsTexturedAndWarningFree) {
    const fs::path folder = kSharedModels / "cube-mcguire";
    const Mesh mesh = loadObj(folder / "cube.obj");

    EXPECT_TRUE(mesh.warnings.empty());
    EXPECT_TRUE(mesh.hasTexcoords);
    EXPECT_EQ(mesh.vertices.size(), 24u);  // 8 positions × 3 faces each, split by normal
    EXPECT_EQ(mesh.stats.normalsComputed, 0u);
    ASSERT_EQ(mesh.materials.size(), 1u);
    EXPECT_EQ(mesh.materials[0].name, "default");
    EXPECT_EQ(mesh.materials[0].diffuseTexture, folder / "default.png");
    EXPECT_EQ(mesh.materials[0].diffuse, glm::vec3(1.0f));
    EXPECT_EQ(mesh.materials[0].shininess, 10.0f);
    EXPECT_EQ(mesh.materials[0].opacity, 1.0f);  // "Tr 0"
}

TEST(ObjImportModels, CornellBoxHasOnePartPerMaterial) {
    const Mesh mesh = loadObj(kSharedModels / "cornell-box" / "CornellBox-Original.obj");

    EXPECT_TRUE(mesh.warnings.empty());
    std::vector<std::string> names;
    for (const Material& m : mesh.materials)
        names.push_back(m.name);
    EXPECT_EQ(names, (std::vector<std::string>{"floor", "ceiling", "backWall", "rightWall", "leftWall",
                                               "shortBox", "tallBox", "light"}));
    EXPECT_EQ(mesh.parts.size(), 8u);
    EXPECT_EQ(mesh.materials[4].diffuse, glm::vec3(0.63f, 0.065f, 0.05f));
}

TEST(ObjImportModels, UnknownMaterialInBundledFileWarnsWithItsLine) {
    const fs::path path = kSharedModels / "lat-long-sphere" / "sphere-cylcoords-1k.obj";
    const Mesh mesh = loadObj(path);
    ASSERT_EQ(mesh.warnings.size(), 1u);
    EXPECT_EQ(mesh.warnings[0].rfind(path.string() + ":", 0), 0u);
    EXPECT_NE(mesh.warnings[0].find("unknown material 'UnwrapChecker'; using the default material"),
              std::string::npos);
}

}  // namespace
}  // namespace facet
