// A scene: what to render (objects, camera, lights) and how (image size, pipeline options).
// Every colour in a Scene is as the user wrote it: sRGB-encoded (renderer.h decodes it).
// Loaded from a JSON scene file (docs/scene-format.md) or built with defaults around one OBJ model.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace facet {

struct CameraSpec {
    std::optional<glm::vec3> eye;     // world space; absent: framed from the scene's bounding box
    std::optional<glm::vec3> target;  // absent: the centre of the bounding box
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovyDegrees = 40.0f;  // vertical field of view
    std::optional<float> near;  // absent: derived from the bounding box
    std::optional<float> far;
};

enum class LightType { Directional, Point };

struct LightSpec {
    LightType type = LightType::Directional;
    glm::vec3 direction{-0.4f, -0.6f, -0.7f};  // directional: the direction light travels, world space
    glm::vec3 position{0.0f};                  // point: world space
    glm::vec3 color{1.0f};                     // sRGB-encoded, decoded to linear by the renderer
    float intensity = 1.0f;                    // multiplies color
    bool cameraRelative = false;               // direction/position given in the camera's view space
};

// Optional per-object material override; each field overrides the MTL value when present.
struct MaterialOverride {
    std::optional<glm::vec3> ambient, diffuse, specular, emission;
    std::optional<float> shininess, opacity;
};

struct ObjectSpec {
    std::filesystem::path model;      // resolved against the scene file's folder
    glm::mat4 worldFromObject{1.0f};  // translate · rotate(Z·Y·X degrees) · scale
    MaterialOverride material;
};

enum class CullChoice { Back, Front, None };
enum class InterpolationChoice { Perspective, Affine };

struct PipelineOptions {
    CullChoice cull = CullChoice::Back;
    InterpolationChoice interpolation = InterpolationChoice::Perspective;
    int subpixelBits = 8;  // 0..8
};

struct Scene {
    std::filesystem::path source;  // the scene or model file this came from (for messages)
    int width = 1280;
    int height = 960;
    glm::vec4 background{0.05f, 0.05f, 0.07f, 1.0f};  // sRGB-encoded RGB, alpha as is
    glm::vec3 ambientLight{0.15f};                    // global ambient, sRGB-encoded
    CameraSpec camera;
    std::vector<LightSpec> lights;    // empty in a file: one default light is used
    std::vector<ObjectSpec> objects;  // at least one
    PipelineOptions pipeline;
};

// Reads a JSON scene file. Throws InputError with a one-line message naming the file and the
// offending key (unknown keys are errors, e.g. "scene.json: unknown key \"camera.fvoy\"").
Scene loadScene(const std::filesystem::path& path);

// The scene "facet render model.obj" uses: that one model and every default.
Scene sceneForModel(const std::filesystem::path& objPath);

// Size limits shared by the scene loader and the command line (absurd sizes are rejected).
inline constexpr int kMaxImageSide = 16384;

}  // namespace facet
