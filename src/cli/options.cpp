#include "cli/options.h"

#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "base/errors.h"
#include "base/memory_limit.h"
#include "base/quote.h"
#include "scene/limits.h"

namespace facet::cli {

CLI::Validator wholeNumber(long long lowest, long long highest) {
    const std::string range = "from " + std::to_string(lowest) + " to " + std::to_string(highest);
    return CLI::Validator(
        [lowest, highest, range](std::string& text) -> std::string {
            long long value = 0;
            const char* end = text.data() + text.size();
            const auto [stop, error] = std::from_chars(text.data(), end, value);
            if (error != std::errc() || stop != end || value < lowest || value > highest)
                return "expects a whole number " + range + " (got " + facet::inQuotes(text) + ")";
            return "";
        },
        "INT " + range);
}

const CLI::Validator kWholeNumber(
    [](std::string& text) -> std::string {
        int value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        if (error != std::errc() || stop != end)
            return "expects a whole number (got " + facet::inQuotes(text) + ")";
        return "";
    },
    "INT");

const CLI::Validator kFiniteNumber(
    [](std::string& text) -> std::string {
        char* stop = nullptr;
        const double value = std::strtod(text.c_str(), &stop);
        if (text.empty() || *stop != '\0' || !std::isfinite(value) || std::abs(value) > FLT_MAX)
            return "expects a finite number (got " + facet::inQuotes(text) + ")";
        return "";
    },
    "NUMBER");

std::string commandLineError(const CLI::ParseError& error) {
    const std::string text = error.what();
    // CLI11's ArgumentMismatch::AtMost: "NAME: At Most 1 required but received N", thrown only when an
    // option of one value is given more than once (a second value after the first is another word).
    const std::string atMost = ": At Most 1 required but received ";
    const std::size_t at = text.find(atMost);
    if (dynamic_cast<const CLI::ArgumentMismatch*>(&error) != nullptr && at != std::string::npos) {
        const std::string name = text.substr(0, at), times = text.substr(at + atMost.size());
        return name + " was given " + (times == "2" ? std::string("twice") : times + " times") +
               "; give it once";
    }
    return text;
}

glm::vec3 parseVec3(const std::string& option, const std::string& text) {
    std::stringstream in(text);
    glm::vec3 v;
    char comma1 = 0, comma2 = 0;
    if (!(in >> v.x >> comma1 >> v.y >> comma2 >> v.z) || comma1 != ',' || comma2 != ',' ||
        !(in >> std::ws).eof() || !std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        throw facet::InputError(option + " expects three numbers separated by commas, like 0,1.5,4 (got " +
                                facet::inQuotes(text) + ")");
    return v;
}

void checkSize(int width, int height, const std::string& fromScene) {
    for (auto [name, value] : {std::pair{"--width", width}, std::pair{"--height", height}})
        if (value < 1 || value > facet::kMaxImageSide)
            throw facet::InputError(std::string(name) + " must be between 1 and " +
                                    std::to_string(facet::kMaxImageSide) + " (got " + std::to_string(value) +
                                    ")");
    if (static_cast<long long>(width) * height > facet::kMaxPixels)
        throw facet::InputError("an image of " + std::to_string(width) + "x" + std::to_string(height) +
                                " pixels is larger than the limit of " + std::to_string(facet::kMaxPixels) +
                                " pixels" + fromScene);
}

std::string sizeFromScene(const std::filesystem::path& input, bool widthGiven, bool heightGiven) {
    if (input.extension() != ".json" || (widthGiven && heightGiven)) return "";
    const std::string keys = widthGiven    ? "\"height\""
                             : heightGiven ? "\"width\""
                                           : "\"width\" and \"height\"";
    return " (" + keys + " from " + input.string() + ")";
}

CLI::Option* addKnobOption(CLI::App& command, const facet::SceneKnob& knob,
                           std::function<void(const std::string&)> take) {
    const std::string help =
        knob.help + " " +
        (knob.defaultNote.empty() ? "(default " + knob.defaultValue() + ")" : knob.defaultNote);
    CLI::Option* option = command.add_option_function<std::string>(knob.flag, std::move(take), help);
    switch (knob.kind) {
        case facet::KnobKind::Names:
            return option->check(CLI::IsMember(knob.names));
        case facet::KnobKind::WholeNumber:
            return option->type_name("INT")->check(kWholeNumber);
        case facet::KnobKind::Number:
            return option->type_name("FLOAT")->check(kFiniteNumber);
    }
    return option;
}

CLI::Option* addKnobOption(CLI::App& command, const std::string& name, SceneArgs& args) {
    const facet::SceneKnob* knob = facet::sceneKnobNamed(name);
    return addKnobOption(command, *knob,
                         [&args, name](const std::string& value) { args.knobs[name] = value; });
}

void addMemoryLimitOption(CLI::App& command) {
    command
        .add_option_function<std::string>(
            "--memory-limit", [](const std::string& text) { facet::setMemoryLimit(text, "--memory-limit"); },
            "Refuse work whose buffers need more memory than SIZE, like 4G or 512M (default: half the "
            "machine's memory, less under ulimit -v or a container's limit; or FACET_MEMORY_LIMIT)")
        ->check(CLI::Validator(
            [](std::string& text) -> std::string {
                try {
                    facet::parseMemorySize(text, "--memory-limit");
                } catch (const facet::InputError& e) {
                    const std::string message = e.what();  // CLI11 puts "--memory-limit: " before it
                    return message.substr(message.find(' ') + 1);
                }
                return "";
            },
            "SIZE"));
}

void addSceneOptions(CLI::App& command, SceneArgs& args) {
    command.add_option("input", args.input, "Model (.obj) or scene (.json)")->required();
    command.add_option("--width", args.width, "Image width in pixels (default 1280)")->check(kWholeNumber);
    command.add_option("--height", args.height, "Image height in pixels (default 960)")->check(kWholeNumber);
    command.add_option("--eye", args.eye, "Camera position x,y,z (default: framed from the front)");
    command.add_option("--target", args.target,
                       "Point the camera looks at, x,y,z (default: the model's centre)");
    command.add_option("--fovy", args.fovy, "Vertical field of view in degrees (default 40)")
        ->check(kFiniteNumber);
    command.add_option("--threads", args.threads, "Worker threads (default: one per hardware thread)")
        ->check(wholeNumber(0, 1024));
    addMemoryLimitOption(command);
    for (const facet::SceneKnob& knob : facet::sceneKnobs())
        if (!knob.flag.empty()) addKnobOption(command, knob.name, args);
    addInfiniteFarOption(command, args);
    addShaderOptions(command, args);
    command
        .add_option("--environment", args.environment,
                    "An equirectangular environment map (PNG, JPEG: sRGB; EXR, HDR: linear): the background "
                    "and the surfaces' mirror reflection (docs/lighting.md)")
        ->type_name("FILE");
    addChoice(command, "--only", args.only, "Render one term of the lighting equation alone");
    addChoice(command, "--encode", args.encode,
              "8-bit output encoding: the exact sRGB curve, a power 1/gamma, or none" +
                  byDefault(TransferCurve::Srgb));
    command.add_option("--gamma", args.gamma, "Encode 8-bit output as c^(1/GAMMA) (e.g. 2.2)")
        ->check(kFiniteNumber);
}

void addShaderOptions(CLI::App& command, SceneArgs& args) {
    command.add_option("--shader", args.shader,
                       "A shader of your own: a C++ file (compiled on first use, then cached) or a module "
                       "(.so) built with facet_add_shader (docs/shaders.md)");
    command
        .add_option("--uniform", args.uniforms,
                    "Set a uniform of your shader: NAME=VALUE, VALUE a number, true/false or x,y,z "
                    "(repeat for more)")
        ->type_name("NAME=VALUE");
}

facet::UniformValue parseUniform(const std::string& text) {
    const std::string origin = "--uniform " + text;
    const std::size_t equals = text.find('=');
    if (equals == std::string::npos || equals == 0)
        throw facet::InputError(origin + ": give NAME=VALUE (e.g. --uniform bands=3)");
    facet::UniformValue value{text.substr(0, equals), {}, false, origin};
    const std::string given = text.substr(equals + 1);
    if (given == "true" || given == "false") {
        value.isBool = true;
        value.numbers.push_back(given == "true" ? 1.0 : 0.0);
        return value;
    }
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = std::min(given.find(',', start), given.size());
        const std::string part = given.substr(start, comma - start);
        std::size_t used = 0;
        double number = 0;
        try {
            number = std::stod(part, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (part.empty() || used != part.size() || !std::isfinite(number))
            throw facet::InputError(origin + ": " + facet::inQuotes(part) +
                                    " is not a number (VALUE is a number, true, false or numbers x,y,z)");
        value.numbers.push_back(number);
        if (comma == given.size()) break;
        start = comma + 1;
    }
    return value;
}

void addInfiniteFarOption(CLI::App& command, SceneArgs& args) {
    command.add_flag("--infinite-far", args.infiniteFar,
                     "Camera: no far plane (the projection's limit as far goes to infinity; best with "
                     "--depth reversed-float)");
}

facet::Scene sceneFromArgs(const SceneArgs& args) {
    const std::filesystem::path input = args.input;
    facet::Scene scene = facet::loadSceneOrModel(input);
    if (args.width) scene.width = *args.width;
    if (args.height) scene.height = *args.height;
    checkSize(scene.width, scene.height,
              sizeFromScene(input, args.width.has_value(), args.height.has_value()));
    if (args.eye) scene.camera.eye = parseVec3("--eye", *args.eye);
    if (args.target) scene.camera.target = parseVec3("--target", *args.target);
    if (args.fovy) {
        if (!facet::fovyAllowed(*args.fovy)) {
            std::ostringstream message;
            message << "--fovy must be from " << facet::kMinFovyDegrees << " to " << facet::kMaxFovyDegrees
                    << " degrees (got " << *args.fovy << ")";
            throw facet::InputError(message.str());
        }
        scene.camera.fovyDegrees = *args.fovy;
    }
    // Compared exactly, not by a length in float: the squared distance between the eye and target of
    // a model of 1e-30 units underflows to 0 in float, though they are far apart at its scale.
    if (scene.camera.eye && scene.camera.target && *scene.camera.eye == *scene.camera.target)
        throw facet::InputError("the camera's eye and target are the same point");
    applyLightingOptions(args, scene);
    return scene;
}

void applyLightingOptions(const SceneArgs& args, facet::Scene& scene) {
    for (const facet::SceneKnob& knob : facet::sceneKnobs()) {
        const auto given = args.knobs.find(knob.name);
        if (given == args.knobs.end()) continue;
        if (const std::optional<std::string> problem = knob.commandLineProblem(given->second))
            throw facet::InputError(*problem);
        knob.set(scene, given->second);
    }
    const facet::FogSpec& fog = scene.fog;
    if ((args.knobs.count("fog-start") || args.knobs.count("fog-end")) && fog.start && fog.end &&
        !(*fog.end > *fog.start))
        throw facet::InputError("the fog's end (" + facet::knobNumberText(*fog.end) +
                                ") must be greater than its start (" + facet::knobNumberText(*fog.start) +
                                "): give --fog-start and --fog-end in that order of distance");
    if (args.shader) scene.shader = facet::ShaderSpec{*args.shader, {}};
    if (args.environment) {
        // The file's own settings (encoding, intensity, rotation) stay when the scene has an environment.
        facet::EnvironmentSpec environment = scene.environment.value_or(facet::EnvironmentSpec{});
        environment.image = *args.environment;
        environment.origin = "--environment";
        if (args.environment->empty()) throw facet::InputError("--environment must name an image file");
        scene.environment = environment;
    }
    for (const std::string& uniform : args.uniforms)
        scene.uniforms.push_back(parseUniform(uniform));
    if (args.infiniteFar) {
        scene.camera.infiniteFar = true;
        scene.camera.far.reset();
    }
    if ((args.encode || args.gamma) && scene.lighting.preset == facet::LightingPreset::GL)
        throw facet::InputError(
            "the " + std::string(nameOf(LightingPreset::GL)) +
            " preset writes colours as OpenGL 1.x does, unencoded: --encode and --gamma do not apply");
    if ((args.encode || args.gamma) && scene.lighting.preset == facet::LightingPreset::Lecture)
        throw facet::InputError("the " + std::string(nameOf(LightingPreset::Lecture)) +
                                " preset encodes with the lecture notes' pure 2.2 power: --encode and "
                                "--gamma do not apply");
    if (args.encode) scene.gamma.encode = *args.encode;
    if (args.gamma) {
        if (!(*args.gamma > 0.0f && *args.gamma <= 10.0f))
            throw facet::InputError("--gamma must be above 0 and at most 10 (got " +
                                    std::to_string(*args.gamma) + ")");
        if (args.encode && *args.encode != TransferCurve::Power)
            throw facet::InputError("--gamma goes with --encode " +
                                    std::string(nameOf(TransferCurve::Power)));
        scene.gamma.encode = facet::TransferCurve::Power;
        scene.gamma.exponent = *args.gamma;
    }
}

}  // namespace facet::cli
