// The exact reference renderer: its pixels against the lighting equation evaluated by hand at the hit
// point, its determinism, culling, transparency, stratified samples and input it must survive.
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "reference/reference.h"
#include "render/renderer.h"
#include "support/analytic_shadow.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

using glm::dvec3;
using testing_support::TempFolderTest;

// A UV sphere of radius r about the origin, its normals the exact unit radii.
std::string sphereObj(double r, int rings, int segments) {
    std::ostringstream obj;
    obj.precision(17);
    obj << "mtllib sphere.mtl\nusemtl shiny\n";
    for (int i = 0; i <= rings; ++i) {
        const double theta = M_PI * i / rings;
        for (int j = 0; j < segments; ++j) {
            const double phi = 2.0 * M_PI * j / segments;
            const dvec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            obj << "v " << r * n.x << " " << r * n.y << " " << r * n.z << "\n";
            obj << "vn " << n.x << " " << n.y << " " << n.z << "\n";
        }
    }
    const auto index = [&](int i, int j) { return i * segments + (j % segments) + 1; };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const int a = index(i, j), b = index(i, j + 1), c = index(i + 1, j + 1), d = index(i + 1, j);
            // Counter-clockwise seen from outside.
            if (i > 0)
                obj << "f " << a << "//" << a << " " << b << "//" << b << " " << c << "//" << c << "\n";
            if (i < rings - 1)
                obj << "f " << a << "//" << a << " " << c << "//" << c << " " << d << "//" << d << "\n";
        }
    return obj.str();
}

class ReferenceTest : public TempFolderTest {
  protected:
    // The sphere, seen from +z, lit head-on by a directional light travelling along −z; colours as
    // written (no sRGB decoding), so the hand computation needs no transfer curve.
    Scene sphereScene() {
        write("sphere.obj", sphereObj(1.0, 24, 48));
        write("sphere.mtl", "newmtl shiny\nKa 0.2 0.3 0.4\nKd 0.6 0.5 0.4\nKs 0.5 0.5 0.5\nNs 40\n");
        Scene scene;
        scene.source = folder_ / "scene.json";
        scene.width = 48;
        scene.height = 48;
        scene.camera.eye = glm::vec3(0.0f, 0.0f, 4.0f);
        scene.camera.target = glm::vec3(0.0f);
        scene.camera.fovyDegrees = 40.0f;
        scene.camera.near = 1.0f;
        scene.camera.far = 10.0f;
        scene.gamma.decodeInputs = false;
        scene.ambientLight = glm::vec3(0.1f);
        LightSpec light;
        light.type = LightKind::Directional;
        light.direction = glm::vec3(0.0f, 0.0f, -1.0f);
        scene.lights.push_back(light);
        ObjectSpec object;
        object.model = folder_ / "sphere.obj";
        scene.objects.push_back(object);
        return scene;
    }
};

// Where the ray from the eye (the origin of eye space) along d first meets the mesh, found by testing
// every triangle in double, and the normal interpolated there.
struct HandHit {
    double t = std::numeric_limits<double>::infinity();
    dvec3 position{0.0}, normal{0.0};
};
HandHit castByHand(const PreparedDraw& draw, const dvec3& d) {
    HandHit best;
    const glm::dmat3 normalFromObject = glm::transpose(glm::inverse(glm::dmat3(draw.viewFromObjectExact)));
    for (std::size_t k = 0; k + 2 < draw.indices.size(); k += 3) {
        dvec3 p[3], n[3];
        for (int c = 0; c < 3; ++c) {
            const MeshVertex& v = draw.vertices[draw.indices[k + c]];
            p[c] = dvec3(draw.viewFromObjectExact * glm::dvec4(dvec3(v.position), 1.0));
            n[c] = normalFromObject * dvec3(v.normal);
        }
        // Solve t·d = p0 + u·(p1 − p0) + v·(p2 − p0) by Cramer's rule.
        const dvec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
        const glm::dmat3 m(-d, e1, e2);
        const double det = glm::determinant(m);
        if (std::abs(det) < 1e-15) continue;
        const dvec3 x = glm::inverse(m) * (-p[0]);  // (t, u, v)
        if (x.x <= 0 || x.y < 0 || x.z < 0 || x.y + x.z > 1 || x.x >= best.t) continue;
        best.t = x.x;
        best.position = x.x * d;
        best.normal = glm::normalize((1 - x.y - x.z) * n[0] + x.y * n[1] + x.z * n[2]);
    }
    return best;
}

