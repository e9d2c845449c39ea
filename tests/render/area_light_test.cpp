// A light's range reaches the image (beyond it, the model is unlit), and an area light's soft shadow:
// a square floating over the ground under a rectangle light. Each ground pixel's visibility v (read
// from the diffuse-only image, which is linear in v) is compared with the fraction of the rectangle a
// dense grid in double sees past the square: fully lit and fully shadowed pixels are exactly 1 and 0,
// the penumbra between; the image is the same at one thread and at two.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render/renderer.h"
#include "scene/scene.h"
#include "support/analytic_shadow.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using namespace analytic_shadow;
// Declared here too: a render() of another test file compiled in the same batch (unity build) would
// hide the directive's.
using analytic_shadow::render;

// The rectangle light of the tests: centred at the point light's place, facing down, 1.2 × 1.2.
constexpr double kLightSide = 1.2;

class AreaLightTest : public ShadowTest {
  protected:
    // The analytic scene with its point light replaced by a rectangle (or a point with `light`).
    fs::path writeAreaScene(const AnalyticShadowScene& scene, const std::string& shadows,
                            const std::string& extra = "", const std::string& type = "rect") const {
        const fs::path path = writeScene(scene, shadows);
        std::string text = readText(path);
        const std::string from = "{\"type\": \"point\",";
        std::string to = "{\"type\": \"" + type + "\",";
        if (type == "rect") to += " \"width\": 1.2, \"height\": 1.2, \"direction\": [0, -1, 0],";
        to += extra;
        text.replace(text.find(from), from.size(), to);
        return write("area.json", text);
    }
    static std::string readText(const fs::path& path) {
        std::ifstream in(path);
        return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
};

// Whether the segment from g to l crosses the quad (convex, planar), in double.
bool blocked(const AnalyticShadowScene& scene, glm::dvec3 g, glm::dvec3 l) {
    const auto& q = scene.quad;
    const glm::dvec3 n = glm::cross(q[1] - q[0], q[2] - q[0]);
    const double denominator = glm::dot(n, l - g);
    if (denominator == 0.0) return false;
    const double t = glm::dot(n, q[0] - g) / denominator;
    if (!(t > 0.0 && t < 1.0)) return false;
    const glm::dvec3 p = g + t * (l - g);
    int positive = 0, negative = 0;
    for (int i = 0; i < 4; ++i) {
        const double side = glm::dot(glm::cross(q[(i + 1) % 4] - q[i], p - q[i]), n);
        positive += side > 0;
        negative += side < 0;
    }
    return positive == 0 || negative == 0;
}

// The fraction of the rectangle light (horizontal, centred at scene.light) that ground point g sees,
// on a 32×32 grid of cell centres.
double visibleFraction(const AnalyticShadowScene& scene, glm::dvec3 g) {
    constexpr int m = 32;
    int seen = 0;
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
            const glm::dvec3 l = scene.light + glm::dvec3(((i + 0.5) / m - 0.5) * kLightSide, 0.0,
                                                          ((j + 0.5) / m - 0.5) * kLightSide);
            seen += !blocked(scene, g, l);
        }
    return double(seen) / (m * m);
}

// The ground point a pixel centre sees (the quad's pixels are excluded by the caller), or none.
std::optional<glm::dvec3> groundPoint(const PreparedScene& prepared, int x, int y) {
    const glm::dmat4 worldFromClip = glm::inverse(clipFromWorld(prepared));
    const glm::dvec2 ndc(2.0 * (x + 0.5) / kWidth - 1.0, 1.0 - 2.0 * (y + 0.5) / kHeight);
    const glm::dvec4 a4 = worldFromClip * glm::dvec4(ndc, -0.5, 1.0),
                     b4 = worldFromClip * glm::dvec4(ndc, 0.5, 1.0);
    const glm::dvec3 a = glm::dvec3(a4) / a4.w, b = glm::dvec3(b4) / b4.w;
    if (!(b.y < a.y)) return std::nullopt;
    return a + (b - a) * (a.y / (a.y - b.y));
}

