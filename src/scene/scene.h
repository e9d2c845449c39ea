// A scene: what to render (objects, camera, lights) and how (image size, pipeline options).
// Every colour in a Scene is as the user wrote it: sRGB-encoded (renderer.h decodes it).
// Loaded from a JSON scene file (docs/scene-format.md) or built with defaults around one OBJ model.
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "pipeline/state.h"
#include "pipeline/texture.h"
#include "scene/limits.h"
#include "scene/mesh.h"
#include "shading/fog.h"
#include "shading/gamma.h"
#include "shading/lighting.h"
#include "shading/shadow.h"

namespace facet {

struct CameraSpec {
    std::optional<glm::vec3> eye;     // world space; absent: framed from the scene's bounding box
    std::optional<glm::vec3> target;  // absent: the centre of the bounding box
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovyDegrees = 40.0f;  // vertical field of view
    std::optional<float> near;  // absent: derived from the bounding box
    std::optional<float> far;
    // "far": "infinite": the projection's limit as far → ∞ (nothing is beyond the far plane); `far` is
    // then absent.
    bool infiniteFar = false;
};

struct LightSpec {
    LightKind type = LightKind::Directional;
    // Directional: the direction light travels, world space. Spot: the cone's axis (pointing away from
    // the light). Absent from the file: [-0.4, -0.6, -0.7] for a directional light, [0, -1, 0] for a spot.
    glm::vec3 direction{-0.4f, -0.6f, -0.7f};
    glm::vec3 position{0.0f};  // point and spot: world space
    glm::vec3 color{1.0f};     // sRGB-encoded, decoded to linear by the renderer
    float intensity = 1.0f;    // multiplies every colour of the light (color, ambient, diffuse, specular)
    // The standard equation's per-term light colours (sRGB-encoded): l_a (absent: black),
    // l_d and l_s (absent: color). The physically based model uses l_d as c_light.
    std::optional<glm::vec3> ambient, diffuse, specular;
    glm::vec3 attenuation{1.0f, 0.0f, 0.0f};  // c0, c1, c2 of 1/(c0 + c1·d + c2·d²); point and spot
    // "attenuation" was given: Cook-Torrance then uses it in place of its physical default 1/d².
    bool attenuationGiven = false;
    // "range": r_max, where the windowed falloff reaches 0 (world units); absent: no window.
    std::optional<float> range;
    RangeWindow window = RangeWindow::Ue4;  // "window": the windowing function
    // Area lights ("rect", "disk"): `position` is the centre, `direction` the way the emitting side faces.
    float width = 1.0f, height = 1.0f;  // rect: the sides, world units (height along `up`)
    float radius = 0.5f;                // disk
    std::optional<glm::vec3> up;        // rect: where its height side points (absent: see areaUp)
    int samples = kDefaultAreaSamples;  // shadow rays per point, a square
    float spotCutoffDegrees = 30.0f;    // spot, OpenGL profile: half-angle of the cone, 0..90
    float spotExponent = 0.0f;          // spot, OpenGL profile: cos^exponent falloff, 0..128
    // Spot, smooth profile (used when both are given): full intensity inside `inner`, none outside
    // `outer`, smoothstep between. 0 ≤ inner < outer ≤ 90.
    std::optional<float> spotInnerDegrees, spotOuterDegrees;
    bool cameraRelative = false;                // direction/position given in the camera's view space
    ShadowMethod shadows = ShadowMethod::None;  // "shadows": none, ray or map (true means ray)
};

// A rectangle light's default "up" (where its height side points): the world's +y, or −z for a light
// facing straight up or down (+y would be parallel to its normal).
inline glm::vec3 areaUp(const glm::vec3& direction) {
    const glm::vec3 n = glm::normalize(direction);
    return std::abs(n.y) > 0.999f ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
}

// Optional per-object material override; each field overrides the MTL value when present.
struct MaterialOverride {
    std::optional<glm::vec3> ambient, diffuse, specular, emission;  // sRGB-encoded
    std::optional<float> shininess, opacity;
    // Physically based parameters (the Cook-Torrance model). A preset names an entry of
    // kMaterialPresets (lighting.h): a metal sets base_color to its F0 colour and metalness to 1, a
    // dielectric sets f0; keys given next to the preset win over it.
    std::optional<std::string> preset;
    std::optional<glm::vec3> baseColor;  // sRGB-encoded; absent: the diffuse colour
    std::optional<float> metalness;      // 0..1
    std::optional<float> roughness;      // 0..1, perceptual (α = roughness²)
    std::optional<glm::vec3>
        f0;  // linear reflectance at normal incidence, 0..1 (a number in the file sets all three)
    std::optional<float> ior;         // index of refraction η, 1..10: F0 = ((1 − η)/(1 + η))²
    std::optional<float> anisotropy;  // −1..1: α_x = α(1 + a), α_y = α(1 − a)

