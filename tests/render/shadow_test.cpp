// Ray-cast shadows drawn: a square floating above a ground plane under a point light casts the shadow
// geometry predicts (its corners projected from the light onto the ground), pixel for pixel away from
// the outline; in shadow a pixel keeps exactly its ambient and emission and loses its diffuse and
// specular; a scene without shadowing lights builds no BVH; the BVH survives triangles Embree must not
// see and moves with the turntable.
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render/renderer.h"
#include "scene/scene.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

// ---- the analytic shadow of a square on a plane -----------------------------------------------------

// A convex quad above the ground plane y = 0 and a point light above it (world space).
struct AnalyticShadowScene {
    std::array<glm::dvec3, 4> quad;  // counter-clockwise seen from above
    glm::dvec3 light;
};

// The shadow's outline on the ground: each corner C projected from the light L onto y = 0,
// L + (C − L) · L.y / (L.y − C.y) (the corners are below the light).
std::array<glm::dvec3, 4> shadowOutline(const AnalyticShadowScene& scene) {
    std::array<glm::dvec3, 4> outline;
    for (int i = 0; i < 4; ++i) {
        const glm::dvec3 c = scene.quad[i], l = scene.light;
        outline[i] = l + (c - l) * (l.y / (l.y - c.y));
    }
    return outline;
}

// Whether p lies inside the convex polygon (any winding), in the plane of coordinates a and b.
template <std::size_t N>
bool insideConvex(const std::array<glm::dvec2, N>& polygon, glm::dvec2 p) {
    int positive = 0, negative = 0;
    for (std::size_t i = 0; i < N; ++i) {
        const glm::dvec2 a = polygon[i], b = polygon[(i + 1) % N];
        const double side = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
        positive += side > 0;
        negative += side < 0;
    }
    return positive == 0 || negative == 0;
}

double distanceToSegment(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
    const glm::dvec2 ab = b - a;
    const double s = glm::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
    return glm::length(p - (a + s * ab));
}

template <std::size_t N>
double distanceToOutline(const std::array<glm::dvec2, N>& polygon, glm::dvec2 p) {
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < N; ++i)
        d = std::min(d, distanceToSegment(p, polygon[i], polygon[(i + 1) % N]));
    return d;
}

// Where a world point lands in the image: x right, y down from the top row, in pixels (pixel (x, y)
// covers [x, x+1) × [y, y+1), its centre at +0.5).
glm::dvec2 imagePoint(const glm::dmat4& clipFromWorld, glm::dvec3 world, int width, int height) {
    const glm::dvec4 clip = clipFromWorld * glm::dvec4(world, 1.0);
    const glm::dvec2 ndc(clip.x / clip.w, clip.y / clip.w);
    return {(ndc.x + 1.0) * 0.5 * width, (1.0 - ndc.y) * 0.5 * height};
}

// A pixel whose centre sees the ground, and whether that point of the ground is in the shadow.
struct GroundPixel {
    int x, y;
    bool inShadow;
};

// The pixels of a width × height image of `scene` (seen through `clipFromWorld`) whose centre's ray
// from the eye meets the ground, not the quad, more than `margin` pixels from the shadow's outline
// and from the quad's: there the answer is certain whatever the rasterizer's edge rules. For each, whether
// the ground point is inside the shadow (the outline polygon, in the ground's x–z coordinates).
std::vector<GroundPixel> groundPixels(const AnalyticShadowScene& scene, const glm::dmat4& clipFromWorld,
                                      int width, int height, double margin) {
    const std::array<glm::dvec3, 4> outline = shadowOutline(scene);
    std::array<glm::dvec2, 4> outlineOnGround, outlineInImage, quadInImage;
    for (int i = 0; i < 4; ++i) {
        outlineOnGround[i] = {outline[i].x, outline[i].z};
        outlineInImage[i] = imagePoint(clipFromWorld, outline[i], width, height);
        quadInImage[i] = imagePoint(clipFromWorld, scene.quad[i], width, height);
    }
    const glm::dmat4 worldFromClip = glm::inverse(clipFromWorld);
    std::vector<GroundPixel> pixels;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const glm::dvec2 centre(x + 0.5, y + 0.5);
            // Under the quad (the quad is between the eye and the ground) or near either outline: skip.
            if (insideConvex(quadInImage, centre) || distanceToOutline(quadInImage, centre) <= margin ||
                distanceToOutline(outlineInImage, centre) <= margin)
                continue;
            // The pixel centre's ray: two points of it unprojected, then met with y = 0.
            const glm::dvec2 ndc(2.0 * centre.x / width - 1.0, 1.0 - 2.0 * centre.y / height);
            const glm::dvec4 nearClip = worldFromClip * glm::dvec4(ndc, -0.5, 1.0);
            const glm::dvec4 farClip = worldFromClip * glm::dvec4(ndc, 0.5, 1.0);
            const glm::dvec3 a = glm::dvec3(nearClip) / nearClip.w, b = glm::dvec3(farClip) / farClip.w;
            if (!(b.y < a.y)) continue;  // looking up: never meets the ground
            const glm::dvec3 ground = a + (b - a) * (a.y / (a.y - b.y));
            pixels.push_back({x, y, insideConvex(outlineOnGround, {ground.x, ground.z})});
        }
    }
    return pixels;
}

