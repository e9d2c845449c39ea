// Shadow maps: the pipeline's depth offset, acne and its cure, the map against the ray-cast shadows,
// percentage-closer filtering, a point light's six faces, and the options reaching the map.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/gtx/string_cast.hpp>

#include "pipeline/pipeline.h"
#include "render/renderer.h"
#include "render/shadow_maps.h"
#include "scene/scene.h"
#include "shaders/shadow_map.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

using ShadowMapTest = testing_support::TempFolderTest;

#define FACET_MODELS FACET_SOURCE_DIR "/models/"

// ---- The pipeline's depth offset ------------------------------------------------------------------

// Position only: window depth is all these draws look at.
struct PositionShader {
    struct Attributes {
        vec3 position;
    };
    struct Varyings {};
    struct Uniforms {};
    static VertexOut<Varyings> vertex(const Attributes& in, const Uniforms&) {
        return {vec4(in.position, 1.0f), {}};
    }
    static vec4 fragment(const Varyings&, const Uniforms&) { return vec4(1.0f); }
};

// One tilted triangle covering most of a 64×64 target, its depth planes with and without an offset.
std::vector<float> tiltedTriangleDepths(DepthOffset offset) {
    // NDC z = 0.25·x + 0.125·y: window depth (z + 1)/2 changes by 0.125·(2/64) per pixel in x and
    // 0.0625·(2/64) in y, so m = 0.125 / 32 = 1/256.
    const std::vector<PositionShader::Attributes> vertices = {
        {{-1.0f, -1.0f, -0.375f}}, {{1.0f, -1.0f, 0.125f}}, {{-1.0f, 1.0f, -0.125f}}};
    const std::vector<std::uint32_t> indices = {0, 1, 2};
    DrawState state;
    state.viewport = {0, 0, 64, 64};
    state.raster.cull = CullMode::None;
    state.depth.offset = offset;
    Framebuffer target(64, 64);
    target.clearDepth();
    DrawContext context(1);
    draw<PositionShader>(state, {}, std::span<const PositionShader::Attributes>(vertices), indices, target,
                         context);
    return target.depthPixels();
}

// z' = z + factor·m + units·r for every fragment, m the larger of the two window-space slopes.
// Breaks caught: the offset not added in setup; m taken from ∂z/∂y (the smaller) or their sum; units
// not scaled by DepthFormat::kResolution.
TEST(DepthOffsetTest, MovesEveryFragmentByFactorTimesSlopePlusUnits) {
    const std::vector<float> plain = tiltedTriangleDepths({});
    const std::vector<float> offset = tiltedTriangleDepths({2.0f, 1000.0f});
    const double expected = 2.0 / 256.0 + 1000.0 * 0x1p-24;
    int covered = 0;
    for (std::size_t i = 0; i < plain.size(); ++i) {
        if (plain[i] == DepthFormat::kClear) continue;
        ++covered;
        EXPECT_NEAR(offset[i] - plain[i], expected, 1e-6) << "pixel " << i;
    }
    EXPECT_GT(covered, 1500);
}

// ---- Scenes ---------------------------------------------------------------------------------------

LinearImage render(const Scene& scene) {
    const PreparedScene prepared = prepareScene(scene);
    Framebuffer framebuffer(scene.width, scene.height);
    DrawContext context(2);
    renderFrame(prepared, framebuffer, context);
    return toImage(framebuffer);
}

// Whether pixel `a` is darker than `b` (some channel by more than `by`).
bool darker(const vec4& a, const vec4& b, float by) {
    return a.r < b.r - by || a.g < b.g - by || a.b < b.b - by;
}

// ---- Acne -----------------------------------------------------------------------------------------

// A 4 × 4 plane alone (nothing can shadow it) under a directional light 8.5° above its horizon.
constexpr const char* kGrazingPlane = R"({
  "width": 160, "height": 120, "ambient": [0.05, 0.05, 0.05], "background": [0, 0, 0],
  "camera": {"eye": [0, 3, 3], "target": [0, 0, 0], "fovy": 50},
  "lights": [{"type": "directional", "direction": [1, -0.15, 0.2], "shadows": "map"}],
  "objects": [{"model": ")" FACET_MODELS R"(fog-and-glass/ground.obj", "scale": 0.1,
               "material": {"diffuse": [0.8, 0.8, 0.8], "specular": [0, 0, 0]}}]
})";

