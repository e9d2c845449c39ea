// Scenes read from files and drawn: what the scene reader's values do to the image.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "base/errors.h"
#include "pipeline/color.h"
#include "pipeline/names.h"
#include "render/renderer.h"
#include "scene/scene.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

using SceneRenderTest = testing_support::TempFolderTest;

// ---- Directions of any length ---------------------------------------------------------------------

// The scene `text` (with "model" the bundled cube) drawn at 48×36 on one thread.
LinearImage renderCube(const fs::path& path, const std::string& text) {
    nlohmann::json document = nlohmann::json::parse(text);
    document["model"] = FACET_SOURCE_DIR "/models/cube/cube.obj";
    document["width"] = 48;
    document["height"] = 36;
    std::ofstream(path) << document.dump();
    const PreparedScene prepared = prepareScene(loadScene(path));
    Framebuffer framebuffer(48, 36);
    DrawContext context(1);
    renderFrame(prepared, framebuffer, context);
    return toImage(framebuffer);
}

// Only an exactly zero vector is refused; any other length lights the model exactly as the same
// direction at unit length (normalising in float turned 1e-30, 1e20 and -3e38 into NaN: black).
TEST_F(SceneRenderTest, DirectionsOfAnyLengthLightLikeUnitOnes) {
    const std::pair<std::string, std::string> cases[] = {
        {R"({"lights": [{"direction": [0, -1e-30, 0]}]})", R"({"lights": [{"direction": [0, -1, 0]}]})"},
        {R"({"lights": [{"direction": [0, -1e20, 0]}]})", R"({"lights": [{"direction": [0, -1, 0]}]})"},
        {R"({"lights": [{"direction": [-3e38, 0, 0]}]})", R"({"lights": [{"direction": [-1, 0, 0]}]})"},
        // 2^-100 · [1, -2, -2]: scaled by a power of two, the same unit vector to the last bit.
        {R"({"lights": [{"direction": [7.888609052210118e-31, -1.5777218104420236e-30, -1.5777218104420236e-30]}]})",
         R"({"lights": [{"direction": [1, -2, -2]}]})"},
        {R"({"lights": [{"type": "spot", "position": [0, 3, 0], "direction": [0, -1e-30, 0], "cutoff": 40}]})",
         R"({"lights": [{"type": "spot", "position": [0, 3, 0], "direction": [0, -1, 0], "cutoff": 40}]})"},
        {R"({"camera": {"eye": [2, 1, 3], "target": [0, 0, 0], "up": [0, 1e-30, 0]}})",
         R"({"camera": {"eye": [2, 1, 3], "target": [0, 0, 0], "up": [0, 1, 0]}})"},
        {R"({"camera": {"eye": [2, 1, 3], "target": [0, 0, 0], "up": [0, 3e38, 0]}})",
         R"({"camera": {"eye": [2, 1, 3], "target": [0, 0, 0], "up": [0, 1, 0]}})"},
    };
    for (const auto& [extreme, unit] : cases) {
        SCOPED_TRACE(extreme);
        const LinearImage expected = renderCube(folder_ / "unit.json", unit);
        const LinearImage actual = renderCube(folder_ / "extreme.json", extreme);
        // The cube is drawn and lit: some pixel is brighter than the background in the corner.
        bool lit = false;
        for (const glm::vec4& p : expected.pixels)
            lit = lit || p.r > expected.pixels[0].r + 0.05f;
        EXPECT_TRUE(lit);
        ASSERT_EQ(actual.pixels.size(), expected.pixels.size());
        std::size_t differing = 0;
        for (std::size_t i = 0; i < expected.pixels.size(); ++i)
            differing += actual.pixels[i] != expected.pixels[i];
        EXPECT_EQ(differing, 0u);
    }
}

// ---- Every scene-file choice reaches the prepared scene ------------------------------------------

#define FACET_CUBE FACET_SOURCE_DIR "/models/cube/cube.obj"