double brightness(const vec4& pixel) {
    return double(pixel.r) + pixel.g + pixel.b;
}

// How many of `pixels` the image gets wrong: dark (brightness below `threshold`) outside the shadow, or
// lit inside it. For any renderer's image of the scene (the rasterizer's, the reference's).
std::size_t shadowDisagreements(const LinearImage& image, std::span<const GroundPixel> pixels,
                                double threshold) {
    std::size_t wrong = 0;
    for (const GroundPixel& p : pixels) {
        const bool dark = brightness(image.at(p.x, p.y)) < threshold;
        if (dark != p.inShadow) {
            if (wrong < 5)
                ADD_FAILURE() << "pixel (" << p.x << ", " << p.y << ") is " << (dark ? "dark" : "lit")
                              << " but the ground there is " << (p.inShadow ? "in shadow" : "lit");
            ++wrong;
        }
    }
    return wrong;
}

// ---- the scene, as files ---------------------------------------------------------------------------

constexpr int kWidth = 160, kHeight = 120;

// The quad: side 1.4 centred at (0.8, 1.2, −0.3), turned 25° about y and tilted 12° about x; the
// light at (0.2, 3.4, 0.1). Off the turntable's axis (the ground's centre), so that turning moves it.
AnalyticShadowScene floatingSquare() {
    AnalyticShadowScene scene;
    const glm::dmat4 place = glm::translate(glm::dmat4(1.0), glm::dvec3(0.8, 1.2, -0.3)) *
                             glm::rotate(glm::dmat4(1.0), glm::radians(25.0), glm::dvec3(0, 1, 0)) *
                             glm::rotate(glm::dmat4(1.0), glm::radians(12.0), glm::dvec3(1, 0, 0));
    const double s = 0.7;
    const glm::dvec3 local[4] = {{-s, 0, -s}, {-s, 0, s}, {s, 0, s}, {s, 0, -s}};
    for (int i = 0; i < 4; ++i)
        scene.quad[i] = glm::dvec3(place * glm::dvec4(local[i], 1.0));
    scene.light = {0.2, 3.4, 0.1};
    return scene;
}

std::string objVertex(glm::dvec3 p) {
    std::string line = "v ";
    line += std::to_string(p.x);
    line += ' ';
    line += std::to_string(p.y);
    line += ' ';
    line += std::to_string(p.z);
    line += '\n';
    return line;
}

class ShadowTest : public testing_support::TempFolderTest {
  protected:
    // The OBJ of a quad (two triangles, counter-clockwise seen from above), plus `extra` lines.
    fs::path writeQuad(const std::string& name, const std::array<glm::dvec3, 4>& corners,
                       const std::string& extra = "") const {
        std::string text;
        for (const glm::dvec3& c : corners)
            text += objVertex(c);
        text += "f 1 2 3\nf 1 3 4\n";
        text += extra;
        return write(name, text);
    }

