// The step mode's lighting screen for a light with a range (d, r_max and the window with its numbers)
// and for an area light (its shape, the sample count, the samples seen and v), each line within 80
// columns, and the recomputed shading still the pipeline's bit for bit.
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "raycast/ray_scene.h"
#include "render/renderer.h"
#include "step/screens.h"
#include "step/shading_view.h"

namespace facet::step {
namespace {

std::string lightingScreen(const SurfaceUniforms& u) {
    const PerPixelSurface::VaryingsT<float> in{vec3(0.0f, 0.0f, -2.0f), vec3(0.0f, 0.0f, 1.0f), vec2(0.0f)};
    FragmentEvent f;
    f.varyingCount = kVaryingFloatCount<PerPixelSurface::VaryingsT<float>>;
    std::memcpy(f.varyings.data(), &in, sizeof in);
    f.shaded = SurfaceShader<ShadingFrequency::Phong>::fragment(in, u);
    const ShadingTrace trace = traceShading(u, ShadingFrequency::Phong, f, {}, 2);
    EXPECT_TRUE(trace.matchesPipeline);
    for (const Screen& screen : shadingScreens(trace)) {
        if (screen.id != "lighting") continue;
        std::size_t start = 0;
        while (start < screen.text.size()) {
            const std::size_t end = std::min(screen.text.find('\n', start), screen.text.size());
            EXPECT_LE(columnsOf(screen.text.substr(start, end - start)), 80u)
                << screen.text.substr(start, end - start);
            start = end + 1;
        }
        return screen.text;
    }
    return "";
}

// A point light 2 from the point straight in front of it (N·L = 1), range 4: f_win = (1 − 0.5⁴)² =
// 0.8789. Breaks if the screen leaves the window out or substitutes other numbers.
SurfaceUniforms rangedUniforms(ReflectionModel model) {
    SurfaceUniforms u;
    u.lightCount = 1;
    LightParams& light = u.lights[0];
    light.kind = LightKind::Point;
    light.position = vec3(0.0f, 0.0f, 0.0f);  // P + 2·(0, 0, 1)
    light.range = 4.0f;
    u.material.diffuse = vec3(0.5f);
    u.reflection = model;
    u.precision = MathPrecision::Exact;
    return u;
}

TEST(LightRangeView, WindowOnTheLightingScreen) {
    const std::string standard = lightingScreen(rangedUniforms(ReflectionModel::BlinnPhong));
    EXPECT_NE(standard.find("f_win = (1 − (d/r_max)⁴)²₊   (Karis 2013, UE4; 0 from d = r_max on)"),
              std::string::npos)
        << standard;
    EXPECT_NE(standard.find("= (1 − (2/4)⁴)²₊ = 0.8789"), std::string::npos) << standard;
    EXPECT_NE(standard.find("diffuse = att·f_win·spot·max(N·L,0)·l_d⊗m_d"), std::string::npos) << standard;
    EXPECT_NE(standard.find("= 1·0.8789·1·max(1, 0)"), std::string::npos) << standard;

    SurfaceUniforms jc2 = rangedUniforms(ReflectionModel::CookTorrance);
    jc2.lights[0].window = RangeWindow::Jc2;
    const std::string pbr = lightingScreen(jc2);
    EXPECT_NE(pbr.find("f_win = (1 − (d/r_max)²)²₊   (Just Cause 2"), std::string::npos) << pbr;
    EXPECT_NE(pbr.find("= (1 − (2/4)²)²₊ = 0.5625"), std::string::npos) << pbr;
    EXPECT_NE(pbr.find("falloff = 1/d² = 1/2² = 0.25"), std::string::npos) << pbr;
    EXPECT_NE(pbr.find("irradiance factor = falloff·f_win·spot·max(N·L,0) = 0.25·0.5625·1·max(1, 0)"),
              std::string::npos)
        << pbr;
    // Attenuation given: Cook-Torrance shows the polynomial.
    jc2.lights[0].attenuationGiven = true;
    jc2.lights[0].c2 = 1.0f;
    const std::string given = lightingScreen(jc2);
    EXPECT_NE(given.find("falloff = 1/(c0 + c1·d + c2·d²) = 1/(1 + 0·2 + 1·2²) = 0.2"), std::string::npos)
        << given;
}

// A 1 × 1 rectangle light 2 in front of the point, facing it, 16 samples; a triangle blocks the
// half of it with x < 0 (the plane z = −1 for x < 0): 8 of 16 samples seen, v = 0.5. Breaks if the
// screen shows no shape or sample count, or v is not the share of samples seen.
TEST(LightRangeView, AreaLightOnTheLightingScreen) {
    SurfaceUniforms u = rangedUniforms(ReflectionModel::BlinnPhong);
    LightParams& light = u.lights[0];
    light.range = 0.0f;
    light.kind = LightKind::Rect;
    light.areaNormal = vec3(0.0f, 0.0f, -1.0f);
    light.areaU = vec3(0.5f, 0.0f, 0.0f);
    light.areaV = vec3(0.0f, 0.5f, 0.0f);
    light.areaSamples = 16;
    const vec3 corners[] = {vec3(-5.0f, -5.0f, -1.0f), vec3(0.0f, -5.0f, -1.0f), vec3(0.0f, 5.0f, -1.0f),
                            vec3(-5.0f, 5.0f, -1.0f)};
    const std::uint32_t indices[] = {0, 1, 2, 0, 2, 3};
    const RayMesh mesh{corners, indices, true};
    const RayScene rays(std::span<const RayMesh>(&mesh, 1));
    SceneShadows shadows;
    shadows.rays = &rays;
    shadows.rayOffset = 1e-4f;
    shadows.lights[0].method = ShadowMethod::Ray;
    u.shadows = &shadows;
    const std::string screen = lightingScreen(u);
    EXPECT_NE(screen.find("rectangle light centred at (0, 0, 0)"), std::string::npos) << screen;
    EXPECT_NE(screen.find("1 × 1 (eye units), 16 shadow samples"), std::string::npos) << screen;
    EXPECT_NE(screen.find("spot = max(−L·n_light, 0) = max(1, 0) = 1 (one-sided emitter)"), std::string::npos)
        << screen;
    EXPECT_NE(screen.find("shadow: 8 of the 16 samples of the rectangle reach P:"), std::string::npos)
        << screen;
    EXPECT_NE(screen.find("v = 8/16 = 0.5"), std::string::npos) << screen;
    EXPECT_NE(screen.find("diffuse = att·spot·v·max(N·L,0)·l_d⊗m_d"), std::string::npos) << screen;
}

}  // namespace
}  // namespace facet::step
