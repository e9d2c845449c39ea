// The numbers behind the named things of the step mode's screens: the normal matrix and the normals
// through the vertex shader, flat shading's face normal and provoking vertex, the computed vertex
// normals' weighted sums, Beckmann's D, the power curve's c^(1/γ) and a transparent triangle's sort
// key, each found on its screen and checked against the same thing computed here in double from the
// scene's numbers; and every screen of these scenes within 80 columns.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render/renderer.h"
#include "small_scene_walk.h"
#include "step/views.h"
#include "step/walk.h"

namespace facet::step {
namespace {

using glm::dmat3;
using glm::dvec3;

// The screen `id` of a walk's screens ("" when absent).
std::string screenText(const StepTrace& trace, const std::string& id) {
    for (const Screen& s : trace.walk.screens)
        if (s.id == id) return s.text;
    return "";
}

using testing_walk::expectVector;
using testing_walk::expectWithin80Columns;
using testing_walk::numbersAfter;

class LectureNumbersTest : public testing_walk::SmallSceneWalkTest {};

// Three faces around the origin A, without normals: face 0 (A, B, C) in the plane z = 0, face 1
// (A, C, D) tilted 26.6° from it, face 2 (A, B, H) at 90° (beyond the 60° crease angle).
constexpr const char* kFan =
    "v 0 0 0\nv 2 0 0\nv 0 1 0\nv -1 0 0.5\nv 0 0 -1\n"
    "f 1 2 3\nf 1 3 4\nf 1 5 2\n";
const dvec3 kA(0, 0, 0), kB(2, 0, 0), kC(0, 1, 0), kD(-1, 0, 0.5), kH(0, 0, -1);

// The transform screen shows M_n = ((V·M)⁻¹)ᵀ scaled to determinant 1, and each corner's normal as read,
// times N, and normalised, for an object scaled unevenly and turned. Catches: N shown as V·M (not its
// inverse transpose), the wrong scale, n_eye not M_n·n_obj, the normalisation missing.
TEST_F(LectureNumbersTest, TransformScreenShowsTheNormalMatrixAndEachNormalThroughIt) {
    Scene scene = sceneOf(
        "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nvn 0.6 0 0.8\nvn 0 0 1\nvn -0.6 0 0.8\n"
        "f 1//1 2//2 3//3\n");
    glm::mat4 world = glm::rotate(glm::mat4(1.0f), 0.4f, glm::vec3(0, 1, 0));
    world = glm::scale(world, glm::vec3(1.5f, 0.5f, 2.0f));
    scene.objects[0].worldFromObject = world;
    const PreparedScene prepared = prepareScene(scene);
    const StepTrace trace = walkAt(prepared, vec3(0.0f, -0.2f, 0.0f), 0);
    const std::string text = screenText(trace, "transform");
    ASSERT_FALSE(text.empty());

    // By hand, in double: N = transpose(inverse(mat3(V·M))), then divided by ∛|det|.
    const dmat3 vm = dmat3(prepared.camera.viewFromWorldExact * glm::dmat4(world));
    const dmat3 inverseTranspose = glm::transpose(glm::inverse(vm));
    const double det = glm::determinant(inverseTranspose);
    const dmat3 n = inverseTranspose / std::cbrt(std::abs(det));
    for (int row = 0; row < 3; ++row) {
        // The matrix's rows, one line each after "M_n = [".
        const std::size_t at = text.find("  M_n = [");
        ASSERT_NE(at, std::string::npos) << text;
        std::size_t line = at;
        for (int r = 0; r < row; ++r)
            line = text.find('\n', line) + 1;
        std::string cells = text.substr(line, text.find('\n', line) - line);
        cells = cells.substr(cells.find_first_of("-0123456789", row == 0 ? cells.find('[') : 0));
        std::istringstream in(cells);
        for (int column = 0; column < 3; ++column) {
            double value = 0;
            in >> value;
            EXPECT_NEAR(value, n[column][row], 1e-5) << "N[" << row << "][" << column << "]\n" << text;
        }
    }
    EXPECT_NEAR(numbersAfter(text, "det = ").at(0), det, 1e-5 * std::abs(det)) << text;

    const dvec3 normals[3] = {{0.6, 0, 0.8}, {0, 0, 1}, {-0.6, 0, 0.8}};
    std::size_t from = 0;
    for (int k = 0; k < 3; ++k) {
        // Appended piece by piece: GCC 12 reports a false -Wrestrict on "v" + std::to_string(k).
        std::string vertex = "v";
        vertex += char('0' + k);
        from = text.find(vertex + "  n_obj", from);
        ASSERT_NE(from, std::string::npos) << text;
        const dvec3 eye = n * normals[k];
        expectVector(numbersAfter(text, "n_eye = M_n·n_obj = ", from), eye, 1e-5, "n_eye " + vertex);
        expectVector(numbersAfter(text, "n_eye/|n_eye| = ", from), glm::normalize(eye), 1e-5,
                     "unit " + vertex);
        EXPECT_NEAR(numbersAfter(text, "|n_eye| = ", from).at(0), glm::length(eye), 1e-5);
    }
    expectWithin80Columns(trace);
}

// A computed vertex normal on the input screen: the faces at the position, their normals and weights
// (the polygons' cross products), the crease decision and the normalised sum, all as computed here from
// the OBJ's positions. Catches: a face beyond the crease angle summed (or one within it left out), the
// weights not the cross products, the sum not normalised, the numbers of another vertex shown.
TEST_F(LectureNumbersTest, InputScreenDerivesAComputedVertexNormalFromItsFaces) {
    const PreparedScene prepared = prepareScene(sceneOf(kFan));
    const StepTrace trace = walkAt(prepared, vec3(0.3f, 0.3f, 0.0f), 0);
    const std::string text = screenText(trace, "input");
    ASSERT_FALSE(text.empty());
    const dvec3 w0 = glm::cross(kB - kA, kC - kA), w1 = glm::cross(kC - kA, kD - kA),
                w2 = glm::cross(kH - kA, kB - kA);
    // v0 is A: faces 0 and 1 within 60° of face 0, face 2 at 90°.
    const std::size_t v0 = text.find("  v0: 3 faces at its position, own face 0");
    ASSERT_NE(v0, std::string::npos) << text;
    const std::size_t v1 = text.find("\n  v1", v0);
    const std::string block = text.substr(v0, v1 - v0);
    expectVector(numbersAfter(block, "face 0: n̂ = "), glm::normalize(w0), 1e-6, "n̂ face 0");
    expectVector(numbersAfter(block, "w = ", block.find("face 1:")), w1, 1e-6, "w face 1");
    expectVector(numbersAfter(block, "w = ", block.find("face 2:")), w2, 1e-6, "w face 2");
    EXPECT_NEAR(numbersAfter(block, "|w| = ", block.find("face 1:")).at(0), glm::length(w1), 1e-5);
    const double cos1 = glm::dot(glm::normalize(w0), glm::normalize(w1));
    const double cos2 = glm::dot(glm::normalize(w0), glm::normalize(w2));
    EXPECT_NEAR(numbersAfter(block, "n̂·n̂_own = ", block.find("face 1:")).at(0), cos1, 1e-6);
    EXPECT_NE(block.find(" ≥ cos: summed", block.find("face 1:")), std::string::npos) << block;
    EXPECT_NEAR(numbersAfter(block, "n̂·n̂_own = ", block.find("face 2:")).at(0), cos2, 1e-6);
    EXPECT_NE(block.find("< cos: left out (crease)", block.find("face 2:")), std::string::npos) << block;
    expectVector(numbersAfter(block, "Σ w = "), w0 + w1, 1e-6, "Σ w");
    expectVector(numbersAfter(block, "n = Σ w / |Σ w| = "), glm::normalize(w0 + w1), 1e-6, "n");
    // The normal shown is the one the vertex has (the input screen's "normal" line for v0).
    EXPECT_EQ(trace.triangle->objectNormals[0], vec3(glm::normalize(w0 + w1))) << text;
    expectWithin80Columns(trace);
}

// Under lighting.normals "angle" each weight is the face's unit normal times its corner angle: at B,
// face 0's angle is atan2(|(A − B) × (C − B)|, (A − B)·(C − B)). Catches: the weights of another rule.
TEST_F(LectureNumbersTest, AngleWeightsAreTheCornerAngles) {
    Scene scene = sceneOf(kFan);
    scene.lighting.normals = VertexNormals::Angle;
    const PreparedScene prepared = prepareScene(scene);
    const StepTrace trace = walkAt(prepared, vec3(0.3f, 0.3f, 0.0f), 0);
    const std::string text = screenText(trace, "input");
    const std::size_t v1 = text.find("\n  v1: ");
    ASSERT_NE(v1, std::string::npos) << text;
    const dvec3 e1 = kA - kB, e2 = kC - kB;
    const double angle = std::atan2(glm::length(glm::cross(e1, e2)), glm::dot(e1, e2));
    EXPECT_NEAR(numbersAfter(text, "|w| = ", text.find("face 0:", v1)).at(0), angle, 1e-6) << text;
    EXPECT_NE(text.find("(angle)"), std::string::npos) << text;
}

// Flat shading: the input screen shows the face normal from two edges and the lighting screen names
// the provoking vertex as the docs do ("v2, the last"). Catches: the cross product of other edges, the
// length or the normalised result wrong, the provoking vertex named by the setup's corner number.
TEST_F(LectureNumbersTest, FlatShadingShowsTheFaceNormalAndTheProvokingVertex) {
    Scene scene = sceneOf(kFan);
    scene.lighting.shading = ShadingFrequency::Flat;
    const PreparedScene prepared = prepareScene(scene);
    // Face 1 (A, C, D), seen at a point inside it.
    const StepTrace trace = walkAt(prepared, vec3(-0.2f, 0.4f, 0.1f), 1);
    const std::string input = screenText(trace, "input");
    const dvec3 cross = glm::cross(kC - kA, kD - kA);
    expectVector(numbersAfter(input, "(v1 − v0) × (v2 − v0) = "), cross, 1e-6, "cross");
    EXPECT_NEAR(numbersAfter(input, "|(v1 − v0) × (v2 − v0)| = ").at(0), glm::length(cross), 1e-5) << input;
    const std::size_t n = input.find("  n = ");
    ASSERT_NE(n, std::string::npos) << input;
    expectVector(numbersAfter(input, " = ", input.find(") / ", n)), glm::normalize(cross), 1e-6, "n");
    const std::string lighting = screenText(trace, "lighting");
    ASSERT_FALSE(lighting.empty());
    std::string oneLine = lighting;
    std::replace(oneLine.begin(), oneLine.end(), '\n', ' ');
    EXPECT_NE(oneLine.find("v2, the provoking vertex (the last, as OpenGL)"), std::string::npos) << lighting;
    expectWithin80Columns(trace);
}

// Beckmann's D with the numbers substituted, and its value as computed here from N·H and α. Catches: the
// substitution missing or D not exp((c² − 1)/(α²c²))/(πα²c⁴).
TEST_F(LectureNumbersTest, BeckmannDistributionSubstituted) {
    Scene scene = sceneOf(kFan);
    scene.lighting.model = ReflectionModel::CookTorrance;
    scene.lighting.brdf.distribution = NormalDistribution::Beckmann;
    const PreparedScene prepared = prepareScene(scene);
    const StepTrace trace = walkAt(prepared, vec3(0.3f, 0.3f, 0.0f), 0);
    const std::string text = screenText(trace, "lighting");
    const std::size_t line = text.find("    = exp((");
    ASSERT_NE(line, std::string::npos) << text;
    // N·H and α as the BRDF computed them (the screen rounds them to 4 digits).
    ASSERT_TRUE(trace.shading);
    const BrdfRecord& brdf = trace.shading->fragment.lighting.lighting.lights[0].brdf;
    const double c = brdf.NdotH, a = brdf.alpha;
    const std::string substituted = text.substr(line, text.find('\n', line) - line);
    EXPECT_NE(substituted.find("/(π·"), std::string::npos) << substituted;
    const double d = std::exp((c * c - 1) / (a * a * c * c)) / (std::numbers::pi * a * a * c * c * c * c);
    // The D after the last "= " of the substituted line (it may wrap onto the next one).
    const std::size_t end = text.find("  F0 = ", line);
    const std::string lines = text.substr(line, end - line);
    const double shown = std::strtod(lines.substr(lines.rfind("= ") + 2).c_str(), nullptr);
    // Within 0.2%: the default fast exp (lighting.powers) is that close; a formula with c² for c⁴
    // would be 2.6% off here.
    EXPECT_NEAR(shown, d, 2e-3 * d) << lines;
    expectWithin80Columns(trace);
}

// The power curve's c′ = c^(1/γ) before 255·c′ is rounded. Catches: the intermediate missing or not
// the power of the linear value.
TEST_F(LectureNumbersTest, PowerCurveShowsItsIntermediateValue) {
    Scene scene = sceneOf(kFan);
    scene.gamma.encode = TransferCurve::Power;
    scene.gamma.exponent = 1.8f;
    const PreparedScene prepared = prepareScene(scene);
    const StepTrace trace = walkAt(prepared, vec3(0.3f, 0.3f, 0.0f), 0);
    const std::string text = screenText(trace, "encode");
    const std::size_t r = text.find("  R: ");
    ASSERT_NE(r, std::string::npos) << text;
    const double c = std::strtod(text.c_str() + r + 5, nullptr);
    ASSERT_GT(c, 0.0) << text;
    const double encoded = std::pow(std::min(c, 1.0), 1.0 / 1.8);
    EXPECT_NE(text.find("^(1/1.8) = ", r), std::string::npos) << text;
    EXPECT_NEAR(numbersAfter(text, "^(1/1.8) = ", r).at(0), encoded, 2e-6) << text;
    EXPECT_NEAR(numbersAfter(text, "255·c′ = ", r).at(0), 255.0 * encoded, 1e-3) << text;
    EXPECT_EQ(int(trace.pixel.finalBytes[0]), int(std::lround(255.0 * encoded))) << text;
    expectWithin80Columns(trace);
}

// A transparent triangle's sort key: −(z0 + z1 + z2)/3 of its corners' eye-space z (the eye at z = 5,
// so z_eye = z − 5), and under "farthest" −min(z). Catches: the key of another triangle or rule.
TEST_F(LectureNumbersTest, BlendScreenShowsTheSortKeyOfATransparentTriangle) {
    // Two overlapping triangles, the far one at z = −1 (drawn first), the near one at z ∈ [0, 0.6].
    Scene scene = sceneOf(
        "v -1 -1 -1\nv 1 -1 -1\nv 0 1 -1\nv -1 -1 0\nv 1 -1 0.6\nv 0 1 0.3\n"
        "f 1 2 3\nf 4 5 6\n");
    scene.objects[0].material.opacity = 0.5f;
    for (const SortKey key : {SortKey::Centroid, SortKey::FarthestVertex}) {
        scene.transparency.key = key;
        const PreparedScene prepared = prepareScene(scene);
        const StepTrace trace = walkAt(prepared, vec3(0.0f, -0.3f, 0.2f), 1);
        const std::string text = screenText(trace, "blend");
        const double z[3] = {0 - 5.0, 0.6 - 5.0, 0.3 - 5.0};
        const double want =
            key == SortKey::Centroid ? -(z[0] + z[1] + z[2]) / 3 : -std::min({z[0], z[1], z[2]});
        // The rule, its numbers, then the key: "= value" on the last line of the three.
        const std::string label =
            key == SortKey::Centroid ? "z_key = −(z0 + z1 + z2)/3\n" : "z_key = −min(z0";
        const std::size_t at = text.find(label);
        ASSERT_NE(at, std::string::npos) << text;
        std::size_t line = at;
        for (int k = 0; k < 3; ++k)
            line = text.find('\n', line + 1);
        const double shown = std::strtod(text.substr(text.rfind("= ", line) + 2).c_str(), nullptr);
        EXPECT_NEAR(shown, want, 1e-5) << text;
        EXPECT_NE(text.find("drawn 2. of"), std::string::npos) << text;
        expectWithin80Columns(trace);
    }
}

}  // namespace
}  // namespace facet::step