    // The scene file: a 40 × 40 ground, the quad, the point light with `shadows` (a JSON value, or
    // empty for none given; "no light" for a scene without lights), the camera looking down at it.
    fs::path writeScene(const AnalyticShadowScene& scene, const std::string& shadows,
                        const std::string& quadExtra = "") const {
        writeQuad("ground.obj", {glm::dvec3(-20, 0, -20), glm::dvec3(-20, 0, 20), glm::dvec3(20, 0, 20),
                                 glm::dvec3(20, 0, -20)});
        writeQuad("quad.obj", scene.quad, quadExtra);
        std::string light = "{\"type\": \"point\", \"position\": [";
        light += std::to_string(scene.light.x) + ", " + std::to_string(scene.light.y) + ", ";
        light += std::to_string(scene.light.z);
        light += "], \"ambient\": [0.2, 0.2, 0.2]";  // the light's own ambient stays in its shadow
        if (!shadows.empty()) {
            light += ", \"shadows\": ";
            light += shadows;
        }
        light += "}";
        std::string text = R"({"width": 160, "height": 120, "ambient": [0.3, 0.3, 0.3],
            "camera": {"eye": [0, 4.5, 5], "target": [0, 0, 0], "fovy": 40, "near": 0.5, "far": 60},
            "objects": [
              {"model": "ground.obj", "material": {"diffuse": [0.8, 0.8, 0.8], "specular": [0.3, 0.3, 0.3],
                "shininess": 4, "emission": [0.05, 0.03, 0]}},
              {"model": "quad.obj", "material": {"diffuse": [0.2, 0.4, 0.9], "emission": [0.1, 0, 0]}}],
            "lights": [)";
        if (shadows != "no light") text += light;
        text += "]}";
        return write("scene.json", text);
    }
};

LinearImage render(const PreparedScene& prepared, std::uint8_t terms = kAllTerms) {
    Framebuffer framebuffer(prepared.scene.width, prepared.scene.height);
    DrawContext context(2);
    renderFrame(prepared, framebuffer, context, terms);
    return toImage(framebuffer);
}

glm::dmat4 clipFromWorld(const PreparedScene& prepared) {
    return prepared.camera.clipFromViewExact * prepared.camera.viewFromWorldExact;
}

// The brightness between the ground's ambient-only value and its lit one, over `pixels`: dark below,
// lit above. Checks that the two are well apart (the light reaches every pixel's ground brightly).
double darkLitThreshold(const PreparedScene& prepared, std::span<const GroundPixel> pixels) {
    const LinearImage ambient = render(prepared, kAmbientTerm | kEmissionTerm);
    double brightestAmbient = 0, dimmestLit = 1e30;
    const LinearImage full = render(prepared);
    for (const GroundPixel& p : pixels) {
        brightestAmbient = std::max(brightestAmbient, brightness(ambient.at(p.x, p.y)));
        if (!p.inShadow) dimmestLit = std::min(dimmestLit, brightness(full.at(p.x, p.y)));
    }
    EXPECT_GT(dimmestLit, 2.0 * brightestAmbient);
    return 0.5 * (brightestAmbient + dimmestLit);
}

// The pixels the analytic check covers: enough of both kinds for it to mean something.
std::vector<GroundPixel> checkedPixels(const AnalyticShadowScene& scene, const PreparedScene& prepared) {
    std::vector<GroundPixel> pixels = groundPixels(scene, clipFromWorld(prepared), kWidth, kHeight, 1.5);
    std::size_t inShadow = 0;
    for (const GroundPixel& p : pixels)
        inShadow += p.inShadow;
    EXPECT_GT(inShadow, 400u);
    EXPECT_GT(pixels.size() - inShadow, 5000u);
    return pixels;
}

// ---- the shadow where geometry puts it ---------------------------------------------------------------

// Every ground pixel more than 1.5 px from the outline is dark inside the projected square and lit
// outside it. Breaks if visibility is ignored (lighting.h: no pixel dark), if the shadow ray goes the
// wrong way or to the wrong place (dark pixels elsewhere), or if the ray's origin is not lifted off
// the surface (ε = 0: the ground shadows itself, acne).
TEST_F(ShadowTest, RayShadowIsTheSquareProjectedFromTheLight) {
    const AnalyticShadowScene scene = floatingSquare();
    const PreparedScene prepared = prepareScene(loadScene(writeScene(scene, "\"ray\"")));
    const std::vector<GroundPixel> pixels = checkedPixels(scene, prepared);
    const LinearImage image = render(prepared);
    EXPECT_EQ(shadowDisagreements(image, pixels, darkLitThreshold(prepared, pixels)), 0u);
}

