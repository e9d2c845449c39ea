// Mesa's OSMesa as the oracle: hand-computed values that OpenGL's fixed-function lighting and the peer's
// GLSL programs must give on softpipe (Mesa's reference rasterizer), and Mesa llvmpipe drawing the image
// Facet draws (the benchmark's check). Every test needs OSMesa: it derives from MesaTest
// (support/mesa_fixture.h), which skips it, with the reason, where OSMesa cannot be opened.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "oracle/mesa_peer.h"
#include "pipeline/blend.h"
#include "pipeline/texture.h"
#include "render/renderer.h"
#include "support/mesa_fixture.h"

namespace facet {
namespace {

// ---- OpenGL as the oracle: hand-computed values on softpipe ------------------------------------------

// The scenes below look down −z from the eye at the origin (eye space is the scene's space: the draws'
// modelview is the identity) at squares at z = −2 facing the eye. 65×65 pixels with a 60° field of view:
// the centre pixel (32, 32) looks exactly down the axis, at the point (0, 0, −2).
constexpr int kSize = 65;
constexpr int kCentre = 32;
const vec4 kClear(0.0f, 0.0f, 0.0f, 0.0f);  // alpha 0: drawn pixels have alpha 1

// Every test of this suite runs on softpipe (skipped where OSMesa cannot give it).
class MesaOracle : public SoftpipeTest {};

GlScene eyeScene() {
    GlScene scene;
    scene.width = scene.height = kSize;
    scene.clearColor = kClear;
    scene.clipFromView = glm::perspective(glm::radians(60.0f), 1.0f, 0.5f, 10.0f);
    scene.globalAmbient = vec3(0.0f);
    return scene;
}

// A square of half-size 1 at z = −2 (or `z`), normal +z, as four counter-clockwise triangles around its
// centre vertex (0, 0, z): the centre pixel's colour is that vertex's even where lighting is per vertex.
// m_diffuse (0.5, 0.25, 0.125), no ambient or specular.
GlDraw fanSquare(GlProgram program, ShadingFrequency frequency, float z = -2.0f) {
    GlDraw draw;
    const vec3 n(0.0f, 0.0f, 1.0f);
    draw.vertices = {{vec3(0.0f, 0.0f, z), n, vec2(0.5f)},
                     {vec3(-1.0f, -1.0f, z), n, vec2(0.0f)},
                     {vec3(1.0f, -1.0f, z), n, vec2(1.0f, 0.0f)},
                     {vec3(1.0f, 1.0f, z), n, vec2(1.0f)},
                     {vec3(-1.0f, 1.0f, z), n, vec2(0.0f, 1.0f)}};
    draw.indices = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1};
    draw.program = program;
    draw.frequency = frequency;
    draw.material.diffuse = vec3(0.5f, 0.25f, 0.125f);
    draw.material.specular = vec3(0.0f);
    draw.material.ambient = vec3(0.0f);
    return draw;
}

// A directional light shining down −z (at the squares), white diffuse and specular, no ambient.
LightParams headOnLight() {
    LightParams light;
    light.kind = LightKind::Directional;
    light.direction = vec3(0.0f, 0.0f, -1.0f);
    return light;
}

LinearImage drawScene(MesaPeer& mesa, const GlScene& scene) {
    mesa.load(scene);
    mesa.renderFrame();
    return mesa.readImage();
}

bool drawn(const vec4& pixel) {
    return pixel.a != 0.0f;
}

#define EXPECT_RGB_NEAR(actual, expected, tolerance)   \
    do {                                               \
        const vec4 a_ = (actual);                      \
        const vec3 e_ = (expected);                    \
        EXPECT_NEAR(a_.r, e_.r, tolerance) << "red";   \
        EXPECT_NEAR(a_.g, e_.g, tolerance) << "green"; \
        EXPECT_NEAR(a_.b, e_.b, tolerance) << "blue";  \
    } while (false)

TEST_F(MesaOracle, SoftpipeGivesACompatibilityContext) {
    EXPECT_EQ(mesa().driver(), MesaDriver::Softpipe);
    EXPECT_NE(mesa().renderer().find("softpipe"), std::string::npos) << mesa().renderer();
    EXPECT_NE(mesa().version().find("Compatibility"), std::string::npos) << mesa().version();
    EXPECT_GE(std::stod(mesa().shadingLanguageVersion()), 1.3) << mesa().shadingLanguageVersion();
    EXPECT_TRUE(mesa().floatColor());
    RecordProperty("renderer", mesa().renderer());
    RecordProperty("version", mesa().version());
    RecordProperty("glsl", mesa().shadingLanguageVersion());
}

TEST_F(MesaOracle, OneDriverPerProcess) {
    std::string whyNot;
    const std::unique_ptr<MesaPeer> second =
        MesaPeer::open(MesaOptions{MesaDriver::Softpipe, 1}, whyNot);  // the same driver: fine
    EXPECT_NE(second, nullptr) << whyNot;
    whyNot.clear();
    EXPECT_EQ(MesaPeer::open(MesaOptions{MesaDriver::Llvmpipe, 1}, whyNot), nullptr);
    EXPECT_NE(whyNot.find("softpipe"), std::string::npos) << whyNot;
    EXPECT_NE(whyNot.find("GALLIUM_DRIVER"), std::string::npos) << whyNot;
    EXPECT_EQ(whyNot.find('\n'), std::string::npos) << whyNot;
    EXPECT_THROW(MesaPeer::open(MesaOptions{MesaDriver::Softpipe, 2}, whyNot), std::invalid_argument);
}

// Fixed function, m_diffuse = (0.5, 0.25, 0.125), a white light straight at the square, nothing else:
// every pixel is m_diffuse, exactly but for float rounding.
TEST_F(MesaOracle, FixedFunctionHeadOnDiffuseIsTheMaterial) {
    GlScene scene = eyeScene();
    scene.lights = {headOnLight()};
    scene.draws = {fanSquare(GlProgram::FixedFunction, ShadingFrequency::Gouraud)};
    const LinearImage image = drawScene(mesa(), scene);
    std::size_t covered = 0;
    for (const vec4& pixel : image.pixels) {
        if (!drawn(pixel)) continue;
        ++covered;
        EXPECT_RGB_NEAR(pixel, vec3(0.5f, 0.25f, 0.125f), 1e-6);
        EXPECT_EQ(pixel.a, 1.0f);
    }
    EXPECT_GT(covered, 3000u);  // the square spans ±0.87 of the view: about 3170 pixels
    EXPECT_EQ(image.at(0, 0), kClear);
}

// A point light 1.5 in front of the square's centre, attenuation 1/(c0 + c1 d + c2 d²) with
// (c0, c1, c2) = (0.5, 0.25, 0.125): at the centre, 1/(0.5 + 0.375 + 0.28125) = 1/1.15625.
TEST_F(MesaOracle, PointLightAttenuates) {
    GlScene scene = eyeScene();
    LightParams light;
    light.kind = LightKind::Point;
    light.position = vec3(0.0f, 0.0f, -0.5f);
    light.c0 = 0.5f;
    light.c1 = 0.25f;
    light.c2 = 0.125f;
    scene.lights = {light};
    const vec3 expected = vec3(0.5f, 0.25f, 0.125f) / 1.15625f;
    for (const auto& [program, frequency] : {std::pair{GlProgram::FixedFunction, ShadingFrequency::Gouraud},
                                             std::pair{GlProgram::PerPixel, ShadingFrequency::Phong},
                                             std::pair{GlProgram::PerVertex, ShadingFrequency::Gouraud}}) {
        SCOPED_TRACE(int(program));
        scene.draws = {fanSquare(program, frequency)};
        EXPECT_RGB_NEAR(drawScene(mesa(), scene).at(kCentre, kCentre), expected, 1e-5);
    }
}

// A spot at the eye: pointing at the square with a 30° cone, the square's centre gets the full light
// (cos 0 = 1, any exponent), its ambient included; turned 45° away with a 10° cone, the square gets
// none (every vertex is outside the cone): black.
TEST_F(MesaOracle, FixedFunctionSpotCone) {
    GlScene scene = eyeScene();
    LightParams spot;
    spot.kind = LightKind::Spot;
    spot.position = vec3(0.0f);
    spot.spotDirection = vec3(0.0f, 0.0f, -1.0f);
    spot.spotCutoffDegrees = 30.0f;
    spot.spotExponent = 5.0f;
    spot.ambient = vec3(0.5f);  // reaches the surface only inside the cone
    scene.lights = {spot};
    GlDraw draw = fanSquare(GlProgram::FixedFunction, ShadingFrequency::Gouraud);
    draw.material.ambient = vec3(0.2f);
    scene.draws = {draw};
    EXPECT_RGB_NEAR(drawScene(mesa(), scene).at(kCentre, kCentre),
                    vec3(0.5f, 0.25f, 0.125f) + vec3(0.5f * 0.2f), 1e-5);

    scene.lights[0].spotDirection = normalize(vec3(1.0f, 0.0f, -1.0f));
    scene.lights[0].spotCutoffDegrees = 10.0f;
    std::size_t covered = 0;
    for (const vec4& pixel : drawScene(mesa(), scene).pixels) {
        if (!drawn(pixel)) continue;
        ++covered;
        EXPECT_EQ(vec3(pixel), vec3(0.0f));
    }
    EXPECT_GT(covered, 3000u);
}

// Two triangles whose four vertices have normals with N·L = 1, 0.8, 0.6 and 0.96 under a head-on
// light, m_diffuse white: flat shading gives each triangle its last (provoking) vertex's value, 0.6 and
// 0.96; Gouraud shading blends them.
GlDraw twoTriangles(GlProgram program, ShadingFrequency frequency) {
    GlDraw draw;
    draw.vertices = {{vec3(-1.0f, -1.0f, -2.0f), vec3(0.0f, 0.0f, 1.0f), vec2(0.0f)},
                     {vec3(1.0f, -1.0f, -2.0f), vec3(0.6f, 0.0f, 0.8f), vec2(0.0f)},
                     {vec3(1.0f, 1.0f, -2.0f), vec3(0.0f, 0.8f, 0.6f), vec2(0.0f)},
                     {vec3(-1.0f, 1.0f, -2.0f), vec3(0.28f, 0.0f, 0.96f), vec2(0.0f)}};
    draw.indices = {0, 1, 2, 0, 2, 3};  // the lower right half, then the upper left
    draw.program = program;
    draw.frequency = frequency;
    draw.material.diffuse = vec3(1.0f);
    draw.material.specular = vec3(0.0f);
    return draw;
}

void expectProvokingVertexColours(MesaPeer& mesa, GlProgram program) {
    GlScene scene = eyeScene();
    scene.lights = {headOnLight()};
    scene.draws = {twoTriangles(program, ShadingFrequency::Flat)};
    const LinearImage flat = drawScene(mesa, scene);
    std::size_t lowerRight = 0, upperLeft = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            if (!drawn(flat.at(x, y))) continue;
            const float xn = (x + 0.5f) / kSize * 2.0f - 1.0f, yn = 1.0f - (y + 0.5f) / kSize * 2.0f;
            if (std::abs(xn - yn) < 3.0f / kSize) continue;  // the shared edge
            const bool first = xn > yn;
            (first ? lowerRight : upperLeft) += 1;
            const vec3 difference = abs(vec3(flat.at(x, y)) - vec3(first ? 0.6f : 0.96f));
            EXPECT_LE(std::max({difference.r, difference.g, difference.b}), 1e-6f)
                << "pixel " << x << ", " << y;
        }
    EXPECT_GT(lowerRight, 1000u);
    EXPECT_GT(upperLeft, 1000u);