// The scene `json` (a JSON object's members; "model" the bundled cube unless it has "objects") read
// and prepared.
PreparedScene prepareCube(const fs::path& path, const std::string& json) {
    const bool objects = json.find("\"objects\"") != std::string::npos;
    std::ofstream(path) << "{" << (objects ? "" : R"("model": ")" FACET_CUBE R"(", )")
                        << R"("width": 32, "height": 24, )" << json << "}";
    return prepareScene(loadScene(path));
}

// For each name E's table offers in a scene file (all but `except`), the scene `json(name)` gives a
// prepared scene in which `reached` reads that very value: a renderer that ignores the key, or maps
// it to another value, fails.
template <class E, class Json, class Reached>
void expectEveryNameReaches(const fs::path& folder, Json json, Reached reached,
                            std::initializer_list<E> except = {}) {
    const std::vector<std::string> names = namesOf<E>(except);
    ASSERT_FALSE(names.empty());
    for (const std::string& name : names) {
        SCOPED_TRACE(name);
        const PreparedScene prepared = prepareCube(folder / "scene.json", json(name));
        ASSERT_FALSE(prepared.draws.empty());
        EXPECT_EQ(reached(prepared), *parseName<E>(name));
    }
}

TEST_F(SceneRenderTest, PipelineChoicesReachTheDrawState) {
    expectEveryNameReaches<CullMode>(
        folder_, [](const std::string& n) { return R"("pipeline": {"cull": ")" + n + R"("})"; },
        [](const PreparedScene& p) { return p.state.raster.cull; });
    expectEveryNameReaches<Interpolation>(
        folder_, [](const std::string& n) { return R"("pipeline": {"interpolation": ")" + n + R"("})"; },
        [](const PreparedScene& p) { return p.state.interpolation; });
}

TEST_F(SceneRenderTest, ObjectBlendReachesTheUniforms) {
    // Half transparent, so that "over" is blended too; a scene object is never "replace".
    expectEveryNameReaches<BlendMode>(
        folder_,
        [](const std::string& n) {
            return R"("objects": [{"model": ")" FACET_CUBE R"(", "material": {"opacity": 0.5}, "blend": ")" +
                   n + R"("}])";
        },
        [](const PreparedScene& p) { return p.draws[0].uniforms.blend; },
        {BlendMode::Replace, BlendMode::OverGL});
}

TEST_F(SceneRenderTest, LightTypeReachesTheUniforms) {
    expectEveryNameReaches<LightKind>(
        folder_,
        [](const std::string& n) {
            const std::string where = n == "directional" ? "" : R"(, "position": [0, 3, 0])";
            return R"("lights": [{"type": ")" + n + "\"" + where + "}]";
        },
        [](const PreparedScene& p) { return p.draws[0].uniforms.lights[0].kind; });
}

TEST_F(SceneRenderTest, LightingChoicesReachTheUniforms) {
    expectEveryNameReaches<ReflectionModel>(
        folder_, [](const std::string& n) { return R"("lighting": {"model": ")" + n + R"("})"; },
        [](const PreparedScene& p) { return p.draws[0].uniforms.reflection; });
    expectEveryNameReaches<ShadingFrequency>(
        folder_, [](const std::string& n) { return R"("lighting": {"shading": ")" + n + R"("})"; },
        [](const PreparedScene& p) { return p.draws[0].frequency; });
    expectEveryNameReaches<NormalDistribution>(
        folder_, [](const std::string& n) { return R"("lighting": {"distribution": ")" + n + R"("})"; },
        [](const PreparedScene& p) { return p.draws[0].uniforms.brdf.distribution; });
    expectEveryNameReaches<FresnelModel>(
        folder_, [](const std::string& n) { return R"("lighting": {"fresnel": ")" + n + R"("})"; },
        [](const PreparedScene& p) { return p.draws[0].uniforms.brdf.fresnel; });
    expectEveryNameReaches<GeometryTerm>(
        folder_, [](const std::string& n) { return R"("lighting": {"geometry": ")" + n + R"("})"; },
        [](const PreparedScene& p) { return p.draws[0].uniforms.brdf.geometry; });
    // The gl preset clamps lit colours as OpenGL 1.x does; the facet preset does not; the lecture preset
    // clamps N·V instead of flipping N.
    expectEveryNameReaches<LightingPreset>(
        folder_, [](const std::string& n) { return R"("lighting": {"preset": ")" + n + R"("})"; },
        [](const PreparedScene& p) {
            return p.draws[0].uniforms.clampNdotV   ? LightingPreset::Lecture
                   : p.draws[0].uniforms.clampColor ? LightingPreset::GL
                                                    : LightingPreset::Facet;
        });
}

