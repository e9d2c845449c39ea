// The analytic shadow of a square floating above a ground plane under a point light: the scene (as
// files), the ground pixels whose centres see the ground with whether geometry puts them in the shadow
// (the square's corners projected from the light onto the ground), and the count of pixels an image
// gets wrong. Shared by the rasterizer's shadow tests (tests/render/shadow_test.cpp) and the reference
// renderer's (tests/reference/).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "render/renderer.h"
#include "scene/scene.h"
#include "support/temp_folder.h"

namespace facet::analytic_shadow {

namespace fs = std::filesystem;

// ---- the analytic shadow of a square on a plane -----------------------------------------------------

// A convex quad above the ground plane y = 0 and a point light above it (world space).
struct AnalyticShadowScene {
    std::array<glm::dvec3, 4> quad;  // counter-clockwise seen from above
    glm::dvec3 light;
};

// The shadow's outline on the ground: each corner C projected from the light L onto y = 0,
// L + (C − L) · L.y / (L.y − C.y) (the corners are below the light).
inline std::array<glm::dvec3, 4> shadowOutline(const AnalyticShadowScene& scene) {
    std::array<glm::dvec3, 4> outline;
    for (int i = 0; i < 4; ++i) {
        const glm::dvec3 c = scene.quad[i], l = scene.light;
        outline[i] = l + (c - l) * (l.y / (l.y - c.y));
    }
    return outline;
}

// Whether p lies inside the convex polygon (any winding), in the plane of coordinates a and b.
template <std::size_t N>
inline bool insideConvex(const std::array<glm::dvec2, N>& polygon, glm::dvec2 p) {
    int positive = 0, negative = 0;
    for (std::size_t i = 0; i < N; ++i) {
        const glm::dvec2 a = polygon[i], b = polygon[(i + 1) % N];
        const double side = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
        positive += side > 0;
        negative += side < 0;
    }
    return positive == 0 || negative == 0;
}

inline double distanceToSegment(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
    const glm::dvec2 ab = b - a;
    const double s = glm::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
    return glm::length(p - (a + s * ab));
}

template <std::size_t N>
inline double distanceToOutline(const std::array<glm::dvec2, N>& polygon, glm::dvec2 p) {
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < N; ++i)
        d = std::min(d, distanceToSegment(p, polygon[i], polygon[(i + 1) % N]));
    return d;
}

// Where a world point lands in the image: x right, y down from the top row, in pixels (pixel (x, y)
// covers [x, x+1) × [y, y+1), its centre at +0.5).
inline glm::dvec2 imagePoint(const glm::dmat4& clipFromWorld, glm::dvec3 world, int width, int height) {
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
inline std::vector<GroundPixel> groundPixels(const AnalyticShadowScene& scene,
                                             const glm::dmat4& clipFromWorld, int width, int height,
                                             double margin) {
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

inline double brightness(const vec4& pixel) {
    return double(pixel.r) + pixel.g + pixel.b;
}

// How many of `pixels` the image gets wrong: dark (brightness below `threshold`) outside the shadow, or
// lit inside it. For any renderer's image of the scene (the rasterizer's, the reference's).
inline std::size_t shadowDisagreements(const LinearImage& image, std::span<const GroundPixel> pixels,
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

inline constexpr int kWidth = 160, kHeight = 120;

// The quad: side 1.4 centred at (0.8, 1.2, −0.3), turned 25° about y and tilted 12° about x; the
// light at (0.2, 3.4, 0.1). Off the turntable's axis (the ground's centre), so that turning moves it.
inline AnalyticShadowScene floatingSquare() {
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

inline std::string objVertex(glm::dvec3 p) {
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

inline LinearImage render(const PreparedScene& prepared, std::uint8_t terms = kAllTerms) {
    Framebuffer framebuffer(prepared.scene.width, prepared.scene.height);
    DrawContext context(2);
    renderFrame(prepared, framebuffer, context, terms);
    return toImage(framebuffer);
}

inline glm::dmat4 clipFromWorld(const PreparedScene& prepared) {
    return prepared.camera.clipFromViewExact * prepared.camera.viewFromWorldExact;
}

// The brightness between the ground's ambient-only value and its lit one, over `pixels`: dark below,
// lit above. Checks that the two are well apart (the light reaches every pixel's ground brightly).
inline double darkLitThreshold(const PreparedScene& prepared, std::span<const GroundPixel> pixels) {
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
inline std::vector<GroundPixel> checkedPixels(const AnalyticShadowScene& scene,
                                              const PreparedScene& prepared) {
    std::vector<GroundPixel> pixels = groundPixels(scene, clipFromWorld(prepared), kWidth, kHeight, 1.5);
    std::size_t inShadow = 0;
    for (const GroundPixel& p : pixels)
        inShadow += p.inShadow;
    EXPECT_GT(inShadow, 400u);
    EXPECT_GT(pixels.size() - inShadow, 5000u);
    return pixels;
}

}  // namespace facet::analytic_shadow