// The share of the plane's pixels that the map darkens (every one of them is lit in truth).
double wronglyShadowed(Scene scene) {
    scene.shadows = ShadowMethod::None;
    const LinearImage truth = render(scene);
    scene.shadows = ShadowMethod::Map;
    const LinearImage mapped = render(scene);
    std::size_t plane = 0, shadowed = 0;
    for (std::size_t i = 0; i < truth.pixels.size(); ++i) {
        if (truth.pixels[i].r == 0.0f) continue;  // background
        ++plane;
        shadowed += darker(mapped.pixels[i], truth.pixels[i], 0.002f);
    }
    EXPECT_GT(plane, truth.pixels.size() / 4);
    return double(shadowed) / double(plane);
}

// With no bias, the map's depth at a texel centre and the plane's own depth at a point of that texel
// disagree by up to the plane's slope across half a texel, so about half the plane shadows itself in
// stripes (acne); the default slope-scaled offset cures it, for every filter.
// Breaks caught: the draw state's offset left at 0 (or its factor not scaled by the filter's width:
// 16 taps reach two texels away); the lookup comparing with Less (every texel-centre tie shadowed).
TEST_F(ShadowMapTest, ZeroBiasGivesAcneAndTheSlopeScaledBiasCuresIt) {
    Scene scene = loadScene(write("plane.json", kGrazingPlane));
    for (int taps : {1, 4, 16}) {
        SCOPED_TRACE(taps);
        scene.shadowMap.filterTaps = taps;
        scene.shadowMap.constantBias = 0;
        scene.shadowMap.slopeBias = 0;
        EXPECT_GT(wronglyShadowed(scene), 0.2);
        scene.shadowMap = ShadowMapOptions{};
        scene.shadowMap.filterTaps = taps;
        EXPECT_LT(wronglyShadowed(scene), 0.005);
    }
}

// ---- The map against the ray-cast shadows ------------------------------------------------------------

// models/shadows.json (a spot and a directional light, Spot and a cube on a ground) at 400×300.
Scene shadowsScene() {
    Scene scene = loadScene(FACET_MODELS "shadows.json");
    scene.width = 400;
    scene.height = 300;
    return scene;
}

struct MapAgainstRay {
    double differing = 0;      // share of the image's pixels where the map's image differs from the ray's
    double awayFromEdges = 0;  // share of the image's pixels that differ beyond kEdgeReach pixels of
                               // an edge of the ray-cast shadows
};
constexpr int kEdgeReach = 3;

MapAgainstRay compareWithRays(Scene scene, const LinearImage& rays, const LinearImage& unshadowed) {
    scene.shadows = ShadowMethod::Map;
    const LinearImage mapped = render(scene);
    const int w = rays.width, h = rays.height;
    // Where the ray-cast shadows darken the image.
    std::vector<char> shadowed(rays.pixels.size());
    for (std::size_t i = 0; i < rays.pixels.size(); ++i)
        shadowed[i] = darker(rays.pixels[i], unshadowed.pixels[i], 0.004f);
    const auto nearEdge = [&](int x, int y) {
        const char here = shadowed[std::size_t(y) * w + x];
        for (int dy = -kEdgeReach; dy <= kEdgeReach; ++dy)
            for (int dx = -kEdgeReach; dx <= kEdgeReach; ++dx) {
                const int u = std::clamp(x + dx, 0, w - 1), v = std::clamp(y + dy, 0, h - 1);
                if (shadowed[std::size_t(v) * w + u] != here) return true;
            }
        return false;
    };
    std::size_t differing = 0, awayFromEdges = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const vec4 a = mapped.at(x, y), b = rays.at(x, y);
            if (!darker(a, b, 0.004f) && !darker(b, a, 0.004f)) continue;
            ++differing;
            awayFromEdges += !nearEdge(x, y);
        }
    return {double(differing) / double(w * h), double(awayFromEdges) / double(w * h)};
}