    scene.draws = {twoTriangles(program, ShadingFrequency::Gouraud)};
    const LinearImage gouraud = drawScene(mesa, scene);
    float least = 2.0f, most = -1.0f;
    for (const vec4& pixel : gouraud.pixels)
        if (drawn(pixel)) {
            least = std::min(least, pixel.r);
            most = std::max(most, pixel.r);
        }
    EXPECT_GT(least, 0.6f - 1e-5f);
    EXPECT_LT(most, 1.0f + 1e-5f);
    EXPECT_GT(most - least, 0.2f);  // blended between the vertices' 0.6 … 1
}

TEST_F(MesaOracle, FixedFunctionFlatShadingTakesTheLastVertex) {
    expectProvokingVertexColours(mesa(), GlProgram::FixedFunction);
}

TEST_F(MesaOracle, PerVertexFlatShadingTakesTheLastVertex) {
    expectProvokingVertexColours(mesa(), GlProgram::PerVertex);
}

// The standard equation at the centre: N = V = (0, 0, 1), a directional light from L = (0.6, 0, 0.8)
// (N·L = 0.8), n = 10. Blinn-Phong: H = (0.6, 0, 1.8)/√3.6, (N·H)² = 3.24/3.6 = 0.9, so (N·H)^10 = 0.9^5
// = 0.59049. Phong: R = 2(N·L)N − L = (−0.6, 0, 0.8), (R·V)^10 = 0.8^10 = 0.1073741824.
//   c = m_e + a_global m_a + l_a m_a + 0.8 l_d m_d + l_s m_s spec
//     = (0.01, 0.02, 0.03) + 0.2·0.5 + 0.1·0.5 + 0.8·(0.5, 0.25, 0.125) + 0.25 spec.
vec3 standardAtCentre(double spec) {
    return vec3(float(0.01 + 0.1 + 0.05 + 0.4 + 0.25 * spec), float(0.02 + 0.1 + 0.05 + 0.2 + 0.25 * spec),
                float(0.03 + 0.1 + 0.05 + 0.1 + 0.25 * spec));
}

