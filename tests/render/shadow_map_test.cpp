// Shadow maps: the pipeline's depth offset, acne and its cure, the map against the ray-cast shadows,
// percentage-closer filtering, a point light's six faces, and the options reaching the map.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace facet
