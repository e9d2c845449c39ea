// Scene loading: defaults, the "model" shorthand, every key's value, the transform order, and the
// one-line error for each kind of mistake (each names the file and the full key path).
// Scene files are written into a fresh folder under the system temp directory per test.
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <future>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "base/errors.h"
#include "scene/mesh.h"
#include "scene/scene.h"
#include "support/temp_folder.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using testing_support::errorWithoutOpening;

// A fresh temporary folder holding the scene files and (empty) model files of one test.
class SceneTest : public testing_support::TempFolderTest {
  protected:
    // The InputError message of loading `text` as scene.json (with an m.obj beside it).
    std::string errorOf(const std::string& text) const {
        touch("m.obj");
        const fs::path scene = write("scene.json", text);
        try {
            loadScene(scene);
        } catch (const InputError& e) {
            return e.what();
        }
        ADD_FAILURE() << "no error for: " << text;
        return {};
    }
};

void expectNear(const glm::vec3& actual, const glm::vec3& expected, float tolerance = 1e-5f) {
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(actual[i], expected[i], tolerance) << "component " << i;
}

glm::vec3 transformPoint(const glm::mat4& m, const glm::vec3& p) {
    return glm::vec3(m * glm::vec4(p, 1.0f));
}

// ---- Loading ------------------------------------------------------------------------------------

TEST_F(SceneTest, ModelShorthandGivesOneObjectAndEveryDefault) {
    touch("bunny.obj");
    const fs::path path = write("scene.json", R"({"model": "bunny.obj"})");
    const Scene scene = loadScene(path);

    EXPECT_EQ(scene.source, path);
    EXPECT_EQ(scene.width, 1280);
    EXPECT_EQ(scene.height, 960);
    EXPECT_EQ(scene.background, glm::vec4(0.05f, 0.05f, 0.07f, 1.0f));
    EXPECT_EQ(scene.ambientLight, glm::vec3(0.15f));
    EXPECT_FALSE(scene.camera.eye.has_value());
    EXPECT_FALSE(scene.camera.target.has_value());
    EXPECT_EQ(scene.camera.up, glm::vec3(0.0f, 1.0f, 0.0f));
    EXPECT_EQ(scene.camera.fovyDegrees, 40.0f);
    EXPECT_FALSE(scene.camera.near.has_value());
    EXPECT_FALSE(scene.camera.far.has_value());
    EXPECT_TRUE(scene.lights.empty());
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].model, folder_ / "bunny.obj");
    EXPECT_EQ(scene.objects[0].worldFromObject, glm::mat4(1.0f));
    EXPECT_FALSE(scene.objects[0].material.diffuse.has_value());
    EXPECT_FALSE(scene.objects[0].material.opacity.has_value());
    EXPECT_EQ(scene.pipeline.cull, CullMode::Back);
    EXPECT_EQ(scene.pipeline.interpolation, Interpolation::PerspectiveCorrect);
    EXPECT_EQ(scene.pipeline.subpixelBits, 8);
}

TEST_F(SceneTest, ReadsEveryKey) {
    touch("models/a.obj");
    touch("models/b.obj");
    const fs::path path = write("scene.json", R"({
        "width": 640, "height": 480,
        "background": [0.1, 0.2, 0.3, 0.5],
        "ambient": [0.01, 0.02, 0.03],
        "camera": {"eye": [0, 1, 5], "target": [0, 0.5, 0], "up": [0, 0, -1], "fovy": 30,
                   "near": 0.25, "far": 100},
        "lights": [
            {"type": "directional", "direction": [0, -1, 0], "color": [1, 0.9, 0.8], "intensity": 2},
            {"type": "point", "position": [1, 2, 3], "space": "camera"},
            {}
        ],
        "objects": [
            {"model": "models/a.obj",
             "material": {"diffuse": [0.8, 0.1, 0.1], "ambient": [0.1, 0, 0], "specular": [0.5, 0.5, 0.5],
                          "emission": [0, 0, 2], "shininess": 64, "opacity": 0.25}},
            {"model": "models/b.obj", "scale": 2}
        ],
        "pipeline": {"cull": "none", "interpolation": "affine", "subpixel_bits": 4}
    })");
    const Scene scene = loadScene(path);

    EXPECT_EQ(scene.width, 640);
    EXPECT_EQ(scene.height, 480);
    EXPECT_EQ(scene.background, glm::vec4(0.1f, 0.2f, 0.3f, 0.5f));
    EXPECT_EQ(scene.ambientLight, glm::vec3(0.01f, 0.02f, 0.03f));

    ASSERT_TRUE(scene.camera.eye && scene.camera.target && scene.camera.near && scene.camera.far);
    EXPECT_EQ(*scene.camera.eye, glm::vec3(0, 1, 5));
    EXPECT_EQ(*scene.camera.target, glm::vec3(0, 0.5f, 0));
    EXPECT_EQ(scene.camera.up, glm::vec3(0, 0, -1));
    EXPECT_EQ(scene.camera.fovyDegrees, 30.0f);
    EXPECT_EQ(*scene.camera.near, 0.25f);
    EXPECT_EQ(*scene.camera.far, 100.0f);

    ASSERT_EQ(scene.lights.size(), 3u);
    EXPECT_EQ(scene.lights[0].type, LightKind::Directional);
    EXPECT_EQ(scene.lights[0].direction, glm::vec3(0, -1, 0));
    EXPECT_EQ(scene.lights[0].color, glm::vec3(1, 0.9f, 0.8f));
    EXPECT_EQ(scene.lights[0].intensity, 2.0f);
    EXPECT_FALSE(scene.lights[0].cameraRelative);
    EXPECT_EQ(scene.lights[1].type, LightKind::Point);
    EXPECT_EQ(scene.lights[1].position, glm::vec3(1, 2, 3));
    EXPECT_TRUE(scene.lights[1].cameraRelative);
    EXPECT_EQ(scene.lights[1].color, glm::vec3(1.0f));
    EXPECT_EQ(scene.lights[1].intensity, 1.0f);
    // An empty light object is the LightSpec defaults.
    EXPECT_EQ(scene.lights[2].type, LightKind::Directional);
    EXPECT_EQ(scene.lights[2].direction, LightSpec{}.direction);

    ASSERT_EQ(scene.objects.size(), 2u);
    EXPECT_EQ(scene.objects[0].model, folder_ / "models/a.obj");
    const MaterialOverride& m = scene.objects[0].material;
    ASSERT_TRUE(m.diffuse && m.ambient && m.specular && m.emission && m.shininess && m.opacity);
    EXPECT_EQ(*m.diffuse, glm::vec3(0.8f, 0.1f, 0.1f));
    EXPECT_EQ(*m.ambient, glm::vec3(0.1f, 0, 0));
    EXPECT_EQ(*m.specular, glm::vec3(0.5f));
    EXPECT_EQ(*m.emission, glm::vec3(0, 0, 2));
    EXPECT_EQ(*m.shininess, 64.0f);
    EXPECT_EQ(*m.opacity, 0.25f);
    EXPECT_EQ(scene.objects[1].model, folder_ / "models/b.obj");
    EXPECT_FALSE(scene.objects[1].material.diffuse.has_value());
    EXPECT_EQ(scene.objects[1].worldFromObject, glm::mat4(glm::vec4(2, 0, 0, 0), glm::vec4(0, 2, 0, 0),
                                                          glm::vec4(0, 0, 2, 0), glm::vec4(0, 0, 0, 1)));

    EXPECT_EQ(scene.pipeline.cull, CullMode::None);
    EXPECT_EQ(scene.pipeline.interpolation, Interpolation::Affine);
    EXPECT_EQ(scene.pipeline.subpixelBits, 4);
}

TEST_F(SceneTest, CullFrontAndPerspectiveAreRead) {
    touch("m.obj");
    const Scene scene = loadScene(write(
        "scene.json", R"({"model": "m.obj", "pipeline": {"cull": "front", "interpolation": "perspective",
                                                                "subpixel_bits": 0}})"));
    EXPECT_EQ(scene.pipeline.cull, CullMode::Front);
    EXPECT_EQ(scene.pipeline.interpolation, Interpolation::PerspectiveCorrect);
    EXPECT_EQ(scene.pipeline.subpixelBits, 0);
}

// worldFromObject = T · Rz · Ry · Rx · S. Hand-computed: (1,0,0) scaled by 2 is (2,0,0); rotated 90°
// about Z it is (0,2,0); translated by (1,2,3) it is (1,4,3).
TEST_F(SceneTest, TransformIsTranslateRotateScale) {
    touch("m.obj");
    const Scene scene = loadScene(write("scene.json", R"({"objects": [
        {"model": "m.obj", "translate": [1, 2, 3], "rotate": [0, 0, 90], "scale": 2}]})"));
    const glm::mat4& worldFromObject = scene.objects[0].worldFromObject;
    expectNear(transformPoint(worldFromObject, {1, 0, 0}), {1, 4, 3});
    expectNear(transformPoint(worldFromObject, {0, 0, 0}), {1, 2, 3});
    expectNear(transformPoint(worldFromObject, {0, 1, 0}), {1 - 2, 2, 3});
}

// X is applied before Y: (0,1,0) turns to (0,0,1) about X, then to (1,0,0) about Y. The other order
// would give (0,0,1).
TEST_F(SceneTest, RotationAppliesXThenYThenZ) {
    touch("m.obj");
    const Scene scene =
        loadScene(write("scene.json", R"({"objects": [{"model": "m.obj", "rotate": [90, 90, 0]}]})"));
    expectNear(transformPoint(scene.objects[0].worldFromObject, {0, 1, 0}), {1, 0, 0});

    const Scene zAfterY =
        loadScene(write("scene2.json", R"({"objects": [{"model": "m.obj", "rotate": [0, 90, 90]}]})"));
    // (1,0,0) → about Y: (0,0,-1) → about Z: unchanged.
    expectNear(transformPoint(zAfterY.objects[0].worldFromObject, {1, 0, 0}), {0, 0, -1});
}

TEST_F(SceneTest, ScaleAcceptsOneNumberOrThree) {
    touch("m.obj");
    const Scene scene = loadScene(write(
        "scene.json", R"({"objects": [{"model": "m.obj", "scale": [1, 2, -3], "translate": [0, 0, 1]}]})"));
    expectNear(transformPoint(scene.objects[0].worldFromObject, {1, 1, 1}), {1, 2, -2});
}

TEST_F(SceneTest, ModelPathsAreRelativeToTheSceneFolder) {
    touch("models/m.obj");
    const fs::path path = write("scenes/deep/s.json", R"({"model": "../../models/m.obj"})");
    const Scene scene = loadScene(path);
    EXPECT_EQ(scene.objects[0].model, folder_ / "scenes/deep/../../models/m.obj");
    EXPECT_TRUE(fs::exists(scene.objects[0].model));
}

TEST_F(SceneTest, AbsoluteModelPathIsKept) {
    const fs::path model = touch("elsewhere/m.obj");
    const nlohmann::json scene = {{"model", model.string()}};
    const Scene loaded = loadScene(write("scenes/s.json", scene.dump()));
    EXPECT_EQ(loaded.objects[0].model, model);
}

TEST_F(SceneTest, CommentsAreAllowed) {
    touch("m.obj");
    const Scene scene = loadScene(write("scene.json", R"({
        // the test model
        "model": "m.obj",
        /* a small image */ "width": 32
    })"));
    EXPECT_EQ(scene.width, 32);
}