GlScene standardScene(GlProgram program, ShadingFrequency frequency, ReflectionModel reflection) {
    GlScene scene = eyeScene();
    scene.globalAmbient = vec3(0.2f);
    LightParams light = headOnLight();
    light.direction = vec3(-0.6f, 0.0f, -0.8f);
    light.ambient = vec3(0.1f);
    scene.lights = {light};
    GlDraw draw = fanSquare(program, frequency);
    draw.reflection = reflection;
    draw.material.emission = vec3(0.01f, 0.02f, 0.03f);
    draw.material.ambient = vec3(0.5f);
    draw.material.specular = vec3(0.25f);
    draw.material.shininess = 10.0f;
    scene.draws = {draw};
    return scene;
}

TEST_F(MesaOracle, StandardEquationAtTheCentre) {
    const vec3 blinn = standardAtCentre(0.59049), phong = standardAtCentre(0.1073741824);
    auto centre = [&](GlProgram program, ShadingFrequency frequency, ReflectionModel reflection) {
        return drawScene(mesa(), standardScene(program, frequency, reflection)).at(kCentre, kCentre);
    };
    EXPECT_RGB_NEAR(centre(GlProgram::PerPixel, ShadingFrequency::Phong, ReflectionModel::BlinnPhong), blinn,
                    2e-5);
    EXPECT_RGB_NEAR(centre(GlProgram::PerPixel, ShadingFrequency::Phong, ReflectionModel::Phong), phong,
                    2e-5);
    EXPECT_RGB_NEAR(centre(GlProgram::PerVertex, ShadingFrequency::Gouraud, ReflectionModel::BlinnPhong),
                    blinn, 2e-5);
    EXPECT_RGB_NEAR(centre(GlProgram::PerVertex, ShadingFrequency::Gouraud, ReflectionModel::Phong), phong,
                    2e-5);
    // OpenGL's own: the centre vertex lit by fixed function (local viewer, so V = (0, 0, 1) there too).
    EXPECT_RGB_NEAR(centre(GlProgram::FixedFunction, ShadingFrequency::Gouraud, ReflectionModel::BlinnPhong),
                    blinn, 2e-5);
}

// Cook-Torrance head on (N = V = L = H): roughness 0.5, α = 0.25, α² = 1/16. D = 1/(π α²) for GGX and
// Beckmann alike; G = 1 for both geometry terms; F = F0 for Schlick and, with F0 = 0.04 (η = 1.5), for
// exact Fresnel too. Dielectric, c_base = (0.5, 0.25, 0.125), c_light = 1:
//   π (F0 D G / 4 + (1 − F0) c_base/π) = F0/(4α²) + 0.96 c_base = 0.16 + 0.96 c_base,
// plus a_global c_base = 0.1 c_base and m_emission (0.01, 0.02, 0.03). Gold (metal, F0 = c_base):
// F0/(4α²) = 4 F0, unclamped in the float buffer, + 0.1 c_base + emission. Exact Fresnel at normal
// incidence is ((η − 1)/(η + 1))² = F0 with η from F0 kept below 1: gold's red F0 = 1 reflects 0.9999.
TEST_F(MesaOracle, CookTorranceHeadOn) {
    const vec3 emission(0.01f, 0.02f, 0.03f);
    const vec3 dielectric(0.5f, 0.25f, 0.125f), gold(1.0f, 0.782f, 0.344f);
    for (const NormalDistribution d : {NormalDistribution::GGX, NormalDistribution::Beckmann})
        for (const FresnelModel f : {FresnelModel::Schlick, FresnelModel::Exact})
            for (const GeometryTerm g : {GeometryTerm::SmithGGX, GeometryTerm::CookTorrance})
                for (const GlProgram program : {GlProgram::PerPixel, GlProgram::PerVertex})
                    for (const bool metal : {false, true}) {
                        SCOPED_TRACE(::testing::Message()
                                     << "D " << int(d) << ", F " << int(f) << ", G " << int(g) << ", program "
                                     << int(program) << (metal ? ", gold" : ", dielectric"));
                        GlScene scene = eyeScene();
                        scene.globalAmbient = vec3(0.1f);
                        scene.brdf = {d, f, g};
                        scene.lights = {headOnLight()};
                        GlDraw draw =
                            fanSquare(program, program == GlProgram::PerPixel ? ShadingFrequency::Phong
                                                                              : ShadingFrequency::Gouraud);
                        draw.reflection = ReflectionModel::CookTorrance;
                        draw.material.emission = emission;
                        draw.pbr.baseColor = metal ? gold : dielectric;
                        draw.pbr.metalness = metal ? 1.0f : 0.0f;
                        draw.pbr.roughness = 0.5f;
                        draw.pbr.f0 = vec3(0.04f);
                        scene.draws = {draw};
                        const vec3 goldF0 = f == FresnelModel::Exact ? min(gold, vec3(0.9999f)) : gold;
                        const vec3 expected = metal
                                                  ? 4.0f * goldF0 + 0.1f * gold + emission
                                                  : 0.16f + 0.96f * dielectric + 0.1f * dielectric + emission;
                        EXPECT_RGB_NEAR(drawScene(mesa(), scene).at(kCentre, kCentre), expected, 5e-5);
                    }
}

// A diffuse map of one texel colour t: per pixel and per vertex, t multiplies the diffuse term only;
// with clampColor and in fixed function (GL_MODULATE) it multiplies the whole clamped colour.
TEST_F(MesaOracle, DiffuseMapMultipliesAsDocumented) {
    Texture map;
    map.width = map.height = 2;
    map.texels.assign(4, vec4(0.5f, 0.75f, 1.0f, 1.0f));
    const vec3 t(0.5f, 0.75f, 1.0f);
    GlScene scene = eyeScene();
    scene.globalAmbient = vec3(0.2f);
    scene.lights = {headOnLight()};
    const vec3 emission(0.1f), ambient = 0.2f * vec3(0.5f), diffuse(0.5f, 0.25f, 0.125f);
    auto centre = [&](GlProgram program, ShadingFrequency frequency, bool clampColor) {
        GlDraw draw = fanSquare(program, frequency);
        draw.material.emission = emission;
        draw.material.ambient = vec3(0.5f);
        draw.diffuseMap = &map;
        draw.clampColor = clampColor;
        scene.draws = {draw};
        return drawScene(mesa(), scene).at(kCentre, kCentre);
    };
    const vec3 diffuseOnly = emission + ambient + diffuse * t;
    const vec3 whole = t * (emission + ambient + diffuse);
    EXPECT_RGB_NEAR(centre(GlProgram::PerPixel, ShadingFrequency::Phong, false), diffuseOnly, 1e-5);
    EXPECT_RGB_NEAR(centre(GlProgram::PerVertex, ShadingFrequency::Gouraud, false), diffuseOnly, 1e-5);
    EXPECT_RGB_NEAR(centre(GlProgram::PerVertex, ShadingFrequency::Flat, false), diffuseOnly, 1e-5);
    EXPECT_RGB_NEAR(centre(GlProgram::PerVertex, ShadingFrequency::Gouraud, true), whole, 1e-5);
    EXPECT_RGB_NEAR(centre(GlProgram::FixedFunction, ShadingFrequency::Gouraud, false), whole, 1e-5);
}