struct PenumbraCheck {
    std::size_t umbra = 0, umbraWrong = 0, lit = 0, litWrong = 0, penumbra = 0, fractional = 0;
    double meanError = 0;
};

// v per ground pixel (the diffuse-only image shadowed over unshadowed) against the dense fraction.
PenumbraCheck checkPenumbra(const AnalyticShadowScene& scene, const PreparedScene& shadowed,
                            const LinearImage& diffuse, const LinearImage& unshadowedDiffuse,
                            const std::vector<GroundPixel>& pixels) {
    PenumbraCheck c;
    double errorSum = 0;
    for (const GroundPixel& p : pixels) {
        const std::optional<glm::dvec3> g = groundPoint(shadowed, p.x, p.y);
        if (!g) continue;
        const double lit = brightness(unshadowedDiffuse.at(p.x, p.y));
        if (lit < 0.05) continue;
        const double v = brightness(diffuse.at(p.x, p.y)) / lit;
        const double f = visibleFraction(scene, *g);
        if (f == 0.0) {
            ++c.umbra;
            c.umbraWrong += v != 0.0;
        } else if (f == 1.0) {
            ++c.lit;
            c.litWrong += std::abs(v - 1.0) > 1e-5;
        } else {
            ++c.penumbra;
            c.fractional += v > 0.0 && v < 1.0 - 1e-5;
            errorSum += std::abs(v - f);
        }
    }
    c.meanError = c.penumbra ? errorSum / double(c.penumbra) : 0.0;
    return c;
}

// The soft shadow where geometry puts it: pixels that see none of the light are exactly 0 (bar a few
// next to the umbra's edge, where a 16-sample pattern and the dense grid can disagree), those that see
// all of it exactly 1, and the penumbra has fractional v close to the fraction of the light seen.
// Breaks if the visibility is one ray to the centre (no fractional pixels), if the samples lie off the
// emitter (wrong umbra or lit pixels) or if v is not the fraction of samples seen (large mean error).
TEST_F(AreaLightTest, SoftShadowMatchesTheFractionOfTheLightSeen) {
    const AnalyticShadowScene scene = floatingSquare();
    const PreparedScene shadowed = prepareScene(loadScene(writeAreaScene(scene, "\"ray\"")));
    const PreparedScene unshadowed = prepareScene(loadScene(writeAreaScene(scene, "\"none\"")));
    const std::vector<GroundPixel> pixels =
        groundPixels(scene, clipFromWorld(shadowed), kWidth, kHeight, 1.5);
    const PenumbraCheck c = checkPenumbra(scene, shadowed, render(shadowed, kDiffuseTerm),
                                          render(unshadowed, kDiffuseTerm), pixels);
    EXPECT_GT(c.umbra, 100u);
    EXPECT_GT(c.lit, 2000u);
    EXPECT_GT(c.penumbra, 300u);
    EXPECT_LE(c.umbraWrong, c.umbra / 50);
    EXPECT_LE(c.litWrong, c.lit / 50);
    EXPECT_GT(c.fractional, c.penumbra * 2 / 3);  // the rest see < 1/16 or > 15/16 of it
    EXPECT_LT(c.meanError, 0.06) << "16 samples";
    // More samples come closer to the truth: --area-samples reaches every area light.
    Scene many = loadScene(writeAreaScene(scene, "\"ray\""));
    many.areaSamples = 256;
    const PreparedScene fine = prepareScene(many);
    const PenumbraCheck f =
        checkPenumbra(scene, fine, render(fine, kDiffuseTerm), render(unshadowed, kDiffuseTerm), pixels);
    EXPECT_LT(f.meanError, c.meanError);
    EXPECT_LT(f.meanError, 0.02) << "256 samples";
    std::printf("penumbra pixels %zu: mean |v - fraction| %.4f at 16 samples, %.4f at 256\n", c.penumbra,
                c.meanError, f.meanError);
}