    // Whether any physically based key (or a preset) is given.
    bool physicallyBased() const {
        return preset || baseColor || metalness || roughness || f0 || ior || anisotropy;
    }
};

// A value for a uniform of a shader of one's own ("shader": {"uniforms": {...}} in a scene file,
// --uniform NAME=VALUE): its numbers as given (a bool's as 0 or 1), checked against the shader's
// declaration of it when the frame is prepared.
struct UniformValue {
    std::string name;
    std::vector<double> numbers;
    bool isBool = false;  // given as true or false
    std::string origin;   // where it was given, for messages: "scene.json: \"shader.uniforms.bands\""
};

// "shader": a shader of one's own (docs/shaders.md), for the whole scene or for one object: a C++
// file compiled into a module on first use and cached, or a module built with facet_add_shader (.so).
struct ShaderSpec {
    std::filesystem::path source;  // resolved against the scene file's folder
    std::vector<UniformValue> uniforms;
};

struct ObjectSpec {
    std::filesystem::path model;      // resolved against the scene file's folder
    glm::mat4 worldFromObject{1.0f};  // translate · rotate(Z·Y·X degrees) · scale
    MaterialOverride material;
    // Per-object "lighting": {"model", "shading"}; absent: the scene's "lighting" settings (an object
    // whose material is physically based, see MaterialOverride::physicallyBased, defaults to Cook-Torrance).
    std::optional<ReflectionModel> reflection;
    std::optional<ShadingFrequency> shading;
    // How the object's colour combines with what is behind it ("blend"; never Replace). Absent: over.
    // An object whose opacity (material d / 1 − Tr, the override, or a texture's alpha) is below 1, or
    // whose blend is not over, is transparent: drawn after the opaque ones, without depth writes,
    // sorted. The shaders write what each blend needs: over c with α; additive and premultiplied α·c
    // (so additive adds α·c_s); multiply mix(1, c_s, α), a coloured filter.
    std::optional<BlendMode> blend;
    std::optional<ShaderSpec> shader;  // absent: the scene's shader, or the built-in ones
};

// How the scene is lit ("lighting" in the scene file).
enum class LightingPreset {
    Facet,  // linear-light rendering: colours decoded from sRGB, output encoded, per-pixel by default
    GL,     // OpenGL 1.x fixed function: colours as given, no gamma, Gouraud by default (docs/lighting.md)
    // The lecture notes' forms: Cook-Torrance with π(N·V)(N·L), F at N·L and the tinted metal lobe; N·V
    // clamped instead of the flip; lit colours clamped; output encoded with a pure 2.2 power.
    Lecture,
};
inline constexpr EnumName<LightingPreset> kLightingPresetNames[] = {
    {LightingPreset::Facet, "facet"}, {LightingPreset::GL, "gl"}, {LightingPreset::Lecture, "lecture"}};
constexpr std::span<const EnumName<LightingPreset>> enumNames(LightingPreset) {
    return kLightingPresetNames;
}

struct LightingOptions {
    LightingPreset preset = LightingPreset::Facet;
    ReflectionModel model = ReflectionModel::BlinnPhong;
    std::optional<ShadingFrequency> shading;  // absent: Phong (Facet preset) or Gouraud (GL preset)
    float creaseAngleDegrees = 60.0f;  // computed normals: faces meeting at a sharper angle keep a hard edge
    BrdfModel brdf;                    // Cook-Torrance's D, F and G; Blinn-Phong's exponent
    VertexNormals normals = VertexNormals::PolygonArea;  // computed normals: how the faces are weighted
    MathPrecision powers = MathPrecision::Fast;          // pow and exp in lighting and fog (wide.h)
    Normalization normalize = Normalization::Exact;      // N, L, V, H made unit length (wide.h)
    ShadingFrequency shadingOrDefault() const {
        return shading.value_or(preset == LightingPreset::GL ? ShadingFrequency::Gouraud
                                                             : ShadingFrequency::Phong);
    }
};

// Anti-aliasing of the frame ("pipeline": {"antialiasing": ...}, --aa). Supersampling (SSAA) draws the
// whole frame once per sample of the standard pattern (pipeline/sample_position.h), the image shifted so
// that the pixel centres land on that sample, and averages the passes in linear light (a box filter):
// N samples cost N frames and shade every sample. Multisampling (MSAA) draws the frame once, testing
// coverage and depth at each of the pattern's samples but shading once per pixel and triangle, and
// averages each pixel's samples in linear light after the frame's draws. None draws the frame once,
// sampling pixel centres.
enum class Antialiasing : std::uint8_t { None, Ssaa2, Ssaa4, Ssaa8, Ssaa16, Msaa2, Msaa4, Msaa8, Msaa16 };
inline constexpr EnumName<Antialiasing> kAntialiasingNames[] = {
    {Antialiasing::None, "none"},   {Antialiasing::Ssaa2, "ssaa2"},   {Antialiasing::Ssaa4, "ssaa4"},
    {Antialiasing::Ssaa8, "ssaa8"}, {Antialiasing::Ssaa16, "ssaa16"}, {Antialiasing::Msaa2, "msaa2"},
    {Antialiasing::Msaa4, "msaa4"}, {Antialiasing::Msaa8, "msaa8"},   {Antialiasing::Msaa16, "msaa16"}};
constexpr std::span<const EnumName<Antialiasing>> enumNames(Antialiasing) {
    return kAntialiasingNames;
}
// Samples per pixel, whether supersampled or multisampled: 1 for None.
constexpr int samplesPerPixel(Antialiasing aa) {
    switch (aa) {
        case Antialiasing::Ssaa2:
        case Antialiasing::Msaa2:
            return 2;
        case Antialiasing::Ssaa4:
        case Antialiasing::Msaa4:
            return 4;
        case Antialiasing::Ssaa8:
        case Antialiasing::Msaa8:
            return 8;
        case Antialiasing::Ssaa16:
        case Antialiasing::Msaa16:
            return 16;
        case Antialiasing::None:
            break;
    }
    return 1;
}
// Whether the samples are multisampled (one pass, shaded per pixel) rather than supersampled.
constexpr bool isMultisampled(Antialiasing aa) {
    return aa == Antialiasing::Msaa2 || aa == Antialiasing::Msaa4 || aa == Antialiasing::Msaa8 ||
           aa == Antialiasing::Msaa16;
}

// Whether the MTL's texture maps (map_Kd, map_Ke) are used ("textures": {"maps"}, --textures): off
// draws every surface in its material's colours, as an untextured model.
enum class TextureMaps : std::uint8_t { On, Off };
inline constexpr EnumName<TextureMaps> kTextureMapsNames[] = {{TextureMaps::On, "on"},
                                                              {TextureMaps::Off, "off"}};
constexpr std::span<const EnumName<TextureMaps>> enumNames(TextureMaps) {
    return kTextureMapsNames;
}

// "textures": whether the maps are used and how they are filtered (pipeline/texture.h).
struct TextureOptions {
    TextureMaps maps = TextureMaps::On;
    TextureFilter filter = TextureFilter::Bilinear;
};

struct PipelineOptions {
    CullMode cull = CullMode::Back;
    Interpolation interpolation = Interpolation::PerspectiveCorrect;
    int subpixelBits = 8;                                      // 0..8
    DepthBufferFormat depth = DepthBufferFormat::Float;        // "depth" (docs/trade.md)
    ColorBufferFormat colorBuffer = ColorBufferFormat::Float;  // "color_buffer" (docs/trade.md)
    Antialiasing antialiasing = Antialiasing::None;            // per frame: how many passes renderFrame draws
};

// How transparent triangles are ordered ("transparency").
enum class TransparencyMode {
    Sorted,    // back to front by the sort key, insertion sort remembering the last frame's order (default)
    Unsorted,  // in the order of the file: wrong wherever transparent surfaces overlap (for comparison)
    Exact,  // per-pixel fragment lists sorted by depth (an A-buffer): right even for intersecting triangles
};
inline constexpr EnumName<TransparencyMode> kTransparencyModeNames[] = {
    {TransparencyMode::Sorted, "sorted"},
    {TransparencyMode::Unsorted, "unsorted"},
    {TransparencyMode::Exact, "exact"}};
constexpr std::span<const EnumName<TransparencyMode>> enumNames(TransparencyMode) {
    return kTransparencyModeNames;
}
enum class SortKey {
    Centroid,        // the view-space depth of the triangle's centroid
    FarthestVertex,  // the view-space depth of its farthest vertex
};
inline constexpr EnumName<SortKey> kSortKeyNames[] = {{SortKey::Centroid, "centroid"},
                                                      {SortKey::FarthestVertex, "farthest"}};
constexpr std::span<const EnumName<SortKey>> enumNames(SortKey) {
    return kSortKeyNames;
}
struct TransparencyOptions {
    TransparencyMode mode = TransparencyMode::Sorted;
    SortKey key = SortKey::Centroid;
};

// Fog ("fog"); the colour is sRGB-encoded as every colour of a scene.
struct FogSpec {
    FogMode mode = FogMode::None;
    glm::vec3 color{0.5f};
    // Linear fog's range along the fog distance; absent: from the scene's bounding sphere, start at its
    // nearest point to the eye and end at its farthest.
    std::optional<float> start, end;
    float density = 1.0f;  // exp and exp²: per unit of length; height: a, at the base height
    FogDistance distance = FogDistance::EyeDepth;
    // Height fog: ρ(h) = density·e^(−falloff·(h − base_height)), h measured along `up` (world space).
    float falloff = 1.0f;
    float baseHeight = 0.0f;
    glm::vec3 up{0.0f, 1.0f, 0.0f};
};

// How an environment map's file holds its colours ("environment.encoding").
enum class EnvironmentEncoding { Srgb, Linear };
inline constexpr EnumName<EnvironmentEncoding> kEnvironmentEncodingNames[] = {
    {EnvironmentEncoding::Srgb, "srgb"}, {EnvironmentEncoding::Linear, "linear"}};
constexpr std::span<const EnumName<EnvironmentEncoding>> enumNames(EnvironmentEncoding) {
    return kEnvironmentEncodingNames;
}

// An equirectangular environment map ("environment", --environment; shading/environment.h): the
// background where no surface is, and the surfaces' mirror reflection.
struct EnvironmentSpec {
    std::filesystem::path image;  // resolved against the scene file's folder
    // 8-bit files: sRGB codes (decoded) or linear values (code/255). Float files (EXR, HDR) are linear.
    EnvironmentEncoding encoding = EnvironmentEncoding::Srgb;
    float intensity = 1.0f;
    float rotationDegrees = 0.0f;  // the map turned about the world's up (+y), counter-clockwise from above
    bool background = true;        // the map is the background too (else the "background" colour is)
    std::string origin = "environment.image";  // the key or flag that named it, for messages
};

// Colour encoding of inputs and outputs ("gamma"). The gl preset ignores it: no decoding, no encoding.
struct GammaOptions {
    TransferCurve encode = TransferCurve::Srgb;  // 8-bit outputs; EXR always keeps the linear values
    float exponent = 2.2f;                       // TransferCurve::Power: code = 255·c^(1/exponent)
    bool decodeInputs = true;                    // read scene and MTL colours as sRGB-encoded
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
    TextureOptions textures;
    LightingOptions lighting;
    TransparencyOptions transparency;
    FogSpec fog;
    std::optional<EnvironmentSpec> environment;  // none: no map, no reflections
    GammaOptions gamma;
    ShadowMapOptions shadowMap;  // "shadow_map": how every light with map shadows draws and reads its map
    // The command line's --shadows: every light's method, the default light's too (absent: each light's).
    std::optional<ShadowMethod> shadows;
    // --area-samples: every area light's shadow samples (absent: each light's "samples").
    std::optional<int> areaSamples;
    // "shader" (--shader): the shader of every object that names none; absent: the built-in ones.
    std::optional<ShaderSpec> shader;
    // --uniform NAME=VALUE: set in every shader of one's own that declares NAME (at least one must).
    std::vector<UniformValue> uniforms;
};

// Reads a JSON scene file. Throws InputError with a one-line message naming the file and the
// offending key (unknown keys are errors, e.g. "scene.json: unknown key \"camera.fvoy\"").
Scene loadScene(const std::filesystem::path& path);

// The scene "facet render model.obj" uses: that one model and every default.
Scene sceneForModel(const std::filesystem::path& objPath);

// What every command reads: a .json path as a scene file (loadScene), any other as a model
// (sceneForModel; the OBJ loader checks that file when the scene is prepared).
Scene loadSceneOrModel(const std::filesystem::path& path);

}  // namespace facet
