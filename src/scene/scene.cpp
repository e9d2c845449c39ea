// Scene files: reads the JSON scene format (docs/scene-format.md) into a Scene, checking every key.
// Strict on purpose: an unknown key, a wrong type or an absurd value is a one-line error naming the file
// and the key path (`scene.json: unknown key "camera.fvoy" (did you mean "fovy"?)`), never a silent default.
#include "scene/scene.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <span>
#include <string_view>
#include <system_error>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "base/errors.h"
#include "base/quote.h"
#include "scene/mesh.h"

namespace facet {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

// A list of allowed keys or choices; named constexpr arrays, so messages can list them.
using KeyList = std::span<const std::string_view>;

// ---- Text helpers --------------------------------------------------------------------------------

std::string formatNumber(double value) {
    char buffer[32];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

std::string childPath(const std::string& parent, std::string_view key) {
    return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

std::string elementPath(const std::string& parent, std::size_t index) {
    return parent + "[" + std::to_string(index) + "]";
}

// "a string", "an array of 2", ...: what the user wrote instead, for "must be X (got Y)" messages.
std::string describe(const Json& value) {
    switch (value.type()) {
        case Json::value_t::null:
            return "null";
        case Json::value_t::boolean:
            return value.get<bool>() ? "true" : "false";
        case Json::value_t::string:
            return "the string " + inQuotes(value.get<std::string>());
        case Json::value_t::array:
            return "an array of " + std::to_string(value.size());
        case Json::value_t::object:
            return "an object";
        case Json::value_t::number_integer:
        case Json::value_t::number_unsigned:
        case Json::value_t::number_float:
            return formatNumber(value.get<double>());
        default:
            return "a value of another type";
    }
}

// Levenshtein distance counting a swap of two neighbours as one edit (optimal string alignment),
// since "fvoy" for "fovy" is the typical typo.
int editDistance(std::string_view a, std::string_view b) {
    const std::size_t n = a.size(), m = b.size();
    std::vector<std::vector<int>> d(n + 1, std::vector<int>(m + 1));
    for (std::size_t i = 0; i <= n; ++i)
        d[i][0] = static_cast<int>(i);
    for (std::size_t j = 0; j <= m; ++j)
        d[0][j] = static_cast<int>(j);
    for (std::size_t i = 1; i <= n; ++i) {
        for (std::size_t j = 1; j <= m; ++j) {
            const int cost = a[i - 1] == b[j - 1] ? 0 : 1;
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) {
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
            }
        }
    }
    return d[n][m];
}

// " (did you mean "fovy"?)" for the closest candidate within two edits, otherwise "".
std::string suggestion(std::string_view word, KeyList candidates) {
    constexpr int kMaxSuggestionDistance = 2;
    std::string_view best;
    int bestDistance = kMaxSuggestionDistance + 1;
    for (std::string_view candidate : candidates) {
        const int distance = editDistance(word, candidate);
        if (distance < bestDistance) {
            best = candidate;
            bestDistance = distance;
        }
    }
    return best.empty() ? "" : " (did you mean " + inQuotes(best) + "?)";
}

std::string oneLine(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    return text;
}

// 1-based line and column (in characters, as editors count) of a 0-based byte offset into `text`.
std::string lineAndColumn(std::string_view text, std::size_t offset) {
    offset = std::min(offset, text.size());
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i < offset; ++i) {
        if (text[i] == '\n') {
            ++line;
            column = 1;
        } else if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) {
            ++column;  // UTF-8 continuation bytes do not start a character
        }
    }
    return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// ---- Duplicate keys ------------------------------------------------------------------------------

// JSON allows a key twice in one object and nlohmann keeps the last, silently dropping the first
// (a second "camera" block would win unnoticed). This SAX handler records the first repeat's path.
// A pass of its own over the text, rather than a parse callback: nlohmann's callback parser scans
// the whole enclosing array after each element, so 200,000 lights took 24 s to parse.
class DuplicateKeyFinder : public nlohmann::json_sax<Json> {
  public:
    bool null() override { return value(); }
    bool boolean(bool) override { return value(); }
    bool number_integer(number_integer_t) override { return value(); }
    bool number_unsigned(number_unsigned_t) override { return value(); }
    bool number_float(number_float_t, const string_t&) override { return value(); }
    bool string(string_t&) override { return value(); }
    bool binary(binary_t&) override { return value(); }
    bool start_object(std::size_t) override {
        value();
        frames_.push_back({true, {}, {}, 0});
        return true;
    }
    bool start_array(std::size_t) override {
        value();
        frames_.push_back({false, {}, {}, 0});
        return true;
    }
    bool end_object() override { return end(); }
    bool end_array() override { return end(); }
    bool key(string_t& name) override {
        Frame& frame = frames_.back();
        frame.key = name;
        if (!frame.keys.insert(frame.key).second && firstDuplicate_.empty()) firstDuplicate_ = currentPath();
        return true;
    }
    // The text was parsed before this pass, so there are no errors left to report.
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false;
    }

