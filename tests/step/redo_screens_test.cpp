// Screens a student can redo by hand: clipping names the planes that cut, the corners of every screen
// are v0, v1, v2 of the triangle as drawn, flat shading derives its face normal, the interpolation
// screen lists each varying at the corners, the input screen shows the file's values, and the shadow
// screen names what blocks the light. Each number is checked against the same thing worked out here
// from the scene's own numbers (or the trace's data), in double.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "pipeline/clip.h"
#include "render/renderer.h"
#include "small_scene_walk.h"
#include "step/views.h"
#include "step/walk.h"

namespace facet::step {
namespace {

using glm::dvec3;
using glm::dvec4;

const Screen* screenOf(const StepTrace& trace, const std::string& id) {
    for (const Screen& s : trace.walk.screens)
        if (s.id == id) return &s;
    return nullptr;
}

// Every line of the screens these tests are about within 80 columns, the titles too.
void expectRedoneScreensWithin80Columns(const StepTrace& trace) {
    testing_walk::expectWithin80Columns(trace, {"input", "clip", "interpolate", "lighting"});
}

// The text with its line breaks and the indentation after them read as one space.
std::string flat(const std::string& text) {
    std::string out;
    for (const char c : text)
        if (!(c == ' ' && !out.empty() && out.back() == ' ')) out += c == '\n' ? ' ' : c;
    return out;
}

using testing_walk::expectVector;
using testing_walk::numbersAfter;

class RedoScreensTest : public testing_walk::SmallSceneWalkTest {};

// A triangle counter-clockwise on screen (so setup exchanges v1 and v2), corners in face order.
constexpr const char* kTriangle =
    "v -1 -0.8 0\nv 1.2 -0.6 -0.5\nv -0.2 1 0.3\n"
    "vt 0.1 0.2\nvt 0.9 0.3\nvt 0.4 0.95\n"
    "vn 0 0 2\nvn 0.3 0 0.4\nvn 0 1.2 1.6\n"
    "f 1/1/1 2/2/2 3/3/3\n";
const dvec3 kCorners[3] = {{-1, -0.8, 0}, {1.2, -0.6, -0.5}, {-0.2, 1, 0.3}};
const double kUv[3][2] = {{0.1, 0.2}, {0.9, 0.3}, {0.4, 0.95}};
const dvec3 kNormals[3] = {{0, 0, 2}, {0.3, 0, 0.4}, {0, 1.2, 1.6}};

// The plane distances of clip.h (≥ 0 inside), in double, under OpenGL's depth range.
double distanceTo(const dvec4& p, std::uint8_t plane) {
    switch (plane) {
        case kClipLeft:
            return p.w + p.x;
        case kClipRight:
            return p.w - p.x;
        case kClipBottom:
            return p.w + p.y;
        case kClipTop:
            return p.w - p.y;
        case kClipNear:
            return p.w + p.z;
        case kClipFar:
            return p.w - p.z;
        default:
            return p.w - kMinClipW;
    }
}

// A triangle with a corner behind the eye: its outcodes name the w plane (w < 0 there), but the near
// plane, clipped before it, leaves nothing behind the eye. Sutherland-Hodgman is replayed here in
// double on the corners' clip positions, plane by plane in the clipper's order, to find the planes
// that cut and each new vertex's t = d_in / (d_in − d_out).
// Catches: the title naming every plane of the outcodes (the w plane among them) instead of those
// that cut, the planes named but not cut left unlisted, or a new vertex's t not the replay's.
TEST_F(RedoScreensTest, ClippingNamesThePlanesThatCutAndListsTheOthers) {
    const PreparedScene prepared = prepareScene(sceneOf("v -1 -0.5 0\nv 1 -0.5 0\nv 0 -0.1 6\nf 1 2 3\n"));
    const StepTrace trace = walkAt(prepared, vec3(0.0f, -0.466f, 0.5f), 0);
    ASSERT_TRUE(trace.triangle);
    const TriangleTrace& t = *trace.triangle;
    std::vector<dvec4> polygon;
    std::uint8_t named = 0;
    for (int k = 0; k < 3; ++k) {
        polygon.push_back(dvec4(t.clipPositions[k]));
        for (const std::uint8_t plane :
             {kClipLeft, kClipRight, kClipBottom, kClipTop, kClipNear, kClipFar, kClipW})
            if (distanceTo(polygon.back(), plane) < 0) named |= plane;
    }
    std::uint8_t cut = 0;
    std::vector<double> ts;
    for (const std::uint8_t plane :
         {kClipLeft, kClipRight, kClipBottom, kClipTop, kClipNear, kClipFar, kClipW}) {
        if (!(named & plane)) continue;
        bool outside = false;
        for (const dvec4& p : polygon)
            outside = outside || distanceTo(p, plane) < 0;
        if (!outside) continue;
        cut |= plane;
        std::vector<dvec4> next;
        for (std::size_t i = 0; i < polygon.size(); ++i) {
            const dvec4 &a = polygon[i], &b = polygon[(i + 1) % polygon.size()];
            const double da = distanceTo(a, plane), db = distanceTo(b, plane);
            if (da >= 0) next.push_back(a);
            if ((da >= 0) != (db >= 0)) {
                const double tIn = da >= 0 ? da / (da - db) : db / (db - da);
                ts.push_back(tIn);
                next.push_back(da >= 0 ? a + tIn * (b - a) : b + tIn * (a - b));
            }
        }
        polygon = next;
    }
    const std::uint8_t uncut = named & ~cut;
    ASSERT_TRUE(named & kClipW);
    ASSERT_TRUE(uncut & kClipW);  // the premise: the w plane is named but not cut
    ASSERT_TRUE(cut & kClipNear);

    const Screen* clip = screenOf(trace, "clip");
    ASSERT_NE(clip, nullptr);
    EXPECT_EQ(clip->title,
              "Clipping: " + clipPlaneNames(cut) + " cut" + (cut & (cut - 1) ? "" : "s") + " the triangle");
    const std::string text = flat(clip->text);
    EXPECT_NE(text.find("Planes that cut it: " + clipPlaneNames(cut) + " "), std::string::npos) << clip->text;
    EXPECT_NE(text.find("Outside but not cut after the earlier planes: " + clipPlaneNames(uncut) + " "),
              std::string::npos)
        << clip->text;
    // One section per cutting plane, none for the others.
    for (const std::uint8_t plane :
         {kClipLeft, kClipRight, kClipBottom, kClipTop, kClipNear, kClipFar, kClipW}) {
        const bool section = clip->text.find("\nPlane " + clipPlaneNames(plane) + " ") != std::string::npos;
        EXPECT_EQ(section, (cut & plane) != 0) << clipPlaneNames(plane) << "\n" << clip->text;
    }
    // Every new vertex's t, in order.
    std::vector<double> shown;
    for (std::size_t at = clip->text.find("new vertex on "); at != std::string::npos;
         at = clip->text.find("new vertex on ", at + 1)) {
        const std::string line = clip->text.substr(at, clip->text.find('\n', at) - at);
        shown.push_back(std::strtod(line.c_str() + line.rfind("= ") + 2, nullptr));
    }
    ASSERT_EQ(shown.size(), ts.size()) << clip->text;
    for (std::size_t k = 0; k < ts.size(); ++k)
        EXPECT_NEAR(shown[k], ts[k], 1e-5 * std::max(1.0, ts[k])) << k << "\n" << clip->text;
    expectRedoneScreensWithin80Columns(trace);
}

// The input screen shows the file's position, texture coordinates and normal of each corner as the
// file writes them (a normal of length 2 stays (0, 0, 2)), with the line it comes from, then the
// normal normalised; v0, v1, v2 are the face's corners in the file's order.
// Catches: the normalised normal shown as the file's, the texture coordinates missing, or the corners
// listed in another order than the face's.
TEST_F(RedoScreensTest, InputScreenShowsTheFilesValuesThenNormalised) {
    const PreparedScene prepared = prepareScene(sceneOf(kTriangle));
    const StepTrace trace = walkAt(prepared, vec3(0.0f, -0.1f, 0.0f), 0);
    const Screen* input = screenOf(trace, "input");
    ASSERT_NE(input, nullptr);
    const std::string& text = input->text;
    std::size_t at = text.find("As the model file gives them");
    ASSERT_NE(at, std::string::npos) << text;
    for (int k = 0; k < 3; ++k) {
        const std::string corner = "  v" + std::to_string(k) + "  position  ";
        at = text.find(corner, at);
        ASSERT_NE(at, std::string::npos) << corner << "\n" << text;
        expectVector(numbersAfter(text, corner, at), kCorners[k], 1e-6, "position");
        EXPECT_NE(text.find("(v " + std::to_string(k + 1) + ")", at), std::string::npos) << text;
        const std::vector<double> uv = numbersAfter(text, "texture   ", at);
        ASSERT_GE(uv.size(), 2u) << text;
        EXPECT_NEAR(uv[0], kUv[k][0], 1e-6);
        EXPECT_NEAR(uv[1], kUv[k][1], 1e-6);
        const std::vector<double> normal = numbersAfter(text, "normal    ", at);
        ASSERT_GE(normal.size(), 3u) << text;
        expectVector({normal[0], normal[1], normal[2]}, kNormals[k], 1e-6, "file normal");
        const double length = glm::length(kNormals[k]);
        const std::size_t line = text.find("length ", at);
        ASSERT_NE(line, std::string::npos) << text;
        EXPECT_NEAR(numbersAfter(text, "length ", at).at(0), length, 1e-5) << text;
        expectVector(numbersAfter(text, "normalised: ", at), kNormals[k] / length, 1e-6, "normalised");
    }
    expectRedoneScreensWithin80Columns(trace);
}

// Flat shading: the lighting screen derives the face normal from v1 − v0 and v2 − v0 of the triangle
// as drawn (the face's corners in file order), says it is the face normal, and names v2 as the
// provoking vertex, as the docs do, although setup exchanged v1 and v2 of this counter-clockwise
// triangle. Catches: edges taken in the setup's order (the cross product reversed), the face normal not
// named, or the provoking vertex called by its place in the setup's order.
TEST_F(RedoScreensTest, FlatShadingDerivesItsFaceNormalOnTheLightingScreen) {
    Scene scene = sceneOf(kTriangle);
    scene.lighting.shading = ShadingFrequency::Flat;
    const PreparedScene prepared = prepareScene(scene);
    const StepTrace trace = walkAt(prepared, vec3(0.0f, -0.1f, 0.0f), 0);
    ASSERT_TRUE(trace.triangle);
    ASSERT_FALSE(trace.triangle->pieces.empty());
    ASSERT_LT(trace.triangle->pieces[0].signedDoubleArea, 0);  // the premise: setup exchanged v1 and v2
    const Screen* lighting = screenOf(trace, "lighting");
    ASSERT_NE(lighting, nullptr);
    const std::string& text = lighting->text;
    const std::string oneLine = flat(text);
    EXPECT_NE(oneLine.find("v2, the provoking vertex (the last, as OpenGL)"), std::string::npos) << text;
    EXPECT_EQ(oneLine.find("setup's order"), std::string::npos) << text;
    EXPECT_EQ(oneLine.find("corner 1"), std::string::npos) << text;
    for (int k = 0; k < 3; ++k)
        expectVector(numbersAfter(text, "  v" + std::to_string(k) + " = "), kCorners[k], 1e-4, "v");
    const dvec3 e1 = kCorners[1] - kCorners[0], e2 = kCorners[2] - kCorners[0];
    const dvec3 cross = glm::cross(e1, e2);
    expectVector(numbersAfter(text, "v1 − v0 = "), e1, 1e-3, "v1 − v0");
    expectVector(numbersAfter(text, "v2 − v0 = "), e2, 1e-3, "v2 − v0");
    expectVector(numbersAfter(text, "(v1 − v0) × (v2 − v0) = "), cross, 1e-3, "cross");
    // The face normal agrees with the file's normals here (not turned).
    const std::size_t n = text.find("  n = normalize(");
    ASSERT_NE(n, std::string::npos) << text;
    expectVector(numbersAfter(text, "    = ", n), glm::normalize(cross), 1e-3, "n");
    EXPECT_NE(oneLine.find("the face normal"), std::string::npos) << text;
    expectRedoneScreensWithin80Columns(trace);
}

// Gouraud shading: the lighting screen's corners are v0, v1, v2 in that order, each at the face's
// corner of that number (object space), and the interpolation weights follow the same order: the
// printed λ′ times the printed 1/w ratios agree with the printed λ. Catches: the corners in the
// setup's order (v0, v2, v1 here) or named by their place in it.
TEST_F(RedoScreensTest, GouraudCornersAreTheTrianglesAsDrawn) {
    Scene scene = sceneOf(kTriangle);
    scene.lighting.shading = ShadingFrequency::Gouraud;
    const PreparedScene prepared = prepareScene(scene);
    const StepTrace trace = walkAt(prepared, vec3(0.0f, -0.1f, 0.0f), 0);
    const Screen* lighting = screenOf(trace, "lighting");
    ASSERT_NE(lighting, nullptr);
    const std::string& text = lighting->text;
    std::size_t at = 0;
    for (int k = 0; k < 3; ++k) {
        const std::string head = "---- v" + std::to_string(k) + ": the vertex at ";
        at = text.find(head, at);
        ASSERT_NE(at, std::string::npos) << head << "\n" << text;
        expectVector(numbersAfter(text, head, at), kCorners[k], 1e-3, head);
    }
    const std::vector<double> lambda = numbersAfter(text, "  λ = (λ0, λ1, λ2) = ");
    const std::vector<double> invW = numbersAfter(text, "  1/w0, 1/w1, 1/w2 = ");
    const std::vector<double> mu = numbersAfter(text, ": λ′ = ");
    const std::vector<double> pixel = numbersAfter(text, "  1/w at the pixel = λ0/w0 + λ1/w1 + λ2/w2 = ");
    ASSERT_EQ(lambda.size(), 3u) << text;
    ASSERT_EQ(invW.size(), 3u) << text;
    ASSERT_EQ(mu.size(), 3u) << text;
    ASSERT_EQ(pixel.size(), 1u) << text;
    // The corners' own 1/w: w_clip of each file corner, worked out here.
    const glm::dmat4 clipFromWorld = prepared.camera.clipFromViewExact * prepared.camera.viewFromWorldExact;
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(invW[k], 1.0 / (clipFromWorld * dvec4(kCorners[k], 1.0)).w, 1e-3) << k;
        EXPECT_NEAR(mu[k], lambda[k] * invW[k] / pixel[0], 2e-3) << k;
    }
    expectRedoneScreensWithin80Columns(trace);
}

// The interpolation screen lists every varying at v0, v1, v2 and at the pixel: the eye-space
// position and normal, u and v of each corner, worked out here from the file (P_eye = V·p, N_eye = the
// normal matrix times the file's normal, normalised by the importer), and at the pixel the sum with the
// printed λ′ weights. Catches: a varying left out, corner values in the setup's order (v0, v2, v1 for
// this triangle) against weights in the drawn order, or weights that are not the ones used.
TEST_F(RedoScreensTest, InterpolationListsEveryVaryingAtTheCorners) {
    const PreparedScene prepared = prepareScene(sceneOf(kTriangle));
    const StepTrace trace = walkAt(prepared, vec3(0.0f, -0.1f, 0.0f), 0);
    const Screen* interpolate = screenOf(trace, "interpolate");
    ASSERT_NE(interpolate, nullptr);
    const std::string& text = interpolate->text;
    const std::vector<double> weights = numbersAfter(text, "  λ′ = ");
    ASSERT_EQ(weights.size(), 3u) << text;
    const glm::dmat4 view = prepared.camera.viewFromWorldExact;
    const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(view)));
    std::vector<std::vector<double>> expected(8);  // per varying: its value at v0, v1, v2
    for (int k = 0; k < 3; ++k) {
        const dvec3 p = dvec3(view * dvec4(kCorners[k], 1.0));
        const dvec3 n = normalMatrix * glm::normalize(kNormals[k]);
        const double values[8] = {p.x, p.y, p.z, n.x, n.y, n.z, kUv[k][0], kUv[k][1]};
        for (int i = 0; i < 8; ++i)
            expected[i].push_back(values[i]);
    }
    const char* names[8] = {"P_eye.x", "P_eye.y", "P_eye.z", "N_eye.x", "N_eye.y", "N_eye.z", "u", "v"};
    const std::size_t table = text.find("at the pixel\n");
    ASSERT_NE(table, std::string::npos) << text;
    for (int i = 0; i < 8; ++i) {
        std::string label = std::string("\n  ") + names[i];
        label.resize(13, ' ');  // the name's column
        const std::vector<double> row = numbersAfter(text, label, table);
        ASSERT_EQ(row.size(), 4u) << names[i] << "\n" << text;
        double sum = 0;
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR(row[k], expected[i][k], 1e-4) << names[i] << " at v" << k;
            sum += weights[k] * row[k];
        }
        EXPECT_NEAR(row[3], sum, 1e-4) << names[i];
    }
    expectRedoneScreensWithin80Columns(trace);
}