// Fixed function clamps the lit vertex colour to [0, 1]; the GLSL programs only with clampColor.
TEST_F(MesaOracle, ColourClamping) {
    GlScene scene = eyeScene();
    LightParams light = headOnLight();
    light.diffuse = vec3(4.0f);
    scene.lights = {light};
    auto centre = [&](GlProgram program, ShadingFrequency frequency, bool clampColor) {
        GlDraw draw = fanSquare(program, frequency);
        draw.clampColor = clampColor;
        scene.draws = {draw};
        return drawScene(mesa(), scene).at(kCentre, kCentre);
    };
    const vec3 clamped(1.0f, 1.0f, 0.5f), unclamped(2.0f, 1.0f, 0.5f);
    EXPECT_RGB_NEAR(centre(GlProgram::FixedFunction, ShadingFrequency::Gouraud, false), clamped, 1e-6);
    EXPECT_RGB_NEAR(centre(GlProgram::PerPixel, ShadingFrequency::Phong, false), unclamped, 1e-6);
    EXPECT_RGB_NEAR(centre(GlProgram::PerPixel, ShadingFrequency::Phong, true), clamped, 1e-6);
    EXPECT_RGB_NEAR(centre(GlProgram::PerVertex, ShadingFrequency::Gouraud, true), clamped, 1e-6);
}

// A smooth spot through the GLSL programs: at 25° off its axis, between the 20° inner and 30° outer
// cones, smoothstep(cos 30°, cos 20°, cos 25°).
TEST_F(MesaOracle, SmoothSpotThroughGlsl) {
    GlScene scene = eyeScene();
    LightParams spot;
    spot.kind = LightKind::Spot;
    spot.spotProfile = SpotProfile::Smooth;
    spot.position = vec3(0.0f, 0.0f, -1.0f);  // 1 in front of the centre: d = 1, no attenuation
    const float angle = glm::radians(25.0f);
    spot.spotDirection = vec3(std::sin(angle), 0.0f, -std::cos(angle));
    scene.lights = {spot};
    scene.draws = {fanSquare(GlProgram::PerPixel, ShadingFrequency::Phong)};
    const double pi = 3.14159265358979323846;
    const double c30 = std::cos(30.0 * pi / 180.0), c20 = std::cos(20.0 * pi / 180.0);
    const double t = (std::cos(25.0 * pi / 180.0) - c30) / (c20 - c30);
    const float factor = float(t * t * (3.0 - 2.0 * t));
    EXPECT_RGB_NEAR(drawScene(mesa(), scene).at(kCentre, kCentre), factor * vec3(0.5f, 0.25f, 0.125f), 2e-5);

    // Fixed function has no smooth spot.
    scene.draws = {fanSquare(GlProgram::FixedFunction, ShadingFrequency::Gouraud)};
    EXPECT_THROW(mesa().load(scene), std::invalid_argument);
}

TEST_F(MesaOracle, RefusesWhatOpenGlCannotDraw) {
    GlScene scene = eyeScene();
    scene.lights = {headOnLight()};
    auto loads = [&](const GlDraw& draw) {
        scene.draws = {draw};
        try {
            mesa().load(scene);
            return std::string();
        } catch (const std::invalid_argument& error) {
            EXPECT_EQ(std::string(error.what()).find('\n'), std::string::npos) << error.what();
            return std::string(error.what());
        }
    };
    GlDraw draw = fanSquare(GlProgram::FixedFunction, ShadingFrequency::Gouraud);
    EXPECT_EQ(loads(draw), "");
    draw.material.shininess = 129.0f;
    EXPECT_NE(loads(draw).find("shininess"), std::string::npos);
    draw = fanSquare(GlProgram::FixedFunction, ShadingFrequency::Gouraud);
    draw.reflection = ReflectionModel::CookTorrance;
    EXPECT_NE(loads(draw).find("Blinn-Phong"), std::string::npos);
    EXPECT_NE(loads(fanSquare(GlProgram::PerPixel, ShadingFrequency::Gouraud)).find("Phong"),
              std::string::npos);
    EXPECT_NE(loads(fanSquare(GlProgram::PerVertex, ShadingFrequency::Phong)).find("Gouraud"),
              std::string::npos);
    draw = fanSquare(GlProgram::PerPixel, ShadingFrequency::Phong);
    draw.indices.insert(draw.indices.end(), {0, 1, 7});
    EXPECT_NE(loads(draw).find("index 7"), std::string::npos);
    scene.lights.assign(9, headOnLight());
    EXPECT_NE(loads(fanSquare(GlProgram::PerPixel, ShadingFrequency::Phong)).find("9 lights"),
              std::string::npos);
    scene.lights = {headOnLight()};
    scene.lights[0].kind = LightKind::Spot;
    scene.lights[0].spotCutoffDegrees = 120.0f;
    EXPECT_NE(loads(fanSquare(GlProgram::FixedFunction, ShadingFrequency::Gouraud)).find("cutoff"),
              std::string::npos);
    EXPECT_EQ(loads(fanSquare(GlProgram::PerPixel, ShadingFrequency::Phong)), "");  // GLSL takes any cone

    // Fixed function writes (c, α): Replace and Over only.
    scene.lights = {headOnLight()};
    for (const BlendMode blend : {BlendMode::PremultipliedOver, BlendMode::Additive, BlendMode::Multiply}) {
        draw = fanSquare(GlProgram::FixedFunction, ShadingFrequency::Gouraud);
        draw.blend = blend;
        EXPECT_NE(loads(draw).find("PerVertex"), std::string::npos);
        draw.program = GlProgram::PerVertex;
        EXPECT_EQ(loads(draw), "");
    }
    draw = fanSquare(GlProgram::FixedFunction, ShadingFrequency::Gouraud);
    draw.blend = BlendMode::Over;
    EXPECT_EQ(loads(draw), "");
    // glFog has no wall (linear fog with end = start) and no negative density; the GLSL programs do.
    scene.fog.mode = FogMode::Linear;
    scene.fog.start = scene.fog.end = 2.0f;
    EXPECT_NE(loads(fanSquare(GlProgram::FixedFunction, ShadingFrequency::Gouraud)).find("end = start"),
              std::string::npos);
    EXPECT_EQ(loads(fanSquare(GlProgram::PerPixel, ShadingFrequency::Phong)), "");
    scene.fog.mode = FogMode::Exponential;
    scene.fog.density = -0.5f;
    EXPECT_NE(loads(fanSquare(GlProgram::FixedFunction, ShadingFrequency::Gouraud)).find("density"),
              std::string::npos);
    EXPECT_EQ(loads(fanSquare(GlProgram::PerVertex, ShadingFrequency::Gouraud)), "");
}