    const std::string& firstDuplicate() const { return firstDuplicate_; }

  private:
    struct Frame {
        bool isObject;
        std::set<std::string> keys;  // keys seen so far in this object
        std::string key;             // object: the key being read
        std::size_t index;           // array: 1 + the index of the element being read
    };

    // Every value starts an array's next element.
    bool value() {
        if (!frames_.empty() && !frames_.back().isObject) ++frames_.back().index;
        return true;
    }
    bool end() {
        if (!frames_.empty()) frames_.pop_back();
        return true;
    }

    std::string currentPath() const {
        std::string path;
        for (const Frame& frame : frames_) {
            path = frame.isObject ? childPath(path, frame.key) : elementPath(path, frame.index - 1);
        }
        return path;
    }

    std::vector<Frame> frames_;
    std::string firstDuplicate_;
};

// ---- The reader ----------------------------------------------------------------------------------

// Reads values out of the parsed document. Every accessor takes the key path it reads, so each
// message can name it; `fail` prefixes the scene file's path.
class SceneReader {
  public:
    explicit SceneReader(const fs::path& file) : file_(file) {}

    [[noreturn]] void fail(const std::string& what) const {
        throw InputError(file_.string() + ": " + oneLine(what));
    }

    // Rejects keys of `object` that are not in `known`, naming the likely intended key.
    void checkKeys(const Json& object, const std::string& path, KeyList known) const {
        for (const auto& [key, value] : object.items()) {
            if (std::find(known.begin(), known.end(), key) != known.end()) continue;
            fail("unknown key " + inQuotes(childPath(path, key)) + suggestion(key, known));
        }
    }

    void requireObject(const Json& value, const std::string& path, std::string_view what) const {
        if (!value.is_object())
            fail(inQuotes(path) + " must be " + std::string(what) + " (got " + describe(value) + ")");
    }

    const Json* find(const Json& object, std::string_view key) const {
        const auto it = object.find(key);
        return it == object.end() ? nullptr : &*it;
    }

    // A number that fits a 32-bit float: JSON allows 1e300, a float does not.
    float number(const Json& value, const std::string& path) const {
        if (!value.is_number()) fail(inQuotes(path) + " must be a number (got " + describe(value) + ")");
        const double number = value.get<double>();
        if (std::abs(number) > std::numeric_limits<float>::max()) {
            fail(inQuotes(path) + " is too large (got " + formatNumber(number) + ")");
        }
        return static_cast<float>(number);
    }

    int wholeNumber(const Json& value, const std::string& path, int lowest, int highest) const {
        if (!value.is_number())
            fail(inQuotes(path) + " must be a whole number (got " + describe(value) + ")");
        const double number = value.get<double>();
        if (number != std::floor(number) || number < lowest || number > highest) {
            fail(inQuotes(path) + " must be a whole number from " + std::to_string(lowest) + " to " +
                 std::to_string(highest) + " (got " + formatNumber(number) + ")");
        }
        return static_cast<int>(number);
    }

    float nonNegative(const Json& value, const std::string& path) const {
        const float x = number(value, path);
        if (x < 0.0f) fail(inQuotes(path) + " must not be negative (got " + describe(value) + ")");
        return x;
    }

    // A number from `lowest` to `highest`, both included; `unit` (" degrees") follows the range.
    float numberFromTo(const Json& value, const std::string& path, float lowest, float highest,
                       std::string_view unit = "") const {
        const float x = number(value, path);
        if (!(x >= lowest && x <= highest)) {
            fail(inQuotes(path) + " must be from " + formatNumber(lowest) + " to " + formatNumber(highest) +
                 std::string(unit) + " (got " + describe(value) + ")");
        }
        return x;
    }

    // [x, y, z]; example shows the expected shape in the message.
    glm::vec3 vec3(const Json& value, const std::string& path, std::string_view example = "[0, 1, 0]") const {
        if (!value.is_array() || value.size() != 3) {
            fail(inQuotes(path) + " must be an array of 3 numbers like " + std::string(example) + " (got " +
                 describe(value) + ")");
        }
        glm::vec3 v;
        for (int i = 0; i < 3; ++i)
            v[i] = number(value[i], elementPath(path, i));
        return v;
    }