TEST_F(SceneRenderTest, FogTransparencyAndGammaChoicesReachThePreparedScene) {
    expectEveryNameReaches<FogMode>(
        folder_, [](const std::string& n) { return R"("fog": {"mode": ")" + n + R"("})"; },
        [](const PreparedScene& p) { return p.draws[0].uniforms.fog.mode; }, {FogMode::None});
    expectEveryNameReaches<FogDistance>(
        folder_, [](const std::string& n) { return R"("fog": {"mode": "exp", "distance": ")" + n + R"("})"; },
        [](const PreparedScene& p) { return p.draws[0].uniforms.fog.distance; });
    expectEveryNameReaches<TransferCurve>(
        folder_, [](const std::string& n) { return R"("gamma": {"encode": ")" + n + R"("})"; },
        [](const PreparedScene& p) { return p.encoding.curve; });
    expectEveryNameReaches<TransparencyMode>(
        folder_, [](const std::string& n) { return R"("transparency": {"mode": ")" + n + R"("})"; },
        [](const PreparedScene& p) { return p.scene.transparency.mode; });
    expectEveryNameReaches<SortKey>(
        folder_, [](const std::string& n) { return R"("transparency": {"sort_key": ")" + n + R"("})"; },
        [](const PreparedScene& p) { return p.scene.transparency.key; });
}

// Computed normals: the scene's "normals" weighting reaches the vertices the draws hold. At the origin
// a 2×1 quad in z = 0 (the origin in its second fan triangle only) meets a triangle in x = 0
// (tests/io/obj_import_test.cpp computes the three by hand).
TEST_F(SceneRenderTest, NormalsChoiceReachesTheVertices) {
    const fs::path model = folder_ / "quad.obj";
    std::ofstream(model) << "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nv 0 0 1\nf 2 3 4 1\nf 1 4 5\n";
    const auto normalAtOrigin = [](const PreparedScene& p) {
        for (const PreparedDraw& draw : p.draws)
            for (const MeshVertex& v : draw.vertices)
                if (v.position == glm::vec3(0.0f)) return v.normal;
        return glm::vec3(0.0f);
    };
    const std::pair<VertexNormals, glm::vec3> expected[] = {
        {VertexNormals::PolygonArea, glm::vec3(1, 0, 4) / std::sqrt(17.0f)},
        {VertexNormals::TriangleArea, glm::vec3(1, 0, 2) / std::sqrt(5.0f)},
        {VertexNormals::Angle, glm::vec3(1, 0, 1) / std::sqrt(2.0f)}};
    for (const auto& [normals, want] : expected) {
        SCOPED_TRACE(nameOf(normals));
        const glm::vec3 got = normalAtOrigin(
            prepareCube(folder_ / "scene.json", R"("objects": [{"model": ")" + model.string() +
                                                    R"("}], "lighting": {"crease_angle": 180, "normals": ")" +
                                                    std::string(nameOf(normals)) + R"("})"));
        EXPECT_LT(glm::length(got - want), 1e-6f);
    }
}

