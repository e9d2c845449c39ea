// Reading a scene file's JSON: the text read within the size limit, parsed with comments allowed and
// duplicate keys refused, and typed key readers (numbers, vectors, colours, choices) whose every
// message names the file and the key path. Internal to the scene reader (scene.cpp, scene_sections.cpp).
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "pipeline/names.h"

namespace facet::scene_file {

namespace fs = std::filesystem;
using Json = nlohmann::json;

// A list of allowed keys or choices; named constexpr arrays, so messages can list them.
using KeyList = std::span<const std::string_view>;

// Numbers as messages show them: "0.5", "1e+30".
std::string formatNumber(double value);
// "camera" + "eye" → "camera.eye"; "" + "width" → "width".
std::string childPath(const std::string& parent, std::string_view key);
// "lights" + 2 → "lights[2]".
std::string elementPath(const std::string& parent, std::size_t index);

// "a string", "an array of 2", ...: what the user wrote instead, for "must be X (got Y)" messages.
std::string describe(const Json& value);

// " (did you mean "fovy"?)" for the closest candidate within two edits, otherwise "".
std::string suggestion(std::string_view word, KeyList candidates);
// Choices in a sentence: "\"a\", \"b\" or \"c\"" with `last` " or ".
std::string quotedList(const std::vector<std::string>& names, std::string_view last);

// ---- The reader ----------------------------------------------------------------------------------

// Reads values out of the parsed document. Every accessor takes the key path it reads, so each
// message can name it; `fail` prefixes the scene file's path.
class SceneReader {
  public:
    explicit SceneReader(const fs::path& file) : file_(file) {}
    const fs::path& file() const { return file_; }

    [[noreturn]] void fail(const std::string& what) const;

    // Rejects keys of `object` that are not in `known`, naming the likely intended key.
    void checkKeys(const Json& object, const std::string& path, KeyList known) const;

    void requireObject(const Json& value, const std::string& path, std::string_view what) const;

    const Json* find(const Json& object, std::string_view key) const;

    // A number that fits a 32-bit float: JSON allows 1e300, a float does not.
    float number(const Json& value, const std::string& path) const;

    int wholeNumber(const Json& value, const std::string& path, int lowest, int highest) const;

    float nonNegative(const Json& value, const std::string& path) const;

    // A number from `lowest` to `highest`, both included; `unit` (" degrees") follows the range.
    float numberFromTo(const Json& value, const std::string& path, float lowest, float highest,
                       std::string_view unit = "") const;

    // [x, y, z]; example shows the expected shape in the message.
    glm::vec3 vec3(const Json& value, const std::string& path, std::string_view example = "[0, 1, 0]") const;

    // [x, y, z] with no negative component.
    glm::vec3 nonNegativeVector(const Json& value, const std::string& path, std::string_view example) const;

    // A colour component or an intensity: from 0 to kMaxColorComponent (above 1 is allowed: light can
    // be bright, but not so bright that summing the lights overflows to an infinite, white pixel).
    float brightness(const Json& value, const std::string& path) const;

    // A colour: three numbers from 0 to kMaxColorComponent.
    glm::vec3 color(const Json& value, const std::string& path) const;

    glm::vec3 nonZeroVector(const Json& value, const std::string& path) const;

    bool boolean(const Json& value, const std::string& path) const;

    std::string string(const Json& value, const std::string& path) const;

    // One of `choices`; returns its index.
    std::size_t choice(const Json& value, const std::string& path, KeyList choices) const;

    // One of the names of E's table (pipeline/names.h) but those of `except`; returns its value.
    template <class E>
    E enumChoice(const Json& value, const std::string& path, std::initializer_list<E> except = {}) const {
        const std::vector<std::string> names = namesOf<E>(except);
        const std::vector<std::string_view> choices(names.begin(), names.end());
        return *parseName<E>(choices[choice(value, path, choices)]);
    }

    void checkModelFile(const fs::path& model, const std::string& written, const std::string& path) const;

  private:
    const fs::path& file_;
};

// The scene file's text, refused unread when it is not a regular file or larger than
// kMaxSceneFileBytes.
std::string readText(const SceneReader& reader, const fs::path& path);

// Parses with comments allowed (// and /* */: a scene file is hand-written) and turns nlohmann's
// errors into "line L, column C" messages.
Json parseJson(const SceneReader& reader, const std::string& text);

}  // namespace facet::scene_file