// ---- Transparency, blend modes and fog ------------------------------------------------------------------

// How a draw is lit: a program with a frequency it goes with.
struct Lighting {
    GlProgram program;
    ShadingFrequency frequency;
};
const Lighting kFixedFunction{GlProgram::FixedFunction, ShadingFrequency::Gouraud};
const Lighting kPerPixel{GlProgram::PerPixel, ShadingFrequency::Phong};
const Lighting kPerVertex{GlProgram::PerVertex, ShadingFrequency::Gouraud};
const Lighting kPerVertexFlat{GlProgram::PerVertex, ShadingFrequency::Flat};

::testing::Message describe(const Lighting& lighting) {
    return ::testing::Message() << "program " << int(lighting.program) << ", frequency "
                                << int(lighting.frequency);
}

GlDraw fanSquare(const Lighting& lighting, float z = -2.0f) {
    return fanSquare(lighting.program, lighting.frequency, z);
}

// Head on, fanSquare's colour is its m_diffuse: the opaque square's d, and the transparent one's s.
const vec3 kOpaque(0.5f, 0.25f, 0.125f);
const vec3 kTransparent(0.25f, 0.5f, 0.75f);

// The opaque square (Replace) at z = −3, then a transparent one at z = −2, without depth writes, over
// it. The nearer square is seen larger: its pixels beyond the farther one's (|x| > 0.58 in NDC, column
// 51 and on) are over the clear colour (0, 0, 0, 0).
constexpr int kFrontOnly = 58;  // NDC 0.8: the nearer square only (it spans ±0.87)
GlScene overlapScene(const Lighting& lighting, BlendMode blend, float opacity) {
    GlScene scene = eyeScene();
    scene.lights = {headOnLight()};
    GlDraw transparent = fanSquare(lighting);
    transparent.material.diffuse = kTransparent;
    transparent.opacity = opacity;
    transparent.blend = blend;
    transparent.depthWrite = false;
    scene.draws = {fanSquare(lighting, -3.0f), transparent};
    return scene;
}

// What a blend gives for the shader's colour c of opacity α (gl_scene.h: the shader writes (c, α),
// (α·c, α) or (mix(1, c, α), α)) over a destination (d, α_d), by pipeline/state.h's equations:
//   Replace (c, α); Over and PremultipliedOver (α·c + (1 − α)·d, α + (1 − α)·α_d);
//   Additive (α·c + d, α + α_d); Multiply (((1 − α) + α·c)·d, α_d); OverGL (the gl preset's over:
//   glBlendFunc(SRC_ALPHA, ONE_MINUS_SRC_ALPHA) on alpha too) (α·c + (1 − α)·d, α² + (1 − α)·α_d).
vec4 blended(BlendMode blend, const vec3& c, float a, const vec4& destination) {
    const vec3 d(destination);
    const float ad = destination.a;
    switch (blend) {
        case BlendMode::Replace:
            return vec4(c, a);
        case BlendMode::Over:
        case BlendMode::PremultipliedOver:
            return vec4(a * c + (1.0f - a) * d, a + (1.0f - a) * ad);
        case BlendMode::Additive:
            return vec4(a * c + d, a + ad);
        case BlendMode::Multiply:
            return vec4(((1.0f - a) + a * c) * d, ad);
        case BlendMode::OverGL:
            return vec4(a * c + (1.0f - a) * d, a * a + (1.0f - a) * ad);
    }
    return vec4(0.0f);
}

#define EXPECT_RGBA_NEAR(actual, expected, tolerance)         \
    do {                                                      \
        const vec4 e4_ = (expected);                          \
        EXPECT_RGB_NEAR(actual, vec3(e4_), tolerance);        \
        EXPECT_NEAR((actual).a, e4_.a, tolerance) << "alpha"; \
    } while (false)

// A square of opacity 0.25 over an opaque one and, at the nearer square's edge, over the clear colour:
// every blend mode through the GLSL programs; Replace and Over in fixed function (the others need a
// shader's output, RefusesWhatOpenGlCannotDraw). The framebuffer's alpha follows state.h too:
// glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA) alone would give Over α² + (1 − α)·α_d.
TEST_F(MesaOracle, BlendModesOverAnOpaqueSquare) {
    const float a = 0.25f;
    for (const Lighting& lighting : {kFixedFunction, kPerPixel, kPerVertex, kPerVertexFlat})
        for (const BlendMode blend : {BlendMode::Replace, BlendMode::Over, BlendMode::PremultipliedOver,
                                      BlendMode::Additive, BlendMode::Multiply}) {
            if (lighting.program == GlProgram::FixedFunction && blend != BlendMode::Replace &&
                blend != BlendMode::Over)
                continue;
            SCOPED_TRACE(describe(lighting) << ", blend " << blend);
            const LinearImage image = drawScene(mesa(), overlapScene(lighting, blend, a));
            EXPECT_RGBA_NEAR(image.at(kCentre, kCentre), blended(blend, kTransparent, a, vec4(kOpaque, 1.0f)),
                             1e-6);
            EXPECT_RGBA_NEAR(image.at(kFrontOnly, kCentre), blended(blend, kTransparent, a, kClear), 1e-6);
        }
}

// α = opacity × the diffuse map's alpha: opacity 0.5 with a white map of alpha 0.5 is α = 0.25 (fixed
// function: GL_MODULATE multiplies the lit alpha, the material's diffuse alpha, by the texel's).
TEST_F(MesaOracle, DiffuseMapAlphaMultipliesOpacity) {
    Texture map;
    map.width = map.height = 2;
    map.texels.assign(4, vec4(1.0f, 1.0f, 1.0f, 0.5f));
    for (const Lighting& lighting : {kFixedFunction, kPerPixel, kPerVertex}) {
        SCOPED_TRACE(describe(lighting));
        GlScene scene = overlapScene(lighting, BlendMode::Over, 0.5f);
        scene.draws[1].diffuseMap = &map;
        EXPECT_RGBA_NEAR(drawScene(mesa(), scene).at(kCentre, kCentre),
                         blended(BlendMode::Over, kTransparent, 0.25f, vec4(kOpaque, 1.0f)), 1e-6);
    }
}

