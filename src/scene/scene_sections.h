// The scene file's sections, each read and checked into its part of the Scene: background, camera,
// lights, objects (model, transform, material, lighting, blend), pipeline, lighting, transparency, fog
// and gamma. Internal to the scene reader (scene.cpp).
#pragma once

#include <string>
#include <string_view>

#include "scene/json_reader.h"
#include "scene/scene.h"

namespace facet::scene_file {

inline constexpr std::string_view kTopLevelKeys[] = {
    "shader", "width",   "height",     "background", "ambient",    "camera",
    "lights", "objects", "model",      "pipeline",   "lighting",   "transparency",
    "fog",    "gamma",   "shadow_map", "textures",   "environment"};

glm::vec4 readBackground(const SceneReader& reader, const Json& value);
CameraSpec readCamera(const SceneReader& reader, const Json& camera);
LightSpec readLight(const SceneReader& reader, const Json& light, const std::string& path);
// The model path as written, checked for existence relative to the scene file's folder.
fs::path readModel(const SceneReader& reader, const Json& value, const std::string& path,
                   const fs::path& folder);
// "shader": a file name, or {"source": file, "uniforms": {"name": value, …}}; the file resolved against
// `folder`, each uniform's value a number, true/false or an array of numbers (checked against the
// shader's declarations when the frame is prepared).
ShaderSpec readShader(const SceneReader& reader, const Json& value, const std::string& path,
                      const fs::path& folder);

ObjectSpec readObject(const SceneReader& reader, const Json& object, const std::string& path,
                      const fs::path& folder);
// A section whose every key is a knob (scene/knobs.h: "pipeline", "textures", "transparency",
// "shadow_map", "lighting"), each value checked by its knob's entry and set in `scene`; `example` says
// what the section must be when it is not an object.
void readKnobSection(const SceneReader& reader, const Json& object, const std::string& section,
                     std::string_view example, Scene& scene);
// The scene's "lighting": a preset name alone, or a section of knobs.
void readLighting(const SceneReader& reader, const Json& lighting, Scene& scene);
FogSpec readFog(const SceneReader& reader, const Json& fog);
// "environment": the image (resolved against `folder`, which must hold it), its encoding, intensity,
// rotation and whether it is the background.
EnvironmentSpec readEnvironment(const SceneReader& reader, const Json& environment, const fs::path& folder);
GammaOptions readGamma(const SceneReader& reader, const Json& gamma);

}  // namespace facet::scene_file