// The standard equation with Blinn-Phong's specular, written out for this scene: one directional light
// with l_d = l_s = 1 and l_a = 0, c = a_global·m_a + max(N·L, 0)·m_d + (N·H)^n·m_s.
dvec3 blinnPhongByHand(const HandHit& hit, const dvec3& lightDirectionEye) {
    const dvec3 ka(0.2, 0.3, 0.4), kd(0.6, 0.5, 0.4), ks(0.5);
    const double n = 40.0, ambient = 0.1;
    const dvec3 L = -glm::normalize(lightDirectionEye);
    const dvec3 V = glm::normalize(-hit.position);
    const dvec3 H = glm::normalize(L + V);
    const double NdotL = glm::dot(hit.normal, L);
    dvec3 c = dvec3(double(float(ambient))) * dvec3(glm::vec3(ka));
    c += std::max(NdotL, 0.0) * dvec3(glm::vec3(kd));
    if (NdotL > 1e-4) c += std::pow(std::max(glm::dot(hit.normal, H), 0.0), n) * dvec3(glm::vec3(ks));
    return c;
}

// A sphere lit head-on: every pixel the sphere covers equals the lighting equation evaluated by hand at
// the point where that pixel's centre ray meets the mesh, to float's rounding of the output: the hit
// point, its interpolated normal, the view vector and the terms are the right ones. (That the formulas
// really run in double is DoubleLanes' test: here the lighting is too well conditioned for float's
// rounding to show above the output's.)
TEST_F(ReferenceTest, SpherePixelsEqualTheLightingEquationByHand) {
    const PreparedScene prepared = prepareScene(sphereScene());
    ThreadPool pool(2);
    const LinearImage image = renderReference(prepared, {.samples = 1}, pool);
    const PreparedDraw& draw = prepared.draws.at(0);
    const dvec3 lightEye = dvec3(prepared.draws[0].uniforms.lights[0].direction);
    const glm::dmat4 viewFromClip = glm::inverse(prepared.camera.clipFromViewExact);
    int checked = 0;
    double worst = 0;
    for (int y = 0; y < image.height; y += 3)
        for (int x = 0; x < image.width; x += 3) {
            const glm::dvec4 near =
                viewFromClip * glm::dvec4(2.0 * (x + 0.5) / image.width - 1.0,
                                          1.0 - 2.0 * (y + 0.5) / image.height, -1.0, 1.0);
            const HandHit hit = castByHand(draw, dvec3(near) / near.w);
            if (!std::isfinite(hit.t)) continue;
            const dvec3 expected = blinnPhongByHand(hit, lightEye);
            for (int c = 0; c < 3; ++c) {
                worst = std::max(worst, std::abs(double(image.at(x, y)[c]) - expected[c]));
                // The image is float: the double result rounded to it, half a unit in the last place.
                EXPECT_NEAR(image.at(x, y)[c], expected[c], 6e-8 * expected[c] + 1e-12) << x << "," << y;
            }
            ++checked;
        }
    EXPECT_GT(checked, 60);
    EXPECT_LT(worst, 1e-7);
}

// The same bytes whatever the number of threads, at one and at several samples per pixel.
TEST_F(ReferenceTest, SameImageForAnyThreadCount) {
    Scene scene = sphereScene();
    scene.lights[0].direction = glm::vec3(-0.5f, -0.7f, -0.4f);
    scene.lights[0].shadows = ShadowMethod::Ray;
    const PreparedScene prepared = prepareScene(scene);
    for (int samples : {1, 3}) {
        ThreadPool one(1), two(2);
        const LinearImage a = renderReference(prepared, {.samples = samples}, one);
        const LinearImage b = renderReference(prepared, {.samples = samples}, two);
        ASSERT_EQ(a.pixels.size(), b.pixels.size());
        EXPECT_EQ(0, std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec4)));
    }
}