// The same bytes at one thread and at two. Breaks if the samples depend on the thread or the tile.
TEST_F(AreaLightTest, SameImageAtAnyThreadCount) {
    const AnalyticShadowScene scene = floatingSquare();
    const PreparedScene prepared = prepareScene(loadScene(writeAreaScene(scene, "\"ray\"")));
    Framebuffer one(kWidth, kHeight), two(kWidth, kHeight);
    DrawContext single(1), dual(2);
    renderFrame(prepared, one, single);
    renderFrame(prepared, two, dual);
    EXPECT_EQ(toImage(one).pixels, toImage(two).pixels);
}

// Without shadows an area light lights as a point light at its centre times the emitter's cosine: the
// ground straight below it gets exactly the point light's light (cos = 1). Breaks if the emitter cosine
// is missing or inverted (the ground is lit from a light facing away).
TEST_F(AreaLightTest, UnshadowedAreaLightIsItsCentreTimesTheEmitterCosine) {
    const AnalyticShadowScene scene = floatingSquare();
    const LinearImage area = render(prepareScene(loadScene(writeAreaScene(scene, "\"none\""))), kDiffuseTerm);
    const LinearImage point = render(prepareScene(loadScene(writeScene(scene, "\"none\""))), kDiffuseTerm);
    std::size_t brighter = 0, darker = 0;
    for (std::size_t i = 0; i < area.pixels.size(); ++i) {
        brighter += brightness(area.pixels[i]) > brightness(point.pixels[i]) + 1e-6;
        darker += brightness(area.pixels[i]) < brightness(point.pixels[i]) - 1e-6;
    }
    EXPECT_EQ(brighter, 0u);
    EXPECT_GT(darker, 1000u);
    // Facing up, away from the ground: no light reaches it.
    const fs::path up = writeAreaScene(scene, "\"none\"");
    std::string text = readText(up);
    text.replace(text.find("\"direction\": [0, -1, 0]"), 23, "\"direction\": [0, 1, 0]");
    const LinearImage facingAway = render(prepareScene(loadScene(write("up.json", text))), kDiffuseTerm);
    for (const vec4& p : facingAway.pixels)
        ASSERT_EQ(brightness(p), 0.0);
}

// A range shorter than the distance to the model: that light leaves it unlit (the diffuse and specular
// images black); a long range changes the image only a little, and no range is the image without
// the key. Breaks if "range" never reaches the shaders, or the window is applied inside out.
TEST_F(AreaLightTest, RangeShorterThanTheDistanceLeavesTheModelUnlit) {
    const AnalyticShadowScene scene = floatingSquare();  // the light is 3.4 above the ground
    const LinearImage plain =
        render(prepareScene(loadScene(writeScene(scene, ""))), kDiffuseTerm | kSpecularTerm);
    const auto withLight = [&](const std::string& extra) {
        return render(prepareScene(loadScene(writeAreaScene(scene, "", extra, "point"))),
                      kDiffuseTerm | kSpecularTerm);
    };
    EXPECT_EQ(withLight("").pixels, plain.pixels);
    const LinearImage shortRange = withLight(" \"range\": 1.0,");
    for (const vec4& p : shortRange.pixels)
        ASSERT_EQ(brightness(p), 0.0);
    const LinearImage longRange = withLight(" \"range\": 40,");
    EXPECT_NE(longRange.pixels, plain.pixels);
    double plainSum = 0, longSum = 0;
    for (std::size_t i = 0; i < plain.pixels.size(); ++i) {
        plainSum += brightness(plain.pixels[i]);
        longSum += brightness(longRange.pixels[i]);
    }
    EXPECT_LT(longSum, plainSum);
    EXPECT_GT(longSum, 0.99 * plainSum);
}

}  // namespace
}  // namespace facet