// Depth writes off: the transparent square at z = −2, drawn first, leaves the depth buffer as it was,
// so the opaque square at z = −3 drawn after it passes GL_LESS and replaces it: OpenGL draws in the
// order given, which is why transparent draws come last. With depth writes on, the farther square
// fails the depth test there, and the nearer one's α·s over the clear colour stays.
TEST_F(MesaOracle, DepthWritesOffLetALaterFartherDrawReplace) {
    for (const Lighting& lighting : {kFixedFunction, kPerPixel}) {
        SCOPED_TRACE(describe(lighting));
        GlScene scene = overlapScene(lighting, BlendMode::Over, 0.25f);
        std::swap(scene.draws[0], scene.draws[1]);  // the transparent square first
        EXPECT_RGBA_NEAR(drawScene(mesa(), scene).at(kCentre, kCentre), vec4(kOpaque, 1.0f), 1e-6);
        scene.draws[0].depthWrite = true;
        EXPECT_RGBA_NEAR(drawScene(mesa(), scene).at(kCentre, kCentre), vec4(0.25f * kTransparent, 0.25f),
                         1e-6);
    }

    // A frame whose last draw turned depth writes off: the next frame still starts from a cleared depth
    // buffer (else the opaque square would fail GL_LESS against its own depth of the frame before).
    const GlScene scene = overlapScene(kPerPixel, BlendMode::Over, 0.25f);
    const LinearImage first = drawScene(mesa(), scene);
    mesa().renderFrame();
    EXPECT_EQ(mesa().readImage().pixels, first.pixels);
}

// A fog of colour (0.2, 0.4, 0.6) and the factor f it should have.
struct FogCase {
    FogParams fog;
    float f;
};

FogParams fogParams(FogMode mode, float start, float end, float density = 1.0f) {
    FogParams fog;
    fog.mode = mode;
    fog.color = vec3(0.2f, 0.4f, 0.6f);
    fog.start = start;
    fog.end = end;
    fog.density = density;
    return fog;
}

vec3 fogged(const vec3& c, const FogParams& fog, float f) {
    return f * c + (1.0f - f) * fog.color;
}

// Fog on the square at z = −2, |z_eye| = 2 at every pixel, of colour c = (0.5, 0.25, 0.125) head on:
// c·f + c_fog·(1 − f) with
//   linear from 2 to 4 (at the start): f = 1;  1 to 3 (the middle): 0.5;  0 to 2 (at the end): 0;
//   0 to 1 (beyond the end): −1, clamped to 0;  3 to 5 (before the start): 1.5, clamped to 1;
//   exp, density 0.25: e^(−0.5);  exp², density 0.25: e^(−0.25).
// Every pixel, fixed function included: |z_eye| is linear across the square, so fixed function's
// interpolating it from the vertices is exact. Then the GLSL programs' linear fog with end = start (a
// wall, fog.h): at 2, the square is behind it (f = 0); at 2.5, in front of it (f = 1).
TEST_F(MesaOracle, FogAtAKnownDepth) {
    const std::vector<FogCase> cases = {
        {fogParams(FogMode::Linear, 2.0f, 4.0f), 1.0f},
        {fogParams(FogMode::Linear, 1.0f, 3.0f), 0.5f},
        {fogParams(FogMode::Linear, 0.0f, 2.0f), 0.0f},
        {fogParams(FogMode::Linear, 0.0f, 1.0f), 0.0f},
        {fogParams(FogMode::Linear, 3.0f, 5.0f), 1.0f},
        {fogParams(FogMode::Exponential, 0.0f, 1.0f, 0.25f), float(std::exp(-0.5))},
        {fogParams(FogMode::ExponentialSquared, 0.0f, 1.0f, 0.25f), float(std::exp(-0.25))},
    };
    auto expectEveryPixel = [&](const Lighting& lighting, const FogCase& fogCase) {
        SCOPED_TRACE(describe(lighting) << ", fog mode " << int(fogCase.fog.mode) << ", start "
                                        << fogCase.fog.start << ", end " << fogCase.fog.end);
        GlScene scene = eyeScene();
        scene.lights = {headOnLight()};
        scene.fog = fogCase.fog;
        scene.draws = {fanSquare(lighting)};
        const vec3 expected = fogged(kOpaque, fogCase.fog, fogCase.f);
        std::size_t covered = 0;
        for (const vec4& pixel : drawScene(mesa(), scene).pixels) {
            if (!drawn(pixel)) continue;
            ++covered;
            const vec3 difference = abs(vec3(pixel) - expected);
            if (std::max({difference.r, difference.g, difference.b}) > 1e-5f) {
                EXPECT_RGB_NEAR(pixel, expected, 1e-5);
                return;
            }
            EXPECT_EQ(pixel.a, 1.0f);
        }
        EXPECT_GT(covered, 3000u);
    };
    for (const Lighting& lighting : {kFixedFunction, kPerPixel, kPerVertex, kPerVertexFlat})
        for (const FogCase& fogCase : cases)
            expectEveryPixel(lighting, fogCase);
    for (const Lighting& lighting : {kPerPixel, kPerVertex}) {
        expectEveryPixel(lighting, {fogParams(FogMode::Linear, 2.0f, 2.0f), 0.0f});
        expectEveryPixel(lighting, {fogParams(FogMode::Linear, 2.5f, 2.5f), 1.0f});
    }
}

// The fog distance is |z_eye|, not −z_eye: a projection looking down +z (clip space does not care which
// way the eye looks) shows a square at z = +2, fogged as at z = −2 (linear from 1 to 3: f = 0.5);
// −z_eye = −2 would leave it unfogged. Emission only, without lights: c = m_emission.
TEST_F(MesaOracle, FogDistanceIsTheAbsoluteEyeDepth) {
    const FogParams fog = fogParams(FogMode::Linear, 1.0f, 3.0f);
    for (const Lighting& lighting : {kFixedFunction, kPerPixel, kPerVertex}) {
        SCOPED_TRACE(describe(lighting));
        GlScene scene = eyeScene();
        scene.clipFromView = scene.clipFromView * glm::scale(mat4(1.0f), vec3(1.0f, 1.0f, -1.0f));
        scene.cullBackFaces = false;  // the mirror turns the square's winding
        scene.fog = fog;
        GlDraw draw = fanSquare(lighting, 2.0f);
        draw.material.diffuse = vec3(0.0f);
        draw.material.emission = kOpaque;
        scene.draws = {draw};
        EXPECT_RGB_NEAR(drawScene(mesa(), scene).at(kCentre, kCentre), fogged(kOpaque, fog, 0.5f), 1e-6);
    }
}