// The formulas' choices: "powers" and "normalize" reach every draw's uniforms.
TEST_F(SceneRenderTest, FormulaChoicesReachTheUniforms) {
    expectEveryNameReaches<MathPrecision>(
        folder_, [](const std::string& n) { return R"("lighting": {"powers": ")" + n + R"("})"; },
        [](const PreparedScene& p) { return p.draws[0].uniforms.precision; });
    expectEveryNameReaches<Normalization>(
        folder_, [](const std::string& n) { return R"("lighting": {"normalize": ")" + n + R"("})"; },
        [](const PreparedScene& p) { return p.draws[0].uniforms.normalization; });
}

// The lecture preset reaches every draw (the notes' BRDF fields, N·V clamped instead of the flip, the
// colour clamped), the output curve (a pure 2.2 power: 0.5 is code round(255·0.5^(1/2.2)) = 186 where
// sRGB's 1.055·0.5^(1/2.4) − 0.055 gives 188) and the image. Catches: the preset read but not applied to
// the uniforms or the encoding, or applied to the facet preset too.
TEST_F(SceneRenderTest, LecturePresetReachesTheUniformsTheEncodingAndTheImage) {
    const std::string lectureScene = R"("lighting": {"preset": "lecture", "model": "cook-torrance"})";
    const std::string facetScene = R"("lighting": {"model": "cook-torrance"})";
    const PreparedScene lecture = prepareCube(folder_ / "lecture.json", lectureScene);
    const PreparedScene facet = prepareCube(folder_ / "facet.json", facetScene);
    const SurfaceUniforms& u = lecture.draws[0].uniforms;
    EXPECT_EQ(u.brdf.fresnelCosine, FresnelCosine::NdotL);
    EXPECT_EQ(u.brdf.denominator, MicrofacetDenominator::Pi);
    EXPECT_EQ(u.brdf.metal, MetalBlend::TintedLobe);
    EXPECT_TRUE(u.clampNdotV && !u.twoSidedFlip && u.clampColor);
    const SurfaceUniforms& f = facet.draws[0].uniforms;
    EXPECT_EQ(f.brdf.fresnelCosine, FresnelCosine::VdotH);
    EXPECT_EQ(f.brdf.denominator, MicrofacetDenominator::Four);
    EXPECT_EQ(f.brdf.metal, MetalBlend::F0);
    EXPECT_TRUE(!f.clampNdotV && f.twoSidedFlip && !f.clampColor);

    EXPECT_EQ(encodeChannel(0.5f, lecture.encoding), std::lround(255.0 * std::pow(0.5, 1.0 / 2.2)));
    EXPECT_EQ(encodeChannel(0.5f, lecture.encoding), 186);
    EXPECT_EQ(encodeChannel(0.5f, facet.encoding),
              std::lround(255.0 * (1.055 * std::pow(0.5, 1.0 / 2.4) - 0.055)));
    EXPECT_EQ(encodeChannel(0.5f, facet.encoding), 188);

    const LinearImage lectureImage = renderCube(folder_ / "lecture.json", "{" + lectureScene + "}");
    const LinearImage facetImage = renderCube(folder_ / "facet.json", "{" + facetScene + "}");
    std::size_t differing = 0;
    for (std::size_t i = 0; i < facetImage.pixels.size(); ++i)
        differing += lectureImage.pixels[i] != facetImage.pixels[i];
    EXPECT_GT(differing, 100u);
}