// At 2048 texels the map's shadows are the ray-cast ones but for their edges (a few pixels of
// filtering and texel steps) and a few pixels at the terminator of Spot's smooth normals (where the
// shading normal still faces the light, the triangle no longer does, and the map sees it from behind);
// at 256 texels the edges are coarse enough to shift visibly.
// Breaks caught: a map's rows upside down, a wrong projection (the spot's cone or the directional
// light's fit), receivers compared in another face's space, the size option not reaching the draw.
TEST(ShadowMapAgainstRays, DifferOnlyNearTheShadowEdgesAndLessWithLargerMaps) {
    Scene scene = shadowsScene();
    scene.shadows = ShadowMethod::None;
    const LinearImage unshadowed = render(scene);
    scene.shadows = ShadowMethod::Ray;
    const LinearImage rays = render(scene);
    scene.shadowMap.size = 2048;
    const MapAgainstRay fine = compareWithRays(scene, rays, unshadowed);
    scene.shadowMap.size = 256;
    const MapAgainstRay coarse = compareWithRays(scene, rays, unshadowed);
    EXPECT_LT(fine.differing, 0.02);
    EXPECT_LT(fine.awayFromEdges, 0.001);
    EXPECT_GT(coarse.differing, 2 * fine.differing);
}

// ---- Percentage-closer filtering ------------------------------------------------------------------

// A unit cube standing on a 4 × 4 ground, lit from above and a little from the side.
constexpr const char* kCubeOnGround = R"({
  "width": 64, "height": 48,
  "camera": {"eye": [1, 5, 4], "target": [0.5, 0, 0], "fovy": 50},
  "lights": [{"type": "directional", "direction": [0.3, -1, 0.1], "shadows": "map"}],
  "shadow_map": {"size": 256},
  "objects": [{"model": ")" FACET_MODELS R"(fog-and-glass/ground.obj", "scale": 0.1},
              {"model": ")" FACET_MODELS R"(cube/cube.obj", "translate": [0, 0.5, 0]}]
})";

// The map's lit share at `count` points of the ground along x ∈ [−1, 2] (across the cube's shadow and
// its edge), z = 0.1, in eye space.
std::vector<float> litSharesAcrossTheEdge(const PreparedScene& prepared, int count) {
    const ShadowMap& map = *prepared.shadows->maps.at(0);
    std::vector<float> shares;
    for (int k = 0; k < count; ++k) {
        const double x = -1.0 + 3.0 * k / (count - 1);
        const vec3 P(prepared.camera.viewFromWorldExact * glm::dvec4(x, 0.0, 0.1, 1.0));
        shares.push_back(shadowMapLitShare(map, P));
    }
    return shares;
}

// 1 tap: lit or not; 2×2: quarters; 4×4: sixteenths, some of them not quarters, at the edge.
// Breaks caught: the filter option not reaching the map, a side of 4 taps for 16 (or 1 for 4), the
// sum not divided by the number of taps.
TEST_F(ShadowMapTest, OneTapIsAllOrNothingAndMoreTapsRampAtTheEdge) {
    Scene scene = loadScene(write("cube.json", kCubeOnGround));
    for (int taps : {1, 4, 16}) {
        SCOPED_TRACE(taps);
        scene.shadowMap.filterTaps = taps;
        const PreparedScene prepared = prepareScene(scene);
        ASSERT_NE(prepared.shadows, nullptr);
        ASSERT_EQ(prepared.shadows->maps.size(), 1u);
        EXPECT_EQ(prepared.shadows->maps[0]->filterTaps, taps);
        int lit = 0, shadowed = 0, between = 0, notQuarters = 0;
        for (float share : litSharesAcrossTheEdge(prepared, 3001)) {
            EXPECT_EQ(share * float(taps), std::round(share * float(taps))) << share;
            lit += share == 1.0f;
            shadowed += share == 0.0f;
            between += share > 0.0f && share < 1.0f;
            notQuarters += share * 4.0f != std::round(share * 4.0f);
        }
        EXPECT_GT(lit, 100);
        EXPECT_GT(shadowed, 100);
        if (taps == 1) {
            EXPECT_EQ(between, 0);
        } else {
            EXPECT_GT(between, 10);
        }
        if (taps == 16) {
            EXPECT_GT(notQuarters, 5);
        }
    }
}