// Radial fog, linear from 1 to 3 along |P_eye|, on the square at z = −2. At the centre |P| = 2: f = 0.5.
// Along the middle row (y = 0), at x: |P| = √(4 + x²) per pixel, as Facet and the GLSL programs take it
// (flat ones too: the eye-space position is interpolated for the fog whatever the colour's
// interpolation). Fixed function (GL_EYE_RADIAL_NV) takes |P| at the vertices and interpolates it:
// between the centre (|P| = 2) and the corners (1, ±1, −2) (|P| = √6), (1 − x)·2 + x·√6, farther than
// √(4 + x²). Then exp² radial fog (density 0.25) in fixed function: its factor is computed per
// fragment from the interpolated distance, e^(−(0.25·d)²), not interpolated from the vertices' factors.
TEST_F(MesaOracle, RadialFog) {
    FogParams fog = fogParams(FogMode::Linear, 1.0f, 3.0f);
    fog.distance = FogDistance::Radial;
    constexpr int column = 48;
    const double tan30 = std::tan(3.14159265358979323846 / 6.0);
    const double x = ((column + 0.5) / kSize * 2.0 - 1.0) * 2.0 * tan30;  // the eye-space x it sees
    const double perPixel = std::sqrt(4.0 + x * x), perVertex = (1.0 - x) * 2.0 + x * std::sqrt(6.0);
    ASSERT_GT(perVertex - perPixel, 0.15);
    auto draw = [&](const Lighting& lighting, const FogParams& params) {
        GlScene scene = eyeScene();
        scene.lights = {headOnLight()};
        scene.fog = params;
        scene.draws = {fanSquare(lighting)};
        return drawScene(mesa(), scene);
    };
    for (const Lighting& lighting : {kPerPixel, kPerVertex, kPerVertexFlat}) {
        SCOPED_TRACE(describe(lighting));
        const LinearImage image = draw(lighting, fog);
        EXPECT_RGB_NEAR(image.at(kCentre, kCentre), fogged(kOpaque, fog, 0.5f), 1e-6);
        EXPECT_RGB_NEAR(image.at(column, kCentre), fogged(kOpaque, fog, float((3.0 - perPixel) / 2.0)), 1e-5);
    }

    LinearImage image;
    try {
        image = draw(kFixedFunction, fog);
    } catch (const std::invalid_argument& error) {
        GTEST_SKIP() << error.what();  // no GL_NV_fog_distance
    }
    EXPECT_RGB_NEAR(image.at(kCentre, kCentre), fogged(kOpaque, fog, 0.5f), 1e-6);
    EXPECT_RGB_NEAR(image.at(column, kCentre), fogged(kOpaque, fog, float((3.0 - perVertex) / 2.0)), 1e-5);
    FogParams exp2 = fogParams(FogMode::ExponentialSquared, 0.0f, 1.0f, 0.25f);
    exp2.distance = FogDistance::Radial;
    const double dz = 0.25 * perVertex;
    EXPECT_RGB_NEAR(draw(kFixedFunction, exp2).at(column, kCentre),
                    fogged(kOpaque, exp2, float(std::exp(-dz * dz))), 1e-5);
}

// Fog before the blend: linear fog from 1 to 5 fogs the opaque square at z = −3 with f = 0.5 and the
// transparent one (α = 0.25) at z = −2 with f = 0.75; the blend then combines s' = 0.75·s + 0.25·c_fog
// with d' = 0.5·d + 0.5·c_fog.
TEST_F(MesaOracle, FogBeforeTheBlend) {
    const FogParams fog = fogParams(FogMode::Linear, 1.0f, 5.0f);
    const vec3 d = fogged(kOpaque, fog, 0.5f), s = fogged(kTransparent, fog, 0.75f);
    for (const auto& [lighting, blend] :
         {std::pair{kFixedFunction, BlendMode::Over}, std::pair{kPerPixel, BlendMode::Over},
          std::pair{kPerVertex, BlendMode::PremultipliedOver}, std::pair{kPerPixel, BlendMode::Additive},
          std::pair{kPerVertexFlat, BlendMode::Multiply}}) {
        SCOPED_TRACE(describe(lighting) << ", blend " << blend);
        GlScene scene = overlapScene(lighting, blend, 0.25f);
        scene.fog = fog;
        EXPECT_RGBA_NEAR(drawScene(mesa(), scene).at(kCentre, kCentre),
                         blended(blend, s, 0.25f, vec4(d, 1.0f)), 1e-6);
    }
}

// ---- The scene's buffer formats and texture filter (facet compare --depth, --color-buffer,
// --texture-filter) --------------------------------------------------------------------------------

// A colour no buffer format holds exactly reads back rounded as Facet's colour buffer rounds it (half:
// to a neighbouring half, see below): the peer renders into RGBA8, RGBA16F or RGBA32F as
// GlScene::colorFormat says.
TEST_F(MesaOracle, ColourBufferFormatRoundsAsFacetStoresIt) {
    GlScene scene = eyeScene();
    scene.lights = {headOnLight()};
    GlDraw draw = fanSquare(GlProgram::PerPixel, ShadingFrequency::Phong);
    draw.material.diffuse = vec3(0.31f, 0.1f, 0.71f);  // N·L = 1 at the centre; no 8-bit or half ties
    scene.draws = {draw};
    for (const ColorBufferFormat format :
         {ColorBufferFormat::Float, ColorBufferFormat::Half, ColorBufferFormat::Unorm8}) {
        SCOPED_TRACE(std::string(nameOf(format)));
        scene.colorFormat = format;
        const vec4 expected = roundToColorBuffer(format, vec4(0.31f, 0.1f, 0.71f, 1.0f));
        const vec4 drawn = drawScene(mesa(), scene).at(kCentre, kCentre);
        if (format == ColorBufferFormat::Half) {
            // Measured: softpipe converts to RGBA16F toward zero (0.31 → 0.30981), Facet to nearest
            // (0.31006): within one half step (at most 2^-10 relative) of each other, and not the float
            // value.
            for (int k = 0; k < 3; ++k) {
                EXPECT_NEAR(drawn[k], expected[k], expected[k] * 0x1p-10f) << k;
                EXPECT_EQ(roundToColorBuffer(format, vec4(drawn[k])).r, drawn[k]) << k << ": not a half";
            }
        } else {
            EXPECT_RGB_NEAR(drawn, vec3(expected), 2e-6);
        }
    }
    EXPECT_NE(roundToColorBuffer(ColorBufferFormat::Unorm8, vec4(0.3f)).r, 0.3f);  // the test can fail
}

// Two squares 0.0003 apart at 9 units (near 0.5, far 10), the farther (red) drawn first: their window
// depths are 65151.75 and 65151.63 in 16-bit codes — the same code, so the nearer (green) fails
// GL_LESS — but 33 codes apart in 24 bits. The peer's depth renderbuffer is GlScene::depthFormat's.
TEST_F(MesaOracle, DepthFormatResolvesAsItsBits) {
    GlScene scene = eyeScene();
    scene.clipFromView = glm::perspective(glm::radians(60.0f), 1.0f, 0.5f, 10.0f);
    GlDraw far = fanSquare(GlProgram::PerPixel, ShadingFrequency::Phong, -9.0f);
    GlDraw near = fanSquare(GlProgram::PerPixel, ShadingFrequency::Phong, -8.9997f);
    far.material.diffuse = vec3(0.0f);
    far.material.emission = vec3(1.0f, 0.0f, 0.0f);
    near.material.diffuse = vec3(0.0f);
    near.material.emission = vec3(0.0f, 1.0f, 0.0f);
    scene.draws = {far, near};
    const auto centre = [&](DepthBufferFormat format) {
        scene.depthFormat = format;
        return drawScene(mesa(), scene).at(kCentre, kCentre);
    };
    {
        SCOPED_TRACE("16 bits z-fight");
        EXPECT_RGB_NEAR(centre(DepthBufferFormat::Unorm16), vec3(1.0f, 0.0f, 0.0f), 1e-6);
    }
    {
        SCOPED_TRACE("24 bits resolve");
        EXPECT_RGB_NEAR(centre(DepthBufferFormat::Unorm24), vec3(0.0f, 1.0f, 0.0f), 1e-6);
    }
    {
        SCOPED_TRACE("float resolves");
        EXPECT_RGB_NEAR(centre(DepthBufferFormat::Float), vec3(0.0f, 1.0f, 0.0f), 1e-6);
    }
}