// Gouraud after clipping: the near plane cuts the tip C of the triangle off, and the pixel lies in a
// fan piece with a new corner. The lighting screen shows each new corner's colours as the mix of its
// edge's ends with t, c = (1 − t)·c_a + t·c_b: worked out here from the corners' colours (the vertex
// shader's outputs at v0, v1, v2, as traced) and the clip record's t, then the weights λ′ of the piece's
// corners, whose weighted sum is the colour the pixel received. Catches: the piece's corners' colours
// missing (only "themselves mixes"), t applied from the wrong end (1 − t), or λ′ from other corners.
TEST_F(RedoScreensTest, GouraudAfterClippingMixesThePiecesCornersWithT) {
    Scene scene = sceneOf("v -1 -0.5 0\nv 1 -0.5 0\nv 0 -0.1 4.6\nf 2 1 3\n");
    scene.lighting.shading = ShadingFrequency::Gouraud;
    const PreparedScene prepared = prepareScene(scene);
    const StepTrace trace = walkAt(prepared, vec3(0.0f, -0.239f, 3.0f), 0);
    ASSERT_TRUE(trace.triangle);
    ASSERT_TRUE(trace.shading);
    const TriangleTrace& t = *trace.triangle;
    ASSERT_EQ(t.clipSteps.size(), 1u);
    const ClipStep& step = t.clipSteps[0];
    const Screen* lighting = screenOf(trace, "lighting");
    ASSERT_NE(lighting, nullptr);
    const std::string& text = lighting->text;
    std::size_t mixes = 0;
    for (const ClipStep::NewVertex& made : step.made) {
        // "pK: made by near on vA→vB, t = …": the new vertex of this edge, its ends the triangle's.
        const std::string edge =
            " on v" + std::to_string(made.from) + "→v" + std::to_string(made.to) + ", t = ";
        const std::size_t at = text.find(edge);
        if (at == std::string::npos) continue;  // not a corner of the pixel's piece
        ++mixes;
        EXPECT_NEAR(numbersAfter(text, edge, at).at(0), made.t, 1e-4) << text;
        const std::vector<float>& a = t.vertexVaryings[static_cast<std::size_t>(made.from)];
        const std::vector<float>& b = t.vertexVaryings[static_cast<std::size_t>(made.to)];
        // The line after: "    modulated = (1 − t)·RGB(a) + t·RGB(b)", then "= RGB(result)".
        const std::size_t line = text.find("    modulated = ", at);
        ASSERT_NE(line, std::string::npos) << text;
        const std::vector<double> mix = numbersAfter(text, "    modulated = ", at);
        ASSERT_GE(mix.size(), 1u) << text;
        EXPECT_NEAR(mix[0], 1.0 - made.t, 1e-3) << text;
        const std::size_t result = text.find("              = RGB", line);
        ASSERT_NE(result, std::string::npos) << text;
        const std::vector<double> mixed = numbersAfter(text, "= RGB", result);
        for (int c = 0; c < 3; ++c) {
            const double want =
                (1.0 - made.t) * a[static_cast<std::size_t>(c)] + made.t * b[static_cast<std::size_t>(c)];
            EXPECT_NEAR(mixed.at(static_cast<std::size_t>(c)), want, 1e-3 * std::max(1.0, std::abs(want)))
                << "c_mod." << c << "\n"
                << text;
        }
    }
    EXPECT_GE(mixes, 1u) << text;
    // λ′ of the piece's corners weight their colours into the pixel's (the interpolator's) colour.
    const std::vector<double> mu = numbersAfter(text, ": λ′ = ");
    ASSERT_EQ(mu.size(), 3u) << text;
    EXPECT_NEAR(mu[0] + mu[1] + mu[2], 1.0, 1e-3) << text;
    std::vector<std::vector<double>> corners;
    for (int i = 0; i < 3; ++i) {
        const std::size_t at = text.find("  c" + std::to_string(i) + " (p");
        ASSERT_NE(at, std::string::npos) << text;
        corners.push_back(numbersAfter(text, "modulated RGB", at));
        ASSERT_GE(corners.back().size(), 3u) << text;
    }
    const vec3 pixel = trace.shading->fragment.modulatedIn;
    for (int c = 0; c < 3; ++c) {
        const double sum = mu[0] * corners[0][c] + mu[1] * corners[1][c] + mu[2] * corners[2][c];
        EXPECT_NEAR(sum, pixel[c], 2e-3 * std::max(1.0, double(pixel[c]))) << c << "\n" << text;
    }
    expectRedoneScreensWithin80Columns(trace);
}