TEST_F(SceneTest, EmptyLightsListMeansDefaultLight) {
    touch("m.obj");
    const Scene scene = loadScene(write("scene.json", R"({"model": "m.obj", "lights": []})"));
    EXPECT_TRUE(scene.lights.empty());
}

TEST_F(SceneTest, HugeButFloatSizedValuesAreAccepted) {
    touch("m.obj");
    const Scene scene = loadScene(write(
        "scene.json", R"({"model": "m.obj", "lights": [{"intensity": 1e6}], "camera": {"far": 1e38}})"));
    EXPECT_EQ(scene.lights[0].intensity, kMaxColorComponent);
    EXPECT_EQ(*scene.camera.far, 1e38f);
}

TEST_F(SceneTest, WholeNumberMayBeWrittenWithAFraction) {
    touch("m.obj");
    const Scene scene =
        loadScene(write("scene.json", R"({"model": "m.obj", "width": 800.0, "height": 16384})"));
    EXPECT_EQ(scene.width, 800);
    EXPECT_EQ(scene.height, kMaxImageSide);
}

// ---- Lighting ------------------------------------------------------------------------------------

TEST_F(SceneTest, LightingDefaultsWhenAbsent) {
    touch("m.obj");
    const Scene scene = loadScene(write("scene.json", R"({"model": "m.obj"})"));
    EXPECT_EQ(scene.lighting.preset, LightingPreset::Facet);
    EXPECT_EQ(scene.lighting.model, ReflectionModel::BlinnPhong);
    EXPECT_FALSE(scene.lighting.shading.has_value());
    EXPECT_EQ(scene.lighting.shadingOrDefault(), ShadingFrequency::Phong);
    EXPECT_EQ(scene.lighting.creaseAngleDegrees, 60.0f);
    EXPECT_EQ(scene.lighting.brdf.distribution, NormalDistribution::GGX);
    EXPECT_EQ(scene.lighting.brdf.fresnel, FresnelModel::Schlick);
    EXPECT_EQ(scene.lighting.brdf.geometry, GeometryTerm::SmithGGX);
    EXPECT_FALSE(scene.objects[0].reflection.has_value());
    EXPECT_FALSE(scene.objects[0].shading.has_value());
    EXPECT_FALSE(scene.objects[0].material.physicallyBased());
}

// The string form sets the preset and nothing else; the GL preset's shading default is Gouraud.
TEST_F(SceneTest, LightingStringIsAPresetOnly) {
    touch("m.obj");
    const Scene gl = loadScene(write("gl.json", R"({"model": "m.obj", "lighting": "gl"})"));
    EXPECT_EQ(gl.lighting.preset, LightingPreset::GL);
    EXPECT_EQ(gl.lighting.model, ReflectionModel::BlinnPhong);
    EXPECT_FALSE(gl.lighting.shading.has_value());
    EXPECT_EQ(gl.lighting.shadingOrDefault(), ShadingFrequency::Gouraud);
    EXPECT_EQ(gl.lighting.creaseAngleDegrees, 60.0f);

    const Scene facet = loadScene(write("facet.json", R"({"model": "m.obj", "lighting": "facet"})"));
    EXPECT_EQ(facet.lighting.preset, LightingPreset::Facet);
    EXPECT_EQ(facet.lighting.shadingOrDefault(), ShadingFrequency::Phong);
}

TEST_F(SceneTest, LightingReadsEveryKey) {
    touch("m.obj");
    const Scene scene = loadScene(write("scene.json", R"({"model": "m.obj", "lighting": {
        "preset": "gl", "model": "cook-torrance", "shading": "flat", "crease_angle": 35.5,
        "distribution": "beckmann", "fresnel": "exact", "geometry": "cook-torrance"}})"));
    EXPECT_EQ(scene.lighting.preset, LightingPreset::GL);
    EXPECT_EQ(scene.lighting.model, ReflectionModel::CookTorrance);
    ASSERT_TRUE(scene.lighting.shading.has_value());
    EXPECT_EQ(*scene.lighting.shading, ShadingFrequency::Flat);
    EXPECT_EQ(scene.lighting.shadingOrDefault(), ShadingFrequency::Flat);
    EXPECT_EQ(scene.lighting.creaseAngleDegrees, 35.5f);
    EXPECT_EQ(scene.lighting.brdf.distribution, NormalDistribution::Beckmann);
    EXPECT_EQ(scene.lighting.brdf.fresnel, FresnelModel::Exact);
    EXPECT_EQ(scene.lighting.brdf.geometry, GeometryTerm::CookTorrance);
}

// Every name maps to its own enum value (both ends of the crease range are allowed).
TEST_F(SceneTest, LightingChoicesMapToTheirEnums) {
    touch("m.obj");
    const auto lighting = [&](const std::string& object) {
        return loadScene(write("scene.json", R"({"model": "m.obj", "lighting": )" + object + "}")).lighting;
    };
    EXPECT_EQ(lighting(R"({"model": "phong"})").model, ReflectionModel::Phong);
    EXPECT_EQ(lighting(R"({"model": "blinn-phong"})").model, ReflectionModel::BlinnPhong);
    EXPECT_EQ(lighting(R"({"model": "cook-torrance"})").model, ReflectionModel::CookTorrance);
    EXPECT_EQ(lighting(R"({"shading": "flat"})").shading, ShadingFrequency::Flat);
    EXPECT_EQ(lighting(R"({"shading": "gouraud"})").shading, ShadingFrequency::Gouraud);
    EXPECT_EQ(lighting(R"({"shading": "phong"})").shading, ShadingFrequency::Phong);
    EXPECT_EQ(lighting(R"({"preset": "gl"})").preset, LightingPreset::GL);
    EXPECT_EQ(lighting(R"({"preset": "facet"})").preset, LightingPreset::Facet);
    EXPECT_EQ(lighting(R"({"preset": "lecture"})").preset, LightingPreset::Lecture);
    EXPECT_EQ(lighting(R"("lecture")").preset, LightingPreset::Lecture);
    EXPECT_EQ(lighting(R"({"distribution": "ggx"})").brdf.distribution, NormalDistribution::GGX);
    EXPECT_EQ(lighting(R"({"distribution": "beckmann"})").brdf.distribution, NormalDistribution::Beckmann);
    EXPECT_EQ(lighting(R"({"fresnel": "schlick"})").brdf.fresnel, FresnelModel::Schlick);
    EXPECT_EQ(lighting(R"({"fresnel": "exact"})").brdf.fresnel, FresnelModel::Exact);
    EXPECT_EQ(lighting(R"({"geometry": "smith-ggx"})").brdf.geometry, GeometryTerm::SmithGGX);
    EXPECT_EQ(lighting(R"({"geometry": "cook-torrance"})").brdf.geometry, GeometryTerm::CookTorrance);
    EXPECT_EQ(lighting(R"({"crease_angle": 0})").creaseAngleDegrees, 0.0f);
    EXPECT_EQ(lighting(R"({"crease_angle": 180})").creaseAngleDegrees, 180.0f);
    // The GL preset with an explicit shading keeps it.
    EXPECT_EQ(lighting(R"({"preset": "gl", "shading": "phong"})").shadingOrDefault(),
              ShadingFrequency::Phong);
}

TEST_F(SceneTest, ObjectLightingSetsModelAndShading) {
    touch("m.obj");
    const Scene scene = loadScene(write("scene.json", R"({"objects": [
        {"model": "m.obj", "lighting": {"model": "cook-torrance", "shading": "gouraud"}},
        {"model": "m.obj", "lighting": {"shading": "flat"}},
        {"model": "m.obj", "lighting": {"model": "phong"}},
        {"model": "m.obj", "lighting": {}}]})"));
    ASSERT_EQ(scene.objects.size(), 4u);
    EXPECT_EQ(scene.objects[0].reflection, ReflectionModel::CookTorrance);
    EXPECT_EQ(scene.objects[0].shading, ShadingFrequency::Gouraud);
    EXPECT_FALSE(scene.objects[1].reflection.has_value());
    EXPECT_EQ(scene.objects[1].shading, ShadingFrequency::Flat);
    EXPECT_EQ(scene.objects[2].reflection, ReflectionModel::Phong);
    EXPECT_FALSE(scene.objects[2].shading.has_value());
    EXPECT_FALSE(scene.objects[3].reflection.has_value());
    EXPECT_FALSE(scene.objects[3].shading.has_value());
    // The scene-wide settings are untouched.
    EXPECT_EQ(scene.lighting.model, ReflectionModel::BlinnPhong);
    EXPECT_FALSE(scene.lighting.shading.has_value());
}

// ---- Lights: spot, per-term colours, attenuation ---------------------------------------------------

TEST_F(SceneTest, SpotLightReadsEveryKey) {
    touch("m.obj");
    const Scene scene = loadScene(write("scene.json", R"({"model": "m.obj", "lights": [
        {"type": "spot", "position": [1, 2, 3], "direction": [0, -1, -1], "color": [1, 0.5, 0.25],
         "intensity": 4, "ambient": [0.1, 0.2, 0.3], "diffuse": [0.9, 0.8, 0.7], "specular": [0.5, 0.6, 0.7],
         "attenuation": [0.5, 0.25, 0.125], "cutoff": 25, "exponent": 12, "space": "camera"}]})"));
    ASSERT_EQ(scene.lights.size(), 1u);
    const LightSpec& light = scene.lights[0];
    EXPECT_EQ(light.type, LightKind::Spot);
    EXPECT_EQ(light.position, glm::vec3(1, 2, 3));
    EXPECT_EQ(light.direction, glm::vec3(0, -1, -1));
    EXPECT_EQ(light.color, glm::vec3(1, 0.5f, 0.25f));
    EXPECT_EQ(light.intensity, 4.0f);
    ASSERT_TRUE(light.ambient && light.diffuse && light.specular);
    EXPECT_EQ(*light.ambient, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(*light.diffuse, glm::vec3(0.9f, 0.8f, 0.7f));
    EXPECT_EQ(*light.specular, glm::vec3(0.5f, 0.6f, 0.7f));
    EXPECT_EQ(light.attenuation, glm::vec3(0.5f, 0.25f, 0.125f));
    EXPECT_EQ(light.spotCutoffDegrees, 25.0f);
    EXPECT_EQ(light.spotExponent, 12.0f);
    EXPECT_FALSE(light.spotInnerDegrees.has_value());
    EXPECT_FALSE(light.spotOuterDegrees.has_value());
    EXPECT_TRUE(light.cameraRelative);
}

TEST_F(SceneTest, SpotLightSmoothProfile) {
    touch("m.obj");
    const Scene scene = loadScene(write("scene.json", R"({"model": "m.obj", "lights": [
        {"type": "spot", "inner": 12.5, "outer": 30},
        {"type": "spot", "inner": 0, "outer": 90}]})"));
    ASSERT_EQ(scene.lights.size(), 2u);
    ASSERT_TRUE(scene.lights[0].spotInnerDegrees && scene.lights[0].spotOuterDegrees);
    EXPECT_EQ(*scene.lights[0].spotInnerDegrees, 12.5f);
    EXPECT_EQ(*scene.lights[0].spotOuterDegrees, 30.0f);
    // The OpenGL profile's values stay at their defaults.
    EXPECT_EQ(scene.lights[0].spotCutoffDegrees, LightSpec{}.spotCutoffDegrees);
    EXPECT_EQ(scene.lights[0].spotExponent, LightSpec{}.spotExponent);
    // The extremes of the range are allowed.
    EXPECT_EQ(scene.lights[1].spotInnerDegrees, 0.0f);
    EXPECT_EQ(scene.lights[1].spotOuterDegrees, 90.0f);
}