// The gl preset lights faces without a material with OpenGL 1.x's default glMaterial (ambient 0.2,
// diffuse 0.8, specular 0, shininess 0), used as given; the facet preset keeps its own default (Ka and
// Kd 0.8, Ks 0.2, Ns 32), decoded from sRGB. And the gl preset clamps the shininess to 128, as
// GL_SHININESS's range is [0, 128].
TEST_F(SceneRenderTest, GlPresetHasOpenGLsDefaultMaterialAndShininessRange) {
    const fs::path model = folder_ / "bare.obj";
    std::ofstream(model) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const auto materialWith = [&](const std::string& lighting, const std::string& material) {
        return prepareCube(folder_ / "scene.json", R"("objects": [{"model": ")" + model.string() + "\"" +
                                                       material + R"(}], "lighting": ")" + lighting + "\"")
            .draws[0]
            .uniforms.material;
    };
    const PhongMaterial gl = materialWith("gl", "");
    EXPECT_EQ(gl.ambient, vec3(0.2f));
    EXPECT_EQ(gl.diffuse, vec3(0.8f));
    EXPECT_EQ(gl.specular, vec3(0.0f));
    EXPECT_EQ(gl.emission, vec3(0.0f));
    EXPECT_EQ(gl.shininess, 0.0f);
    const PhongMaterial facet = materialWith("facet", "");
    EXPECT_EQ(facet.diffuse, vec3(srgbToLinear(0.8f)));
    EXPECT_EQ(facet.specular, vec3(srgbToLinear(0.2f)));
    EXPECT_EQ(facet.shininess, 32.0f);

    const std::string shiny = R"(, "material": {"shininess": 500})";
    EXPECT_EQ(materialWith("gl", shiny).shininess, 128.0f);
    EXPECT_EQ(materialWith("facet", shiny).shininess, 500.0f);
    EXPECT_EQ(materialWith("gl", R"(, "material": {"shininess": 100})").shininess, 100.0f);
}

// The gl preset blends a transparent object's over as OpenGL does (alpha squared); facet's keeps
// Porter–Duff's.
TEST_F(SceneRenderTest, GlPresetBlendsOverAsOpenGL) {
    const auto blendWith = [&](const std::string& lighting) {
        return prepareCube(folder_ / "scene.json", R"("objects": [{"model": ")" FACET_CUBE
                                                   R"(", "material": {"opacity": 0.5}}], "lighting": ")" +
                                                       lighting + "\"")
            .draws[0]
            .uniforms.blend;
    };
    EXPECT_EQ(blendWith("gl"), BlendMode::OverGL);
    EXPECT_EQ(blendWith("facet"), BlendMode::Over);
}