// N×N samples are a box filter: a pixel the sphere's silhouette crosses gets a value between the
// background's and the surface's, while the one-sample image has only the two.
TEST_F(ReferenceTest, SamplesAverageAcrossTheSilhouette) {
    Scene scene = sphereScene();
    scene.background = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    const PreparedScene prepared = prepareScene(scene);
    ThreadPool pool(2);
    const LinearImage one = renderReference(prepared, {.samples = 1}, pool);
    const LinearImage many = renderReference(prepared, {.samples = 4}, pool);
    // The pixels the two images tell apart more than the rounding: the silhouette's, where some of the
    // 4×4 samples miss the sphere; inside it every sample lands on it and the means stay close.
    int differing = 0;
    for (std::size_t k = 0; k < many.pixels.size(); ++k)
        if (glm::any(glm::greaterThan(glm::abs(many.pixels[k] - one.pixels[k]), glm::vec4(0.05f))))
            ++differing;
    EXPECT_GT(differing, 20);                           // the silhouette's pixels
    EXPECT_LT(differing, int(many.pixels.size() / 4));  // and not the inside
}

// Supersampling brings the rasterizer towards the reference's box filter at the sphere's silhouette:
// over the pixels the silhouette crosses (where the reference at 8×8 samples differs from its one
// sample at the centre), the error against the 8×8 reference drops from one sample to ssaa4 and again
// to ssaa16. Measured sums of |R|+|G|+|B| over
// its 102 pixels: none 14.26, ssaa4 5.37, ssaa16 2.94, msaa4 5.37 (7.77 when multisampling shaded
// at the pixel centre even where it missed the sphere). Breaks if the passes are not shifted (each ssaa
// image is then the one-sample image) or not averaged, if multisampling tests coverage at the pixel
// centre only (msaa4 is then the one-sample image), or if it shades a silhouette pixel at its centre
// outside the sphere instead of at a covered sample.
TEST_F(ReferenceTest, SupersamplingApproachesTheReferenceAtTheSilhouette) {
    Scene scene = sphereScene();
    scene.background = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    ThreadPool pool(2);
    const LinearImage exact = renderReference(prepareScene(scene), {.samples = 8}, pool);
    const LinearImage centres = renderReference(prepareScene(scene), {.samples = 1}, pool);
    std::vector<std::size_t> silhouette;
    for (std::size_t k = 0; k < exact.pixels.size(); ++k)
        if (glm::any(glm::greaterThan(glm::abs(exact.pixels[k] - centres.pixels[k]), glm::vec4(0.01f))))
            silhouette.push_back(k);
    ASSERT_GT(silhouette.size(), 50u);
    std::vector<double> errors;
    for (const Antialiasing aa :
         {Antialiasing::None, Antialiasing::Ssaa4, Antialiasing::Ssaa16, Antialiasing::Msaa4}) {
        scene.pipeline.antialiasing = aa;
        const PreparedScene prepared = prepareScene(scene);
        Framebuffer target(scene.width, scene.height);
        DrawContext context(2);
        FrameMemory memory;
        renderFrame(prepared, target, context, memory);
        double error = 0;
        for (const std::size_t k : silhouette)
            for (int c = 0; c < 3; ++c)
                error += std::abs(double(target.colorPixels()[k][c]) - double(exact.pixels[k][c]));
        errors.push_back(error);
    }
    std::printf("silhouette error over %zu pixels: none %.4f ssaa4 %.4f ssaa16 %.4f msaa4 %.4f\n",
                silhouette.size(), errors[0], errors[1], errors[2], errors[3]);
    EXPECT_LT(errors[1], 0.6 * errors[0]);
    EXPECT_LT(errors[2], 0.8 * errors[1]);
    // Multisampling at the same 4 samples: the same coverage as ssaa4, each silhouette pixel shaded
    // once, at a sample on the sphere (the centroid rule): within a few percent of ssaa4's error here
    // (shaded at the centre, extrapolated where it misses the sphere, it was 1.45 times ssaa4's).
    EXPECT_LT(errors[3], 0.6 * errors[0]);
    EXPECT_LT(errors[3], 1.1 * errors[1]);
}