    // [x, y, z] with no negative component.
    glm::vec3 nonNegativeVector(const Json& value, const std::string& path, std::string_view example) const {
        const glm::vec3 v = vec3(value, path, example);
        for (int i = 0; i < 3; ++i) {
            if (v[i] < 0.0f) {
                fail(inQuotes(elementPath(path, i)) + " must not be negative (got " + describe(value[i]) +
                     ")");
            }
        }
        return v;
    }

    // A colour component or an intensity: from 0 to kMaxColorComponent (above 1 is allowed: light can
    // be bright, but not so bright that summing the lights overflows to an infinite, white pixel).
    float brightness(const Json& value, const std::string& path) const {
        const float x = nonNegative(value, path);
        if (x > kMaxColorComponent) {
            fail(inQuotes(path) + " must be at most " +
                 std::to_string(static_cast<long>(kMaxColorComponent)) + " (got " + describe(value) + ")");
        }
        return x;
    }

    // A colour: three numbers from 0 to kMaxColorComponent.
    glm::vec3 color(const Json& value, const std::string& path) const {
        const glm::vec3 c = nonNegativeVector(value, path, "[1, 0.5, 0.2]");
        for (int i = 0; i < 3; ++i)
            brightness(value[i], elementPath(path, i));
        return c;
    }

    glm::vec3 nonZeroVector(const Json& value, const std::string& path) const {
        const glm::vec3 v = vec3(value, path);
        if (glm::length(glm::dvec3(v)) == 0.0) fail(inQuotes(path) + " must not be the zero vector");
        return v;
    }

    bool boolean(const Json& value, const std::string& path) const {
        if (!value.is_boolean())
            fail(inQuotes(path) + " must be true or false (got " + describe(value) + ")");
        return value.get<bool>();
    }

    std::string string(const Json& value, const std::string& path) const {
        if (!value.is_string()) fail(inQuotes(path) + " must be a string (got " + describe(value) + ")");
        return value.get<std::string>();
    }

    // One of `choices`; returns its index.
    std::size_t choice(const Json& value, const std::string& path, KeyList choices) const {
        const std::string text = string(value, path);
        const auto it = std::find(choices.begin(), choices.end(), text);
        if (it != choices.end()) return static_cast<std::size_t>(it - choices.begin());
        std::string list;
        for (std::string_view c : choices)
            list += (list.empty() ? "" : ", ") + inQuotes(c);
        fail(inQuotes(path) + " must be one of " + list + " (got " + inQuotes(text) + ")" +
             suggestion(text, choices));
    }

    void checkModelFile(const fs::path& model, const std::string& written, const std::string& path) const {
        std::error_code error;
        const fs::file_status status = fs::status(model, error);
        std::string where =
            model.string() == written ? "" : " (looked for " + quotedPath(model.string()) + ")";
        if (!fs::exists(status))
            fail(inQuotes(path) + ": model file " + inQuotes(written) + " not found" + where);
        if (fs::is_directory(status))
            fail(inQuotes(path) + ": model file " + inQuotes(written) + " is a folder" + where);
        if (!fs::is_regular_file(status)) {
            fail(inQuotes(path) + ": model file " + inQuotes(written) +
                 " is not a regular file (a device, a pipe or a socket)" + where);
        }
    }

  private:
    const fs::path& file_;
};

// ---- The scene sections --------------------------------------------------------------------------

constexpr std::string_view kTopLevelKeys[] = {"width",        "height",  "background", "ambient",  "camera",
                                              "lights",       "objects", "model",      "pipeline", "lighting",
                                              "transparency", "fog",     "gamma"};
constexpr std::string_view kCameraKeys[] = {"eye", "target", "up", "fovy", "near", "far"};
constexpr std::string_view kLightKeys[] = {"type",     "direction", "position", "color",       "intensity",
                                           "ambient",  "diffuse",   "specular", "attenuation", "cutoff",
                                           "exponent", "inner",     "outer",    "space"};
constexpr std::string_view kSpotOnlyKeys[] = {"cutoff", "exponent", "inner", "outer"};
constexpr std::string_view kObjectKeys[] = {"model",    "translate", "rotate", "scale",
                                            "material", "lighting",  "blend"};
constexpr std::string_view kMaterialKeys[] = {"ambient",   "diffuse",   "specular", "emission",
                                              "shininess", "opacity",   "preset",   "base_color",
                                              "metalness", "roughness", "f0"};