// In shadow a pixel is exactly its ambient and emission (as the ambient-only image draws them), and
// outside it exactly the unshadowed image: the shadow takes the light's diffuse and specular, and only
// where the ray is blocked. The ambient-only image is the same with shadows or without; the
// diffuse-only image is black in the shadow. Breaks if the visibility also scales the ambient term
// (or the emission), or scales a lit pixel by anything but 1, or is ignored for the specular term.
TEST_F(ShadowTest, ShadowKeepsAmbientAndEmissionAndTakesDiffuseAndSpecular) {
    const AnalyticShadowScene scene = floatingSquare();
    const PreparedScene shadowed = prepareScene(loadScene(writeScene(scene, "\"ray\"")));
    const PreparedScene unshadowed = prepareScene(loadScene(writeScene(scene, "\"none\"")));
    const std::vector<GroundPixel> pixels = checkedPixels(scene, shadowed);

    const LinearImage ambientShadowed = render(shadowed, kAmbientTerm | kEmissionTerm);
    const LinearImage ambientUnshadowed = render(unshadowed, kAmbientTerm | kEmissionTerm);
    EXPECT_EQ(ambientShadowed.pixels, ambientUnshadowed.pixels);
    const LinearImage ambientOnly = render(shadowed, kAmbientTerm);
    const LinearImage emissionOnly = render(shadowed, kEmissionTerm);
    EXPECT_EQ(ambientOnly.pixels, render(unshadowed, kAmbientTerm).pixels);
    EXPECT_EQ(emissionOnly.pixels, render(unshadowed, kEmissionTerm).pixels);

    const LinearImage full = render(shadowed), fullUnshadowed = render(unshadowed);
    const LinearImage diffuse = render(shadowed, kDiffuseTerm), specular = render(shadowed, kSpecularTerm);
    const LinearImage diffuseUnshadowed = render(unshadowed, kDiffuseTerm);
    const LinearImage specularUnshadowed = render(unshadowed, kSpecularTerm);
    std::size_t inShadow = 0, specularInShadow = 0;
    for (const GroundPixel& p : pixels) {
        SCOPED_TRACE(testing::Message() << "pixel " << p.x << ", " << p.y);
        if (p.inShadow) {
            ++inShadow;
            ASSERT_EQ(full.at(p.x, p.y), ambientShadowed.at(p.x, p.y));
            ASSERT_EQ(diffuse.at(p.x, p.y), vec4(0, 0, 0, 1));
            ASSERT_EQ(specular.at(p.x, p.y), vec4(0, 0, 0, 1));
            ASSERT_GT(brightness(diffuseUnshadowed.at(p.x, p.y)), 0.1);
            specularInShadow += brightness(specularUnshadowed.at(p.x, p.y)) > 0.01;
        } else {
            ASSERT_EQ(full.at(p.x, p.y), fullUnshadowed.at(p.x, p.y));
            ASSERT_EQ(diffuse.at(p.x, p.y), diffuseUnshadowed.at(p.x, p.y));
        }
    }
    EXPECT_GT(inShadow, 400u);
    EXPECT_GT(specularInShadow, 50u);  // the light's highlight lies in the shadow: specular goes too
}

// ---- plumbing ---------------------------------------------------------------------------------------