// A spot without "direction" points straight down; a directional light keeps its own default.
TEST_F(SceneTest, SpotDirectionDefaultsDown) {
    touch("m.obj");
    const Scene scene = loadScene(write("scene.json", R"({"model": "m.obj", "lights": [
        {"type": "spot", "position": [0, 3, 0]}, {"type": "directional"}, {"type": "point"}]})"));
    ASSERT_EQ(scene.lights.size(), 3u);
    EXPECT_EQ(scene.lights[0].type, LightKind::Spot);
    EXPECT_EQ(scene.lights[0].direction, glm::vec3(0, -1, 0));
    EXPECT_EQ(scene.lights[0].position, glm::vec3(0, 3, 0));
    EXPECT_EQ(scene.lights[0].spotCutoffDegrees, 30.0f);
    EXPECT_EQ(scene.lights[0].spotExponent, 0.0f);
    EXPECT_EQ(scene.lights[0].attenuation, glm::vec3(1, 0, 0));
    EXPECT_EQ(scene.lights[1].direction, glm::vec3(-0.4f, -0.6f, -0.7f));
    EXPECT_EQ(scene.lights[2].type, LightKind::Point);
}

TEST_F(SceneTest, PointLightTermColoursAndAttenuation) {
    touch("m.obj");
    const Scene scene = loadScene(write("scene.json", R"({"model": "m.obj", "lights": [
        {"type": "point", "attenuation": [0, 0, 1], "specular": [0, 0, 0]},
        {"type": "directional", "ambient": [0.2, 0.2, 0.2]},
        {"type": "point"}]})"));
    ASSERT_EQ(scene.lights.size(), 3u);
    EXPECT_EQ(scene.lights[0].attenuation, glm::vec3(0, 0, 1));
    EXPECT_FALSE(scene.lights[0].ambient.has_value());
    EXPECT_FALSE(scene.lights[0].diffuse.has_value());
    ASSERT_TRUE(scene.lights[0].specular.has_value());
    EXPECT_EQ(*scene.lights[0].specular, glm::vec3(0.0f));
    EXPECT_EQ(scene.lights[1].ambient, glm::vec3(0.2f));
    EXPECT_EQ(scene.lights[1].attenuation, glm::vec3(1, 0, 0));
    EXPECT_EQ(scene.lights[2].attenuation, glm::vec3(1, 0, 0));
}

// ---- Materials: physically based keys -------------------------------------------------------------

TEST_F(SceneTest, MaterialReadsPhysicallyBasedKeys) {
    touch("m.obj");
    const Scene scene = loadScene(write("scene.json", R"({"objects": [
        {"model": "m.obj", "material": {"preset": "gold", "base_color": [0.9, 0.6, 0.2], "metalness": 0.75,
                                        "roughness": 0.3, "f0": [0.1, 0.2, 0.3], "diffuse": [0.5, 0.5, 0.5]}},
        {"model": "m.obj", "material": {"roughness": 0}},
        {"model": "m.obj", "material": {"diffuse": [1, 0, 0]}}]})"));
    const MaterialOverride& m = scene.objects[0].material;
    ASSERT_TRUE(m.preset && m.baseColor && m.metalness && m.roughness && m.f0 && m.diffuse);
    EXPECT_EQ(*m.preset, "gold");
    EXPECT_EQ(*m.baseColor, glm::vec3(0.9f, 0.6f, 0.2f));
    EXPECT_EQ(*m.metalness, 0.75f);
    EXPECT_EQ(*m.roughness, 0.3f);
    EXPECT_EQ(*m.f0, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(*m.diffuse, glm::vec3(0.5f));
    EXPECT_TRUE(m.physicallyBased());

    const MaterialOverride& rough = scene.objects[1].material;
    EXPECT_EQ(rough.roughness, 0.0f);
    EXPECT_FALSE(rough.preset.has_value());
    EXPECT_FALSE(rough.metalness.has_value());
    EXPECT_TRUE(rough.physicallyBased());
    EXPECT_FALSE(scene.objects[2].material.physicallyBased());
}

// Preset names ignore case and are stored as kMaterialPresets spells them; "aluminum" is accepted.
TEST_F(SceneTest, MaterialPresetIgnoresCase) {
    touch("m.obj");
    const Scene scene = loadScene(write("scene.json", R"({"objects": [
        {"model": "m.obj", "material": {"preset": "Gold"}},
        {"model": "m.obj", "material": {"preset": "ALUMINUM"}},
        {"model": "m.obj", "material": {"preset": "water"}}]})"));
    EXPECT_EQ(scene.objects[0].material.preset, "gold");
    EXPECT_EQ(scene.objects[1].material.preset, "aluminium");
    EXPECT_EQ(scene.objects[2].material.preset, "water");
}

// Every preset of the table is accepted by name.
TEST_F(SceneTest, EveryMaterialPresetIsAccepted) {
    touch("m.obj");
    for (const MaterialPreset& preset : kMaterialPresets) {
        const std::string name(preset.name);
        const Scene scene = loadScene(write(
            "scene.json", R"({"objects": [{"model": "m.obj", "material": {"preset": ")" + name + "\"}}]}"));
        EXPECT_EQ(scene.objects[0].material.preset, name);
    }
}

TEST_F(SceneTest, F0NumberSetsAllThreeChannels) {
    touch("m.obj");
    const Scene scene = loadScene(write("scene.json", R"({"objects": [
        {"model": "m.obj", "material": {"f0": 0.04}},
        {"model": "m.obj", "material": {"f0": 1}},
        {"model": "m.obj", "material": {"f0": [0, 0.5, 1]}}]})"));
    EXPECT_EQ(scene.objects[0].material.f0, glm::vec3(0.04f));
    EXPECT_EQ(scene.objects[1].material.f0, glm::vec3(1.0f));
    EXPECT_EQ(scene.objects[2].material.f0, glm::vec3(0, 0.5f, 1));
}

// The full message for an unknown preset lists every name.
TEST_F(SceneTest, UnknownMaterialPresetListsEveryName) {
    const std::string message =
        errorOf(R"({"objects": [{"model": "m.obj", "material": {"preset": "unobtainium"}}]})");
    EXPECT_EQ(message,
              (folder_ / "scene.json").string() +
                  R"(: "objects[0].material.preset" must be one of the material presets "water", )"
                  R"("living-tissue", "skin", "eyes", "hair", "teeth", "fabric", "stone", "plastic", )"
                  R"("glass", "crystal-glass", "gems", "diamond", "titanium", "chromium", "iron", "nickel", )"
                  R"("platinum", "copper", "palladium", "mercury", "brass", "zinc", "gold", "aluminium", )"
                  R"("silver" (got "unobtainium"))");
}

// ---- Transparency, blend, fog and gamma ------------------------------------------------------------

TEST_F(SceneTest, TransparencyFogAndGammaDefaultsWhenAbsent) {
    touch("m.obj");
    const Scene scene = loadScene(write("scene.json", R"({"model": "m.obj"})"));
    EXPECT_FALSE(scene.objects[0].blend.has_value());
    EXPECT_EQ(scene.transparency.mode, TransparencyMode::Sorted);
    EXPECT_EQ(scene.transparency.key, SortKey::Centroid);
    EXPECT_EQ(scene.fog.mode, FogMode::None);
    EXPECT_EQ(scene.fog.color, glm::vec3(0.5f));
    EXPECT_FALSE(scene.fog.start.has_value());
    EXPECT_FALSE(scene.fog.end.has_value());
    EXPECT_EQ(scene.fog.density, 1.0f);
    EXPECT_EQ(scene.fog.distance, FogDistance::EyeDepth);
    EXPECT_EQ(scene.gamma.encode, TransferCurve::Srgb);
    EXPECT_EQ(scene.gamma.exponent, 2.2f);
    EXPECT_TRUE(scene.gamma.decodeInputs);
}

TEST_F(SceneTest, ObjectBlendMapsToItsEnum) {
    touch("m.obj");
    const Scene scene = loadScene(write("scene.json", R"({"objects": [
        {"model": "m.obj", "blend": "over"},
        {"model": "m.obj", "blend": "additive"},
        {"model": "m.obj", "blend": "multiply"},
        {"model": "m.obj", "blend": "premultiplied", "material": {"opacity": 0.5}},
        {"model": "m.obj"}]})"));
    ASSERT_EQ(scene.objects.size(), 5u);
    EXPECT_EQ(scene.objects[0].blend, BlendMode::Over);
    EXPECT_EQ(scene.objects[1].blend, BlendMode::Additive);
    EXPECT_EQ(scene.objects[2].blend, BlendMode::Multiply);
    EXPECT_EQ(scene.objects[3].blend, BlendMode::PremultipliedOver);
    EXPECT_EQ(scene.objects[3].material.opacity, 0.5f);
    EXPECT_FALSE(scene.objects[4].blend.has_value());
}

TEST_F(SceneTest, TransparencyReadsEveryKey) {
    touch("m.obj");
    const Scene scene = loadScene(write("scene.json", R"({"model": "m.obj",
        "transparency": {"mode": "unsorted", "sort_key": "farthest"}})"));
    EXPECT_EQ(scene.transparency.mode, TransparencyMode::Unsorted);
    EXPECT_EQ(scene.transparency.key, SortKey::FarthestVertex);
}

// Every name maps to its own enum value; an empty object keeps the defaults, and sort_key is accepted
// (unused) with the exact mode.
TEST_F(SceneTest, TransparencyChoicesMapToTheirEnums) {
    touch("m.obj");
    const auto transparency = [&](const std::string& object) {
        return loadScene(write("scene.json", R"({"model": "m.obj", "transparency": )" + object + "}"))
            .transparency;
    };
    EXPECT_EQ(transparency(R"({"mode": "sorted"})").mode, TransparencyMode::Sorted);
    EXPECT_EQ(transparency(R"({"mode": "unsorted"})").mode, TransparencyMode::Unsorted);
    EXPECT_EQ(transparency(R"({"mode": "exact"})").mode, TransparencyMode::Exact);
    EXPECT_EQ(transparency(R"({"sort_key": "centroid"})").key, SortKey::Centroid);
    EXPECT_EQ(transparency(R"({"sort_key": "farthest"})").key, SortKey::FarthestVertex);
    const TransparencyOptions empty = transparency("{}");
    EXPECT_EQ(empty.mode, TransparencyMode::Sorted);
    EXPECT_EQ(empty.key, SortKey::Centroid);
    const TransparencyOptions exact = transparency(R"({"mode": "exact", "sort_key": "farthest"})");
    EXPECT_EQ(exact.mode, TransparencyMode::Exact);
    EXPECT_EQ(exact.key, SortKey::FarthestVertex);
}

TEST_F(SceneTest, LinearFogReadsEveryKey) {
    touch("m.obj");
    const Scene scene = loadScene(write("scene.json", R"({"model": "m.obj", "fog": {
        "mode": "linear", "color": [0.7, 0.75, 0.8], "start": 2, "end": 12.5, "distance": "radial"}})"));
    EXPECT_EQ(scene.fog.mode, FogMode::Linear);
    EXPECT_EQ(scene.fog.color, glm::vec3(0.7f, 0.75f, 0.8f));
    EXPECT_EQ(scene.fog.start, 2.0f);
    EXPECT_EQ(scene.fog.end, 12.5f);
    EXPECT_EQ(scene.fog.density, 1.0f);  // unused by linear fog
    EXPECT_EQ(scene.fog.distance, FogDistance::Radial);
}

