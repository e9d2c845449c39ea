// The step mode's trace (step/trace.h, walk.h, views.h): what it records of a frame and what its screens
// say, checked against numbers computed by hand here. Each test names the one-line break it catches.
#include "step/trace.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "base/errors.h"
#include "pipeline/clip.h"
#include "step/views.h"
#include "step/walk.h"
#include "support/temp_folder.h"
#include "support/test_shaders.h"

namespace facet::step {
namespace {

namespace fs = std::filesystem;

// Whether `part` is in `text`, the line breaks and indentation of wrapped lines read as one space.
bool contains(const std::string& text, const std::string& part) {
    std::string flat;
    for (char c : text)
        if (!(c == ' ' && !flat.empty() && flat.back() == ' ')) flat += c == '\n' ? ' ' : c;
    return text.find(part) != std::string::npos || flat.find(part) != std::string::npos;
}

const Screen* screenOf(const Walk& walk, const std::string& id) {
    for (const Screen& s : walk.screens)
        if (s.id == id) return &s;
    return nullptr;
}

const TriangleAtPixel* entryOf(const PixelTrace& p, std::uint32_t number) {
    for (const TriangleAtPixel& e : p.triangles)
        if (e.ref.number == number) return &e;
    return nullptr;
}

// The JSON names each fate by its table: every fate has one name, and no two share one. Catches: a fate
// added to the enum without a name (nameOf would give "?"), or a name copied onto a second fate.
TEST(PixelHistory, EveryFateHasItsOwnName) {
    std::set<std::string_view> names;
    for (int k = 0; k <= static_cast<int>(PixelFate::Stored); ++k) {
        const std::string_view name = nameOf(static_cast<PixelFate>(k));
        EXPECT_NE(name, "?") << k;
        EXPECT_TRUE(names.insert(name).second) << name;
    }
    EXPECT_EQ(std::size(kPixelFateNames), names.size());
}

// ---- the recorder on draw() with shaders of the test's own, positions given in clip space ----

using testing::ClipSpaceColorShader;
using Vertex = ClipSpaceColorShader::Attributes;

constexpr int kSide = 16;  // a 16×16 target: window x = (x_ndc + 1)·8, exact in float

// Clip-space position of window point (x, y) at depth z_ndc, w = 1.
vec4 atWindow(float x, float y, float zNdc = 0.0f) {
    return vec4(x / 8.0f - 1.0f, 1.0f - y / 8.0f, zNdc, 1.0f);
}

DrawState targetState() {
    DrawState state;
    state.viewport = {0, 0, kSide, kSide};
    state.raster.cull = CullMode::None;
    return state;
}

FrameShape shapeOf(std::uint32_t triangles) {
    FrameShape shape;
    shape.width = shape.height = kSide;
    shape.firstNumberOfDraw = {0};
    (void)triangles;
    return shape;
}

// One draw of `vertices`/`indices` with shader S, watched; returns the trace of `pixel`.
template <class S = ClipSpaceColorShader>
PixelTrace traceDraw(std::span<const typename S::Attributes> vertices, std::span<const std::uint32_t> indices,
                     std::pair<int, int> pixel, const DrawState& state = targetState(),
                     const typename S::Uniforms& uniforms = {}) {
    TraceRequest request;
    request.pixels = {pixel};
    TraceRecorder recorder(request, shapeOf(static_cast<std::uint32_t>(indices.size() / 3)), 64);
    Framebuffer target(kSide, kSide);
    DrawContext context(1);
    target.clear(vec4(0.0f), 1.0f, context.pool);
    recorder.beginCall(0, state, indices, vertices.size());
    draw<S>(state, uniforms, vertices, indices, target, context, recorder);
    return std::move(recorder.finish(target).pixels.front());
}

// Two triangles share the vertical edge x = 8.5 from y = 2 to 14; pixel (8, 8)'s centre (8.5, 8.5) lies
// exactly on it. For the right triangle it is a left edge (the triangle lies to its right): the fill
// rule gives it the pixel; for the left triangle it is a right edge, and the tie is lost.
// Catches: the recorder calling every uncovered pixel "outside an edge" (no LostTie), or the owner
// not searched (tieOwner empty), or isTopLeft reversed in setup (the left triangle would own it).
TEST(PixelHistory, SharedEdgeThroughACentreNamesTheOwnerAndTheTieLost) {
    const std::vector<Vertex> vertices = {
        {atWindow(2, 8), vec4(1, 0, 0, 1)},     {atWindow(8.5f, 2), vec4(1, 0, 0, 1)},
        {atWindow(8.5f, 14), vec4(1, 0, 0, 1)}, {atWindow(8.5f, 2), vec4(0, 1, 0, 1)},
        {atWindow(15, 8), vec4(0, 1, 0, 1)},    {atWindow(8.5f, 14), vec4(0, 1, 0, 1)}};
    const std::vector<std::uint32_t> indices = {0, 1, 2, 3, 4, 5};
    const PixelTrace p = traceDraw(std::span(vertices), std::span(indices), {8, 8});
    ASSERT_EQ(p.triangles.size(), 2u);
    const TriangleAtPixel& left = p.triangles[0];
    const TriangleAtPixel& right = p.triangles[1];
    EXPECT_EQ(left.fate, PixelFate::LostTie);
    ASSERT_TRUE(left.coverage);
    EXPECT_NE(left.coverage->tiesExcluded(), 0);
    ASSERT_TRUE(left.tieOwner);
    EXPECT_EQ(left.tieOwner->number, 1u);
    EXPECT_EQ(right.fate, PixelFate::Written);
    EXPECT_NE(right.coverage->tiesIncluded(), 0);
    EXPECT_EQ(p.finalBytes[1], 255);  // green: the right triangle's colour
    const std::string history = historyScreen(p).text;
    EXPECT_TRUE(contains(history, "lost a tie")) << history;
    EXPECT_TRUE(contains(history, "triangle 1 owns the pixel")) << history;
    EXPECT_TRUE(contains(history, "* triangle 1:")) << history;
}

// A far triangle drawn after a near one over the same pixel fails the depth test; its history line
// gives both depths and the compare. Catches: depthBefore not recorded (0 printed), or the fate of a
// DepthFailed fragment taken as Written (the coverage's provisional fate kept).
TEST(PixelHistory, OccludedFragmentShowsItsFailedDepthTestWithBothDepths) {
    const float nearZ = -0.5f, farZ = 0.5f;  // window depths 0.25 and 0.75
    const std::vector<Vertex> vertices = {
        {atWindow(1, 1, nearZ), vec4(1, 0, 0, 1)},  {atWindow(15, 1, nearZ), vec4(1, 0, 0, 1)},
        {atWindow(1, 15, nearZ), vec4(1, 0, 0, 1)}, {atWindow(1, 1, farZ), vec4(0, 0, 1, 1)},
        {atWindow(15, 1, farZ), vec4(0, 0, 1, 1)},  {atWindow(1, 15, farZ), vec4(0, 0, 1, 1)}};
    const std::vector<std::uint32_t> indices = {0, 1, 2, 3, 4, 5};
    const PixelTrace p = traceDraw(std::span(vertices), std::span(indices), {4, 4});
    ASSERT_EQ(p.triangles.size(), 2u);
    const TriangleAtPixel& occluded = p.triangles[1];
    EXPECT_EQ(occluded.fate, PixelFate::DepthFailed);
    ASSERT_TRUE(occluded.fragment);
    EXPECT_FLOAT_EQ(occluded.fragment->depth, 0.75f);
    EXPECT_FLOAT_EQ(occluded.fragment->depthBefore, 0.25f);
    EXPECT_EQ(p.producer, 0u);
    const std::string history = historyScreen(p).text;
    EXPECT_TRUE(contains(history, "depth test failed: 0.75 < 0.25 is false")) << history;
    EXPECT_TRUE(contains(verdictOf(p), "the shader computed this colour: triangle 0")) << verdictOf(p);
}

// A shader that discards the left half of the target.
struct DiscardLeftShader {
    using Attributes = Vertex;
    struct Varyings {
        vec4 color;
    };
    struct Uniforms {};
    static VertexOut<Varyings> vertex(const Attributes& in, const Uniforms&) {
        return {in.position, {in.color}};
    }
    static std::optional<vec4> fragment(const Varyings& in, const Uniforms&) {
        if (in.color.r > 0.5f) return std::nullopt;
        return in.color;
    }
};

// Catches: FragmentFate::Discarded mapped to anything but PixelFate::Discarded, and the verdict not
// saying that everything was rejected.
TEST(PixelHistory, DiscardedFragmentIsReportedAsDiscarded) {
    const std::vector<Vertex> vertices = {{atWindow(1, 1), vec4(1, 0, 0, 1)},
                                          {atWindow(15, 1), vec4(1, 0, 0, 1)},
                                          {atWindow(1, 15), vec4(1, 0, 0, 1)}};
    const std::vector<std::uint32_t> indices = {0, 1, 2};
    const PixelTrace p = traceDraw<DiscardLeftShader>(std::span(vertices), std::span(indices), {3, 3});
    ASSERT_EQ(p.triangles.size(), 1u);
    EXPECT_EQ(p.triangles[0].fate, PixelFate::Discarded);
    EXPECT_FALSE(p.producer);
    EXPECT_TRUE(contains(historyScreen(p).text, "discarded by the fragment shader"));
    EXPECT_TRUE(contains(verdictOf(p), "everything was rejected")) << verdictOf(p);
}

// Catches: a pixel outside every box given a history (the bounding box test inverted), or the verdict
// of an empty history not saying "nothing drew here".
TEST(PixelHistory, PixelNoTriangleCameNearSaysNothingDrewHere) {
    const std::vector<Vertex> vertices = {
        {atWindow(1, 1), vec4(1)}, {atWindow(5, 1), vec4(1)}, {atWindow(1, 5), vec4(1)}};
    const std::vector<std::uint32_t> indices = {0, 1, 2};
    const PixelTrace p = traceDraw(std::span(vertices), std::span(indices), {12, 12});
    EXPECT_TRUE(p.triangles.empty());
    EXPECT_TRUE(contains(verdictOf(p), "nothing drew here")) << verdictOf(p);
}

// ---- a scene through traceStep ----

class StepTraceTest : public testing_support::TempFolderTest {
  protected:
    // A 64×48 scene of one OBJ, seen from (0, 0, 5) looking down −z, near 1, far 10, fovy 60°.
    Scene sceneOf(const std::string& obj) const {
        Scene scene;
        scene.source = folder_ / "scene.json";
        scene.width = 64;
        scene.height = 48;
        scene.camera.eye = vec3(0.0f, 0.0f, 5.0f);
        scene.camera.target = vec3(0.0f, 0.0f, 0.0f);
        scene.camera.near = 1.0f;
        scene.camera.far = 10.0f;
        scene.camera.fovyDegrees = 60.0f;
        ObjectSpec object;
        object.model = write("model.obj", obj);
        scene.objects.push_back(object);
        return scene;
    }
};

// The clipping of the two tests below, whose triangle ABC has C alone in front of the near plane:
// outcodes 0, 0, near; one cut, by the near plane, making two vertices, each at t = 4/4.6 from an inside
// vertex towards C, on the near plane z_clip = nearSign·w (−w under OpenGL's depth range, w under
// reversed Z).
void expectOneNearPlaneCut(const TriangleTrace& t, float nearSign) {
    EXPECT_EQ(t.outcodes[0], 0);
    EXPECT_EQ(t.outcodes[1], 0);
    EXPECT_EQ(t.outcodes[2], kClipNear);
    ASSERT_EQ(t.clipSteps.size(), 1u);
    const ClipStep& step = t.clipSteps[0];
    EXPECT_EQ(step.plane, kClipNear);
    ASSERT_EQ(step.made.size(), 2u);
    for (const ClipStep::NewVertex& made : step.made) {
        EXPECT_NEAR(made.t, 4.0 / 4.6, 1e-5);
        EXPECT_EQ(made.to, 2);  // towards C, the outside vertex
        EXPECT_NEAR(made.position.z, nearSign * made.position.w, 1e-5);
    }
}

// A triangle reaching from z = 0 to z = 4.6, 0.4 in front of the eye: the near plane (eye
// distance 1, world z = 4) cuts it. By hand: the clipper's t on edge A→C is where z_eye = −1 along
// z_eye = −5 → −0.4, t = (−5 + 1)/(−5 + 0.4) = 4/4.6, and the new vertex is A + t·(C − A).
// Catches: the clip steps recorded from the wrong vertex (t measured from the outside vertex: 1 − t),
// a plane missing from the record, the window coordinates of the pieces not the viewport transform of
// the clipped polygon, the pixel's barycentrics not E_i / 2A.
TEST_F(StepTraceTest, TriangleCutByTheNearPlaneMatchesHandComputationStageByStage) {
    Scene scene = sceneOf("v -1 -0.5 0\nv 1 -0.5 0\nv 0 -0.1 4.6\nf 2 1 3\n");
    // One point light with attenuation 1/(1 + 0.5·d + 0.25·d²), above the triangle.
    LightSpec light;
    light.type = LightKind::Point;
    light.position = vec3(0.0f, 1.0f, 3.0f);
    light.attenuation = vec3(1.0f, 0.5f, 0.25f);
    scene.lights = {light};
    const PreparedScene prepared = prepareScene(scene);
    DrawContext context(1);
    // The pixel of the triangle's point (0, −0.239, 3), inside what is left after clipping.
    const vec4 clip = prepared.camera.clipFromView * prepared.camera.viewFromWorld * vec4(0, -0.239f, 3, 1);
    const int px = int((clip.x / clip.w + 1) * 0.5f * 64), py = int((1 - clip.y / clip.w) * 0.5f * 48);
    StepRequest request;
    request.pixel = std::pair(px, py);
    request.triangle = 0;
    const StepTrace trace = traceStep(prepared, context, request);
    ASSERT_TRUE(trace.triangle);
    const TriangleTrace& t = *trace.triangle;

    expectOneNearPlaneCut(t, -1.0f);  // the near plane at z_clip = −w
    ASSERT_EQ(t.clipSteps.size(), 1u);
    const ClipStep& step = t.clipSteps[0];
    ASSERT_EQ(step.polygon.size(), 4u);
    // Drawn as a fan of two pieces, whose window vertices are the viewport transform of the polygon.
    ASSERT_EQ(t.pieces.size(), 2u);
    const vec4& q2 = step.polygon[2];
    const double xw = (double(q2.x) / q2.w + 1) * 0.5 * 64, yw = (1 - double(q2.y) / q2.w) * 0.5 * 48;
    EXPECT_NEAR(t.pieces[0].vertices[2].window.x, xw, 1e-3);
    EXPECT_NEAR(t.pieces[0].vertices[2].window.y, yw, 1e-3);
    EXPECT_EQ(t.pieces[0].vertices[2].xFixed, std::llround(t.pieces[0].vertices[2].window.x * 256));

    // The pixel: covered by one piece; λ_i = E_i / 2A of that piece's setup, at the pixel centre.
    const TriangleAtPixel* entry = entryOf(trace.pixel, 0);
    ASSERT_NE(entry, nullptr);
    ASSERT_TRUE(entry->fragment);
    EXPECT_EQ(entry->fate, PixelFate::Written);
    bool found = false;
    for (const WindowPiece& piece : t.pieces) {
        const std::int64_t X = std::int64_t(px) * 256 + 128, Y = std::int64_t(py) * 256 + 128;
        std::int64_t E[3];
        for (int i = 0; i < 3; ++i)
            E[i] = piece.setup.edges[i].a * X + piece.setup.edges[i].b * Y + piece.setup.edges[i].c;
        if (E[0] < 0 || E[1] < 0 || E[2] < 0) continue;
        found = true;
        EXPECT_EQ(E[0] + E[1] + E[2], piece.setup.doubleArea);  // the edge functions sum to 2A
        for (int i = 0; i < 3; ++i)
            EXPECT_NEAR(entry->fragment->barycentrics[i], double(E[i]) / double(piece.setup.doubleArea),
                        1e-6);
    }
    EXPECT_TRUE(found);
    // The history's perspective weights use the covering piece's corners: they sum to 1 only with the
    // 1/w of the corners that 1/w at the pixel was interpolated from (catches another piece's taken).
    ASSERT_TRUE(entry->cornerInvW);
    const vec3 weights = entry->fragment->barycentrics * *entry->cornerInvW / entry->fragment->invW;
    EXPECT_NEAR(weights.x + weights.y + weights.z, 1.0, 1e-5);

    // The light, by hand: d from the fragment's eye-space position (its interpolated varyings) to the
    // light's, then att = 1/(c0 + c1·d + c2·d²) and N·L with the interpolated normal, normalised.
    ASSERT_TRUE(trace.shading);
    const LightRecord& lit = trace.shading->fragment.lighting.lighting.lights[0];
    const glm::dvec3 P(entry->fragment->varyings[0], entry->fragment->varyings[1],
                       entry->fragment->varyings[2]);
    const glm::dvec3 N = glm::normalize(
        glm::dvec3(entry->fragment->varyings[3], entry->fragment->varyings[4], entry->fragment->varyings[5]));
    const glm::dvec3 lightEye =
        glm::dvec3(prepared.camera.viewFromWorldExact * glm::dvec4(0.0, 1.0, 3.0, 1.0));
    const double d = glm::length(lightEye - P);
    const double att = 1.0 / (1.0 + 0.5 * d + 0.25 * d * d);
    EXPECT_NEAR(lit.distance, d, 1e-5);
    EXPECT_NEAR(lit.attenuation, att, 1e-6);
    EXPECT_NEAR(lit.NdotL, glm::dot(N, glm::normalize(lightEye - P)), 1e-5);
    EXPECT_TRUE(trace.shading->matchesPipeline);
    const Screen* lighting = screenOf(trace.walk, "lighting");
    ASSERT_NE(lighting, nullptr);
    char attLine[128];
    std::snprintf(attLine, sizeof attLine,
                  "att = 1/(c0 + c1·d + c2·d²) = 1/(1 + 0.5·%.4g + 0.25·%.4g²) = %.4g", d, d, att);
    EXPECT_TRUE(contains(lighting->text, attLine)) << attLine << "\n" << lighting->text;

    // The screens say so, in numbers.
    const Screen* clipScreen = screenOf(trace.walk, "clip");
    ASSERT_NE(clipScreen, nullptr);
    EXPECT_TRUE(contains(clipScreen->title, "near")) << clipScreen->title;
    EXPECT_TRUE(contains(clipScreen->text, "= " + number(step.made[0].t) + "\n")) << clipScreen->text;
    EXPECT_TRUE(contains(clipScreen->text, "outside near")) << clipScreen->text;
    const Screen* window = screenOf(trace.walk, "window");
    ASSERT_NE(window, nullptr);
    EXPECT_TRUE(contains(window->text, std::to_string(t.pieces[0].vertices[2].xFixed) + "/256"))
        << window->text;
    const Screen* interpolate = screenOf(trace.walk, "interpolate");
    ASSERT_NE(interpolate, nullptr);
    EXPECT_TRUE(contains(interpolate->text, "λ0 = " + std::to_string(entry->coverage->edgeValues[0]) + " / "))
        << interpolate->text;
}

// The same triangle under reversed Z, whose projection puts the near plane at z_clip = w and the far
// plane at z_clip = 0: the trace replays the clipper against those planes (the same cut, t = 4/4.6,
// new vertices at z = w) and the screen states them. Catches the replay against −w ≤ z ≤ w, which
// takes the vertex before the near plane for one beyond the far plane.
TEST_F(StepTraceTest, ReversedZClipsAtTheReversedNearPlane) {
    Scene scene = sceneOf("v -1 -0.5 0\nv 1 -0.5 0\nv 0 -0.1 4.6\nf 2 1 3\n");
    scene.pipeline.depth = DepthBufferFormat::ReversedFloat;
    const PreparedScene prepared = prepareScene(scene);
    DrawContext context(1);
    const vec4 clip = prepared.camera.clipFromView * prepared.camera.viewFromWorld * vec4(0, -0.239f, 3, 1);
    StepRequest request;
    request.pixel = std::pair(int((clip.x / clip.w + 1) * 0.5f * 64), int((1 - clip.y / clip.w) * 0.5f * 48));
    request.triangle = 0;
    const StepTrace trace = traceStep(prepared, context, request);
    ASSERT_TRUE(trace.triangle);
    const TriangleTrace& t = *trace.triangle;
    expectOneNearPlaneCut(t, 1.0f);  // the near plane at z_clip = w
    ASSERT_EQ(t.clipSteps.size(), 1u);
    const ClipStep& step = t.clipSteps[0];
    const Screen* clipScreen = screenOf(trace.walk, "clip");
    ASSERT_NE(clipScreen, nullptr);
    EXPECT_TRUE(contains(clipScreen->text, "0 ≤ z ≤ w")) << clipScreen->text;
    EXPECT_TRUE(contains(clipScreen->text, "near   (z ≤ w,  d = w − z; reversed Z)")) << clipScreen->text;
    EXPECT_TRUE(contains(clipScreen->text, "= " + number(step.made[0].t) + "\n")) << clipScreen->text;
    const Screen* window = screenOf(trace.walk, "window");
    ASSERT_NE(window, nullptr);
    EXPECT_TRUE(contains(window->text, "z_w = d_near + z_ndc·(d_far − d_near)")) << window->text;
}

// The three numbers of "(a, b, c)" right after `marker` in `text`; empty when the marker is missing.
std::vector<double> tripleAfter(const std::string& text, const std::string& marker) {
    const std::size_t at = text.find(marker);
    if (at == std::string::npos) return {};
    const char* p = text.c_str() + at + marker.size();
    if (*p++ != '(') return {};
    std::vector<double> values;
    for (int i = 0; i < 3; ++i) {
        char* end = nullptr;
        values.push_back(std::strtod(p, &end));
        if (end == p || *end != (i < 2 ? ',' : ')')) return {};
        p = end + 1;
    }
    return values;
}

// The number ending the line that begins with `marker` ("  λ0 = 120 / 345 = 0.347826"): what follows
// the line's last "= ".
std::optional<double> lineValue(const std::string& text, const std::string& marker) {
    const std::size_t at = text.find(marker);
    if (at == std::string::npos) return std::nullopt;
    const std::string line = text.substr(at, text.find('\n', at) - at);
    return std::strtod(line.c_str() + line.rfind("= ") + 2, nullptr);
}

// A screen's printed λ and λ′ against the test's own: the corners in the order of the printed λ
// (the setup may exchange two), then each printed λ′_i within `tolerance` of the lecture's value.
void expectPrintedWeights(const std::vector<double>& printedLambda, const std::vector<double>& printedPrime,
                          const glm::dvec3& lambda, const glm::dvec3& prime, double tolerance) {
    ASSERT_EQ(printedLambda.size(), 3u);
    ASSERT_EQ(printedPrime.size(), 3u);
    int order[3] = {0, 1, 2};
    bool matched = false;
    do {
        matched = true;
        for (int i = 0; i < 3; ++i)
            matched = matched && std::abs(printedLambda[i] - lambda[order[i]]) <= tolerance;
    } while (!matched && std::next_permutation(order, order + 3));
    ASSERT_TRUE(matched) << "printed λ (" << printedLambda[0] << ", " << printedLambda[1] << ", "
                         << printedLambda[2] << "), computed (" << lambda.x << ", " << lambda.y << ", "
                         << lambda.z << ")";
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(printedPrime[i], prime[order[i]], tolerance) << i;
}

// A triangle slanting away from the eye (its corners at w = 2, 5 and 9), Gouraud-shaded: every screen
// that prints the perspective-correct weights prints the lecture's λ′_i = (λ_i/w_i) / Σ_j (λ_j/w_j),
// computed here from the corners' window positions (snapped to 1/256 pixel, as the rasterizer does)
// and their w: the pixel history's λ′, the interpolation screen's λ′ and the lighting screen's λ′. The
// affine weights λ differ from them by more than 0.05 here. Catches any of the three printing the
// screen-space λ (or weights from the wrong corners' 1/w) as the perspective-correct ones: views.cpp's
// history and interpolation screens, shading_view.cpp's Gouraud mix.
TEST_F(StepTraceTest, PerspectiveWeightsOnEveryScreenAreTheLecturesFromTheCornersW) {
    const glm::dvec3 corners[3] = {{-1.2, -0.9, 3.0}, {2.0, -1.0, 0.0}, {0.0, 1.5, -4.0}};
    Scene scene = sceneOf("v -1.2 -0.9 3\nv 2 -1 0\nv 0 1.5 -4\nf 1 2 3\n");
    scene.lighting.shading = ShadingFrequency::Gouraud;
    const PreparedScene prepared = prepareScene(scene);
    DrawContext context(1);
    const glm::dmat4 clipFromWorld = prepared.camera.clipFromViewExact * prepared.camera.viewFromWorldExact;
    glm::dvec2 window[3];
    double w[3];
    for (int i = 0; i < 3; ++i) {
        const glm::dvec4 clip = clipFromWorld * glm::dvec4(corners[i], 1.0);
        w[i] = clip.w;
        window[i] = glm::dvec2(std::llround((clip.x / clip.w + 1) * 0.5 * 64 * 256) / 256.0,
                               std::llround((1 - clip.y / clip.w) * 0.5 * 48 * 256) / 256.0);
    }
    EXPECT_NEAR(w[0], 2.0, 1e-9);
    EXPECT_NEAR(w[2], 9.0, 1e-9);
    // The pixel of the world-space centroid (whose screen-space λ is not (1/3, 1/3, 1/3)).
    const glm::dvec4 centroid = clipFromWorld * glm::dvec4((corners[0] + corners[1] + corners[2]) / 3.0, 1.0);
    const int px = int((centroid.x / centroid.w + 1) * 0.5 * 64);
    const int py = int((1 - centroid.y / centroid.w) * 0.5 * 48);
    const glm::dvec2 centre(px + 0.5, py + 0.5);
    const auto area = [](glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
        return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    };
    const double whole = area(window[0], window[1], window[2]);
    glm::dvec3 lambda, prime;
    for (int i = 0; i < 3; ++i)
        lambda[i] = area(centre, window[(i + 1) % 3], window[(i + 2) % 3]) / whole;
    const double invW = lambda[0] / w[0] + lambda[1] / w[1] + lambda[2] / w[2];
    for (int i = 0; i < 3; ++i)
        prime[i] = lambda[i] / w[i] / invW;
    EXPECT_GT(std::max({std::abs(prime[0] - lambda[0]), std::abs(prime[1] - lambda[1]),
                        std::abs(prime[2] - lambda[2])}),
              0.05);

    StepRequest request;
    request.pixel = std::pair(px, py);
    const StepTrace trace = traceStep(prepared, context, request);
    ASSERT_TRUE(trace.shading);
    ASSERT_TRUE(trace.shading->weightsMatchCorners);  // unclipped: the λ′ line is printed

    // Printed to 6 significant digits ("%.6g"); the pipeline's float arithmetic adds a little.
    const Screen* history = screenOf(trace.walk, "history");
    ASSERT_NE(history, nullptr);
    {
        SCOPED_TRACE(history->text);
        expectPrintedWeights(tripleAfter(history->text, "  λ  = "), tripleAfter(history->text, "  λ′ = "),
                             lambda, prime, 2e-5);
    }
    const Screen* interpolate = screenOf(trace.walk, "interpolate");
    ASSERT_NE(interpolate, nullptr);
    {
        SCOPED_TRACE(interpolate->text);
        std::vector<double> printedLambda;
        for (const char* marker : {"  λ0 = ", "  λ1 = ", "  λ2 = "})
            if (const std::optional<double> value = lineValue(interpolate->text, marker))
                printedLambda.push_back(*value);
        expectPrintedWeights(printedLambda, tripleAfter(interpolate->text, "  λ′ = "), lambda, prime, 2e-5);
    }
    // The lighting screen prints 4 significant digits ("%.4g").
    const Screen* lighting = screenOf(trace.walk, "lighting");
    ASSERT_NE(lighting, nullptr);
    {
        SCOPED_TRACE(lighting->text);
        expectPrintedWeights(tripleAfter(lighting->text, "  λ = (λ0, λ1, λ2) = "),
                             tripleAfter(lighting->text, "  λ′_i = (λ_i/w_i)/(1/w): λ′ = "), lambda, prime,
                             2e-4);
    }
}

// With no --pixel, the covered pixel nearest the centre; with no --triangle, the one that gave it its
// colour. Catches: the default pixel taken as the image centre whatever it shows, or the default
// triangle as the first in the history rather than the producer.
TEST_F(StepTraceTest, DefaultsAreTheCoveredPixelNearestTheCentreAndItsProducer) {
    // A small triangle right of centre: the centre itself is background.
    const Scene scene = sceneOf(
        "v 0.5 -0.3 0\nv 1.5 -0.3 0\nv 1 0.5 0\nf 1 2 3\n"
        "v 0.6 -0.2 -1\nv 1.4 -0.2 -1\nv 1 0.4 -1\nf 4 5 6\n");
    const PreparedScene prepared = prepareScene(scene);
    DrawContext context(1);
    const StepTrace trace = traceStep(prepared, context, {});
    const std::vector<bool> covered = coveredPixels(prepared, context, kAllTerms);
    EXPECT_TRUE(covered[std::size_t(trace.walk.y) * 64 + trace.walk.x]);
    EXPECT_FALSE(covered[std::size_t(24) * 64 + 32]);
    EXPECT_LT(trace.walk.x, 44);  // the left edge of the triangle, not the middle of it
    ASSERT_TRUE(trace.walk.triangle);
    ASSERT_TRUE(trace.pixel.producer);
    EXPECT_EQ(*trace.walk.triangle, trace.pixel.triangles[*trace.pixel.producer].ref);
}

// Triangles are numbered over the draws in order: the second object's first triangle is number 1, and
// its history and walk say so. Catches: a draw's numbers offset by another draw's count (a stray entry
// in FrameShape::firstNumberOfDraw), or the numbering restarting at 0 in every draw.
TEST_F(StepTraceTest, TrianglesAreNumberedAcrossTheDrawsInOrder) {
    Scene scene = sceneOf("v -2 -1 0\nv -0.5 -1 0\nv -1.25 1 0\nf 1 2 3\n");
    ObjectSpec second;
    second.model = write("second.obj", "v 0.5 -1 0\nv 2 -1 0\nv 1.25 1 0\nf 1 2 3\n");
    scene.objects.push_back(second);
    const PreparedScene prepared = prepareScene(scene);
    ASSERT_EQ(prepared.draws.size(), 2u);
    EXPECT_EQ(triangleCount(prepared), 2u);
    const std::optional<TriangleRef> ref = triangleByNumber(prepared, 1);
    ASSERT_TRUE(ref);
    EXPECT_EQ(ref->draw, 1u);
    EXPECT_EQ(ref->triangle, 0u);
    DrawContext context(1);
    const vec4 clip = prepared.camera.clipFromView * prepared.camera.viewFromWorld * vec4(1.25f, -0.3f, 0, 1);
    StepRequest request;
    request.pixel = std::pair(int((clip.x / clip.w + 1) * 32), int((1 - clip.y / clip.w) * 24));
    const StepTrace trace = traceStep(prepared, context, request);
    ASSERT_TRUE(trace.walk.triangle);
    EXPECT_EQ(trace.walk.triangle->number, 1u);
    EXPECT_EQ(trace.walk.triangle->draw, 1u);
    EXPECT_TRUE(contains(trace.walk.verdict, "triangle 1's fragment")) << trace.walk.verdict;
}

// A back face smaller than the gap between pixel centres is culled before its box is worked out; its
// setup screen says both: culled, and that kept it would have covered no pixel (no edge functions of a
// setup that was never made). The scene's pixels are 0.1203 units wide at z = 0, and world (0, 0) is
// the corner of pixels (31, 23) to (32, 24): the triangle's box, ±0.03, holds no centre.
// Catches: the screen printing the would-be setup's edges for a culled triangle that has none.
TEST_F(StepTraceTest, CulledTriangleBetweenPixelCentresSaysItWouldCoverNoPixel) {
    const PreparedScene prepared =
        prepareScene(sceneOf("v -0.03 -0.03 0\nv 0.03 -0.03 0\nv 0 0.03 0\nf 1 3 2\n"));
    DrawContext context(1);
    StepRequest request;
    request.pixel = std::pair(32, 24);
    request.triangle = 0;
    const StepTrace trace = traceStep(prepared, context, request);
    const Screen* setup = screenOf(trace.walk, "setup");
    ASSERT_NE(setup, nullptr);
    EXPECT_EQ(setup->title, "Setup: culled for its facing");
    EXPECT_TRUE(contains(setup->text, "Back-facing, and that side is culled")) << setup->text;
    EXPECT_TRUE(contains(setup->text, "Kept, it would have covered no pixel")) << setup->text;
    EXPECT_FALSE(contains(setup->text, "Edge functions")) << setup->text;
}

// Catches: a pixel outside the image or a triangle beyond the scene's accepted (and read out of range).
TEST_F(StepTraceTest, PixelOutsideTheImageAndTriangleBeyondTheSceneAreRefused) {
    const PreparedScene prepared = prepareScene(sceneOf("v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n"));
    DrawContext context(1);
    StepRequest outside;
    outside.pixel = std::pair(64, 0);
    try {
        traceStep(prepared, context, outside);
        ADD_FAILURE() << "pixel 64,0 accepted";
    } catch (const InputError& e) {
        EXPECT_TRUE(contains(e.what(), "outside the image, which is 64x48")) << e.what();
    }
    StepRequest beyond;
    beyond.triangle = 1;
    try {
        traceStep(prepared, context, beyond);
        ADD_FAILURE() << "triangle 1 accepted";
    } catch (const InputError& e) {
        EXPECT_TRUE(contains(e.what(), "there is no triangle 1: the scene has 1")) << e.what();
    }
}

// The web page's walks, traced many at once, are the walks `facet step --pixel` prints, screen for
// screen. Catches: a view matched to the wrong pixel in traceWalks (its raster centred elsewhere),
// or a pixel given another triangle than its default.
TEST(TraceWalks, ManyAtOnceAreTheWalksOfOneAtATime) {
    Scene scene = loadSceneOrModel(fs::path(FACET_SOURCE_DIR) / "models/spot/spot_triangulated.obj");
    scene.width = 96;
    scene.height = 72;
    const PreparedScene prepared = prepareScene(scene);
    DrawContext context(1);
    const std::vector<std::pair<int, int>> pixels = {{48, 36}, {0, 0}, {40, 30}, {47, 35}, {60, 20}};
    const std::vector<Walk> walks = traceWalks(prepared, context, pixels);
    ASSERT_EQ(walks.size(), pixels.size());
    for (std::size_t k = 0; k < pixels.size(); ++k) {
        StepRequest request;
        request.pixel = pixels[k];
        EXPECT_EQ(printWalk(walks[k]), printWalk(traceStep(prepared, context, request).walk))
            << pixels[k].first << "," << pixels[k].second;
    }
}

}  // namespace
}  // namespace facet::step