constexpr std::string_view kPipelineKeys[] = {"cull", "interpolation", "subpixel_bits"};
constexpr std::string_view kLightingKeys[] = {"preset",       "model",   "shading", "crease_angle",
                                              "distribution", "fresnel", "geometry"};
constexpr std::string_view kObjectLightingKeys[] = {"model", "shading"};
constexpr std::string_view kLightTypes[] = {"directional", "point", "spot"};  // in LightType order
constexpr std::string_view kLightingPresetNames[] = {"facet", "gl"};          // in LightingPreset order
constexpr std::string_view kReflectionModelNames[] = {"phong", "blinn-phong", "cook-torrance"};  // enum order
constexpr std::string_view kShadingNames[] = {"flat", "gouraud", "phong"};  // in ShadingFrequency order
constexpr std::string_view kDistributionNames[] = {"ggx", "beckmann"};
constexpr std::string_view kFresnelNames[] = {"schlick", "exact"};
constexpr std::string_view kGeometryNames[] = {"smith-ggx", "cook-torrance"};
constexpr std::string_view kLightSpaces[] = {"world", "camera"};
constexpr std::string_view kCullNames[] = {"back", "front", "none"};  // in CullChoice order
constexpr std::string_view kInterpolationNames[] = {"perspective", "affine"};
constexpr std::string_view kBlendNames[] = {"over", "additive", "multiply", "premultiplied"};  // BlendChoice
constexpr std::string_view kTransparencyKeys[] = {"mode", "sort_key"};
constexpr std::string_view kTransparencyModeNames[] = {"sorted", "unsorted", "exact"};  // TransparencyMode
constexpr std::string_view kSortKeyNames[] = {"centroid", "farthest"};                  // in SortKey order
constexpr std::string_view kFogKeys[] = {"mode", "color", "start", "end", "density", "distance"};
constexpr std::string_view kFogModeNames[] = {"linear", "exp", "exp2"};  // FogMode after None
constexpr std::string_view kFogDistanceNames[] = {"depth", "radial"};    // in FogDistance order
constexpr std::string_view kGammaKeys[] = {"encode", "exponent", "decode_inputs"};
constexpr std::string_view kEncodeNames[] = {"srgb", "power", "linear"};  // in TransferCurve order

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
        if (!(spec.fovyDegrees >= kMinFovyDegrees && spec.fovyDegrees <= kMaxFovyDegrees)) {
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
    if (const Json* v = reader.find(camera, "far")) {
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
        constexpr LightType kTypes[] = {LightType::Directional, LightType::Point, LightType::Spot};
        spec.type = kTypes[reader.choice(*v, childPath(path, "type"), kLightTypes)];
    }
    // A key that the type ignores is almost always a forgotten "type": say so rather than ignore it.
    if (spec.type == LightType::Directional && light.contains("position")) {
        reader.fail(key("position") + " is only for point and spot lights (add \"type\": \"point\")");
    }
    if (spec.type == LightType::Directional && light.contains("attenuation")) {
        reader.fail(key("attenuation") +
                    " is only for point and spot lights: a directional light is infinitely far and does "
                    "not fade (add \"type\": \"point\")");
    }
    if (spec.type == LightType::Point && light.contains("direction")) {
        reader.fail(key("direction") +
                    " is only for directional and spot lights: a point light shines every way (add "
                    "\"type\": \"spot\" for a cone)");
    }
    if (spec.type != LightType::Spot) {
        for (std::string_view name : kSpotOnlyKeys) {
            if (light.contains(name))
                reader.fail(key(name) + " is only for spot lights (add \"type\": \"spot\")");
        }
    }

    if (const Json* v = reader.find(light, "direction")) {
        spec.direction = reader.nonZeroVector(*v, childPath(path, "direction"));
    } else if (spec.type == LightType::Spot) {
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
        spec.attenuation = reader.nonNegativeVector(*v, childPath(path, "attenuation"), "[1, 0.1, 0.01]");
        if (spec.attenuation == glm::vec3(0.0f)) {
            reader.fail(key("attenuation") +
                        " must not be all zero: 1/(c0 + c1*d + c2*d^2) would divide by zero (got [0, 0, 0])");
        }
    }

    // The spot's profile: "cutoff" and "exponent" (OpenGL's) or "inner" and "outer" (smooth), not a mix.
    if (spec.type == LightType::Spot) {
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
    return spec;
}

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
    return spec;
}

ReflectionModel readReflectionModel(const SceneReader& reader, const Json& value, const std::string& path) {
    constexpr ReflectionModel kModels[] = {ReflectionModel::Phong, ReflectionModel::BlinnPhong,
                                           ReflectionModel::CookTorrance};
    return kModels[reader.choice(value, path, kReflectionModelNames)];
}