TEST_F(SceneTest, ExponentialFogReadsEveryKey) {
    touch("m.obj");
    const Scene scene = loadScene(write("scene.json", R"({"model": "m.obj", "fog": {
        "mode": "exp2", "color": [0.1, 0.2, 0.3], "density": 0.35, "distance": "depth"}})"));
    EXPECT_EQ(scene.fog.mode, FogMode::ExponentialSquared);
    EXPECT_EQ(scene.fog.color, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_FALSE(scene.fog.start.has_value());
    EXPECT_FALSE(scene.fog.end.has_value());
    EXPECT_EQ(scene.fog.density, 0.35f);
    EXPECT_EQ(scene.fog.distance, FogDistance::EyeDepth);
}

// Every mode and distance maps to its enum; each key's defaults hold when only "mode" is given;
// start or end may come alone (the other is derived by the renderer), and 0 is allowed for both.
TEST_F(SceneTest, FogChoicesMapToTheirEnums) {
    touch("m.obj");
    const auto fog = [&](const std::string& object) {
        return loadScene(write("scene.json", R"({"model": "m.obj", "fog": )" + object + "}")).fog;
    };
    EXPECT_EQ(fog(R"({"mode": "linear"})").mode, FogMode::Linear);
    EXPECT_EQ(fog(R"({"mode": "exp"})").mode, FogMode::Exponential);
    EXPECT_EQ(fog(R"({"mode": "exp2"})").mode, FogMode::ExponentialSquared);
    EXPECT_EQ(fog(R"({"mode": "exp", "distance": "depth"})").distance, FogDistance::EyeDepth);
    EXPECT_EQ(fog(R"({"mode": "exp", "distance": "radial"})").distance, FogDistance::Radial);

    const FogSpec defaults = fog(R"({"mode": "exp"})");
    EXPECT_EQ(defaults.color, glm::vec3(0.5f));
    EXPECT_EQ(defaults.density, 1.0f);
    EXPECT_EQ(defaults.distance, FogDistance::EyeDepth);

    const FogSpec startOnly = fog(R"({"mode": "linear", "start": 3})");
    EXPECT_EQ(startOnly.start, 3.0f);
    EXPECT_FALSE(startOnly.end.has_value());
    const FogSpec endOnly = fog(R"({"mode": "linear", "end": 0})");
    EXPECT_FALSE(endOnly.start.has_value());
    EXPECT_EQ(endOnly.end, 0.0f);
    EXPECT_EQ(fog(R"({"mode": "linear", "start": 0, "end": 0.5})").start, 0.0f);
    EXPECT_EQ(fog(R"({"mode": "exp", "density": 0})").density, 0.0f);
}

TEST_F(SceneTest, GammaReadsEveryKey) {
    touch("m.obj");
    const Scene scene = loadScene(write("scene.json", R"({"model": "m.obj",
        "gamma": {"encode": "power", "exponent": 1.8, "decode_inputs": false}})"));
    EXPECT_EQ(scene.gamma.encode, TransferCurve::Power);
    EXPECT_EQ(scene.gamma.exponent, 1.8f);
    EXPECT_FALSE(scene.gamma.decodeInputs);
}

TEST_F(SceneTest, GammaChoicesMapToTheirEnums) {
    touch("m.obj");
    const auto gamma = [&](const std::string& object) {
        return loadScene(write("scene.json", R"({"model": "m.obj", "gamma": )" + object + "}")).gamma;
    };
    EXPECT_EQ(gamma(R"({"encode": "srgb"})").encode, TransferCurve::Srgb);
    EXPECT_EQ(gamma(R"({"encode": "linear"})").encode, TransferCurve::Linear);
    const GammaOptions power = gamma(R"({"encode": "power"})");
    EXPECT_EQ(power.encode, TransferCurve::Power);
    EXPECT_EQ(power.exponent, 2.2f);
    EXPECT_TRUE(power.decodeInputs);
    EXPECT_TRUE(gamma(R"({"decode_inputs": true})").decodeInputs);
    EXPECT_EQ(gamma(R"({"decode_inputs": false})").encode, TransferCurve::Srgb);
    const GammaOptions empty = gamma("{}");
    EXPECT_EQ(empty.encode, TransferCurve::Srgb);
    EXPECT_TRUE(empty.decodeInputs);
}

// "gamma" is checked against the preset however "lighting" is written, before or after it; the facet
// preset accepts it.
TEST_F(SceneTest, GammaIsRejectedWithTheGlPresetOnly) {
    touch("m.obj");
    const std::string message =
        "\"gamma\" cannot be used with the gl lighting preset: the gl preset writes colours as OpenGL 1.x "
        "does, without decoding or encoding; remove \"gamma\"";
    EXPECT_EQ(errorOf(R"({"model": "m.obj", "lighting": "gl", "gamma": {}})"),
              (folder_ / "scene.json").string() + ": " + message);
    EXPECT_NE(errorOf(R"({"gamma": {"encode": "linear"}, "model": "m.obj", "lighting": {"preset": "gl"}})")
                  .find(message),
              std::string::npos);
    const Scene facet = loadScene(write("facet.json", R"({"model": "m.obj", "lighting": "facet",
        "gamma": {"encode": "linear"}})"));
    EXPECT_EQ(facet.gamma.encode, TransferCurve::Linear);
}

TEST(SceneForModel, OneModelAndEveryDefault) {
    const Scene scene = sceneForModel("models/spot/spot_triangulated.obj");
    EXPECT_EQ(scene.source, fs::path("models/spot/spot_triangulated.obj"));
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].model, fs::path("models/spot/spot_triangulated.obj"));
    EXPECT_EQ(scene.objects[0].worldFromObject, glm::mat4(1.0f));
    EXPECT_TRUE(scene.lights.empty());
    EXPECT_EQ(scene.width, 1280);
    EXPECT_EQ(scene.height, 960);
    EXPECT_FALSE(scene.camera.eye.has_value());
    EXPECT_EQ(scene.pipeline.subpixelBits, 8);
}

// The committed example must load. Its model may not be copied into models/ yet, so the example is
// loaded from a temporary copy beside a stand-in model file.
TEST_F(SceneTest, ExampleSceneLoads) {
    const fs::path example = fs::path(FACET_SOURCE_DIR) / "models/example-scene.json";
    std::ifstream in(example);
    ASSERT_TRUE(in) << example;
    std::stringstream text;
    text << in.rdbuf();
    touch("spot/spot_triangulated.obj");
    const Scene scene = loadScene(write("example-scene.json", text.str()));

    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].model, folder_ / "spot/spot_triangulated.obj");
    EXPECT_TRUE(scene.objects[0].material.diffuse.has_value());
    ASSERT_EQ(scene.lights.size(), 2u);
    EXPECT_EQ(scene.lights[0].type, LightKind::Directional);
    EXPECT_EQ(scene.lights[1].type, LightKind::Point);
    EXPECT_TRUE(scene.camera.eye.has_value());
}

// The bundled lighting example loads as committed (its models are in models/) with the values it shows.
TEST(SceneLightingExample, LoadsWithItsLightingKeys) {
    const fs::path path = fs::path(FACET_SOURCE_DIR) / "models/lighting-scene.json";
    const Scene scene = loadScene(path);

    EXPECT_EQ(scene.lighting.preset, LightingPreset::Facet);
    EXPECT_EQ(scene.lighting.model, ReflectionModel::BlinnPhong);
    EXPECT_EQ(scene.lighting.shading, ShadingFrequency::Phong);
    EXPECT_EQ(scene.lighting.creaseAngleDegrees, 60.0f);

    ASSERT_EQ(scene.lights.size(), 2u);
    const LightSpec& spot = scene.lights[0];
    EXPECT_EQ(spot.type, LightKind::Spot);
    EXPECT_EQ(spot.position, glm::vec3(0.0f, 3.0f, 1.5f));
    EXPECT_EQ(spot.direction, glm::vec3(0.0f, -3.0f, -1.5f));
    EXPECT_EQ(spot.spotInnerDegrees, 18.0f);
    EXPECT_EQ(spot.spotOuterDegrees, 28.0f);
    EXPECT_EQ(spot.attenuation, glm::vec3(0, 0, 1));
    EXPECT_EQ(spot.intensity, 9.0f);
    const LightSpec& point = scene.lights[1];
    EXPECT_EQ(point.type, LightKind::Point);
    EXPECT_EQ(point.attenuation, glm::vec3(1.0f, 0.2f, 0.05f));
    EXPECT_EQ(point.ambient, glm::vec3(0.05f, 0.04f, 0.03f));

    ASSERT_EQ(scene.objects.size(), 2u);
    EXPECT_EQ(scene.objects[0].model, path.parent_path() / "spot/spot_triangulated.obj");
    EXPECT_EQ(scene.objects[0].material.preset, "gold");
    EXPECT_EQ(scene.objects[0].material.roughness, 0.35f);
    EXPECT_EQ(scene.objects[0].reflection, ReflectionModel::CookTorrance);
    EXPECT_FALSE(scene.objects[0].shading.has_value());
    EXPECT_EQ(scene.objects[1].model, path.parent_path() / "cube/cube.obj");
    EXPECT_EQ(scene.objects[1].reflection, ReflectionModel::Phong);
    EXPECT_EQ(scene.objects[1].shading, ShadingFrequency::Flat);
    EXPECT_FALSE(scene.objects[1].material.physicallyBased());
}

// The bundled transparency example loads as committed: an opaque backdrop, then the intersecting quads,
// sorted per triangle (the doc comment asks for a second render with "exact").
TEST(SceneIntersectingQuadsExample, LoadsWithItsTransparencyKeys) {
    const fs::path path = fs::path(FACET_SOURCE_DIR) / "models/intersecting-quads.json";
    const Scene scene = loadScene(path);

    EXPECT_EQ(scene.transparency.mode, TransparencyMode::Sorted);
    EXPECT_EQ(scene.transparency.key, SortKey::Centroid);
    EXPECT_EQ(scene.pipeline.cull, CullMode::None);
    EXPECT_EQ(scene.fog.mode, FogMode::None);
    ASSERT_EQ(scene.objects.size(), 2u);
    EXPECT_EQ(scene.objects[0].model, path.parent_path() / "intersecting-quads/backdrop.obj");
    EXPECT_FALSE(scene.objects[0].blend.has_value());
    EXPECT_EQ(scene.objects[1].model, path.parent_path() / "intersecting-quads/quads.obj");
    EXPECT_EQ(scene.objects[1].blend, BlendMode::Over);
    EXPECT_FALSE(scene.objects[1].material.opacity.has_value());  // the MTL's d 0.5
    EXPECT_TRUE(fs::exists(path.parent_path() / "intersecting-quads/quads.mtl"));
}