// The eight-lane lookup gives each lane what the one-lane one gives, lanes where N·L ≤ 0 and dead
// lanes (non-finite P) are lit, and double lanes look up as float.
// Breaks caught: lanes mixed up (P.y read for x), the N·L gate dropped or inverted.
TEST_F(ShadowMapTest, EightLanesAndDoubleLookUpAsOneLane) {
    Scene scene = loadScene(write("cube.json", kCubeOnGround));
    scene.shadowMap.filterTaps = 16;
    const PreparedScene prepared = prepareScene(scene);
    const ShadowMap& map = *prepared.shadows->maps.at(0);
    const LightParams& light = prepared.draws.at(0).uniforms.lights[0];
    const vec3 up(prepared.camera.viewFromWorldExact * glm::dvec4(0, 1, 0, 0));
    Vec3x8 P{}, N{};
    std::vector<vec3> points;
    for (int lane = 0; lane < 8; ++lane) {
        const vec3 p(prepared.camera.viewFromWorldExact *
                     glm::dvec4(-0.6 + 0.23 * lane, 0.0, 0.13 * lane, 1.0));
        points.push_back(p);
        const vec3 n = lane == 3 ? -up : up;  // lane 3 faces away from the light
        P.x[lane] = p.x, P.y[lane] = p.y, P.z[lane] = p.z;
        N.x[lane] = n.x, N.y[lane] = n.y, N.z[lane] = n.z;
    }
    P.x[5] = std::numeric_limits<float>::quiet_NaN();  // a dead lane
    const Float8 wide = shadowMapVisibility<Float8>(map, light, P, N);
    int shadowed = 0, between = 0;
    for (int lane = 0; lane < 8; ++lane) {
        SCOPED_TRACE(lane);
        const vec3 n = lane == 3 ? -up : up;
        const float one = shadowMapVisibility<float>(map, light, points[lane], n);
        if (lane == 3 || lane == 5) {
            EXPECT_EQ(wide[lane], 1.0f);
        } else {
            EXPECT_EQ(wide[lane], one);
            EXPECT_EQ(shadowMapVisibility<double>(map, light, glm::dvec3(points[lane]), glm::dvec3(n)),
                      double(one));
        }
        if (lane == 3) {
            EXPECT_EQ(one, 1.0f);
        }
        shadowed += one == 0.0f;
        between += one > 0.0f && one < 1.0f;
    }
    EXPECT_GT(shadowed + between, 2);  // the points cross the cube's shadow
}

// ---- A point light's six faces ---------------------------------------------------------------------

// A point light at the origin with a half-unit cube 2 units away along each of ±x, ±y, ±z: behind
// each cube (3.5 units out) the light is blocked, beside it (3.5 units out, 1.5 to the side) it is
// not. The camera looks from an oblique corner, so the cube map's eye-space faces cut across the
// world's axes and several points lie near their seams.
// Breaks caught: a face chosen by the wrong sign or axis, faces in another order than cubeFaceOf's, a
// face's frustum narrower than 90°.
TEST_F(ShadowMapTest, PointLightsShadowAllAroundThemselves) {
    std::string objects;
    const int axes[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const auto& a : axes) {
        if (!objects.empty()) objects += ", ";
        objects += R"({"model": ")" FACET_MODELS R"(cube/cube.obj", "scale": 0.5, "translate": [)";
        objects += std::to_string(2 * a[0]) + ", " + std::to_string(2 * a[1]) + ", " +
                   std::to_string(2 * a[2]) + "]}";
    }
    std::string text = R"({"width": 32, "height": 32, "camera": {"eye": [7, 5, 6], "target": [0, 0, 0]},
        "lights": [{"type": "point", "position": [0, 0, 0], "shadows": "map"}], "objects": [)";
    text += objects;
    text += "]}";
    Scene scene = loadScene(write("point.json", text));
    scene.shadowMap.filterTaps = 1;
    scene.shadowMap.size = 512;
    const PreparedScene prepared = prepareScene(scene);
    const ShadowMap& map = *prepared.shadows->maps.at(0);
    ASSERT_EQ(map.faces.size(), 6u);
    const auto share = [&](glm::dvec3 world) {
        return shadowMapLitShare(map, vec3(prepared.camera.viewFromWorldExact * glm::dvec4(world, 1.0)));
    };
    for (const auto& a : axes) {
        const glm::dvec3 axis(a[0], a[1], a[2]);
        const glm::dvec3 side = glm::dvec3(a[1] + a[2], a[2] + a[0], a[0] + a[1]) * 1.5;  // across the axis
        SCOPED_TRACE(glm::to_string(axis));
        EXPECT_EQ(share(axis * 3.5), 0.0f);
        EXPECT_EQ(share(axis * 3.5 + side), 1.0f);
        EXPECT_EQ(share(axis * 3.5 - side), 1.0f);
        EXPECT_EQ(share(axis * 1.2), 1.0f);  // between the light and the cube
    }
}