// Reversed Z: a projection taking the near plane to z = w and the far plane to 0, drawn with 0..1 clip
// depth, GL_GREATER and depth cleared to 0. The nearer square (green) drawn first stays in front of the
// farther one (red); the same projection drawn as plain float depth (GL_LESS) lets the farther win.
TEST_F(MesaOracle, ReversedZKeepsTheNearerSurface) {
    GlScene scene = eyeScene();
    const float n = 0.5f, f = 10.0f;
    mat4 reversed = glm::perspective(glm::radians(60.0f), 1.0f, n, f);
    reversed[2][2] = n / (f - n);
    reversed[3][2] = f * n / (f - n);
    scene.clipFromView = reversed;
    GlDraw near = fanSquare(GlProgram::PerPixel, ShadingFrequency::Phong, -2.0f);
    GlDraw far = fanSquare(GlProgram::PerPixel, ShadingFrequency::Phong, -4.0f);
    near.material.diffuse = far.material.diffuse = vec3(0.0f);
    near.material.emission = vec3(0.0f, 1.0f, 0.0f);
    far.material.emission = vec3(1.0f, 0.0f, 0.0f);
    scene.draws = {near, far};
    scene.depthFormat = DepthBufferFormat::ReversedFloat;
    EXPECT_RGB_NEAR(drawScene(mesa(), scene).at(kCentre, kCentre), vec3(0.0f, 1.0f, 0.0f), 1e-6);
    scene.depthFormat = DepthBufferFormat::Float;
    EXPECT_RGB_NEAR(drawScene(mesa(), scene).at(kCentre, kCentre), vec3(1.0f, 0.0f, 0.0f), 1e-6);
}

// The texture filter: right of the middle of a 2×1 map, black | white, nearest reads the white texel
// and bilinear a mix; a 512-texel map of one-texel stripes, minified about 9 times, is a uniform
// grey under trilinear (its mip levels average the stripes) and stripes or moiré under bilinear.
TEST_F(MesaOracle, TextureFilterAsTheSceneSays) {
    GlScene scene = eyeScene();
    scene.lights = {headOnLight()};
    GlDraw draw = fanSquare(GlProgram::PerPixel, ShadingFrequency::Phong);
    draw.material.diffuse = vec3(1.0f);
    Texture halves;
    halves.width = 2;
    halves.height = 1;
    halves.texels = {vec4(0.0f, 0.0f, 0.0f, 1.0f), vec4(1.0f)};
    draw.diffuseMap = &halves;
    scene.draws = {draw};
    // Eight pixels right of the centre, u ≈ 0.57: nearest reads the white texel alone, bilinear mixes.
    scene.textureFilter = TextureFilter::Nearest;
    EXPECT_NEAR(drawScene(mesa(), scene).at(kCentre + 8, kCentre).r, 1.0f, 1e-5);
    scene.textureFilter = TextureFilter::Bilinear;
    const float mixed = drawScene(mesa(), scene).at(kCentre + 8, kCentre).r;
    EXPECT_GT(mixed, 0.55f);
    EXPECT_LT(mixed, 0.95f);

    Texture stripes;
    stripes.width = stripes.height = 512;
    stripes.texels.resize(512 * 512);
    for (int y = 0; y < 512; ++y)
        for (int x = 0; x < 512; ++x)
            stripes.texels[static_cast<std::size_t>(y) * 512 + x] =
                x % 2 ? vec4(1.0f) : vec4(0.0f, 0.0f, 0.0f, 1.0f);
    buildMipChain(stripes);
    scene.draws[0].diffuseMap = &stripes;
    const auto largestOffGrey = [&](TextureFilter filter) {
        scene.textureFilter = filter;
        const LinearImage image = drawScene(mesa(), scene);
        float largest = 0.0f;
        for (int x = kCentre - 20; x <= kCentre + 20; ++x)
            largest = std::max(largest, std::abs(image.at(x, kCentre).r - 0.5f));
        return largest;
    };
    EXPECT_LT(largestOffGrey(TextureFilter::Trilinear), 1e-3f);
    EXPECT_GT(largestOffGrey(TextureFilter::Bilinear), 0.1f);
}

// ---- The benchmark's peer: llvmpipe draws what Facet draws -------------------------------------------

// The cow, textured, lit by the default directional light and a point light, at 160×120.
class BenchmarkPeer : public LlvmpipeTest {};

TEST_F(BenchmarkPeer, DrawsTheSameImageAsFacet) {
    EXPECT_NE(mesa().renderer().find("llvmpipe"), std::string::npos) << mesa().renderer();

    Scene scene = sceneForModel(FACET_SOURCE_DIR "/models/spot/spot_triangulated.obj");
    scene.width = 160;
    scene.height = 120;
    LightSpec key;  // the renderer's default key light
    key.direction = vec3(0.45f, -0.55f, -1.0f);
    key.cameraRelative = true;
    LightSpec point;
    point.type = LightKind::Point;
    point.position = vec3(-2.0f, 2.0f, 0.5f);
    point.color = vec3(1.0f, 0.8f, 0.6f);
    point.cameraRelative = true;
    scene.lights = {key, point};
    const PreparedScene prepared = prepareScene(scene);
    ASSERT_NE(prepared.draws.front().uniforms.diffuseMap, nullptr);  // the texture is compared too

    Framebuffer framebuffer(scene.width, scene.height);
    DrawContext context(1);
    renderFrame(prepared, framebuffer, context);
    const GlScene glScene = toGlScene(prepared);
    mesa().load(glScene);
    mesa().renderFrame();
    const LinearImage mesaImage = mesa().readImage();
    const float tolerance = mesa().floatColor() ? 1e-5f : 0.5f / 255.0f + 1e-5f;
    const ImageAgreement agreement =
        compareImages(toImage(framebuffer), mesaImage, prepared.clearColor, tolerance);
    EXPECT_TRUE(agreement.agrees()) << "coverage " << agreement.coverageAgreement << ", colour within "
                                    << agreement.colorWithinTolerance << ", mean difference "
                                    << agreement.meanColorDifference << ", foreground "
                                    << agreement.foregroundA << " vs " << agreement.foregroundB;
    EXPECT_GT(agreement.foregroundA, 2000u);  // the cow fills a good part of the frame

    // A second frame of a reloaded scene is the same.
    mesa().load(glScene);
    mesa().renderFrame();
    EXPECT_EQ(mesa().readImage().pixels, mesaImage.pixels);
}

}  // namespace
}  // namespace facet