// A point light above a small square that shades the ground: the shadow line names the blocker, the
// square's triangle the shadow ray meets (worked out here: the ray from the ground point P to the
// light crosses the square's plane y = 1 at a point of its first fan triangle, where x + z > 0), with
// the triangle number --triangle counts (the ground's two come first) and the distance |hit − P| along
// the ray; under a shadow map the map decides, and the screen says the ray only names the blocker.
// Catches: no blocker named, the triangle numbered within its draw instead of the scene, the other
// triangle of the square, or a distance that is not along the ray to the light.
TEST_F(RedoScreensTest, ShadowScreenNamesTheBlockerAndItsDistance) {
    Scene scene = sceneOf("v -2 0 2\nv 2 0 2\nv 2 0 -2\nv -2 0 -2\nf 1 2 3 4\n");
    ObjectSpec blocker;
    blocker.model =
        folder_.write("blocker.obj", "v -0.5 1 0.5\nv 0.5 1 0.5\nv 0.5 1 -0.5\nv -0.5 1 -0.5\nf 1 2 3 4\n");
    scene.objects.push_back(blocker);
    scene.camera.eye = vec3(0.0f, 3.0f, 4.0f);
    scene.lights[0].position = vec3(0.0f, 3.0f, 0.0f);
    const dvec3 P(0.6, 0.0, 0.3), light(0.0, 3.0, 0.0);
    const double s = 1.0 / 3.0;  // the ray P + s·(light − P) at y = 1
    const dvec3 hit = P + s * (light - P);
    ASSERT_GT(hit.x + hit.z, 0.1);  // in the square's first triangle (1, 2, 3), clear of its diagonal
    ASSERT_LT(std::max(std::abs(hit.x), std::abs(hit.z)), 0.5);
    const double distance = glm::length(hit - P);
    for (const ShadowMethod method : {ShadowMethod::Ray, ShadowMethod::Map}) {
        scene.lights[0].shadows = method;
        const PreparedScene prepared = prepareScene(scene);
        const StepTrace trace = walkAt(prepared, vec3(P), 0);
        const Screen* lighting = screenOf(trace, "lighting");
        ASSERT_NE(lighting, nullptr);
        const std::string text = flat(lighting->text);
        const std::string named = "triangle 2 of object 1 (blocker.obj), at distance ";
        const std::size_t at = text.find(named);
        ASSERT_NE(at, std::string::npos) << lighting->text;
        EXPECT_NEAR(std::strtod(text.c_str() + at + named.size(), nullptr), distance, 2e-3) << lighting->text;
        const bool byMap = text.find("the shadow map decided; a ray from P towards the light only names") !=
                           std::string::npos;
        EXPECT_EQ(byMap, method == ShadowMethod::Map) << lighting->text;
        expectRedoneScreensWithin80Columns(trace);
    }
}