ShadingFrequency readShading(const SceneReader& reader, const Json& value, const std::string& path) {
    constexpr ShadingFrequency kFrequencies[] = {ShadingFrequency::Flat, ShadingFrequency::Gouraud,
                                                 ShadingFrequency::Phong};
    return kFrequencies[reader.choice(value, path, kShadingNames)];
}

// An object's "lighting": only the reflection model and the shading frequency can differ per object.
void readObjectLighting(const SceneReader& reader, const Json& lighting, const std::string& path,
                        ObjectSpec& spec) {
    reader.requireObject(lighting, path,
                         "an object like {\"model\": \"cook-torrance\", \"shading\": \"flat\"}");
    for (const auto& [key, value] : lighting.items()) {
        const bool perObject = std::find(std::begin(kObjectLightingKeys), std::end(kObjectLightingKeys),
                                         key) != std::end(kObjectLightingKeys);
        const bool sceneWide =
            std::find(std::begin(kLightingKeys), std::end(kLightingKeys), key) != std::end(kLightingKeys);
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

// The model path as written, checked for existence relative to the scene file's folder.
fs::path readModel(const SceneReader& reader, const Json& value, const std::string& path,
                   const fs::path& folder) {
    const std::string written = reader.string(value, path);
    if (written.empty()) reader.fail(inQuotes(path) + " must name an OBJ file (got an empty string)");
    const fs::path model = folder / fs::path(written);  // an absolute path replaces the folder
    reader.checkModelFile(model, written, path);
    return model;
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
    if (const Json* v = reader.find(object, "blend")) {
        constexpr BlendChoice kBlends[] = {BlendChoice::Over, BlendChoice::Additive, BlendChoice::Multiply,
                                           BlendChoice::Premultiplied};
        spec.blend = kBlends[reader.choice(*v, childPath(path, "blend"), kBlendNames)];
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

PipelineOptions readPipeline(const SceneReader& reader, const Json& pipeline) {
    const std::string path = "pipeline";
    reader.requireObject(pipeline, path, "an object like {\"cull\": \"back\"}");
    reader.checkKeys(pipeline, path, kPipelineKeys);

    PipelineOptions options;
    if (const Json* v = reader.find(pipeline, "cull")) {
        constexpr CullChoice kCullChoices[] = {CullChoice::Back, CullChoice::Front, CullChoice::None};
        options.cull = kCullChoices[reader.choice(*v, "pipeline.cull", kCullNames)];
    }
    if (const Json* v = reader.find(pipeline, "interpolation")) {
        options.interpolation = reader.choice(*v, "pipeline.interpolation", kInterpolationNames) == 0
                                    ? InterpolationChoice::Perspective
                                    : InterpolationChoice::Affine;
    }
    if (const Json* v = reader.find(pipeline, "subpixel_bits")) {
        options.subpixelBits = reader.wholeNumber(*v, "pipeline.subpixel_bits", 0, 8);
    }
    return options;
}

// The scene's "lighting": a preset name alone, or an object.
LightingOptions readLighting(const SceneReader& reader, const Json& lighting) {
    const std::string path = "lighting";
    constexpr LightingPreset kPresets[] = {LightingPreset::Facet, LightingPreset::GL};
    LightingOptions options;
    if (lighting.is_string()) {
        options.preset = kPresets[reader.choice(lighting, path, kLightingPresetNames)];
        return options;
    }
    reader.requireObject(lighting, path,
                         "\"facet\", \"gl\" or an object like {\"model\": \"cook-torrance\"}");
    reader.checkKeys(lighting, path, kLightingKeys);

    if (const Json* v = reader.find(lighting, "preset"))
        options.preset = kPresets[reader.choice(*v, "lighting.preset", kLightingPresetNames)];
    if (const Json* v = reader.find(lighting, "model"))
        options.model = readReflectionModel(reader, *v, "lighting.model");
    if (const Json* v = reader.find(lighting, "shading"))
        options.shading = readShading(reader, *v, "lighting.shading");
    if (const Json* v = reader.find(lighting, "crease_angle"))
        options.creaseAngleDegrees =
            reader.numberFromTo(*v, "lighting.crease_angle", 0.0f, 180.0f, " degrees");
    if (const Json* v = reader.find(lighting, "distribution")) {
        constexpr NormalDistribution kDistributions[] = {NormalDistribution::GGX,
                                                         NormalDistribution::Beckmann};
        options.brdf.distribution =
            kDistributions[reader.choice(*v, "lighting.distribution", kDistributionNames)];
    }
    if (const Json* v = reader.find(lighting, "fresnel")) {
        constexpr FresnelModel kFresnels[] = {FresnelModel::Schlick, FresnelModel::Exact};
        options.brdf.fresnel = kFresnels[reader.choice(*v, "lighting.fresnel", kFresnelNames)];
    }
    if (const Json* v = reader.find(lighting, "geometry")) {
        constexpr GeometryTerm kGeometries[] = {GeometryTerm::SmithGGX, GeometryTerm::CookTorrance};
        options.brdf.geometry = kGeometries[reader.choice(*v, "lighting.geometry", kGeometryNames)];
    }
    return options;
}

TransparencyOptions readTransparency(const SceneReader& reader, const Json& transparency) {
    const std::string path = "transparency";
    reader.requireObject(transparency, path, "an object like {\"mode\": \"exact\"}");
    reader.checkKeys(transparency, path, kTransparencyKeys);

    TransparencyOptions options;
    if (const Json* v = reader.find(transparency, "mode")) {
        constexpr TransparencyMode kModes[] = {TransparencyMode::Sorted, TransparencyMode::Unsorted,
                                               TransparencyMode::Exact};
        options.mode = kModes[reader.choice(*v, "transparency.mode", kTransparencyModeNames)];
    }
    // Used by "sorted" only, but accepted with every mode: switching the mode (in the file or with
    // --transparency) must not make the rest of the file wrong.
    if (const Json* v = reader.find(transparency, "sort_key")) {
        constexpr SortKey kKeys[] = {SortKey::Centroid, SortKey::FarthestVertex};
        options.key = kKeys[reader.choice(*v, "transparency.sort_key", kSortKeyNames)];
    }
    return options;
}

FogSpec readFog(const SceneReader& reader, const Json& fog) {
    const std::string path = "fog";
    reader.requireObject(fog, path, "an object like {\"mode\": \"exp2\", \"density\": 0.2}");
    reader.checkKeys(fog, path, kFogKeys);

    FogSpec spec;
    const Json* mode = reader.find(fog, "mode");
    if (mode == nullptr) {
        reader.fail(
            "\"fog.mode\" is missing: give \"linear\", \"exp\" or \"exp2\" (or remove \"fog\" for "
            "no fog)");
    }
    constexpr FogMode kModes[] = {FogMode::Linear, FogMode::Exponential, FogMode::ExponentialSquared};
    spec.mode = kModes[reader.choice(*mode, "fog.mode", kFogModeNames)];
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
        reader.fail(
            "\"fog.density\": density is for exp and exp2 fog (the mode is \"linear\", which uses \"start\" "
            "and \"end\")");
    }

    if (const Json* v = reader.find(fog, "color")) spec.color = reader.color(*v, "fog.color");
    if (const Json* v = reader.find(fog, "start")) spec.start = reader.nonNegative(*v, "fog.start");
    if (const Json* v = reader.find(fog, "end")) spec.end = reader.nonNegative(*v, "fog.end");
    if (spec.start && spec.end && !(*spec.end > *spec.start)) {
        reader.fail("\"fog.end\" (" + formatNumber(*spec.end) + ") must be greater than \"fog.start\" (" +
                    formatNumber(*spec.start) + ")");
    }
    if (const Json* v = reader.find(fog, "density")) spec.density = reader.nonNegative(*v, "fog.density");
    if (const Json* v = reader.find(fog, "distance")) {
        constexpr FogDistance kDistances[] = {FogDistance::EyeDepth, FogDistance::Radial};
        spec.distance = kDistances[reader.choice(*v, "fog.distance", kFogDistanceNames)];
    }
    return spec;
}

GammaOptions readGamma(const SceneReader& reader, const Json& gamma) {
    const std::string path = "gamma";
    reader.requireObject(gamma, path, "an object like {\"encode\": \"power\", \"exponent\": 2.2}");
    reader.checkKeys(gamma, path, kGammaKeys);

    GammaOptions options;
    if (const Json* v = reader.find(gamma, "encode")) {
        constexpr TransferCurve kCurves[] = {TransferCurve::Srgb, TransferCurve::Power,
                                             TransferCurve::Linear};
        options.encode = kCurves[reader.choice(*v, "gamma.encode", kEncodeNames)];
    }
    if (const Json* v = reader.find(gamma, "exponent")) {
        if (options.encode != TransferCurve::Power) {
            const std::string curve(kEncodeNames[static_cast<std::size_t>(options.encode)]);
            reader.fail("\"gamma.exponent\" is only for \"encode\": \"power\" (the curve is " +
                        inQuotes(curve) + (gamma.contains("encode") ? ")" : ", the default)"));
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

// ---- File reading and parsing --------------------------------------------------------------------

std::string readText(const SceneReader& reader, const fs::path& path) {
    // Checked before opening: reading /dev/zero never ends and opening a FIFO blocks until someone
    // writes to it; a huge file would be held in memory twice (text and document) before any check.
    std::error_code error;
    const fs::file_status status = fs::status(path, error);
    if (!fs::exists(status)) reader.fail("scene file not found");
    if (fs::is_directory(status)) reader.fail("is a folder, not a scene file");
    if (!fs::is_regular_file(status))
        reader.fail("is not a regular file (a device, a pipe or a socket), not a scene file");
    const std::uintmax_t size = fs::file_size(path, error);
    if (error) reader.fail("cannot read the scene file: " + error.message());
    if (size > kMaxSceneFileBytes) {
        reader.fail("the scene file is " + std::to_string(size) + " bytes, larger than the limit of " +
                    std::to_string(kMaxSceneFileBytes) + " (64 MiB) for a scene file");
    }

    std::ifstream in(path, std::ios::binary);
    if (!in) reader.fail(std::string("cannot open the scene file: ") + std::strerror(errno));
    // At most the size seen above, so a file that grows while read cannot pass the limit.
    std::string text(static_cast<std::size_t>(size), '\0');
    in.read(text.data(), static_cast<std::streamsize>(size));
    if (in.bad()) reader.fail(std::string("cannot read the scene file: ") + std::strerror(errno));
    text.resize(static_cast<std::size_t>(in.gcount()));
    return text;
}

// nlohmann quotes the text it stopped at whole and raw ("last read: '...'", "number overflow parsing
// '...'"): an unterminated 50 MB string or a byte that is not UTF-8 would go to the terminal as is.
// Cuts that text short and escapes it like every other quoted value.
std::string withShortToken(const std::string& detail, std::string_view marker) {
    const std::size_t open = detail.find(marker);
    if (open == std::string::npos) return detail;
    const std::size_t begin = open + marker.size();
    std::size_t end = detail.rfind("'; expected");
    if (end == std::string::npos || end < begin) end = detail.rfind('\'');
    if (end == std::string::npos || end < begin) return detail;
    return detail.substr(0, begin - 1) + inQuotes(std::string_view(detail).substr(begin, end - begin), '\'') +
           detail.substr(end + 1);
}

// Parses with comments allowed (// and /* */: a scene file is hand-written) and turns nlohmann's
// errors into "line L, column C" messages.
Json parseJson(const SceneReader& reader, const std::string& text) {
    Json document;
    try {
        document = Json::parse(text, nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
    } catch (const Json::parse_error& e) {
        // e.byte is the 1-based position of the offending byte (one past the end at end of input).
        // nlohmann's text reads "[json.exception...] parse error at line L, column C: syntax error
        // while parsing value - unexpected '}'; ..."; keep the part after the last " - ".
        std::string detail = e.what();
        if (const std::size_t dash = detail.find(" - "); dash != std::string::npos)
            detail = detail.substr(dash + 3);
        reader.fail("JSON syntax error at " + lineAndColumn(text, e.byte == 0 ? 0 : e.byte - 1) + ": " +
                    withShortToken(detail, "last read: '"));
    } catch (const Json::out_of_range& e) {
        // A number beyond double range ("number overflow parsing '1e400'") carries no position; find
        // the literal in the text.
        std::string detail = e.what();
        if (const std::size_t bracket = detail.find("] "); bracket != std::string::npos)
            detail = detail.substr(bracket + 2);
        const std::size_t open = detail.find('\''), close = detail.rfind('\'');
        std::string where;
        if (open != std::string::npos && close > open) {
            const std::size_t offset = text.find(detail.substr(open + 1, close - open - 1));
            if (offset != std::string::npos) where = " at " + lineAndColumn(text, offset);
        }
        reader.fail("invalid JSON" + where + ": " + withShortToken(detail, "parsing '"));
    }
    DuplicateKeyFinder duplicates;
    Json::sax_parse(text, &duplicates, nlohmann::detail::input_format_t::json, /*strict=*/true,
                    /*ignore_comments=*/true);
    if (!duplicates.firstDuplicate().empty()) {
        reader.fail("key " + inQuotes(duplicates.firstDuplicate()) + " is given twice");
    }
    return document;
}

}  // namespace

Scene loadScene(const fs::path& path) {
    const SceneReader reader(path);
    const Json document = parseJson(reader, readText(reader, path));
    if (!document.is_object()) {
        reader.fail("a scene file must hold a JSON object like {\"model\": \"bunny.obj\"} (got " +
                    describe(document) + ")");
    }
    reader.checkKeys(document, "", kTopLevelKeys);

    Scene scene;
    scene.source = path;
    if (const Json* v = reader.find(document, "width"))
        scene.width = reader.wholeNumber(*v, "width", 1, kMaxImageSide);
    if (const Json* v = reader.find(document, "height"))
        scene.height = reader.wholeNumber(*v, "height", 1, kMaxImageSide);
    if (static_cast<long long>(scene.width) * scene.height > kMaxPixels) {
        reader.fail("\"width\" and \"height\" make an image of " + std::to_string(scene.width) + "x" +
                    std::to_string(scene.height) + " = " +
                    std::to_string(static_cast<long long>(scene.width) * scene.height) +
                    " pixels, larger than the limit of " + std::to_string(kMaxPixels) +
                    " (64 Mpixel, e.g. 8192x8192)");
    }
    if (const Json* v = reader.find(document, "background")) scene.background = readBackground(reader, *v);
    if (const Json* v = reader.find(document, "ambient")) scene.ambientLight = reader.color(*v, "ambient");
    if (const Json* v = reader.find(document, "camera")) scene.camera = readCamera(reader, *v);
    if (const Json* v = reader.find(document, "pipeline")) scene.pipeline = readPipeline(reader, *v);
    if (const Json* v = reader.find(document, "lighting")) scene.lighting = readLighting(reader, *v);
    if (const Json* v = reader.find(document, "transparency"))
        scene.transparency = readTransparency(reader, *v);
    if (const Json* v = reader.find(document, "fog")) scene.fog = readFog(reader, *v);
    if (const Json* v = reader.find(document, "gamma")) {
        // The gl preset neither decodes nor encodes; a "gamma" beside it would silently do nothing.
        if (scene.lighting.preset == LightingPreset::GL) {
            reader.fail(
                "\"gamma\" cannot be used with the gl lighting preset: the gl preset writes colours as "
                "OpenGL "
                "1.x does, without decoding or encoding; remove \"gamma\"");
        }
        scene.gamma = readGamma(reader, *v);
    }

    if (const Json* lights = reader.find(document, "lights")) {
        if (!lights->is_array())
            reader.fail("\"lights\" must be an array of lights (got " + describe(*lights) + ")");
        // Here, before any light is read and long before any model is loaded.
        if (lights->size() > static_cast<std::size_t>(kMaxLights)) {
            reader.fail("\"lights\" has " + std::to_string(lights->size()) + " lights, at most " +
                        std::to_string(kMaxLights) + " are supported (as in OpenGL 1.x)");
        }
        for (std::size_t i = 0; i < lights->size(); ++i) {
            scene.lights.push_back(readLight(reader, (*lights)[i], elementPath("lights", i)));
        }
    }

    // Objects: the "model" shorthand or the "objects" array, exactly one of them.
    const fs::path folder = path.parent_path();
    const Json* model = reader.find(document, "model");
    const Json* objects = reader.find(document, "objects");
    if (model && objects) reader.fail("give either \"model\" or \"objects\", not both");
    if (model) {
        ObjectSpec object;
        object.model = readModel(reader, *model, "model", folder);
        scene.objects.push_back(object);
    } else if (objects) {
        if (!objects->is_array())
            reader.fail("\"objects\" must be an array of objects (got " + describe(*objects) + ")");
        if (objects->size() > kMaxObjects) {
            reader.fail("\"objects\" has " + std::to_string(objects->size()) + " objects, at most " +
                        std::to_string(kMaxObjects) + " are supported in one scene");
        }
        for (std::size_t i = 0; i < objects->size(); ++i) {
            scene.objects.push_back(readObject(reader, (*objects)[i], elementPath("objects", i), folder));
        }
    }
    if (scene.objects.empty()) {
        reader.fail("the scene has no objects: add \"model\": \"file.obj\" or an \"objects\" array");
    }
    return scene;
}

Scene loadSceneOrModel(const fs::path& path) {
    return path.extension() == ".json" ? loadScene(path) : sceneForModel(path);
}

Scene sceneForModel(const fs::path& objPath) {
    Scene scene;
    scene.source = objPath;
    ObjectSpec object;
    object.model = objPath;
    scene.objects.push_back(object);
    return scene;
}

}  // namespace facet