// The bundled fog example loads as committed: three Spots, a ground and a glass cube in exp² fog.
TEST(SceneFogAndGlassExample, LoadsWithItsFogAndBlendKeys) {
    const fs::path path = fs::path(FACET_SOURCE_DIR) / "models/fog-and-glass.json";
    const Scene scene = loadScene(path);

    EXPECT_EQ(scene.fog.mode, FogMode::ExponentialSquared);
    EXPECT_EQ(scene.fog.color, glm::vec3(0.62f, 0.66f, 0.72f));
    EXPECT_EQ(scene.fog.density, 0.1f);
    EXPECT_EQ(scene.fog.distance, FogDistance::Radial);
    EXPECT_FALSE(scene.fog.start.has_value());
    EXPECT_EQ(glm::vec3(scene.background), scene.fog.color);  // the far ground meets the sky
    EXPECT_EQ(scene.transparency.mode, TransparencyMode::Sorted);
    EXPECT_EQ(scene.gamma.encode, TransferCurve::Srgb);

    ASSERT_EQ(scene.objects.size(), 5u);
    EXPECT_EQ(scene.objects[0].model, path.parent_path() / "fog-and-glass/ground.obj");
    for (std::size_t i = 1; i <= 3; ++i) {
        EXPECT_EQ(scene.objects[i].model, path.parent_path() / "spot/spot_triangulated.obj");
        EXPECT_FALSE(scene.objects[i].blend.has_value());
    }
    const ObjectSpec& glass = scene.objects[4];
    EXPECT_EQ(glass.model, path.parent_path() / "cube/cube.obj");
    EXPECT_EQ(glass.material.opacity, 0.4f);
    EXPECT_EQ(glass.blend, BlendMode::Over);
}

// Every ```json block in docs/scene-format.md is a complete scene that loads, so the documentation
// cannot drift from the loader.
TEST_F(SceneTest, DocumentationExamplesLoad) {
    const fs::path doc = fs::path(FACET_SOURCE_DIR) / "docs/scene-format.md";
    std::ifstream in(doc);
    ASSERT_TRUE(in) << doc;
    std::vector<std::string> blocks;
    std::string line, block;
    bool inside = false;
    while (std::getline(in, line)) {
        if (!inside && line == "```json") {
            inside = true;
            block.clear();
        } else if (inside && line == "```") {
            inside = false;
            blocks.push_back(block);
        } else if (inside) {
            block += line + "\n";
        }
    }
    ASSERT_GE(blocks.size(), 2u);
    for (std::size_t i = 0; i < blocks.size(); ++i) {
        SCOPED_TRACE("block " + std::to_string(i) + ":\n" + blocks[i]);
        const nlohmann::json document = nlohmann::json::parse(blocks[i], nullptr, true, true);
        if (document.contains("model")) touch(document["model"].get<std::string>());
        for (const auto& object : document.value("objects", nlohmann::json::array())) {
            touch(object["model"].get<std::string>());
        }
        const fs::path path = write("doc-" + std::to_string(i) + ".json", blocks[i]);
        EXPECT_NO_THROW(loadScene(path));
    }
}

// ---- File-level errors --------------------------------------------------------------------------

TEST_F(SceneTest, MissingFileIsAnError) {
    const fs::path path = folder_ / "nope.json";
    try {
        loadScene(path);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), path.string() + ": scene file not found");
    }
}

TEST_F(SceneTest, FolderIsNotASceneFile) {
    try {
        loadScene(folder_);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), folder_.string() + ": is a folder, not a scene file");
    }
}

TEST_F(SceneTest, SyntaxErrorGivesLineAndColumn) {
    const std::string message = errorOf("{\n  \"width\": 100,\n  \"height\": }\n");
    EXPECT_EQ(
        message,
        (folder_ / "scene.json").string() +
            ": JSON syntax error at line 3, column 13: unexpected '}'; expected '[', '{', or a literal");
}

TEST_F(SceneTest, SyntaxErrorColumnCountsCharactersNotBytes) {
    // "é" is two bytes in UTF-8 but one column in an editor.
    EXPECT_NE(errorOf("{\"model\": \"m.obj\", \"é\": x}").find("line 1, column 25"), std::string::npos);
}

TEST_F(SceneTest, UnexpectedEndOfFileIsLocated) {
    EXPECT_NE(errorOf("{\"model\": \"m.obj\",\n").find("at line 2, column 1: unexpected end of input"),
              std::string::npos);
    EXPECT_NE(errorOf("").find("JSON syntax error at line 1, column 1"), std::string::npos);
}

TEST_F(SceneTest, NumberBeyondDoubleRangeIsLocated) {
    const std::string message = errorOf("{\"model\": \"m.obj\",\n \"width\": 1e400}");
    EXPECT_NE(message.find("at line 2, column 11"), std::string::npos) << message;
    EXPECT_NE(message.find("1e400"), std::string::npos) << message;
}

// ---- Key-level errors: one table, each message checked for the file, the key path and the reason ----

struct ErrorCase {
    const char* name;
    const char* json;
    std::vector<std::string> expected;  // substrings of the message (after the "file: " prefix)
};

std::ostream& operator<<(std::ostream& out, const ErrorCase& c) {
    return out << c.name;
}

class SceneErrors : public SceneTest, public ::testing::WithParamInterface<ErrorCase> {};

TEST_P(SceneErrors, MessageNamesFileAndKey) {
    const ErrorCase& c = GetParam();
    const std::string message = errorOf(c.json);
    const std::string prefix = (folder_ / "scene.json").string() + ": ";
    EXPECT_EQ(message.substr(0, prefix.size()), prefix) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    for (const std::string& part : c.expected)
        EXPECT_NE(message.find(part), std::string::npos) << message;
}