// The pixel history prints the fragment's weights in the same corner order as the interpolation screen
// (v0, v1, v2 as drawn), on a triangle whose setup exchanged v1 and v2. Catches: the history's λ or λ′
// left in the setup's order (v0, v2, v1), so that a student comparing the two screens finds λ1 and λ2
// swapped.
TEST_F(RedoScreensTest, HistoryWeightsAreInTheDrawnOrderOfTheInterpolationScreen) {
    const PreparedScene prepared = prepareScene(sceneOf(kTriangle));
    const StepTrace trace = walkAt(prepared, vec3(0.0f, -0.1f, 0.0f), 0);
    const Screen* interpolate = screenOf(trace, "interpolate");
    const Screen* history = screenOf(trace, "history");
    ASSERT_NE(interpolate, nullptr);
    ASSERT_NE(history, nullptr);
    ASSERT_NE(interpolate->text.find("Setup exchanged v1 and v2"), std::string::npos) << interpolate->text;
    const std::vector<double> weights = numbersAfter(interpolate->text, "  λ′ = ");
    const std::vector<double> historyWeights = numbersAfter(history->text, "  λ′ = ");
    std::vector<double> lambda;
    for (const char* label : {"  λ0 = ", "  λ1 = ", "  λ2 = "}) {
        // "  λ1 = E / 2A = value": the number after the line's last "= ".
        const std::size_t at = interpolate->text.find(label);
        ASSERT_NE(at, std::string::npos) << label << "\n" << interpolate->text;
        const std::string line = interpolate->text.substr(at, interpolate->text.find('\n', at) - at);
        lambda.push_back(std::strtod(line.c_str() + line.rfind("= ") + 2, nullptr));
    }
    const std::vector<double> historyLambda = numbersAfter(history->text, "  λ  = ");
    ASSERT_EQ(weights.size(), 3u) << interpolate->text;
    ASSERT_EQ(historyWeights.size(), 3u) << history->text;
    ASSERT_EQ(historyLambda.size(), 3u) << history->text;
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(historyWeights[k], weights[k], 1e-5) << "λ′" << k;
        EXPECT_NEAR(historyLambda[k], lambda[k], 1e-5) << "λ" << k;
    }
}

}  // namespace
}  // namespace facet::step
