#include "scene/scene_sections.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <optional>
#include <set>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>

#include "base/quote.h"
#include "scene/knobs.h"
#include "scene/limits.h"
#include "scene/mesh.h"

namespace facet::scene_file {

namespace {

constexpr std::string_view kCameraKeys[] = {"eye", "target", "up", "fovy", "near", "far"};
constexpr std::string_view kLightKeys[] = {
    "type",        "direction", "position", "color",  "intensity", "ambient", "diffuse", "specular",
    "attenuation", "cutoff",    "exponent", "inner",  "outer",     "space",   "shadows", "range",
    "window",      "width",     "height",   "radius", "up",        "samples"};
constexpr std::string_view kAreaOnlyKeys[] = {"width", "height", "radius", "up", "samples"};
constexpr std::string_view kSpotOnlyKeys[] = {"cutoff", "exponent", "inner", "outer"};
constexpr std::string_view kObjectKeys[] = {"model",    "translate", "rotate", "scale",
                                            "material", "lighting",  "blend",  "shader"};
constexpr std::string_view kShaderKeys[] = {"source", "uniforms"};
constexpr std::string_view kMaterialKeys[] = {"ambient", "diffuse", "specular",   "emission",  "shininess",
                                              "opacity", "preset",  "base_color", "metalness", "roughness",
                                              "f0",      "ior",     "anisotropy"};
constexpr std::string_view kObjectLightingKeys[] = {"model", "shading"};
constexpr std::string_view kLightSpaces[] = {"world", "camera"};
constexpr std::string_view kFogKeys[] = {"mode",    "color",       "start", "end",     "density",
                                         "falloff", "base_height", "up",    "distance"};
constexpr std::string_view kHeightFogKeys[] = {"falloff", "base_height", "up"};
constexpr std::string_view kEnvironmentKeys[] = {"image", "encoding", "intensity", "rotation", "background"};
constexpr std::string_view kGammaKeys[] = {"encode", "exponent", "decode_inputs"};

}  // namespace

glm::vec4 readBackground(const SceneReader& reader, const Json& value) {
    const std::string path = "background";
    if (!value.is_array() || (value.size() != 3 && value.size() != 4)) {
        reader.fail(inQuotes(path) + " must be [r, g, b] or [r, g, b, a] (got " + describe(value) + ")");
    }
    glm::vec4 background{0.0f, 0.0f, 0.0f, 1.0f};
    for (std::size_t i = 0; i < value.size(); ++i)
        background[i] = reader.brightness(value[i], elementPath(path, i));
    if (background.a > 1.0f) {
        reader.fail(inQuotes(elementPath(path, 3)) + " (alpha) must be from 0 to 1 (got " +
                    formatNumber(background.a) + ")");
    }
    return background;
}

CameraSpec readCamera(const SceneReader& reader, const Json& camera) {
    const std::string path = "camera";
    reader.requireObject(camera, path, "an object like {\"eye\": [0, 1, 5], \"fovy\": 40}");
    reader.checkKeys(camera, path, kCameraKeys);

    CameraSpec spec;
    if (const Json* v = reader.find(camera, "eye")) spec.eye = reader.vec3(*v, "camera.eye", "[0, 1, 5]");
    if (const Json* v = reader.find(camera, "target"))
        spec.target = reader.vec3(*v, "camera.target", "[0, 0, 0]");
    // Normalised here, in double: in float, the squared length of [0, 1e-30, 0] underflows to 0 and
    // that of [0, 1e20, 0] overflows, and the camera would be built from NaNs.
    if (const Json* v = reader.find(camera, "up"))
        spec.up = glm::vec3(glm::normalize(glm::dvec3(reader.nonZeroVector(*v, "camera.up"))));
    if (const Json* v = reader.find(camera, "fovy")) {
        spec.fovyDegrees = reader.number(*v, "camera.fovy");
        if (!fovyAllowed(spec.fovyDegrees)) {
            reader.fail("\"camera.fovy\" must be from " + formatNumber(kMinFovyDegrees) + " to " +
                        formatNumber(kMaxFovyDegrees) + " degrees (got " + formatNumber(spec.fovyDegrees) +
                        ")");
        }
    }
    if (const Json* v = reader.find(camera, "near")) {
        spec.near = reader.number(*v, "camera.near");
        if (!(*spec.near > 0.0f)) {
            reader.fail("\"camera.near\" must be greater than 0 (got " + formatNumber(*spec.near) + ")");
        }
    }
    if (const Json* v = reader.find(camera, "far"); v && v->is_string()) {
        if (v->get<std::string>() != "infinite")
            reader.fail("\"camera.far\" must be a number or \"infinite\" (got \"" + v->get<std::string>() +
                        "\")");
        spec.infiniteFar = true;
    } else if (v) {
        spec.far = reader.number(*v, "camera.far");
        const float lowest = spec.near.value_or(0.0f);
        if (!(*spec.far > lowest)) {
            reader.fail("\"camera.far\" must be greater than " +
                        std::string(spec.near ? "\"camera.near\" (" + formatNumber(lowest) + ")" : "0") +
                        " (got " + formatNumber(*spec.far) + ")");
        }
    }

    // The view direction is known only when both ends are given; otherwise the renderer frames the
    // bounding box and must pick a direction compatible with `up` itself. Doubles, so huge
    // coordinates cannot overflow the check.
    if (spec.eye && spec.target) {
        const glm::dvec3 view = glm::dvec3(*spec.target) - glm::dvec3(*spec.eye);
        if (glm::length(view) == 0.0) reader.fail("\"camera.eye\" and \"camera.target\" must differ");
        const glm::dvec3 side = glm::cross(glm::normalize(view), glm::normalize(glm::dvec3(spec.up)));
        if (glm::length(side) < 1e-6) {
            reader.fail(
                "\"camera.up\" is parallel to the view direction (from \"camera.eye\" to "
                "\"camera.target\"): give an \"up\" across it");
        }
    }
    return spec;
}

LightSpec readLight(const SceneReader& reader, const Json& light, const std::string& path) {
    reader.requireObject(light, path,
                         "an object like {\"type\": \"directional\", \"direction\": [0, -1, 0]}");
    reader.checkKeys(light, path, kLightKeys);
    const auto key = [&](std::string_view name) { return inQuotes(childPath(path, name)); };

    LightSpec spec;
    if (const Json* v = reader.find(light, "type")) {
        spec.type = reader.enumChoice<LightKind>(*v, childPath(path, "type"));
    }
    // A key that the type ignores is almost always a forgotten "type": say so rather than ignore it.
    if (spec.type == LightKind::Directional && light.contains("position")) {
        reader.fail(key("position") + " is only for point and spot lights (add \"type\": \"point\")");
    }
    if (spec.type == LightKind::Directional && light.contains("attenuation")) {
        reader.fail(key("attenuation") +
                    " is only for point and spot lights: a directional light is infinitely far and does "
                    "not fade (add \"type\": \"point\")");
    }
    if (spec.type == LightKind::Point && light.contains("direction")) {
        reader.fail(key("direction") +
                    " is only for directional and spot lights: a point light shines every way (add "
                    "\"type\": \"spot\" for a cone)");
    }
    const bool area = isAreaLight(spec.type);
    if (!area) {
        for (std::string_view name : kAreaOnlyKeys) {
            if (light.contains(name))
                reader.fail(key(name) + " is only for area lights (add \"type\": \"rect\" or \"disk\")");
        }
    }
    for (std::string_view name : {"width", "height", "up"}) {
        if (spec.type == LightKind::Disk && light.contains(name))
            reader.fail(key(name) + " is only for \"rect\" lights: a disk has a \"radius\"");
    }
    if (spec.type == LightKind::Rect && light.contains("radius"))
        reader.fail(key("radius") + " is only for \"disk\" lights: a rectangle has \"width\" and \"height\"");
    if (spec.type == LightKind::Directional && light.contains("range")) {
        reader.fail(key("range") +
                    " is only for point, spot and area lights: a directional light is infinitely far (add "
                    "\"type\": \"point\")");
    }
    if (light.contains("window") && !light.contains("range"))
        reader.fail(key("window") + " needs " + key("range") + ": the window brings the light to 0 there");
    if (spec.type != LightKind::Spot) {
        for (std::string_view name : kSpotOnlyKeys) {
            if (light.contains(name))
                reader.fail(key(name) + " is only for spot lights (add \"type\": \"spot\")");
        }
    }

    if (const Json* v = reader.find(light, "direction")) {
        spec.direction = reader.nonZeroVector(*v, childPath(path, "direction"));
    } else if (spec.type == LightKind::Spot || area) {
        spec.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    }
    if (const Json* v = reader.find(light, "position"))
        spec.position = reader.vec3(*v, childPath(path, "position"));
    if (const Json* v = reader.find(light, "color")) spec.color = reader.color(*v, childPath(path, "color"));
    if (const Json* v = reader.find(light, "intensity"))
        spec.intensity = reader.brightness(*v, childPath(path, "intensity"));
    if (const Json* v = reader.find(light, "ambient"))
        spec.ambient = reader.color(*v, childPath(path, "ambient"));
    if (const Json* v = reader.find(light, "diffuse"))
        spec.diffuse = reader.color(*v, childPath(path, "diffuse"));
    if (const Json* v = reader.find(light, "specular"))
        spec.specular = reader.color(*v, childPath(path, "specular"));
    if (const Json* v = reader.find(light, "attenuation")) {
        spec.attenuationGiven = true;
        spec.attenuation = reader.nonNegativeVector(*v, childPath(path, "attenuation"), "[1, 0.1, 0.01]");
        if (spec.attenuation == glm::vec3(0.0f)) {
            reader.fail(key("attenuation") +
                        " must not be all zero: 1/(c0 + c1*d + c2*d^2) would divide by zero (got [0, 0, 0])");
        }
    }

    // The windowed falloff's range and function.
    if (const Json* v = reader.find(light, "range")) {
        const float range = reader.number(*v, childPath(path, "range"));
        if (!(range > 0.0f)) reader.fail(key("range") + " must be greater than 0 (got " + describe(*v) + ")");
        spec.range = range;
    }
    if (const Json* v = reader.find(light, "window"))
        spec.window = reader.enumChoice<RangeWindow>(*v, childPath(path, "window"));

    // An area light's size, orientation and shadow samples.
    const auto positiveSize = [&](std::string_view name, float& field) {
        if (const Json* v = reader.find(light, name)) {
            field = reader.number(*v, childPath(path, name));
            if (!(field > 0.0f))
                reader.fail(key(name) + " must be greater than 0 (got " + describe(*v) + ")");
        }
    };
    positiveSize("width", spec.width);
    positiveSize("height", spec.height);
    positiveSize("radius", spec.radius);
    if (const Json* v = reader.find(light, "up")) {
        spec.up = reader.nonZeroVector(*v, childPath(path, "up"));
        const glm::dvec3 n = glm::normalize(glm::dvec3(spec.direction));
        if (glm::length(glm::cross(n, glm::normalize(glm::dvec3(*spec.up)))) < 1e-6)
            reader.fail(key("up") + " is parallel to " + key("direction") +
                        ": give an \"up\" across it, in the rectangle's plane");
    }
    if (const Json* v = reader.find(light, "samples")) {
        spec.samples = reader.wholeNumber(*v, childPath(path, "samples"), 1, kMaxAreaSamples);
        const int m = static_cast<int>(std::lround(std::sqrt(double(spec.samples))));
        if (m * m != spec.samples)
            reader.fail(key("samples") +
                        " must be a square number (4, 9, 16, 64, ...) for an m×m grid (got " + describe(*v) +
                        ")");
    }

    // The spot's profile: "cutoff" and "exponent" (OpenGL's) or "inner" and "outer" (smooth), not a mix.
    if (spec.type == LightKind::Spot) {
        const Json* inner = reader.find(light, "inner");
        const Json* outer = reader.find(light, "outer");
        if ((inner == nullptr) != (outer == nullptr)) {
            reader.fail(key(inner ? "inner" : "outer") + " needs " + key(inner ? "outer" : "inner") +
                        " too: give both for the smooth spot profile, or neither");
        }
        for (std::string_view name : {"cutoff", "exponent"}) {
            if (inner && light.contains(name)) {
                reader.fail(key(name) +
                            " cannot be given with \"inner\" and \"outer\": \"cutoff\" and \"exponent\" set "
                            "the OpenGL spot profile, \"inner\" and \"outer\" the smooth one; choose one");
            }
        }
        if (const Json* v = reader.find(light, "cutoff"))
            spec.spotCutoffDegrees =
                reader.numberFromTo(*v, childPath(path, "cutoff"), 0.0f, 90.0f, " degrees");
        if (const Json* v = reader.find(light, "exponent"))
            spec.spotExponent = reader.numberFromTo(*v, childPath(path, "exponent"), 0.0f, 128.0f);
        if (inner) {
            spec.spotInnerDegrees =
                reader.numberFromTo(*inner, childPath(path, "inner"), 0.0f, 90.0f, " degrees");
            spec.spotOuterDegrees =
                reader.numberFromTo(*outer, childPath(path, "outer"), 0.0f, 90.0f, " degrees");
            if (!(*spec.spotInnerDegrees < *spec.spotOuterDegrees)) {
                reader.fail(key("inner") + " (" + describe(*inner) + ") must be less than " + key("outer") +
                            " (" + describe(*outer) + ")");
            }
        }
    }
    if (const Json* v = reader.find(light, "space")) {
        spec.cameraRelative = reader.choice(*v, childPath(path, "space"), kLightSpaces) == 1;
    }
    // "shadows": a method's name, or true (a ray, the exact test) and false (none). The message of a
    // wrong value lists the booleans too, which a plain choice of names would not.
    if (const Json* v = reader.find(light, "shadows")) {
        std::optional<ShadowMethod> method;
        if (v->is_boolean())
            method = v->get<bool>() ? ShadowMethod::Ray : ShadowMethod::None;
        else if (v->is_string())
            method = parseName<ShadowMethod>(v->get<std::string>());
        if (!method) {
            const std::vector<std::string> names = namesOf<ShadowMethod>();
            std::string message = inQuotes(childPath(path, "shadows"));
            message += " must be";
            for (const std::string& name : names) {
                message += ' ';
                message += inQuotes(name);
                message += ',';
            }
            message += " true (a ray) or false (none) (got ";
            message += describe(*v);
            message += ')';
            if (v->is_string())
                message += suggestion(v->get<std::string>(),
                                      std::vector<std::string_view>(names.begin(), names.end()));
            reader.fail(message);
        }
        spec.shadows = *method;
        if (area && spec.shadows == ShadowMethod::Map)
            reader.fail(key("shadows") +
                        " cannot be \"map\" for an area light: its soft shadows are ray-cast (use \"ray\")");
    }
    return spec;
}

namespace {

// f0: one number for all three channels or [r, g, b], each 0..1.
glm::vec3 readF0(const SceneReader& reader, const Json& value, const std::string& path) {
    if (value.is_number()) return glm::vec3(reader.numberFromTo(value, path, 0.0f, 1.0f));
    if (!value.is_array() || value.size() != 3) {
        reader.fail(inQuotes(path) +
                    " must be a number or an array of 3 numbers like [0.04, 0.04, 0.04] (got " +
                    describe(value) + ")");
    }
    glm::vec3 f0;
    for (int i = 0; i < 3; ++i)
        f0[i] = reader.numberFromTo(value[i], elementPath(path, i), 0.0f, 1.0f);
    return f0;
}

// The preset's name as kMaterialPresets spells it ("Gold" and "aluminum" are accepted too).
std::string readMaterialPreset(const SceneReader& reader, const Json& value, const std::string& path) {
    const std::string name = reader.string(value, path);
    if (const std::optional<MaterialPreset> preset = findMaterialPreset(name))
        return std::string(preset->name);

    std::array<std::string_view, std::tuple_size_v<decltype(kMaterialPresets)>> names;
    std::string list;
    for (std::size_t i = 0; i < names.size(); ++i) {
        names[i] = kMaterialPresets[i].name;
        list += (list.empty() ? "" : ", ") + inQuotes(names[i]);
    }
    std::string lower = name;
    for (char& c : lower)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    reader.fail(inQuotes(path) + " must be one of the material presets " + list + " (got " + inQuotes(name) +
                ")" + suggestion(lower, names));
}

MaterialOverride readMaterial(const SceneReader& reader, const Json& material, const std::string& path) {
    reader.requireObject(material, path, "an object like {\"diffuse\": [0.8, 0.2, 0.2]}");
    reader.checkKeys(material, path, kMaterialKeys);

    MaterialOverride spec;
    if (const Json* v = reader.find(material, "ambient"))
        spec.ambient = reader.color(*v, childPath(path, "ambient"));
    if (const Json* v = reader.find(material, "diffuse"))
        spec.diffuse = reader.color(*v, childPath(path, "diffuse"));
    if (const Json* v = reader.find(material, "specular"))
        spec.specular = reader.color(*v, childPath(path, "specular"));
    if (const Json* v = reader.find(material, "emission"))
        spec.emission = reader.color(*v, childPath(path, "emission"));
    if (const Json* v = reader.find(material, "shininess"))
        spec.shininess = reader.nonNegative(*v, childPath(path, "shininess"));
    if (const Json* v = reader.find(material, "opacity"))
        spec.opacity = reader.numberFromTo(*v, childPath(path, "opacity"), 0.0f, 1.0f);

    // Physically based keys.
    if (const Json* v = reader.find(material, "preset"))
        spec.preset = readMaterialPreset(reader, *v, childPath(path, "preset"));
    if (const Json* v = reader.find(material, "base_color"))
        spec.baseColor = reader.color(*v, childPath(path, "base_color"));
    if (const Json* v = reader.find(material, "metalness"))
        spec.metalness = reader.numberFromTo(*v, childPath(path, "metalness"), 0.0f, 1.0f);
    if (const Json* v = reader.find(material, "roughness"))
        spec.roughness = reader.numberFromTo(*v, childPath(path, "roughness"), 0.0f, 1.0f);
    if (const Json* v = reader.find(material, "f0")) spec.f0 = readF0(reader, *v, childPath(path, "f0"));
    if (const Json* v = reader.find(material, "ior"))
        spec.ior = reader.numberFromTo(*v, childPath(path, "ior"), 1.0f, 10.0f);
    if (const Json* v = reader.find(material, "anisotropy"))
        spec.anisotropy = reader.numberFromTo(*v, childPath(path, "anisotropy"), -1.0f, 1.0f);
    return spec;
}

ReflectionModel readReflectionModel(const SceneReader& reader, const Json& value, const std::string& path) {
    return reader.enumChoice<ReflectionModel>(value, path);
}

ShadingFrequency readShading(const SceneReader& reader, const Json& value, const std::string& path) {
    return reader.enumChoice<ShadingFrequency>(value, path);
}

// An object's "lighting": only the reflection model and the shading frequency can differ per object.
void readObjectLighting(const SceneReader& reader, const Json& lighting, const std::string& path,
                        ObjectSpec& spec) {
    reader.requireObject(lighting, path,
                         "an object like {\"model\": \"cook-torrance\", \"shading\": \"flat\"}");
    for (const auto& [key, value] : lighting.items()) {
        const bool perObject = std::find(std::begin(kObjectLightingKeys), std::end(kObjectLightingKeys),
                                         key) != std::end(kObjectLightingKeys);
        const std::vector<std::string_view> lightingKeys = knobKeysOf("lighting");
        const bool sceneWide = std::find(lightingKeys.begin(), lightingKeys.end(), key) != lightingKeys.end();
        if (!perObject && sceneWide) {
            reader.fail(inQuotes(childPath(path, key)) +
                        " cannot be set per object (only \"model\" and \"shading\" can): set it in the "
                        "top-level \"lighting\"");
        }
    }
    reader.checkKeys(lighting, path, kObjectLightingKeys);
    if (const Json* v = reader.find(lighting, "model"))
        spec.reflection = readReflectionModel(reader, *v, childPath(path, "model"));
    if (const Json* v = reader.find(lighting, "shading"))
        spec.shading = readShading(reader, *v, childPath(path, "shading"));
}

}  // namespace

// The model path as written, checked for existence relative to the scene file's folder.
fs::path readModel(const SceneReader& reader, const Json& value, const std::string& path,
                   const fs::path& folder) {
    const std::string written = reader.string(value, path);
    if (written.empty()) reader.fail(inQuotes(path) + " must name an OBJ file (got an empty string)");
    const fs::path model = folder / fs::path(written);  // an absolute path replaces the folder
    reader.checkModelFile(model, written, path);
    return model;
}

ShaderSpec readShader(const SceneReader& reader, const Json& value, const std::string& path,
                      const fs::path& folder) {
    const Json* source = &value;
    const Json* uniforms = nullptr;
    std::string sourcePath = path;
    if (value.is_object()) {
        reader.checkKeys(value, path, kShaderKeys);
        source = reader.find(value, "source");
        if (!source) reader.fail(inQuotes(childPath(path, "source")) + " is missing: name the shader's file");
        sourcePath = childPath(path, "source");
        uniforms = reader.find(value, "uniforms");
    } else if (!value.is_string()) {
        reader.fail(inQuotes(path) +
                    " must be a file name or an object like {\"source\": \"toon.cpp\", "
                    "\"uniforms\": {\"bands\": 3}} (got " +
                    describe(value) + ")");
    }
    const std::string written = reader.string(*source, sourcePath);
    if (written.empty()) reader.fail(inQuotes(sourcePath) + " must name a shader file (got an empty string)");
    ShaderSpec spec{folder / fs::path(written), {}};
    if (!uniforms) return spec;
    const std::string uniformsPath = childPath(path, "uniforms");
    reader.requireObject(*uniforms, uniformsPath, "an object like {\"bands\": 3, \"ink\": [0, 0, 0]}");
    for (const auto& [name, given] : uniforms->items()) {
        const std::string at = childPath(uniformsPath, name);
        UniformValue uniform{name, {}, given.is_boolean(), reader.file().string() + ": " + inQuotes(at)};
        if (given.is_boolean()) {
            uniform.numbers.push_back(given.get<bool>() ? 1.0 : 0.0);
        } else if (given.is_number()) {
            uniform.numbers.push_back(reader.number(given, at));
        } else if (given.is_array() && !given.empty() && given.size() <= 4) {
            for (std::size_t i = 0; i < given.size(); ++i)
                uniform.numbers.push_back(reader.number(given[i], elementPath(at, i)));
        } else {
            reader.fail(inQuotes(at) +
                        " must be a number, true or false, or an array of 2 to 4 numbers (got " +
                        describe(given) + ")");
        }
        spec.uniforms.push_back(std::move(uniform));
    }
    return spec;
}

ObjectSpec readObject(const SceneReader& reader, const Json& object, const std::string& path,
                      const fs::path& folder) {
    reader.requireObject(object, path, "an object like {\"model\": \"bunny.obj\"}");
    reader.checkKeys(object, path, kObjectKeys);

    ObjectSpec spec;
    const Json* model = reader.find(object, "model");
    if (model == nullptr)
        reader.fail(inQuotes(childPath(path, "model")) + " is missing: every object needs a model file");
    spec.model = readModel(reader, *model, childPath(path, "model"), folder);

    glm::vec3 translate{0.0f}, rotateDegrees{0.0f}, scale{1.0f};
    if (const Json* v = reader.find(object, "translate"))
        translate = reader.vec3(*v, childPath(path, "translate"));
    if (const Json* v = reader.find(object, "rotate"))
        rotateDegrees = reader.vec3(*v, childPath(path, "rotate"), "[0, 90, 0]");
    if (const Json* v = reader.find(object, "scale")) {
        const std::string scalePath = childPath(path, "scale");
        scale = v->is_number() ? glm::vec3(reader.number(*v, scalePath))
                               : reader.vec3(*v, scalePath, "[1, 2, 1]");
        // A zero factor flattens the model and leaves its normals undefined (no inverse transpose).
        for (int i = 0; i < 3; ++i) {
            if (scale[i] == 0.0f) {
                reader.fail(inQuotes(scalePath) + " must not be zero" +
                            (v->is_number() ? std::string() : " in any axis"));
            }
        }
    }
    if (const Json* v = reader.find(object, "material"))
        spec.material = readMaterial(reader, *v, childPath(path, "material"));
    if (const Json* v = reader.find(object, "lighting"))
        readObjectLighting(reader, *v, childPath(path, "lighting"), spec);
    if (const Json* v = reader.find(object, "shader"))
        spec.shader = readShader(reader, *v, childPath(path, "shader"), folder);
    if (const Json* v = reader.find(object, "blend")) {
        spec.blend = reader.enumChoice<BlendMode>(*v, childPath(path, "blend"),
                                                  {BlendMode::Replace, BlendMode::OverGL});
    }

    // worldFromObject = T · Rz · Ry · Rx · S: scale first, then rotate about X, Y, Z (fixed axes),
    // then translate. glm::rotate/scale multiply on the right, so the calls read left to right.
    glm::mat4 m = glm::translate(glm::mat4(1.0f), translate);
    m = glm::rotate(m, glm::radians(rotateDegrees.z), glm::vec3(0.0f, 0.0f, 1.0f));
    m = glm::rotate(m, glm::radians(rotateDegrees.y), glm::vec3(0.0f, 1.0f, 0.0f));
    m = glm::rotate(m, glm::radians(rotateDegrees.x), glm::vec3(1.0f, 0.0f, 0.0f));
    spec.worldFromObject = glm::scale(m, scale);
    return spec;
}

namespace {

// A number knob's value in a scene file, checked against its entry's range.
float knobNumber(const SceneReader& reader, const SceneKnob& knob, const Json& value) {
    const std::string path = knob.scenePath();
    const float number = reader.number(value, path);
    if (!knob.allows(number))
        reader.fail(inQuotes(path) + " must be " + knob.allowed() + " (got " + describe(value) + ")");
    return number;
}

// One knob's value in a scene file, checked by its entry: a name of its table, or a number in its range.
std::string knobValue(const SceneReader& reader, const SceneKnob& knob, const Json& value) {
    const std::string path = knob.scenePath();
    switch (knob.kind) {
        case KnobKind::Names: {
            const std::vector<std::string_view> names(knob.names.begin(), knob.names.end());
            return knob.names[reader.choice(value, path, names)];
        }
        case KnobKind::WholeNumber: {
            if (!value.is_number())
                reader.fail(inQuotes(path) + " must be a whole number (got " + describe(value) + ")");
            const double number = value.get<double>();
            if (!knob.allows(number))
                reader.fail(inQuotes(path) + " must be " + (knob.only.empty() ? "a whole number " : "") +
                            knob.allowed() + " (got " + describe(value) + ")");
            return std::to_string(static_cast<int>(number));
        }
        case KnobKind::Number:
            return knobNumberText(knobNumber(reader, knob, value));
    }
    return {};
}

}  // namespace

void readKnobSection(const SceneReader& reader, const Json& object, const std::string& section,
                     std::string_view example, Scene& scene) {
    reader.requireObject(object, section, example);
    reader.checkKeys(object, section, knobKeysOf(section));
    for (const SceneKnob& knob : sceneKnobs())
        if (knob.section == section)
            if (const Json* v = reader.find(object, knob.key)) knob.set(scene, knobValue(reader, knob, *v));
}

void readLighting(const SceneReader& reader, const Json& lighting, Scene& scene) {
    if (lighting.is_string()) {
        scene.lighting.preset = reader.enumChoice<LightingPreset>(lighting, "lighting");
        return;
    }
    readKnobSection(
        reader, lighting, "lighting",
        quotedList(namesOf<LightingPreset>(), ", ") + " or an object like {\"model\": \"cook-torrance\"}",
        scene);
}

FogSpec readFog(const SceneReader& reader, const Json& fog) {
    const std::string path = "fog";
    reader.requireObject(fog, path, "an object like {\"mode\": \"exp2\", \"density\": 0.2}");
    reader.checkKeys(fog, path, kFogKeys);

    FogSpec spec;
    const Json* mode = reader.find(fog, "mode");
    if (mode == nullptr) {
        reader.fail("\"fog.mode\" is missing: give " + quotedList(namesOf<FogMode>({FogMode::None}), " or ") +
                    " (or remove \"fog\" for no fog)");
    }
    spec.mode = reader.enumChoice<FogMode>(*mode, "fog.mode", {FogMode::None});  // no "fog" is none
    const std::string modeName = mode->get<std::string>();

    // A key the mode ignores usually means the wrong mode: say so rather than ignore it.
    const bool linear = spec.mode == FogMode::Linear;
    for (std::string_view name : {"start", "end"}) {
        if (!linear && fog.contains(name)) {
            reader.fail(inQuotes(childPath(path, name)) + ": start and end are for linear fog (the mode is " +
                        inQuotes(modeName) + ", which uses \"density\")");
        }
    }
    if (linear && fog.contains("density")) {
        reader.fail("\"fog.density\": density is for " + std::string(nameOf(FogMode::Exponential)) + " and " +
                    std::string(nameOf(FogMode::ExponentialSquared)) + " fog (the mode is " +
                    inQuotes(nameOf(FogMode::Linear)) + ", which uses \"start\" and \"end\")");
    }

    if (const Json* v = reader.find(fog, "color")) spec.color = reader.color(*v, "fog.color");
    // The numbers in the ranges of their knobs (knobs.cpp: --fog-start, --fog-end, --fog-density).
    const auto number = [&](const char* knob, const Json& value) {
        return knobNumber(reader, *sceneKnobNamed(knob), value);
    };
    if (const Json* v = reader.find(fog, "start")) spec.start = number("fog-start", *v);
    if (const Json* v = reader.find(fog, "end")) spec.end = number("fog-end", *v);
    if (spec.start && spec.end && !(*spec.end > *spec.start)) {
        reader.fail("\"fog.end\" (" + formatNumber(*spec.end) + ") must be greater than \"fog.start\" (" +
                    formatNumber(*spec.start) + ")");
    }
    for (std::string_view name : kHeightFogKeys) {
        if (spec.mode != FogMode::Height && fog.contains(name)) {
            reader.fail(inQuotes(childPath(path, name)) + " is for height fog (the mode is " +
                        inQuotes(modeName) + ")");
        }
    }
    if (spec.mode == FogMode::Height && fog.contains("distance"))
        reader.fail(
            "\"fog.distance\": height fog integrates along the ray from the eye, it takes no distance");
    if (const Json* v = reader.find(fog, "density")) spec.density = number("fog-density", *v);
    if (const Json* v = reader.find(fog, "falloff")) spec.falloff = reader.nonNegative(*v, "fog.falloff");
    if (const Json* v = reader.find(fog, "base_height"))
        spec.baseHeight = reader.number(*v, "fog.base_height");
    if (const Json* v = reader.find(fog, "up")) spec.up = glm::normalize(reader.nonZeroVector(*v, "fog.up"));
    if (const Json* v = reader.find(fog, "distance"))
        spec.distance = reader.enumChoice<FogDistance>(*v, "fog.distance");
    return spec;
}

EnvironmentSpec readEnvironment(const SceneReader& reader, const Json& environment, const fs::path& folder) {
    const std::string path = "environment";
    reader.requireObject(environment, path, "an object like {\"image\": \"sky.png\"}");
    reader.checkKeys(environment, path, kEnvironmentKeys);
    EnvironmentSpec spec;
    const Json* image = reader.find(environment, "image");
    if (image == nullptr) reader.fail("\"environment.image\" is missing: name an equirectangular image file");
    const std::string written = reader.string(*image, "environment.image");
    if (written.empty()) reader.fail("\"environment.image\" must name an image file (got an empty string)");
    spec.image = folder / fs::path(written);
    std::error_code error;
    if (!fs::is_regular_file(spec.image, error))
        reader.fail("\"environment.image\": " + spec.image.string() + ": file not found");
    if (const Json* v = reader.find(environment, "encoding"))
        spec.encoding = reader.enumChoice<EnvironmentEncoding>(*v, "environment.encoding");
    if (const Json* v = reader.find(environment, "intensity"))
        spec.intensity = reader.brightness(*v, "environment.intensity");
    if (const Json* v = reader.find(environment, "rotation"))
        spec.rotationDegrees = reader.numberFromTo(*v, "environment.rotation", -360.0f, 360.0f, " degrees");
    if (const Json* v = reader.find(environment, "background"))
        spec.background = reader.boolean(*v, "environment.background");
    return spec;
}

GammaOptions readGamma(const SceneReader& reader, const Json& gamma) {
    const std::string path = "gamma";
    reader.requireObject(gamma, path, "an object like {\"encode\": \"power\", \"exponent\": 2.2}");
    reader.checkKeys(gamma, path, kGammaKeys);

    GammaOptions options;
    if (const Json* v = reader.find(gamma, "encode"))
        options.encode = reader.enumChoice<TransferCurve>(*v, "gamma.encode");
    if (const Json* v = reader.find(gamma, "exponent")) {
        if (options.encode != TransferCurve::Power) {
            const std::string curve(nameOf(options.encode));
            reader.fail(
                "\"gamma.exponent\" is only for \"encode\": " + inQuotes(nameOf(TransferCurve::Power)) +
                " (the curve is " + inQuotes(curve) + (gamma.contains("encode") ? ")" : ", the default)"));
        }
        options.exponent = reader.number(*v, "gamma.exponent");
        if (!(options.exponent > 0.0f)) {
            reader.fail("\"gamma.exponent\" must be greater than 0 (got " + describe(*v) + ")");
        }
    }
    if (const Json* v = reader.find(gamma, "decode_inputs"))
        options.decodeInputs = reader.boolean(*v, "gamma.decode_inputs");
    return options;
}

}  // namespace facet::scene_file