const ErrorCase kErrorCases[] = {
    // Unknown keys, at every depth, with a suggestion only for a near miss.
    {"UnknownTopLevelKey",
     R"({"model": "m.obj", "widht": 5})",
     {R"(unknown key "widht" (did you mean "width"?))"}},
    {"UnknownCameraKey",
     R"({"model": "m.obj", "camera": {"fvoy": 5}})",
     {R"(unknown key "camera.fvoy" (did you mean "fovy"?))"}},
    {"UnknownLightKey",
     R"({"model": "m.obj", "lights": [{}, {"colour": [1, 1, 1]}]})",
     {R"(unknown key "lights[1].colour" (did you mean "color"?))"}},
    {"UnknownMaterialKey",
     R"({"objects": [{"model": "m.obj", "material": {"glossiness": 1}}]})",
     {R"(unknown key "objects[0].material.glossiness")"}},
    {"UnknownPipelineKey",
     R"({"model": "m.obj", "pipeline": {"subpixelBits": 4}})",
     {R"(unknown key "pipeline.subpixelBits" (did you mean "subpixel_bits"?))"}},
    {"UnknownKeyWithNewline", "{\"model\": \"m.obj\", \"a\\nb\": 1}", {R"(unknown key "a\nb")"}},
    // Wrong types.
    {"FovyNotANumber",
     R"({"model": "m.obj", "camera": {"fovy": "wide"}})",
     {R"("camera.fovy" must be a number (got the string "wide"))"}},
    {"EyeWrongLength",
     R"({"model": "m.obj", "camera": {"eye": [0, 1]}})",
     {R"("camera.eye" must be an array of 3 numbers)", "(got an array of 2)"}},
    {"EyeElementNotANumber",
     R"({"model": "m.obj", "camera": {"eye": [0, true, 1]}})",
     {R"("camera.eye[1]" must be a number (got true))"}},
    {"CameraNotAnObject", R"({"model": "m.obj", "camera": [0, 1, 5]})", {R"("camera" must be an object)"}},
    {"WidthAsString",
     R"({"model": "m.obj", "width": "800"})",
     {R"("width" must be a whole number (got the string "800"))"}},
    {"LightsNotAnArray",
     R"({"model": "m.obj", "lights": {"type": "point"}})",
     {R"("lights" must be an array of lights (got an object))"}},
    {"ObjectsNotAnArray", R"({"objects": {"model": "m.obj"}})", {R"("objects" must be an array)"}},
    {"ModelNotAString", R"({"model": 3})", {R"("model" must be a string (got 3))"}},
    {"CullNotAChoice",
     R"({"model": "m.obj", "pipeline": {"cull": "bakc"}})",
     {R"("pipeline.cull" must be one of "back", "front", "none" (got "bakc") (did you mean "back"?))"}},
    {"LightTypeUnknown",
     R"({"model": "m.obj", "lights": [{"type": "sopt"}]})",
     {R"("lights[0].type" must be one of "directional", "point", "spot", "rect", "disk" (got "sopt") (did you mean "spot"?))"}},
    {"LightSpaceUnknown",
     R"({"model": "m.obj", "lights": [{"space": "view"}]})",
     {R"("lights[0].space" must be one of "world", "camera")"}},
    {"InterpolationUnknown",
     R"({"model": "m.obj", "pipeline": {"interpolation": "linear"}})",
     {R"("pipeline.interpolation" must be one of)"}},
    {"TopLevelNotAnObject", R"([{"model": "m.obj"}])", {"must hold a JSON object", "(got an array of 1)"}},
    // Out-of-range values.
    {"WidthZero",
     R"({"model": "m.obj", "width": 0})",
     {R"("width" must be a whole number from 1 to 16384 (got 0))"}},
    {"HeightTooLarge",
     R"({"model": "m.obj", "height": 16385})",
     {R"("height")", "from 1 to 16384 (got 16385)"}},
    {"WidthFraction",
     R"({"model": "m.obj", "width": 2.5})",
     {R"("width" must be a whole number)", "(got 2.5)"}},
    {"WidthHuge", R"({"model": "m.obj", "width": 1e300})", {R"("width")", "(got 1e+300)"}},
    {"FovyZero",
     R"({"model": "m.obj", "camera": {"fovy": 0}})",
     {R"("camera.fovy" must be from 0.01 to 179 degrees)", "(got 0)"}},
    {"Fovy180", R"({"model": "m.obj", "camera": {"fovy": 180}})", {R"("camera.fovy")", "(got 180)"}},
    // A field of view of 1e-30° is a blank image, not a telescope.
    {"FovyTiny",
     R"({"model": "m.obj", "camera": {"fovy": 1e-30}})",
     {R"("camera.fovy" must be from 0.01 to 179 degrees)"}},
    {"FovyAlmost180",
     R"({"model": "m.obj", "camera": {"fovy": 179.5}})",
     {R"("camera.fovy")", "to 179 degrees (got 179.5)"}},
    {"NearZero",
     R"({"model": "m.obj", "camera": {"near": 0}})",
     {R"("camera.near" must be greater than 0 (got 0))"}},
    {"NearNegative", R"({"model": "m.obj", "camera": {"near": -1}})", {R"("camera.near")", "(got -1)"}},
    {"FarBelowNear",
     R"({"model": "m.obj", "camera": {"near": 10, "far": 5}})",
     {R"("camera.far" must be greater than "camera.near" (10) (got 5))"}},
    {"FarEqualsNear", R"({"model": "m.obj", "camera": {"near": 1, "far": 1}})", {R"("camera.far")"}},
    {"FarNegative",
     R"({"model": "m.obj", "camera": {"far": -2}})",
     {R"("camera.far" must be greater than 0)"}},
    {"EyeEqualsTarget",
     R"({"model": "m.obj", "camera": {"eye": [1, 2, 3], "target": [1, 2, 3]}})",
     {R"("camera.eye" and "camera.target" must differ)"}},
    {"UpParallelToView",
     R"({"model": "m.obj", "camera": {"eye": [0, 5, 0], "target": [0, 0, 0]}})",
     {R"("camera.up" is parallel to the view direction)"}},
    {"UpZero",
     R"({"model": "m.obj", "camera": {"up": [0, 0, 0]}})",
     {R"("camera.up" must not be the zero vector)"}},
    {"IntensityNegative",
     R"({"model": "m.obj", "lights": [{"intensity": -1}]})",
     {R"("lights[0].intensity" must not be negative (got -1))"}},
    {"ColorNegative",
     R"({"model": "m.obj", "lights": [{"color": [1, -0.5, 1]}]})",
     {R"("lights[0].color[1]" must not be negative (got -0.5))"}},
    {"DirectionZero",
     R"({"model": "m.obj", "lights": [{"direction": [0, 0, 0]}]})",
     {R"("lights[0].direction" must not be the zero vector)"}},
    {"PointLightWithDirection",
     R"({"model": "m.obj", "lights": [{"type": "point", "direction": [0, -1, 0]}]})",
     {R"("lights[0].direction" is only for directional and spot lights)"}},
    {"DirectionalLightWithPosition",
     R"({"model": "m.obj", "lights": [{"position": [0, 1, 0]}]})",
     {R"("lights[0].position" is only for point and spot lights (add "type": "point"))"}},
    {"SubpixelBitsTooMany",
     R"({"model": "m.obj", "pipeline": {"subpixel_bits": 9}})",
     {R"("pipeline.subpixel_bits" must be a whole number from 0 to 8 (got 9))"}},
    {"SubpixelBitsNegative",
     R"({"model": "m.obj", "pipeline": {"subpixel_bits": -1}})",
     {R"("pipeline.subpixel_bits")", "(got -1)"}},
    {"OpacityAboveOne",
     R"({"objects": [{"model": "m.obj", "material": {"opacity": 1.5}}]})",
     {R"("objects[0].material.opacity" must be from 0 to 1 (got 1.5))"}},
    {"ShininessNegative",
     R"({"objects": [{"model": "m.obj", "material": {"shininess": -2}}]})",
     {R"("objects[0].material.shininess" must not be negative)"}},
    {"DiffuseNegative",
     R"({"objects": [{"model": "m.obj", "material": {"diffuse": [-1, 0, 0]}}]})",
     {R"("objects[0].material.diffuse[0]" must not be negative)"}},
    {"MaterialNotAnObject",
     R"({"objects": [{"model": "m.obj", "material": "red"}]})",
     {R"("objects[0].material" must be an object)"}},
    {"ScaleZero",
     R"({"objects": [{"model": "m.obj", "scale": 0}]})",
     {R"("objects[0].scale" must not be zero)"}},
    {"ScaleAxisZero",
     R"({"objects": [{"model": "m.obj", "scale": [1, 0, 1]}]})",
     {R"("objects[0].scale" must not be zero in any axis)"}},
    {"TranslateBeyondFloat",
     R"({"objects": [{"model": "m.obj", "translate": [1e300, 0, 0]}]})",
     {R"("objects[0].translate[0]" is too large (got 1e+300))"}},
    {"BackgroundWrongLength",
     R"({"model": "m.obj", "background": [1, 1]})",
     {R"("background" must be [r, g, b] or [r, g, b, a] (got an array of 2))"}},
    {"BackgroundAlphaAboveOne",
     R"({"model": "m.obj", "background": [0, 0, 0, 2]})",
     {R"("background[3]" (alpha) must be from 0 to 1 (got 2))"}},
    {"AmbientNegative",
     R"({"model": "m.obj", "ambient": [0.1, 0.1, -0.1]})",
     {R"("ambient[2]" must not be negative)"}},
    // Objects.
    {"NoObjects", R"({"width": 100})", {"the scene has no objects"}},
    {"EmptyObjects", R"({"objects": []})", {"the scene has no objects"}},
    {"ModelAndObjects",
     R"({"model": "m.obj", "objects": [{"model": "m.obj"}]})",
     {R"(give either "model" or "objects", not both)"}},
    {"ObjectWithoutModel",
     R"({"objects": [{"model": "m.obj"}, {"scale": 2}]})",
     {R"("objects[1].model" is missing)"}},
    {"ModelEmpty", R"({"model": ""})", {R"("model" must name an OBJ file)"}},
    {"ModelNotFound",
     R"({"objects": [{"model": "m.obj"}, {"model": "x.obj"}]})",
     {R"("objects[1].model": model file "x.obj" not found (looked for ")", R"(x.obj"))"}},
    {"ShorthandModelNotFound", R"({"model": "sub/x.obj"})", {R"("model": model file "sub/x.obj" not found)"}},
    // Duplicates: JSON would silently keep the last one.
    {"DuplicateKey",
     R"({"model": "m.obj", "camera": {"fovy": 30, "fovy": 40}})",
     {R"(key "camera.fovy" is given twice)"}},
    {"DuplicateKeyInArray",
     R"({"model": "m.obj", "lights": [{}, {"color": [1, 1, 1], "color": [1, 0, 0]}]})",
     {R"(key "lights[1].color" is given twice)"}},
    {"DuplicateTopLevelKey",
     R"({"model": "m.obj", "width": 10, "width": 20})",
     {R"(key "width" is given twice)"}},
    // Scene-wide "lighting".
    {"LightingUnknownPreset",
     R"({"model": "m.obj", "lighting": "opengl"})",
     {R"("lighting" must be one of "facet", "gl", "lecture" (got "opengl"))"}},
    {"LightingNotAnObject",
     R"({"model": "m.obj", "lighting": 1})",
     {R"("lighting" must be "facet", "gl", "lecture" or an object like {"model": "cook-torrance"} (got 1))"}},
    {"LightingUnknownKey",
     R"({"model": "m.obj", "lighting": {"shadding": "flat"}})",
     {R"(unknown key "lighting.shadding" (did you mean "shading"?))"}},
    {"LightingPresetUnknown",
     R"({"model": "m.obj", "lighting": {"preset": "GL"}})",
     {R"("lighting.preset" must be one of "facet", "gl", "lecture" (got "GL"))"}},
    {"LightingModelUnknown",
     R"({"model": "m.obj", "lighting": {"model": "blinn"}})",
     {R"("lighting.model" must be one of "phong", "blinn-phong", "cook-torrance" (got "blinn"))"}},
    {"LightingModelTypo",
     R"({"model": "m.obj", "lighting": {"model": "blinn_phong"}})",
     {R"("lighting.model")", R"((did you mean "blinn-phong"?))"}},
    {"LightingShadingUnknown",
     R"({"model": "m.obj", "lighting": {"shading": "smooth"}})",
     {R"("lighting.shading" must be one of "constant", "flat", "gouraud", "phong" (got "smooth"))"}},
    {"CreaseAngleAbove180",
     R"({"model": "m.obj", "lighting": {"crease_angle": 181}})",
     {R"("lighting.crease_angle" must be from 0 to 180 degrees (got 181))"}},
    {"CreaseAngleNegative",
     R"({"model": "m.obj", "lighting": {"crease_angle": -1}})",
     {R"("lighting.crease_angle" must be from 0 to 180 degrees (got -1))"}},
    {"CreaseAngleNotANumber",
     R"({"model": "m.obj", "lighting": {"crease_angle": "sharp"}})",
     {R"("lighting.crease_angle" must be a number (got the string "sharp"))"}},
    {"DistributionUnknown",
     R"({"model": "m.obj", "lighting": {"distribution": "phong"}})",
     {R"("lighting.distribution" must be one of "ggx", "beckmann", "gaussian" (got "phong"))"}},
    {"FresnelUnknown",
     R"({"model": "m.obj", "lighting": {"fresnel": "schlik"}})",
     {R"("lighting.fresnel" must be one of "schlick", "exact" (got "schlik") (did you mean "schlick"?))"}},
    {"GeometryUnknown",
     R"({"model": "m.obj", "lighting": {"geometry": "smith"}})",
     {R"("lighting.geometry" must be one of "smith-ggx", "cook-torrance" (got "smith"))"}},
    // Per-object "lighting".
    {"ObjectLightingNotAnObject",
     R"({"objects": [{"model": "m.obj", "lighting": "gl"}]})",
     {R"("objects[0].lighting" must be an object like {"model": "cook-torrance", "shading": "flat"})"}},
    {"ObjectLightingSceneWideKey",
     R"({"objects": [{"model": "m.obj"}, {"model": "m.obj", "lighting": {"crease_angle": 30}}]})",
     {R"("objects[1].lighting.crease_angle" cannot be set per object (only "model" and "shading" can))"}},
    {"ObjectLightingUnknownKey",
     R"({"objects": [{"model": "m.obj", "lighting": {"modle": "phong"}}]})",
     {R"(unknown key "objects[0].lighting.modle" (did you mean "model"?))"}},
    {"ObjectLightingModelUnknown",
     R"({"objects": [{"model": "m.obj", "lighting": {"model": "pbr"}}]})",
     {R"("objects[0].lighting.model" must be one of "phong", "blinn-phong", "cook-torrance" (got "pbr"))"}},
    {"ObjectLightingShadingUnknown",
     R"({"objects": [{"model": "m.obj", "lighting": {"shading": "Flat"}}]})",
     {R"("objects[0].lighting.shading" must be one of "constant", "flat", "gouraud", "phong" (got "Flat"))"}},
    // Lights: keys the type ignores.
    {"SpotKeyOnPointLight",
     R"({"model": "m.obj", "lights": [{}, {"type": "point", "cutoff": 20}]})",
     {R"("lights[1].cutoff" is only for spot lights (add "type": "spot"))"}},
    {"SpotKeyOnDirectionalLight",
     R"({"model": "m.obj", "lights": [{"exponent": 2}]})",
     {R"("lights[0].exponent" is only for spot lights (add "type": "spot"))"}},
    {"InnerOnPointLight",
     R"({"model": "m.obj", "lights": [{"type": "point", "inner": 10, "outer": 20}]})",
     {R"("lights[0].inner" is only for spot lights)"}},
    {"OuterOnDirectionalLight",
     R"({"model": "m.obj", "lights": [{"outer": 20}]})",
     {R"("lights[0].outer" is only for spot lights)"}},
    {"AttenuationOnDirectionalLight",
     R"({"model": "m.obj", "lights": [{"attenuation": [1, 0, 0]}]})",
     {R"("lights[0].attenuation" is only for point and spot lights)", R"((add "type": "point"))"}},
    {"SpotDirectionZero",
     R"({"model": "m.obj", "lights": [{"type": "spot", "direction": [0, 0, 0]}]})",
     {R"("lights[0].direction" must not be the zero vector)"}},
    // Lights: values.
    {"AttenuationAllZero",
     R"({"model": "m.obj", "lights": [{"type": "point", "attenuation": [0, 0, 0]}]})",
     {R"("lights[0].attenuation" must not be all zero)"}},
    {"AttenuationNegative",
     R"({"model": "m.obj", "lights": [{"type": "spot", "attenuation": [1, -0.1, 0]}]})",
     {R"("lights[0].attenuation[1]" must not be negative (got -0.1))"}},
    {"AttenuationWrongLength",
     R"({"model": "m.obj", "lights": [{"type": "point", "attenuation": [1, 0.1]}]})",
     {R"("lights[0].attenuation" must be an array of 3 numbers like [1, 0.1, 0.01] (got an array of 2))"}},
    {"LightAmbientNegative",
     R"({"model": "m.obj", "lights": [{"ambient": [0, -1, 0]}]})",
     {R"("lights[0].ambient[1]" must not be negative (got -1))"}},
    {"LightDiffuseNotAColour",
     R"({"model": "m.obj", "lights": [{"diffuse": 1}]})",
     {R"("lights[0].diffuse" must be an array of 3 numbers like [1, 0.5, 0.2] (got 1))"}},
    {"LightSpecularNegative",
     R"({"model": "m.obj", "lights": [{"specular": [-2, 0, 0]}]})",
     {R"("lights[0].specular[0]" must not be negative (got -2))"}},
    {"CutoffAbove90",
     R"({"model": "m.obj", "lights": [{"type": "spot", "cutoff": 180}]})",
     {R"("lights[0].cutoff" must be from 0 to 90 degrees (got 180))"}},
    {"CutoffNegative",
     R"({"model": "m.obj", "lights": [{"type": "spot", "cutoff": -5}]})",
     {R"("lights[0].cutoff" must be from 0 to 90 degrees (got -5))"}},
    {"ExponentAbove128",
     R"({"model": "m.obj", "lights": [{"type": "spot", "exponent": 128.5}]})",
     {R"("lights[0].exponent" must be from 0 to 128 (got 128.5))"}},
    {"ExponentNegative",
     R"({"model": "m.obj", "lights": [{"type": "spot", "exponent": -1}]})",
     {R"("lights[0].exponent" must be from 0 to 128 (got -1))"}},
    {"InnerWithoutOuter",
     R"({"model": "m.obj", "lights": [{"type": "spot", "inner": 10}]})",
     {R"("lights[0].inner" needs "lights[0].outer" too)"}},
    {"OuterWithoutInner",
     R"({"model": "m.obj", "lights": [{"type": "spot", "outer": 10}]})",
     {R"("lights[0].outer" needs "lights[0].inner" too)"}},
    {"InnerOuterWithCutoff",
     R"({"model": "m.obj", "lights": [{"type": "spot", "inner": 10, "outer": 20, "cutoff": 20}]})",
     {R"("lights[0].cutoff" cannot be given with "inner" and "outer")"}},
    {"InnerOuterWithExponent",
     R"({"model": "m.obj", "lights": [{"type": "spot", "inner": 10, "outer": 20, "exponent": 4}]})",
     {R"("lights[0].exponent" cannot be given with "inner" and "outer")"}},
    {"InnerNotBelowOuter",
     R"({"model": "m.obj", "lights": [{"type": "spot", "inner": 30, "outer": 20}]})",
     {R"("lights[0].inner" (30) must be less than "lights[0].outer" (20))"}},
    {"InnerEqualsOuter",
     R"({"model": "m.obj", "lights": [{"type": "spot", "inner": 20, "outer": 20}]})",
     {R"("lights[0].inner" (20) must be less than "lights[0].outer" (20))"}},
    {"InnerNegative",
     R"({"model": "m.obj", "lights": [{"type": "spot", "inner": -1, "outer": 20}]})",
     {R"("lights[0].inner" must be from 0 to 90 degrees (got -1))"}},
    {"OuterAbove90",
     R"({"model": "m.obj", "lights": [{"type": "spot", "inner": 10, "outer": 91}]})",
     {R"("lights[0].outer" must be from 0 to 90 degrees (got 91))"}},
    // Material: physically based keys.
    {"PresetTypo",
     R"({"objects": [{"model": "m.obj", "material": {"preset": "gld"}}]})",
     {R"("objects[0].material.preset" must be one of the material presets "water", "living-tissue")",
      R"("aluminium", "silver" (got "gld") (did you mean "gold"?))"}},
    {"PresetTypoIgnoresCase",
     R"({"objects": [{"model": "m.obj", "material": {"preset": "COPER"}}]})",
     {R"((got "COPER") (did you mean "copper"?))"}},
    {"PresetNotAString",
     R"({"objects": [{"model": "m.obj", "material": {"preset": 1}}]})",
     {R"("objects[0].material.preset" must be a string (got 1))"}},
    {"BaseColorNegative",
     R"({"objects": [{"model": "m.obj", "material": {"base_color": [1, 1, -1]}}]})",
     {R"("objects[0].material.base_color[2]" must not be negative (got -1))"}},
    {"BaseColorCamelCase",
     R"({"objects": [{"model": "m.obj", "material": {"baseColor": [1, 1, 1]}}]})",
     {R"(unknown key "objects[0].material.baseColor")"}},
    {"MetalnessAboveOne",
     R"({"objects": [{"model": "m.obj", "material": {"metalness": 1.5}}]})",
     {R"("objects[0].material.metalness" must be from 0 to 1 (got 1.5))"}},
    {"RoughnessNegative",
     R"({"objects": [{"model": "m.obj", "material": {"roughness": -0.1}}]})",
     {R"("objects[0].material.roughness" must be from 0 to 1 (got -0.1))"}},
    {"F0AboveOne",
     R"({"objects": [{"model": "m.obj", "material": {"f0": 1.2}}]})",
     {R"("objects[0].material.f0" must be from 0 to 1 (got 1.2))"}},
    {"F0ElementAboveOne",
     R"({"objects": [{"model": "m.obj", "material": {"f0": [0.04, 2, 0.04]}}]})",
     {R"("objects[0].material.f0[1]" must be from 0 to 1 (got 2))"}},
    {"F0WrongShape",
     R"({"objects": [{"model": "m.obj", "material": {"f0": [0.04, 0.04]}}]})",
     {R"("objects[0].material.f0" must be a number or an array of 3 numbers like [0.04, 0.04, 0.04])",
      "(got an array of 2)"}},
    {"F0String",
     R"({"objects": [{"model": "m.obj", "material": {"f0": "0.04"}}]})",
     {R"("objects[0].material.f0" must be a number or an array of 3 numbers)"}},
    // Object "blend".
    {"BlendUnknown",
     R"({"objects": [{"model": "m.obj", "blend": "add"}]})",
     {R"("objects[0].blend" must be one of "over", "additive", "multiply", "premultiplied" (got "add"))"}},
    {"BlendTypo",
     R"({"objects": [{"model": "m.obj"}, {"model": "m.obj", "blend": "multipy"}]})",
     {R"("objects[1].blend")", R"((got "multipy") (did you mean "multiply"?))"}},
    {"BlendNotAString",
     R"({"objects": [{"model": "m.obj", "blend": 1}]})",
     {R"("objects[0].blend" must be a string (got 1))"}},
    {"BlendUnknownObjectKeySuggestsBlend",
     R"({"objects": [{"model": "m.obj", "blnd": "over"}]})",
     {R"(unknown key "objects[0].blnd" (did you mean "blend"?))"}},
    // "transparency".
    {"TransparencyNotAnObject",
     R"({"model": "m.obj", "transparency": "exact"})",
     {R"("transparency" must be an object like {"mode": "exact"} (got the string "exact"))"}},
    {"TransparencyUnknownKey",
     R"({"model": "m.obj", "transparency": {"sortkey": "centroid"}})",
     {R"(unknown key "transparency.sortkey" (did you mean "sort_key"?))"}},
    {"TransparencyModeUnknown",
     R"({"model": "m.obj", "transparency": {"mode": "exat"}})",
     {R"("transparency.mode" must be one of "sorted", "unsorted", "exact" (got "exat") (did you mean "exact"?))"}},
    {"TransparencyModeNotAString",
     R"({"model": "m.obj", "transparency": {"mode": true}})",
     {R"("transparency.mode" must be a string (got true))"}},
    {"SortKeyUnknown",
     R"({"model": "m.obj", "transparency": {"sort_key": "farthest-vertex"}})",
     {R"("transparency.sort_key" must be one of "centroid", "farthest" (got "farthest-vertex"))"}},
    {"TopLevelTypoSuggestsTransparency",
     R"({"model": "m.obj", "transparancy": {}})",
     {R"(unknown key "transparancy" (did you mean "transparency"?))"}},
    // "fog".
    {"FogNotAnObject",
     R"({"model": "m.obj", "fog": "exp2"})",
     {R"("fog" must be an object like {"mode": "exp2", "density": 0.2} (got the string "exp2"))"}},
    {"FogEmpty",
     R"({"model": "m.obj", "fog": {}})",
     {R"("fog.mode" is missing: give "linear", "exp", "exp2" or "height" (or remove "fog" for no fog))"}},
    {"FogWithoutMode", R"({"model": "m.obj", "fog": {"density": 0.5}})", {R"("fog.mode" is missing)"}},
    {"FogModeUnknown",
     R"({"model": "m.obj", "fog": {"mode": "exponential"}})",
     {R"("fog.mode" must be one of "linear", "exp", "exp2", "height" (got "exponential"))"}},
    {"FogModeNone",
     R"({"model": "m.obj", "fog": {"mode": "none"}})",
     {R"("fog.mode" must be one of "linear", "exp", "exp2", "height" (got "none"))"}},
    {"FogUnknownKey",
     R"({"model": "m.obj", "fog": {"mode": "exp", "colour": [1, 1, 1]}})",
     {R"(unknown key "fog.colour" (did you mean "color"?))"}},
    {"FogColorNegative",
     R"({"model": "m.obj", "fog": {"mode": "exp", "color": [0.5, -0.5, 0.5]}})",
     {R"("fog.color[1]" must not be negative (got -0.5))"}},
    {"FogColorWrongLength",
     R"({"model": "m.obj", "fog": {"mode": "exp", "color": [0.5, 0.5]}})",
     {R"("fog.color" must be an array of 3 numbers like [1, 0.5, 0.2] (got an array of 2))"}},
    {"FogStartWithExp",
     R"({"model": "m.obj", "fog": {"mode": "exp", "start": 1}})",
     {R"("fog.start": start and end are for linear fog (the mode is "exp", which uses "density"))"}},
    {"FogEndWithExp2",
     R"({"model": "m.obj", "fog": {"mode": "exp2", "end": 10}})",
     {R"("fog.end": start and end are for linear fog (the mode is "exp2", which uses "density"))"}},
    {"FogDensityWithLinear",
     R"({"model": "m.obj", "fog": {"mode": "linear", "density": 0.5}})",
     {R"("fog.density": density is for exp and exp2 fog (the mode is "linear", which uses "start" and "end"))"}},
    {"FogEndBelowStart",
     R"({"model": "m.obj", "fog": {"mode": "linear", "start": 10, "end": 2}})",
     {R"("fog.end" (2) must be greater than "fog.start" (10))"}},
    {"FogEndEqualsStart",
     R"({"model": "m.obj", "fog": {"mode": "linear", "start": 5, "end": 5}})",
     {R"("fog.end" (5) must be greater than "fog.start" (5))"}},
    {"FogStartNegative",
     R"({"model": "m.obj", "fog": {"mode": "linear", "start": -1, "end": 5}})",
     {R"("fog.start" must be from 0 to 1e30 (got -1))"}},
    {"FogEndNegative",
     R"({"model": "m.obj", "fog": {"mode": "linear", "end": -5}})",
     {R"("fog.end" must be from 0 to 1e30 (got -5))"}},
    {"FogStartNotANumber",
     R"({"model": "m.obj", "fog": {"mode": "linear", "start": "near"}})",
     {R"("fog.start" must be a number (got the string "near"))"}},
    {"FogDensityNegative",
     R"({"model": "m.obj", "fog": {"mode": "exp", "density": -0.1}})",
     {R"("fog.density" must be from 0 to 1e30 (got -0.1))"}},
    {"FogDensityNotANumber",
     R"({"model": "m.obj", "fog": {"mode": "exp2", "density": [1]}})",
     {R"("fog.density" must be a number (got an array of 1))"}},
    {"FogDistanceUnknown",
     R"({"model": "m.obj", "fog": {"mode": "exp", "distance": "radiall"}})",
     {R"("fog.distance" must be one of "depth", "radial" (got "radiall") (did you mean "radial"?))"}},
    // "gamma".
    {"GammaNotAnObject",
     R"({"model": "m.obj", "gamma": 2.2})",
     {R"("gamma" must be an object like {"encode": "power", "exponent": 2.2} (got 2.2))"}},
    {"GammaUnknownKey",
     R"({"model": "m.obj", "gamma": {"decodeInputs": false}})",
     {R"(unknown key "gamma.decodeInputs")"}},
    {"GammaUnknownKeyNearMiss",
     R"({"model": "m.obj", "gamma": {"exponnet": 2}})",
     {R"(unknown key "gamma.exponnet" (did you mean "exponent"?))"}},
    {"GammaEncodeUnknown",
     R"({"model": "m.obj", "gamma": {"encode": "sRGB"}})",
     {R"("gamma.encode" must be one of "srgb", "power", "linear" (got "sRGB"))"}},
    {"GammaExponentWithoutPower",
     R"({"model": "m.obj", "gamma": {"exponent": 2.4}})",
     {R"("gamma.exponent" is only for "encode": "power" (the curve is "srgb", the default))"}},
    {"GammaExponentWithLinear",
     R"({"model": "m.obj", "gamma": {"encode": "linear", "exponent": 2.4}})",
     {R"("gamma.exponent" is only for "encode": "power" (the curve is "linear"))"}},
    {"GammaExponentZero",
     R"({"model": "m.obj", "gamma": {"encode": "power", "exponent": 0}})",
     {R"("gamma.exponent" must be greater than 0 (got 0))"}},
    {"GammaExponentNegative",
     R"({"model": "m.obj", "gamma": {"encode": "power", "exponent": -2.2}})",
     {R"("gamma.exponent" must be greater than 0 (got -2.2))"}},
    {"GammaExponentNotANumber",
     R"({"model": "m.obj", "gamma": {"encode": "power", "exponent": "2.2"}})",
     {R"("gamma.exponent" must be a number (got the string "2.2"))"}},
    {"GammaDecodeInputsNotABoolean",
     R"({"model": "m.obj", "gamma": {"decode_inputs": "no"}})",
     {R"("gamma.decode_inputs" must be true or false (got the string "no"))"}},
    {"GammaDecodeInputsNumber",
     R"({"model": "m.obj", "gamma": {"decode_inputs": 0}})",
     {R"("gamma.decode_inputs" must be true or false (got 0))"}},
    {"GammaWithGlPreset",
     R"({"model": "m.obj", "lighting": "gl", "gamma": {"encode": "srgb"}})",
     {R"("gamma" cannot be used with the gl lighting preset)", R"(remove "gamma")"}},
    // The lecture preset fixes the output curve; the inputs' decoding stays open.
    {"GammaEncodeWithLecturePreset",
     R"({"model": "m.obj", "lighting": "lecture", "gamma": {"encode": "srgb"}})",
     {R"("gamma.encode" and "gamma.exponent" cannot be used with the lecture lighting preset)"}},
    {"GammaWithGlPresetObject",
     R"({"model": "m.obj", "lighting": {"preset": "gl"}, "gamma": {}})",
     {R"("gamma" cannot be used with the gl lighting preset)"}},
    // Counts and sizes, refused while reading the file.
    {"TooManyLights",
     R"({"model": "m.obj", "lights": [{}, {}, {}, {}, {}, {}, {}, {}, {"type": "sopt"}]})",
     {R"("lights" has 9 lights, at most 8 are supported)"}},
    {"TooManyPixels",
     R"({"model": "m.obj", "width": 16384, "height": 4097})",
     {R"("width" and "height" make an image of 16384x4097 = 67125248 pixels, larger than the limit of )"
      "67108864"}},
    // Light can be bright, but not overflow.
    {"EmissionTooBright",
     R"({"objects": [{"model": "m.obj", "material": {"emission": [3e38, 0, 0]}}]})",
     {R"("objects[0].material.emission[0]" must be at most 1000000 (got 3e+38))"}},
    {"IntensityTooBright",
     R"({"model": "m.obj", "lights": [{"intensity": 1.5e6}]})",
     {R"("lights[0].intensity" must be at most 1000000 (got 1500000))"}},
    {"LightColorTooBright",
     R"({"model": "m.obj", "lights": [{"specular": [1, 1, 2e6]}]})",
     {R"("lights[0].specular[2]" must be at most 1000000)"}},
    {"AmbientTooBright",
     R"({"model": "m.obj", "ambient": [1e7, 0, 0]})",
     {R"("ambient[0]" must be at most)"}},
    {"BackgroundTooBright",
     R"({"model": "m.obj", "background": [0, 1e30, 0]})",
     {R"("background[1]" must be at most 1000000 (got 1e+30))"}},
    {"FogColorTooBright",
     R"({"model": "m.obj", "fog": {"mode": "exp", "color": [0, 0, 1e9]}})",
     {R"("fog.color[2]" must be at most)"}},
};

