// What the commands share: the command line's number validators and value parsers, the image size
// checks, and the scene choices (size, camera, knobs, encoding) that render, step, trade and compare take.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

#include "pipeline/names.h"
#include "reference/reference.h"
#include "scene/knobs.h"
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

// The one line for an error of the command line's parsing: CLI11's own words, except where they are not
// a user's (an option given twice: "--width was given twice; give it once" rather than CLI11's "At Most
// 1 required but received 2").
std::string commandLineError(const CLI::ParseError& error);

// Parses "x,y,z" into a vec3; CLI11 hands us the raw text so the error can quote it.
glm::vec3 parseVec3(const std::string& option, const std::string& text);

// `fromScene` names the scene file and key a side came from when the command line did not give it
// (the file itself never holds more than the limit, but its height with a --width can).
void checkSize(int width, int height, const std::string& fromScene = "");

// For checkSize: " (\"height\" from scenes/a.json)" when a side of the image comes from the scene file.
std::string sizeFromScene(const std::filesystem::path& input, bool widthGiven, bool heightGiven);

// The knobs the command line gives (scene/knobs.h), by the knob's name, each value as typed.
using KnobChoices = std::map<std::string, std::string>;

// The choices that decide what a frame shows, which every command that renders a scene takes (render,
// step, trade; compare some of them): the input, the image size, the camera, the knobs (lighting,
// shading, transparency, buffers, shadows, textures, anti-aliasing) and the output's encoding.
struct SceneArgs {
    std::string input;
    std::optional<int> width, height;
    std::optional<std::string> eye, target;
    std::optional<float> fovy;
    int threads = 0;
    std::optional<LightingTerm> only;
    std::optional<TransferCurve> encode;
    std::optional<float> gamma;
    bool infiniteFar = false;
    KnobChoices knobs;
    std::optional<std::string> shader;       // --shader FILE: a shader of one's own for the scene
    std::vector<std::string> uniforms;       // --uniform NAME=VALUE, as typed
    std::optional<std::string> environment;  // --environment FILE: an equirectangular environment map
};

// The knob's option, as every command shows it: its flag, its one help text and its default, the
// value's form checked while parsing (a name of its table, a whole or a finite number); `take` gets the
// value as typed (its range is checked when applied, by the knob's entry).
CLI::Option* addKnobOption(CLI::App& command, const facet::SceneKnob& knob,
                           std::function<void(const std::string&)> take);
// The option of the knob named `name`, into args.knobs.
CLI::Option* addKnobOption(CLI::App& command, const std::string& name, SceneArgs& args);

// --memory-limit SIZE (base/memory_limit.h): the limit the estimates made before the work are checked
// against; render, step, trade and compare take it.
void addMemoryLimitOption(CLI::App& command);
// Adds SceneArgs's options (and the input) to `command`, as `facet render` describes them: every knob
// with a flag, in the table's order.
void addSceneOptions(CLI::App& command, SceneArgs& args);

// --shader FILE and --uniform NAME=VALUE: a shader of one's own (docs/shaders.md) and its uniforms.
void addShaderOptions(CLI::App& command, SceneArgs& args);

// One --uniform NAME=VALUE: VALUE is a number, true or false, or numbers separated by commas (a vector).
facet::UniformValue parseUniform(const std::string& text);

// The infinite far plane (--infinite-far), which compare takes too.
void addInfiniteFarOption(CLI::App& command, SceneArgs& args);

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

// Applies the command line's knobs (each checked by its entry: InputError naming the flag and what it
// must be), the infinite far plane and the encoding to `scene`: they win over the scene file's.
void applyLightingOptions(const SceneArgs& args, facet::Scene& scene);

}  // namespace facet::cli
