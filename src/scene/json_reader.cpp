#include "scene/json_reader.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <set>
#include <system_error>
#include <vector>

#include "base/errors.h"
#include "base/quote.h"
#include "scene/limits.h"
#include "scene/mesh.h"

namespace facet::scene_file {

namespace {

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

}  // namespace

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

std::string quotedList(const std::vector<std::string>& names, std::string_view last) {
    std::string list;
    for (std::size_t i = 0; i < names.size(); ++i)
        list += (i == 0 ? "" : i + 1 == names.size() ? std::string(last) : ", ") + inQuotes(names[i]);
    return list;
}

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

void SceneReader::fail(const std::string& what) const {
    throw InputError(file_.string() + ": " + oneLine(what));
}

void SceneReader::checkKeys(const Json& object, const std::string& path, KeyList known) const {
    for (const auto& [key, value] : object.items()) {
        if (std::find(known.begin(), known.end(), key) != known.end()) continue;
        fail("unknown key " + inQuotes(childPath(path, key)) + suggestion(key, known));
    }
}

void SceneReader::requireObject(const Json& value, const std::string& path, std::string_view what) const {
    if (!value.is_object())
        fail(inQuotes(path) + " must be " + std::string(what) + " (got " + describe(value) + ")");
}

const Json* SceneReader::find(const Json& object, std::string_view key) const {
    const auto it = object.find(key);
    return it == object.end() ? nullptr : &*it;
}

float SceneReader::number(const Json& value, const std::string& path) const {
    if (!value.is_number()) fail(inQuotes(path) + " must be a number (got " + describe(value) + ")");
    const double number = value.get<double>();
    if (std::abs(number) > std::numeric_limits<float>::max()) {
        fail(inQuotes(path) + " is too large (got " + formatNumber(number) + ")");
    }
    return static_cast<float>(number);
}

int SceneReader::wholeNumber(const Json& value, const std::string& path, int lowest, int highest) const {
    if (!value.is_number()) fail(inQuotes(path) + " must be a whole number (got " + describe(value) + ")");
    const double number = value.get<double>();
    if (number != std::floor(number) || number < lowest || number > highest) {
        fail(inQuotes(path) + " must be a whole number from " + std::to_string(lowest) + " to " +
             std::to_string(highest) + " (got " + formatNumber(number) + ")");
    }
    return static_cast<int>(number);
}

float SceneReader::nonNegative(const Json& value, const std::string& path) const {
    const float x = number(value, path);
    if (x < 0.0f) fail(inQuotes(path) + " must not be negative (got " + describe(value) + ")");
    return x;
}

float SceneReader::numberFromTo(const Json& value, const std::string& path, float lowest, float highest,
                                std::string_view unit) const {
    const float x = number(value, path);
    if (!(x >= lowest && x <= highest)) {
        fail(inQuotes(path) + " must be from " + formatNumber(lowest) + " to " + formatNumber(highest) +
             std::string(unit) + " (got " + describe(value) + ")");
    }
    return x;
}

glm::vec3 SceneReader::vec3(const Json& value, const std::string& path, std::string_view example) const {
    if (!value.is_array() || value.size() != 3) {
        fail(inQuotes(path) + " must be an array of 3 numbers like " + std::string(example) + " (got " +
             describe(value) + ")");
    }
    glm::vec3 v;
    for (int i = 0; i < 3; ++i)
        v[i] = number(value[i], elementPath(path, i));
    return v;
}

glm::vec3 SceneReader::nonNegativeVector(const Json& value, const std::string& path,
                                         std::string_view example) const {
    const glm::vec3 v = vec3(value, path, example);
    for (int i = 0; i < 3; ++i) {
        if (v[i] < 0.0f) {
            fail(inQuotes(elementPath(path, i)) + " must not be negative (got " + describe(value[i]) + ")");
        }
    }
    return v;
}

float SceneReader::brightness(const Json& value, const std::string& path) const {
    const float x = nonNegative(value, path);
    if (x > kMaxColorComponent) {
        fail(inQuotes(path) + " must be at most " + std::to_string(static_cast<long>(kMaxColorComponent)) +
             " (got " + describe(value) + ")");
    }
    return x;
}

glm::vec3 SceneReader::color(const Json& value, const std::string& path) const {
    const glm::vec3 c = nonNegativeVector(value, path, "[1, 0.5, 0.2]");
    for (int i = 0; i < 3; ++i)
        brightness(value[i], elementPath(path, i));
    return c;
}

glm::vec3 SceneReader::nonZeroVector(const Json& value, const std::string& path) const {
    const glm::vec3 v = vec3(value, path);
    if (glm::length(glm::dvec3(v)) == 0.0) fail(inQuotes(path) + " must not be the zero vector");
    return v;
}

bool SceneReader::boolean(const Json& value, const std::string& path) const {
    if (!value.is_boolean()) fail(inQuotes(path) + " must be true or false (got " + describe(value) + ")");
    return value.get<bool>();
}

std::string SceneReader::string(const Json& value, const std::string& path) const {
    if (!value.is_string()) fail(inQuotes(path) + " must be a string (got " + describe(value) + ")");
    return value.get<std::string>();
}

std::size_t SceneReader::choice(const Json& value, const std::string& path, KeyList choices) const {
    const std::string text = string(value, path);
    const auto it = std::find(choices.begin(), choices.end(), text);
    if (it != choices.end()) return static_cast<std::size_t>(it - choices.begin());
    std::string list;
    for (std::string_view c : choices)
        list += (list.empty() ? "" : ", ") + inQuotes(c);
    fail(inQuotes(path) + " must be one of " + list + " (got " + inQuotes(text) + ")" +
         suggestion(text, choices));
}

void SceneReader::checkModelFile(const fs::path& model, const std::string& written,
                                 const std::string& path) const {
    std::error_code error;
    const fs::file_status status = fs::status(model, error);
    std::string where = model.string() == written ? "" : " (looked for " + quotedPath(model.string()) + ")";
    if (!fs::exists(status))
        fail(inQuotes(path) + ": model file " + inQuotes(written) + " not found" + where);
    if (fs::is_directory(status))
        fail(inQuotes(path) + ": model file " + inQuotes(written) + " is a folder" + where);
    if (!fs::is_regular_file(status)) {
        fail(inQuotes(path) + ": model file " + inQuotes(written) +
             " is not a regular file (a device, a pipe or a socket)" + where);
    }
}

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

}  // namespace facet::scene_file