INSTANTIATE_TEST_SUITE_P(Scene, SceneErrors, ::testing::ValuesIn(kErrorCases),
                         [](const ::testing::TestParamInfo<ErrorCase>& info) {
                             return std::string(info.param.name);
                         });

// Only a key within two edits of a known one is suggested.
TEST_F(SceneTest, FarFromEveryKeyGivesNoSuggestion) {
    const std::string message =
        errorOf(R"({"objects": [{"model": "m.obj", "material": {"glossiness": 1}}]})");
    EXPECT_EQ(message,
              (folder_ / "scene.json").string() + R"(: unknown key "objects[0].material.glossiness")");
}

// ---- Bad input that used to hang, fill memory or flood the terminal -------------------------------

// A FIFO would block every command until something writes to it; each refuses it unopened (bench:
// tests/bench).
TEST_F(SceneTest, FifoIsRefusedByEveryCommandWithoutOpeningIt) {
    const fs::path fifo = folder_ / "scene.json";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    const std::string expected =
        fifo.string() + ": is not a regular file (a device, a pipe or a socket), not a scene file";
    EXPECT_EQ(errorWithoutOpening(fifo, [&] { loadScene(fifo); }), expected);
    EXPECT_EQ(errorWithoutOpening(fifo, [&] { loadSceneOrModel(fifo); }), expected) << "render, compare";
}