// A wrong choice is refused with every name the table offers there.
TEST_F(SceneRenderTest, WrongChoiceListsTheTablesNames) {
    const auto messageFor = [&](const std::string& json) {
        try {
            prepareCube(folder_ / "scene.json", json);
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    const std::string cull = messageFor(R"("pipeline": {"cull": "sideways"})");
    for (const std::string& name : namesOf<CullMode>())
        EXPECT_NE(cull.find('"' + name + '"'), std::string::npos) << cull;
    const std::string blend = messageFor(R"("objects": [{"model": ")" FACET_CUBE R"(", "blend": "screen"}])");
    for (const std::string& name : namesOf<BlendMode>({BlendMode::Replace, BlendMode::OverGL}))
        EXPECT_NE(blend.find('"' + name + '"'), std::string::npos) << blend;
    EXPECT_EQ(blend.find(std::string(nameOf(BlendMode::Replace))), std::string::npos) << blend;
}

// ---- Eye space scaled for huge and tiny scenes --------------------------------------------------------

// Case `kind` of a scene at scale `s`: an 8 × 8 ground at y = 0 and a unit cube on it, seen from
// (1.5, 3, 6), with every length of the scene file times s: the objects' scale and place, the camera,
// light positions, fog start and end; and what is per length divided by it: c1 by s, c2 by s², fog
// density by s. The renderer draws scenes of 2^20 and 2^-20 units in an eye space rescaled by
// Camera::viewScale (a power of two near 1/size), so such a scene must look as at scale 1.
nlohmann::json scaledScene(const std::string& kind, double s) {
    using Json = nlohmann::json;
    const auto at = [s](double x, double y, double z) { return Json::array({x * s, y * s, z * s}); };
    Json scene = {
        {"width", 48},
        {"height", 36},
        {"background", {0.6, 0.65, 0.7}},
        {"ambient", {0.1, 0.1, 0.1}},
        {"camera", {{"eye", at(1.5, 3, 6)}, {"target", at(0, 0.3, 0)}, {"near", 0.5 * s}, {"far", 40 * s}}},
        {"objects",
         {{{"model", FACET_SOURCE_DIR "/models/fog-and-glass/ground.obj"}, {"scale", 0.2 * s}},
          {{"model", FACET_CUBE}, {"translate", at(0, 0.5, 0)}, {"scale", s}}}}};
    Json light = {{"type", "point"}, {"position", at(-1, 2.5, 1.5)}};
    if (kind == "linear attenuation") light["attenuation"] = {0.2, 0.6 / s, 0};
    if (kind == "quadratic attenuation") light["attenuation"] = {0.2, 0, 0.3 / (s * s)};
    if (kind == "camera-space light") {
        // Just right of and above the cube, as the camera sees it, falling off over the scene.
        light = {{"type", "point"},
                 {"space", "camera"},
                 {"position", at(0.8, 0.4, -4)},
                 {"attenuation", {0.2, 0.5 / s, 0}}};
    }
    if (kind == "ray-cast shadow")
        light = {{"type", "directional"}, {"direction", {-1, -1.5, -0.5}}, {"shadows", "ray"}};
    if (kind == "linear fog") scene["fog"] = {{"mode", "linear"}, {"start", 5.5 * s}, {"end", 9 * s}};
    if (kind == "linear fog, bounds") scene["fog"] = {{"mode", "linear"}};  // start and end from the bounds
    if (kind == "exp fog") scene["fog"] = {{"mode", "exp"}, {"density", 0.2 / s}};
    if (kind == "exp2 fog") scene["fog"] = {{"mode", "exp2"}, {"density", 0.12 / s}, {"distance", "radial"}};
    scene["lights"] = Json::array({light});
    return scene;
}

// Each eye-space length the renderer rescales, in a scene of 2^20 and one of 2^-20 units scaled
// together with it: the image is the one at scale 1. Breaks caught (renderer.cpp), one case each:
// fog start, end or density left in world units (linear fog, its start and end from the bounds, exp
// and exp² fog), a light's c1 or c2 not divided by viewScale (linear and quadratic attenuation), a
// camera-space light's position not scaled into eye space, and the shadow rays' offset from a scene
// extent in world units (ray-cast shadow: offset past the cube, the shadow gone); also the projection's
// near or far plane left in world units (scene/camera.cpp), which every case catches.
TEST_F(SceneRenderTest, ScaledScenesLookAsAtUnitScale) {
    const auto render = [&](const nlohmann::json& scene) {
        const fs::path path = folder_ / "scene.json";
        std::ofstream(path) << scene.dump();
        const PreparedScene prepared = prepareScene(loadScene(path));
        Framebuffer framebuffer(prepared.scene.width, prepared.scene.height);
        DrawContext context(1);
        renderFrame(prepared, framebuffer, context);
        return toImage(framebuffer);
    };
    for (const char* kind : {"linear fog", "linear fog, bounds", "exp fog", "exp2 fog", "linear attenuation",
                             "quadratic attenuation", "camera-space light", "ray-cast shadow"}) {
        const LinearImage unit = render(scaledScene(kind, 1.0));
        for (const double s : {0x1p20, 0x1p-20}) {
            SCOPED_TRACE(std::string(kind) + " at scale 2^" + std::to_string(std::lround(std::log2(s))));
            const LinearImage scaled = render(scaledScene(kind, s));
            ASSERT_EQ(scaled.pixels.size(), unit.pixels.size());
            float worst = 0.0f;
            std::size_t worstAt = 0;
            for (std::size_t i = 0; i < unit.pixels.size(); ++i) {
                const float d = glm::length(scaled.pixels[i] - unit.pixels[i]);
                if (!(d <= worst)) {
                    worst = d;
                    worstAt = i;
                }
            }
            EXPECT_LE(worst, 1e-3f) << "pixel " << worstAt % 48 << ", " << worstAt / 48;
        }
    }
}

// ---- Surfaces: constant shading, the index of refraction --------------------------------------------

// Constant shading lights nothing: turning the light leaves the image as it is, while the flat shading
// of the same scene changes. Catches SurfaceUniforms::unlit not reaching the flat shader.
TEST_F(SceneRenderTest, ConstantShadingIgnoresTheLights) {
    const auto scene = [](const std::string& shading, const std::string& direction) {
        return R"({"lighting": {"shading": ")" + shading +
               R"("}, "lights": [{"type": "directional", "direction": )" + direction + "}]}";
    };
    const fs::path path = folder_ / "scene.json";
    const LinearImage constantA = renderCube(path, scene("constant", "[-1, -1, -1]"));
    const LinearImage constantB = renderCube(path, scene("constant", "[1, -0.2, -1]"));
    const LinearImage flatA = renderCube(path, scene("flat", "[-1, -1, -1]"));
    const LinearImage flatB = renderCube(path, scene("flat", "[1, -0.2, -1]"));
    EXPECT_EQ(constantA.pixels, constantB.pixels);
    EXPECT_NE(flatA.pixels, flatB.pixels);
    EXPECT_NE(constantA.pixels, flatA.pixels);
}