// No light casts shadows: nothing is built, no draw points at shadows (the shaders skip the test
// entirely). One that does: the BVH, the SceneShadows with its method and ε, every draw pointing at it;
// a shadow map light: no BVH. Breaks if prepareShadows builds the BVH unconditionally or for any
// shadowing light, or forgets to point a draw at the shadows.
TEST_F(ShadowTest, BvhIsBuiltOnlyForAShadowingLight) {
    const AnalyticShadowScene scene = floatingSquare();
    for (const char* none : {"", "\"none\"", "false"}) {
        SCOPED_TRACE(none);
        const PreparedScene prepared = prepareScene(loadScene(writeScene(scene, none)));
        EXPECT_EQ(prepared.rays, nullptr);
        EXPECT_EQ(prepared.shadows, nullptr);
        EXPECT_TRUE(prepared.shadowMaps.empty());
        for (const PreparedDraw& d : prepared.draws)
            EXPECT_EQ(d.uniforms.shadows, nullptr);
    }
    for (const char* ray : {"\"ray\"", "true"}) {
        SCOPED_TRACE(ray);
        const PreparedScene prepared = prepareScene(loadScene(writeScene(scene, ray)));
        ASSERT_NE(prepared.rays, nullptr);
        ASSERT_NE(prepared.shadows, nullptr);
        EXPECT_EQ(prepared.shadows->rays, prepared.rays.get());
        EXPECT_EQ(prepared.shadows->lights[0].method, ShadowMethod::Ray);
        EXPECT_EQ(prepared.shadows->lights[1].method, ShadowMethod::None);
        EXPECT_FLOAT_EQ(prepared.shadows->rayOffset, kShadowRayOffset * prepared.sceneExtent);
        EXPECT_GT(prepared.shadows->rayOffset, 0.0f);
        EXPECT_EQ(prepared.rays->stats().triangles, 4u);  // the ground's two and the quad's two
        ASSERT_EQ(prepared.draws.size(), 2u);
        for (const PreparedDraw& d : prepared.draws)
            EXPECT_EQ(d.uniforms.shadows, prepared.shadows.get());
    }
    // A shadow map needs no BVH.
    const PreparedScene mapped = prepareScene(loadScene(writeScene(scene, "\"map\"")));
    EXPECT_EQ(mapped.rays, nullptr);
    ASSERT_NE(mapped.shadows, nullptr);
    EXPECT_EQ(mapped.shadows->rays, nullptr);
    EXPECT_EQ(mapped.shadows->lights[0].method, ShadowMethod::Map);
    EXPECT_EQ(mapped.draws[0].uniforms.shadows, mapped.shadows.get());
}

// The command line's --shadows (Scene::shadows) overrides every light's, the default light's too when
// the file has none: that light then casts the square's shadow onto the ground (some ground pixels
// darker than without). And --shadows none turns a file's "ray" off. Breaks if the default light is
// left out of the methods (it is added after the file's lights are read), or Scene::shadows is ignored.
TEST_F(ShadowTest, CommandLineShadowsReachEveryLightTheDefaultOneToo) {
    const AnalyticShadowScene scene = floatingSquare();
    Scene noLights = loadScene(writeScene(scene, "no light"));
    const LinearImage unshadowed = render(prepareScene(noLights));
    noLights.shadows = ShadowMethod::Ray;
    const PreparedScene prepared = prepareScene(noLights);
    EXPECT_EQ(prepared.shadowMethods[0], ShadowMethod::Ray);
    ASSERT_NE(prepared.rays, nullptr);
    const LinearImage shadowed = render(prepared);
    std::size_t darker = 0;
    for (std::size_t i = 0; i < shadowed.pixels.size(); ++i)
        darker += brightness(shadowed.pixels[i]) < 0.8 * brightness(unshadowed.pixels[i]);
    EXPECT_GT(darker, 200u);

    Scene rayInFile = loadScene(writeScene(scene, "\"ray\""));
    rayInFile.shadows = ShadowMethod::None;
    const PreparedScene off = prepareScene(rayInFile);
    EXPECT_EQ(off.rays, nullptr);
    EXPECT_EQ(off.shadows, nullptr);
}

// ---- robustness -------------------------------------------------------------------------------------

// Degenerate triangles in the quad's model (a repeated corner, three corners on a line, a sliver of
// zero area) change nothing: the shadow is still exactly the square's. Breaks if such a triangle
// upsets the BVH (Embree's robust mode is meant to take them) or the renderer drops the model.
TEST_F(ShadowTest, DegenerateTrianglesLeaveTheShadowExact) {
    const AnalyticShadowScene scene = floatingSquare();
    const std::string degenerate = "f 1 1 2\nf 1 2 1\nf 3 3 3\nv " + std::to_string(scene.quad[0].x) + " " +
                                   std::to_string(scene.quad[0].y) + " " + std::to_string(scene.quad[0].z) +
                                   "\nf 1 5 2\n";
    const PreparedScene prepared = prepareScene(loadScene(writeScene(scene, "\"ray\"", degenerate)));
    ASSERT_NE(prepared.rays, nullptr);
    const std::vector<GroundPixel> pixels = checkedPixels(scene, prepared);
    EXPECT_EQ(shadowDisagreements(render(prepared), pixels, darkLitThreshold(prepared, pixels)), 0u);
}