// A device never ends (/dev/zero) or reads as empty (/dev/null): refused by its type, not by its text.
TEST_F(SceneTest, DeviceIsNotASceneFile) {
    const fs::path link = folder_ / "null.json";
    fs::create_symlink("/dev/null", link);
    try {
        loadScene(link);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()),
                  link.string() + ": is not a regular file (a device, a pipe or a socket), not a scene file");
    }
}

TEST_F(SceneTest, ModelThatIsAFifoIsAnError) {
    ASSERT_EQ(::mkfifo((folder_ / "pipe.obj").c_str(), 0600), 0);
    const std::string message = errorOf(R"({"model": "pipe.obj"})");
    EXPECT_NE(message.find(R"("model": model file "pipe.obj" is not a regular file)"), std::string::npos)
        << message;
}

// Refused by its size alone: a sparse file, so the test writes nothing.
TEST_F(SceneTest, SceneFileLargerThan64MiBIsRefusedUnread) {
    const fs::path path = write("huge.json", "{}");
    fs::resize_file(path, kMaxSceneFileBytes + 1);
    try {
        loadScene(path);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), path.string() +
                                             ": the scene file is 67108865 bytes, larger than the "
                                             "limit of 67108864 (64 MiB) for a scene file");
    }
}

// The light count is checked as soon as "lights" is seen, before any light is read: every light here
// is wrong (an unknown key), so reading even the first would give another message. Breaks if the lights
// are read (100,000 of them) before their count is checked. The time of parsing a large scene file is a
// benchmark's matter, not a test's.
TEST_F(SceneTest, HundredThousandLightsAreRefusedBeforeAnyIsRead) {
    std::string lights = R"({"not_a_light_key": 1})";
    for (int i = 1; i < 100000; ++i)
        lights += R"(, {"not_a_light_key": 1})";
    EXPECT_EQ(errorOf(R"({"model": "m.obj", "lights": [)" + lights + "]}"),
              (folder_ / "scene.json").string() +
                  R"(: "lights" has 100000 lights, at most 8 are supported (as in OpenGL 1.x))");
}

// Breaks if the object count is checked after reading every object (or not at all).
TEST_F(SceneTest, ObjectsBeyondTheLimitAreRefusedWhileReading) {
    std::string objects = R"({"model": "m.obj"})";
    for (std::size_t i = 1; i <= kMaxObjects; ++i)
        objects += R"(, {"model": "missing.obj"})";  // never opened: the count is refused first
    const std::string message = errorOf(R"({"objects": [)" + objects + "]}");
    EXPECT_NE(message.find(R"("objects" has 100001 objects, at most 100000 are supported)"),
              std::string::npos)
        << message;
}

TEST_F(SceneTest, DuplicateKeyIsStillFoundDeepInAnArray) {
    const std::string message = errorOf(
        R"({"objects": [{"model": "m.obj"}, {"model": "m.obj", "rotate": [0, 0, 0], "rotate": [1, 1, 1]}]})");
    EXPECT_NE(message.find(R"(key "objects[1].rotate" is given twice)"), std::string::npos) << message;
}

// A value quoted in a message is cut to 40 characters, and what a terminal would not show as
// written (control characters, bytes that are not UTF-8) is escaped.
TEST_F(SceneTest, QuotedValuesAreShortAndPrintable) {
    const std::string file = (folder_ / "scene.json").string() + ": ";
    const std::string longText(100000, 'a');
    const std::string forty(40, 'a');
    EXPECT_EQ(errorOf(R"({"model": "m.obj", "width": ")" + longText + R"("})"),
              file + R"("width" must be a whole number (got the string ")" + forty + "…\")");
    EXPECT_EQ(errorOf(R"({"model": "m.obj", ")" + longText + R"(": 1})"),
              file + R"(unknown key ")" + forty + "…\"");
    EXPECT_EQ(errorOf(R"({"model": "m.obj", "\u001b[2J": 1})"), file + R"(unknown key "\x1B[2J")");
    // Raw bytes that are not UTF-8, and a string that never ends, stop the JSON parser itself.
    EXPECT_EQ(errorOf("{\"model\": \"m.obj\", \"\xFF\": 1}"),
              file + R"(JSON syntax error at line 1, column 21: invalid string: ill-formed UTF-8 byte; )"
                     R"(last read: '"\xFF'; expected string literal)");
    EXPECT_EQ(errorOf(R"({"model": ")" + longText),
              file +
                  "JSON syntax error at line 1, column 100012: invalid string: missing closing quote; "
                  "last read: '\"" +
                  std::string(39, 'a') + "…'");
}

TEST_F(SceneTest, ModelThatIsAFolderIsAnError) {
    fs::create_directories(folder_ / "dir.obj");
    const std::string message = errorOf(R"({"model": "dir.obj"})");
    EXPECT_NE(message.find(R"("model": model file "dir.obj" is a folder)"), std::string::npos) << message;
}

}  // namespace
}  // namespace facet