// "ior" reaches the material (F0 from it) and the image; an MTL's Ni above 1 does too, Ni 1 does not.
TEST_F(SceneRenderTest, IndexOfRefractionReachesTheMaterialAndTheImage) {
    const fs::path path = folder_ / "scene.json";
    const auto objects = [&](const std::string& model, const std::string& material) {
        return nlohmann::json::parse(R"({"width": 48, "height": 36,
                                         "lighting": {"model": "cook-torrance", "fresnel": "exact"},
                                         "objects": [{"model": ")" +
                                     model + R"(", "material": )" + material + "}]}");
    };
    const auto draw = [&](const nlohmann::json& document) {
        std::ofstream(path) << document.dump();
        const PreparedScene prepared = prepareScene(loadScene(path));
        Framebuffer framebuffer(48, 36);
        DrawContext context(1);
        renderFrame(prepared, framebuffer, context);
        return std::pair{toImage(framebuffer).pixels, prepared.draws[0].uniforms};
    };
    const std::string cube = FACET_SOURCE_DIR "/models/cube/cube.obj";
    const auto [low, lowUniforms] = draw(objects(cube, R"({"ior": 1.2})"));
    const auto [high, highUniforms] = draw(objects(cube, R"({"ior": 2.0})"));
    EXPECT_NE(low, high);
    EXPECT_FLOAT_EQ(highUniforms.pbr.ior, 2.0f);
    EXPECT_FLOAT_EQ(highUniforms.pbr.f0.x, 1.0f / 9.0f);  // ((1 − 2)/(1 + 2))²

    // The MTL's Ni: used above 1 (Cook-Torrance), not at 1.
    for (const auto& [ni, ior] : {std::pair{"2.0", 2.0f}, std::pair{"1.0", 0.0f}}) {
        std::ofstream(folder_ / "m.mtl") << "newmtl glassy\nKd 0.5 0.5 0.5\nNi " << ni << "\n";
        std::ofstream(folder_ / "m.obj")
            << "mtllib m.mtl\nusemtl glassy\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        const SurfaceUniforms u = draw(objects((folder_ / "m.obj").string(), "{}")).second;
        EXPECT_FLOAT_EQ(u.pbr.ior, ior) << "Ni " << ni;
        EXPECT_FLOAT_EQ(u.pbr.f0.x, ior > 0 ? 1.0f / 9.0f : 0.04f) << "Ni " << ni;
    }
}

}  // namespace
}  // namespace facet