// A draw holding triangles with a NaN and an infinite corner (as a model scaled past the float range
// gives in eye space) before the BVH is built: they are counted and left out, the frame renders, and
// the square's shadow is still exact. Breaks if a non-finite corner reaches Embree (the BVH's bounds
// become NaN: rays miss everything or Embree fails) or the renderer gives up on the frame.
TEST_F(ShadowTest, NonFiniteTrianglesAreLeftOutOfTheBvhAndTheShadowStays) {
    const AnalyticShadowScene scene = floatingSquare();
    PreparedScene prepared = prepareScene(loadScene(writeScene(scene, "\"ray\"")));
    ASSERT_EQ(prepared.draws.size(), 2u);
    PreparedDraw& quad = prepared.draws[1];
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    for (const vec3 bad : {vec3(nan, 0, 0), vec3(0, inf, 0), vec3(-inf, nan, 1e30f)}) {
        const auto first = static_cast<std::uint32_t>(quad.vertices.size());
        MeshVertex corner = quad.vertices[0];
        quad.vertices.push_back(corner);
        corner.position = bad;
        quad.vertices.push_back(corner);
        corner = quad.vertices[2];
        quad.vertices.push_back(corner);
        quad.indices.insert(quad.indices.end(), {first, first + 1, first + 2});
    }
    prepareShadows(prepared);
    ASSERT_NE(prepared.rays, nullptr);
    EXPECT_EQ(prepared.rays->stats().nonFiniteSkipped, 3u);
    const std::vector<GroundPixel> pixels = checkedPixels(scene, prepared);
    const LinearImage image = render(prepared);
    std::size_t covered = 0;
    for (const vec4& pixel : image.pixels)
        covered += pixel != prepared.clearColor;
    EXPECT_EQ(covered, image.pixels.size());  // the ground fills the frame
    EXPECT_EQ(shadowDisagreements(image, pixels, darkLitThreshold(prepared, pixels)), 0u);
}

// ---- turntable ----------------------------------------------------------------------------------------

// Turned on the turntable, the square's shadow is where the turned square's corners project: the BVH
// is rebuilt from the objects as placed now. Turning back gives the first image again. Breaks if
// setTurntable does not rebuild the shadows (the shadow stays where the square was).
TEST_F(ShadowTest, TurntableMovesTheShadowWithTheObjects) {
    const AnalyticShadowScene scene = floatingSquare();
    PreparedScene prepared = prepareScene(loadScene(writeScene(scene, "\"ray\"")));
    const LinearImage first = render(prepared);
    for (const float degrees : {90.0f, 200.0f}) {
        SCOPED_TRACE(degrees);
        setTurntable(prepared, degrees);
        ASSERT_NE(prepared.rays, nullptr);
        AnalyticShadowScene turned = scene;
        const glm::dvec3 c(prepared.turntableCentre);
        const glm::dmat4 turn =
            glm::translate(glm::dmat4(1.0), c) *
            glm::rotate(glm::dmat4(1.0), glm::radians(double(degrees)), glm::dvec3(0, 1, 0)) *
            glm::translate(glm::dmat4(1.0), -c);
        for (glm::dvec3& corner : turned.quad)
            corner = glm::dvec3(turn * glm::dvec4(corner, 1.0));
        const std::vector<GroundPixel> pixels = checkedPixels(turned, prepared);
        EXPECT_EQ(shadowDisagreements(render(prepared), pixels, darkLitThreshold(prepared, pixels)), 0u);
    }
    setTurntable(prepared, 0.0f);
    EXPECT_EQ(render(prepared).pixels, first.pixels);
}

}  // namespace
}  // namespace facet