// ---- A spot light's cone -----------------------------------------------------------------------------

// A spot 4 units above a ground, pointing straight down, and a half-unit cube on the ground whose
// shadow falls 35° off the spot's axis (inside a 40° cone), or 70° off it (inside an 80° cone, drawn
// as a cube map): the map covers the whole cone, its rim included.
// Breaks caught: the field of view the cone's half-angle instead of twice it; the smooth profile's
// outer angle not used; a wide spot given one perspective map (which cannot reach 80°).
TEST_F(ShadowMapTest, SpotMapsCoverTheirWholeCone) {
    const struct {
        const char* cone;
        double degrees;
        std::size_t faces;
    } cases[] = {
        {R"("cutoff": 40)", 35, 1}, {R"("inner": 20, "outer": 40)", 35, 1}, {R"("cutoff": 80)", 70, 6}};
    for (const auto& c : cases) {
        SCOPED_TRACE(c.cone);
        // The cube halfway between the spot and the shadowed point of the ground, 35° or 70° off the axis.
        const double out = 4.0 * std::tan(glm::radians(c.degrees));
        std::string text = R"({"width": 32, "height": 32, "camera": {"eye": [0, 9, 9], "target": [0, 0, 0]},
            "lights": [{"type": "spot", "position": [0, 4, 0], "direction": [0, -1, 0], "shadows": "map", )";
        text += c.cone;
        text += R"(}], "objects": [{"model": ")" FACET_MODELS R"(fog-and-glass/ground.obj", "scale": 1},
            {"model": ")" FACET_MODELS R"(cube/cube.obj", "scale": 0.5, "translate": [)";
        text += std::to_string(out / 2) + ", 2, 0]}]}";
        Scene scene = loadScene(write("spot.json", text));
        scene.shadowMap.filterTaps = 1;
        const PreparedScene prepared = prepareScene(scene);
        const ShadowMap& map = *prepared.shadows->maps.at(0);
        EXPECT_EQ(map.faces.size(), c.faces);
        const auto share = [&](double x) {
            return shadowMapLitShare(map, vec3(prepared.camera.viewFromWorldExact * glm::dvec4(x, 0, 0, 1)));
        };
        EXPECT_EQ(share(out), 0.0f);        // in the cube's shadow
        EXPECT_EQ(share(-out), 1.0f);       // as far out on the other side: lit
        EXPECT_EQ(share(out * 0.7), 1.0f);  // nearer the axis than the shadow
    }
}

// ---- The options reach the image --------------------------------------------------------------------

// Each of the map's options, changed alone, changes the image of models/shadows.json.
// Breaks caught: any one of size, constant bias, slope bias and filter taps not reaching the map's
// draw or lookup (drawShadowMap or shadowMapDrawState reading ShadowMapOptions{} for it, the map
// keeping 4 taps whatever the filter).
TEST(ShadowMapOptionsTest, EachOptionChangesTheImage) {
    Scene scene = shadowsScene();
    scene.width = 200;
    scene.height = 150;
    scene.shadows = ShadowMethod::Map;
    const LinearImage standard = render(scene);
    const auto changes = [&](const char* what, auto change) {
        SCOPED_TRACE(what);
        Scene changed = scene;
        change(changed.shadowMap);
        const LinearImage image = render(changed);
        std::size_t differing = 0;
        for (std::size_t i = 0; i < image.pixels.size(); ++i)
            differing += image.pixels[i] != standard.pixels[i];
        EXPECT_GT(differing, 20u);
    };
    changes("size", [](ShadowMapOptions& o) { o.size = 512; });
    changes("bias", [](ShadowMapOptions& o) { o.constantBias = 300000; });  // 0.018 of the depth range
    changes("slope bias", [](ShadowMapOptions& o) { o.slopeBias = 0; });
    // 16 taps with half the slope bias: the map's draw is the same (its offset factor is the slope
    // bias times the filter's width), so only the lookup can change the image.
    changes("filter", [](ShadowMapOptions& o) {
        o.filterTaps = 16;
        o.slopeBias /= 2;
    });
}

}  // namespace
}  // namespace facet
