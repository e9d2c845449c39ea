// What the commands share: the command line's number validators and value parsers, the image size
// checks, and the scene choices (size, camera, lighting, transparency, encoding) of render and compare.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

#include "pipeline/names.h"
#include "reference/reference.h"
#include "scene/scene.h"
#include "shaders/shaders.h"

namespace facet::cli {

// Command-line numbers, checked on the text before CLI11 converts it, so a bad value is named with
// what is expected rather than CLI11's "Could not convert" or "not in range".
CLI::Validator wholeNumber(long long lowest, long long highest);
// A whole number whose range the program checks afterwards with its own message (--width, --height).
extern const CLI::Validator kWholeNumber;
// Any finite number: "nan", "inf" and values beyond a float (1e39) are refused; each option checks
// its own range afterwards.
extern const CLI::Validator kFiniteNumber;

// An option whose value is one of the names of E's table (pipeline/names.h): CLI11 checks the text
// against the table's names (and lists them in the help and in its message), then `value` gets the
// named value.
template <class E>
CLI::Option* addChoice(CLI::App& command, const std::string& name, std::optional<E>& value,
                       const std::string& description) {
    return command
        .add_option_function<std::string>(
            name, [&value](const std::string& text) { value = parseName<E>(text); }, description)
        ->check(CLI::IsMember(namesOf<E>()));
}

// "... (default blinn-phong)": an option's default, by its name.
template <class E>
std::string byDefault(E value) {
    return " (default " + std::string(nameOf(value)) + ")";
}

// Parses "x,y,z" into a vec3; CLI11 hands us the raw text so the error can quote it.
glm::vec3 parseVec3(const std::string& option, const std::string& text);

// `fromScene` names the scene file and key a side came from when the command line did not give it
// (the file itself never holds more than the limit, but its height with a --width can).
void checkSize(int width, int height, const std::string& fromScene = "");

// For checkSize: " (\"height\" from scenes/a.json)" when a side of the image comes from the scene file.
std::string sizeFromScene(const std::filesystem::path& input, bool widthGiven, bool heightGiven);

// The choices that decide what a frame shows, which every command that renders a scene takes (render,
// step; compare some of them): the input, the image size, the camera and the lighting, shading,
// transparency and encoding options.
struct SceneArgs {
    std::string input;
    std::optional<int> width, height;
    std::optional<std::string> eye, target;
    std::optional<float> fovy;
    int threads = 0;
    std::optional<LightingPreset> lighting;
    std::optional<ReflectionModel> reflection;
    std::optional<ShadingFrequency> shading;
    std::optional<LightingTerm> only;
    std::optional<float> creaseAngle;
    std::optional<VertexNormals> normals;
    std::optional<MathPrecision> powers;
    std::optional<Normalization> normalize;
    std::optional<FresnelModel> fresnel;
    std::optional<TransparencyMode> transparency;
    std::optional<SortKey> sortKey;
    std::optional<TransferCurve> encode;
    std::optional<float> gamma;
    std::optional<Interpolation> interpolation;
    std::optional<CullMode> cull;
    std::optional<int> subpixelBits;
    std::optional<DepthBufferFormat> depth;
    std::optional<ColorBufferFormat> colorBuffer;
    bool infiniteFar = false;
    std::optional<Antialiasing> antialiasing;
    std::optional<ShadowMethod> shadows;
    std::optional<int> shadowMapSize;
    std::optional<float> shadowBias, shadowSlopeBias;
    std::optional<int> shadowFilter;
    std::optional<TextureMaps> textures;
    std::optional<TextureFilter> textureFilter;
};

// Adds the accuracy choices of the formulas (--normals, --powers, --normalize, --fresnel) to `command`:
// part of addSceneOptions, and what `facet compare` takes of them.
void addFormulaOptions(CLI::App& command, SceneArgs& args);

// Adds SceneArgs's options (and the input) to `command`, as `facet render` describes them.
void addSceneOptions(CLI::App& command, SceneArgs& args);

// The depth and colour buffer formats and the infinite far plane (--depth, --color-buffer,
// --infinite-far), which compare takes too.
void addBufferFormatOptions(CLI::App& command, SceneArgs& args);

// Loads the input and applies every choice of `args` to it; throws InputError for a bad value or an
// unusable input. The size is checked (checkSize), the camera's eye and target are not the same point.
facet::Scene sceneFromArgs(const SceneArgs& args);

struct RenderArgs : SceneArgs {
    // facet render's inputs: those of the command line, then those of --list (cli/batch.h). `input`
    // is the one being rendered (after parsing, the first of the command line).
    std::vector<std::string> inputs;
    std::optional<std::string> list;   // --list FILE: one input per line
    std::optional<std::string> shard;  // --shard I/N: the inputs whose index % N == I
    std::string output;                // may hold {name} and {index}
    bool quiet = false;
    bool components = false;
    std::optional<std::string> frames;  // "0-59"
    std::optional<float> turntable;     // degrees over the frames
    std::optional<int> pngCompression;  // zlib's level for PNG files, 0-9
    bool stats = false;
    std::optional<RendererKind> renderer;
    std::optional<int> samples;  // --renderer reference: N×N rays per pixel
};

// Applies the command line's lighting choices to every object (they win over the scene file's).
void applyLightingOptions(const SceneArgs& args, facet::Scene& scene);

}  // namespace facet::cli