// Faces are culled as the scene's pipeline culls them: the sphere seen from inside shows only back faces.
TEST_F(ReferenceTest, CullsBackFacesAsThePipelineDoes) {
    Scene scene = sphereScene();
    scene.camera.eye = glm::vec3(0.0f, 0.0f, 0.5f);
    scene.camera.near = 0.01f;
    ReferenceStats stats;
    ThreadPool pool(1);
    {
        const PreparedScene prepared = prepareScene(scene);
        renderReference(prepared, {.samples = 1}, pool, &stats);
        EXPECT_EQ(stats.surfaceHits, 0u);
    }
    scene.pipeline.cull = CullMode::None;
    const PreparedScene prepared = prepareScene(scene);
    renderReference(prepared, {.samples = 1}, pool, &stats);
    EXPECT_EQ(stats.surfaceHits, std::uint64_t(scene.width) * scene.height);
}

// A mesh with a non-finite corner still renders: the triangle is left out of the BVH (Embree never sees
// a NaN), the rest is drawn.
TEST_F(ReferenceTest, NonFiniteTrianglesAreLeftOut) {
    PreparedScene prepared = prepareScene(sphereScene());
    std::vector<DrawTriangles> triangles;
    for (const PreparedDraw& d : prepared.draws)
        triangles.push_back({{d.vertices.begin(), d.vertices.end()}, {d.indices.begin(), d.indices.end()}});
    triangles[0].vertices[triangles[0].indices[0]].position.x = std::numeric_limits<float>::quiet_NaN();
    triangles[0].vertices[triangles[0].indices[30]].position.y = std::numeric_limits<float>::infinity();
    setTriangles(prepared, std::move(triangles));
    ThreadPool pool(1);
    ReferenceStats stats;
    const LinearImage image = renderReference(prepared, {.samples = 1}, pool, &stats);
    EXPECT_GE(stats.nonFiniteSkipped, 2u);
    EXPECT_GT(stats.surfaceHits, 500u);
    for (const glm::vec4& p : image.pixels)
        ASSERT_TRUE(std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b) && std::isfinite(p.a));
}

}  // namespace
}  // namespace facet

namespace facet {
namespace {

class ReferenceShadowTest : public analytic_shadow::ShadowTest {};

// The reference's shadow where geometry puts it: every ground pixel more than 1.5 px from the outline of
// the square projected from the light is dark inside and lit outside, as in the rasterizer's test
// (tests/render/shadow_test.cpp) — at one sample per pixel, and at 4×4 (whose box filter only blurs the
// outline, within the margin). Breaks if the reference ignores the scene's shadowing lights.
TEST_F(ReferenceShadowTest, RayShadowIsTheSquareProjectedFromTheLight) {
    using namespace analytic_shadow;
    const AnalyticShadowScene scene = floatingSquare();
    const PreparedScene prepared = prepareScene(loadScene(writeScene(scene, "\"ray\"")));
    const std::vector<GroundPixel> pixels = checkedPixels(scene, prepared);
    const double threshold = darkLitThreshold(prepared, pixels);
    ThreadPool pool(2);
    for (int samples : {1, 4}) {
        const LinearImage image = renderReference(prepared, {.samples = samples}, pool);
        EXPECT_EQ(shadowDisagreements(image, pixels, threshold), 0u) << samples << "x" << samples;
    }
    // The same scene asking for a shadow map: the reference still casts rays.
    const PreparedScene mapped = prepareScene(loadScene(writeScene(scene, "\"map\"")));
    EXPECT_EQ(shadowDisagreements(renderReference(mapped, {.samples = 1}, pool), pixels, threshold), 0u);
}

}  // namespace
}  // namespace facet
