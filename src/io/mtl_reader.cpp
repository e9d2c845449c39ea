#include "io/mtl_reader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <system_error>
#include <utility>

#include "base/quote.h"

namespace facet::obj {

namespace {

std::string lowerCase(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

}  // namespace

bool LibraryReader::operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                               std::map<std::string, int>* materialIds, std::string* /*warn*/,
                               std::string* /*err*/) {
    // Returning false makes tinyobjloader go on to the next name of the same mtllib line: the
    // format reads them all, tinyobjloader alone stops at the first one found.
    if (name.empty() || byName_.count(name) != 0) return false;
    read(name, materials, materialIds);
    if (libraries_[byName_[name]].problem.empty()) {
        missingRun_.clear();
        return false;
    }
    // Not found: with the names missing before it on the line, it may be one file name with blanks.
    // (A run may span two mtllib lines, as tinyobjloader does not say where a line ends; such a name
    // would have to exist as a file.)
    missingRun_ = missingRun_.empty() ? name : missingRun_ + " " + name;
    if (missingRun_ != name && byName_.count(missingRun_) == 0) {
        std::error_code error;
        if (fs::is_regular_file(objFolder_ / missingRun_, error)) {
            read(missingRun_, materials, materialIds);
            missingRun_.clear();
        }
    }
    return false;
}

void LibraryReader::read(const std::string& name, std::vector<tinyobj::material_t>* materials,
                         std::map<std::string, int>* materialIds) {
    Library library;
    library.path = objFolder_ / name;
    std::string text;
    library.problem = readTextFile(library.path, text);
    if (library.problem.empty()) {
        text = checkMtlNumbers(text, library.path.string(), library.warnings);
        std::istringstream stream(text);
        std::string ignoredWarnings, ignoredErrors;  // LoadMtl only warns of d + Tr, even when they agree
        tinyobj::LoadMtl(materialIds, materials, &stream, &ignoredWarnings, &ignoredErrors);
        scanMtl(text, library);
        materialLibrary_.resize(materials->size(), libraries_.size());
    }
    byName_[name] = libraries_.size();
    libraries_.push_back(std::move(library));
}

std::string LibraryReader::checkMtlNumbers(std::string_view text, const std::string& file,
                                           std::vector<std::string>& warnings) {
    struct Rule {
        std::string_view keyword;
        int count;               // numbers read: 3 (a colour) or 1
        double lowest, highest;  // the range allowed, both included
        bool whole;
    };
    constexpr double kAny = std::numeric_limits<float>::max();
    constexpr double kColor = kMaxColorComponent;
    constexpr Rule kRules[] = {
        {"Ka", 3, 0, kColor, false},    {"Kd", 3, 0, kColor, false},      {"Ks", 3, 0, kColor, false},
        {"Ke", 3, 0, kColor, false},    {"Kt", 3, 0, kColor, false},      {"Tf", 3, 0, kColor, false},
        {"Ns", 1, 0, kAny, false},      {"Ni", 1, -kAny, kAny, false},    {"d", 1, 0, 1, false},
        {"Tr", 1, 0, 1, false},         {"illum", 1, 0, 10, true},        {"Pr", 1, -kAny, kAny, false},
        {"Pm", 1, -kAny, kAny, false},  {"Ps", 1, -kAny, kAny, false},    {"Pc", 1, -kAny, kAny, false},
        {"Pcr", 1, -kAny, kAny, false}, {"aniso", 1, -kAny, kAny, false}, {"anisor", 1, -kAny, kAny, false},
    };
    // Warnings of statements ignored or clamped: the first few in full, then how many more.
    constexpr std::size_t kShown = 3;
    std::size_t changed = 0;
    auto warn = [&](std::size_t line, const std::string& what) {
        if (changed++ < kShown) warnings.push_back(located(file, line, what));
    };
    std::size_t strayCount = 0, strayLine = kNoLine;
    std::string strayToken;
    double strayValue = 0.0;

    std::string out;  // the text for LoadMtl: the same lines, some rewritten
    out.reserve(text.size());
    std::size_t lineNumber = 0;
    std::size_t pos = 0;
    while (pos < text.size()) {
        const std::size_t end = lineEnd(text, pos);
        const std::size_t next =
            std::min(text.size(),
                     end + ((end + 1 < text.size() && text[end] == '\r' && text[end + 1] == '\n') ? 2 : 1));
        const std::string_view line = text.substr(pos, end - pos);
        const std::string_view lineBreak = text.substr(end, next - end);
        pos = next;
        ++lineNumber;
        std::string_view s = line;
        while (!s.empty() && isBlank(s.front()))
            s.remove_prefix(1);
        // Matched as LoadMtl matches: the keyword, then a blank (so "Kd" alone is no statement).
        const Rule* rule = nullptr;
        for (const Rule& r : kRules) {
            if (s.size() > r.keyword.size() && s.substr(0, r.keyword.size()) == r.keyword &&
                isBlank(s[r.keyword.size()]))
                rule = &r;
        }
        if (rule == nullptr) {
            out.append(line).append(lineBreak);
            continue;
        }

        // The numbers LoadMtl takes (the first one or three; the rest it ignores, like the "illum 2" that
        // follows "Tr 0" on one line of cube-mcguire's MTL), as it reads them.
        Tokens tokens(s.substr(rule->keyword.size()));
        std::string_view token;
        std::string got;
        std::string numbers[3];  // each as LoadMtl is to read it
        double values[3] = {};
        int read = 0;
        bool usable = true, inRange = true, rewrite = false;
        std::size_t lineStrays = 0;  // counted once the statement is known to be used
        std::string_view lineStray;
        double lineStrayValue = 0.0;
        for (; read < rule->count; ++read) {
            if (!tokens.next(token) || token[0] == '#') break;
            if (!got.empty()) got += ' ';
            got.append(token);
            const NumberRead number = readNumber(token);
            if (number.check != NumberCheck::kFinite && number.check != NumberCheck::kStrayCharacters) {
                usable = false;
                continue;
            }
            if (number.check == NumberCheck::kStrayCharacters) {
                rewrite = true;
                if (lineStrays++ == 0) {
                    lineStray = token;
                    lineStrayValue = number.value;
                }
            }
            numbers[read] = std::string(token.substr(0, number.length));
            values[read] = number.value;
        }
        // The MTL format: "Ka r g b ... g and b are optional. If only r is specified, then g, and b are
        // assumed to be equal to r" (tinyobjloader reads them as 0).
        if (rule->count == 3 && read == 1 && usable) {
            numbers[2] = numbers[1] = numbers[0];
            values[2] = values[1] = values[0];
            read = 3;
            rewrite = true;
        }
        if (read < rule->count) usable = false;
        for (int i = 0; usable && i < rule->count; ++i) {
            if (values[i] < rule->lowest || values[i] > rule->highest ||
                (rule->whole && values[i] != std::floor(values[i])))
                inRange = false;
        }
        const std::string keyword(rule->keyword);
        if (!usable || (rule->whole && !inRange)) {
            // tinyobjloader would read what it cannot parse as 0 and 1e39 as inf: the statement is left
            // out instead, so the material keeps what it would have without it.
            const std::string expected = rule->whole        ? "a whole number from 0 to 10"
                                         : rule->count == 3 ? "three finite numbers"
                                                            : "a finite number";
            warn(lineNumber,
                 keyword + " expects " + expected + " (got " + inQuotes(got) + "); the statement is ignored");
            out.append(line.size(), ' ').append(lineBreak);
            continue;
        }
        if (lineStrays > 0 && strayCount == 0) {
            strayLine = lineNumber;
            strayToken = std::string(lineStray.substr(0, 64));
            strayValue = lineStrayValue;
        }
        strayCount += lineStrays;
        if (!inRange) {
            std::string range = rule->highest == kAny
                                    ? "must not be negative"
                                    : "must be from 0 to " + std::to_string(int(rule->highest));
            if (rule->count == 3) range += " in each component";
            std::string clamped;
            for (int i = 0; i < rule->count; ++i) {
                const double value = std::clamp(values[i], rule->lowest, rule->highest);
                if (value != values[i]) numbers[i] = numberText(value);
                clamped += (i ? " " : "") + numbers[i];
            }
            warn(lineNumber, keyword + " " + range + " (got " + inQuotes(got) + "); read as " + clamped);
            rewrite = true;
        }
        if (!rewrite) {
            out.append(line).append(lineBreak);
            continue;
        }
        // The statement as LoadMtl is to read it: the numbers, then whatever followed them.
        out += keyword;
        for (int i = 0; i < rule->count; ++i)
            out += ' ' + numbers[i];
        const std::string_view rest =
            s.substr(std::min(s.size(), std::size_t(token.data() + token.size() - s.data())));
        if (read == rule->count && !rest.empty() && token[0] != '#') out += rest;
        out.append(lineBreak);
    }
    if (changed > kShown) {
        warnings.push_back(located(file, kNoLine,
                                   std::to_string(changed - kShown) +
                                       " more statements with numbers ignored or clamped, like those above"));
    }
    if (strayCount > 0)
        warnings.push_back(strayNumberWarning(file, strayLine, strayToken, strayValue, strayCount));
    return out;
}

void LibraryReader::scanMtl(const std::string& text, Library& library) {
    struct Opacity {
        double value = 0.0;
        std::size_t line = kNoLine;
    };
    std::string material;
    Opacity d, tr;                                                  // tr.value holds 1 - Tr
    std::map<std::string, std::pair<std::size_t, int>> unusedMaps;  // statement → first line, uses
    auto checkOpacity = [&] {
        if (d.line != kNoLine && tr.line != kNoLine && std::abs(d.value - tr.value) > 1e-6) {
            std::ostringstream what;
            what << "material " << inSingleQuotes(material) << " sets opacity twice, d " << d.value
                 << " and Tr " << 1.0 - tr.value << " (opacity " << tr.value << "); d wins";
            library.warnings.push_back(located(library.path.string(), std::max(d.line, tr.line), what.str()));
        }
        d = tr = Opacity{};
    };
    std::size_t lineNumber = 0;
    std::size_t pos = 0;
    while (pos < text.size()) {
        std::size_t end = lineEnd(text, pos);
        std::string_view s = std::string_view(text).substr(pos, end - pos);
        pos = end + ((end + 1 < text.size() && text[end] == '\r' && text[end + 1] == '\n') ? 2 : 1);
        ++lineNumber;
        while (!s.empty() && isBlank(s.back()))
            s.remove_suffix(1);
        while (!s.empty() && isBlank(s.front()))
            s.remove_prefix(1);
        auto keyword = [&](std::string_view word) {
            return s.size() > word.size() && s.substr(0, word.size()) == word && isBlank(s[word.size()]);
        };
        auto number = [&](std::size_t skip) {
            return std::strtod(std::string(s.substr(skip)).c_str(), nullptr);
        };
        if (keyword("newmtl")) {
            checkOpacity();
            material = std::string(s.substr(7));
        } else if (keyword("map_Kd")) {
            library.diffuseMapLines[material] = lineNumber;
        } else if (keyword("map_Ke")) {
            library.emissionMapLines[material] = lineNumber;
        } else if (const std::string_view map = unusedMap(s); !map.empty()) {
            auto& [firstLine, materials] = unusedMaps[std::string(map)];
            if (materials++ == 0) firstLine = lineNumber;
        } else if (keyword("d")) {
            d = {number(2), lineNumber};
        } else if (keyword("Tr")) {
            tr = {1.0 - number(3), lineNumber};
        }
    }
    checkOpacity();
    // Texture statements Facet does not use: one warning each, at the first, so that an image
    // without the bumps or the specular map does not surprise.
    std::vector<std::pair<std::size_t, std::string>> byLine;
    for (const auto& [statement, use] : unusedMaps) {
        std::string what = statement + " is not supported and is ignored";
        if (use.second > 1) what += " (" + std::to_string(use.second) + " times in this file)";
        byLine.emplace_back(use.first, what);
    }
    std::sort(byLine.begin(), byLine.end());
    for (const auto& [line, what] : byLine)
        library.warnings.push_back(located(library.path.string(), line, what));
}

std::string_view LibraryReader::unusedMap(std::string_view s) {
    static constexpr std::string_view kOthers[] = {"bump", "disp", "decal", "refl", "norm"};
    const std::string_view word = s.substr(0, s.find_first_of(" \t"));
    if (word.size() == s.size()) return {};  // a statement needs a file name after it
    if (word.rfind("map_", 0) == 0) return word == "map_Kd" || word == "map_Ke" ? std::string_view{} : word;
    for (const std::string_view other : kOthers)
        if (word == other) return word;
    return {};
}

Material convertMaterial(const tinyobj::material_t& source, std::vector<std::string>& warnings,
                         const std::string& libraryFile) {
    Material m;
    m.name = source.name;
    const Material defaults;
    bool replaced = false;
    auto colour = [&](const tinyobj::real_t* rgb, glm::vec3 fallback) {
        const glm::vec3 c(rgb[0], rgb[1], rgb[2]);
        if (std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z)) return c;
        replaced = true;
        return fallback;
    };
    auto scalar = [&](float value, float fallback) {
        if (std::isfinite(value)) return value;
        replaced = true;
        return fallback;
    };
    m.ambient = colour(source.ambient, defaults.ambient);
    m.diffuse = colour(source.diffuse, defaults.diffuse);
    m.specular = colour(source.specular, defaults.specular);
    m.emission = colour(source.emission, defaults.emission);
    m.shininess = scalar(source.shininess, defaults.shininess);
    m.opacity = std::clamp(scalar(source.dissolve, defaults.opacity), 0.0f, 1.0f);
    m.ior = scalar(source.ior, defaults.ior);
    if (replaced) {
        warnings.push_back(
            located(libraryFile, kNoLine,
                    "material " + inSingleQuotes(m.name) + " has a non-finite number; its default is used"));
    }
    return m;
}

namespace {

// The texture `name` as written (relative to `folder`, or absolute), its '\\' read as '/', each
// component matched case-insensitively when not found exactly.
FoundTexture findTextureAsWritten(const fs::path& folder, const std::string& name) {
    std::error_code error;
    fs::path candidate = folder / name;
    if (fs::is_regular_file(candidate, error)) return {candidate, {}};
    std::string slashed = name;
    std::replace(slashed.begin(), slashed.end(), '\\', '/');
    candidate = folder / slashed;
    if (fs::is_regular_file(candidate, error)) return {candidate, {}};

    fs::path found = fs::path(slashed).is_absolute() ? fs::path(slashed).root_path() : folder;
    for (const fs::path& component : fs::path(slashed).relative_path()) {
        const fs::path exact = found / component;
        if (fs::exists(exact, error) || component == "." || component == "..") {
            found = exact;
            continue;
        }
        const std::string wanted = lowerCase(component.string());
        std::vector<fs::path> matches;
        for (fs::directory_iterator it(found, error), end; !error && it != end; it.increment(error))
            if (lowerCase(it->path().filename().string()) == wanted) matches.push_back(it->path());
        if (matches.empty()) return {};
        if (matches.size() > 1) {
            std::sort(matches.begin(), matches.end());
            std::string names;
            for (const fs::path& match : matches)
                names += (names.empty() ? "" : ", ") + inSingleQuotes(match.filename().string());
            return {{},
                    "differs only in case from " + names + " in " + pathInSingleQuotes(found) +
                        ", which is ambiguous"};
        }
        found = matches.front();
    }
    if (!fs::is_regular_file(found, error)) return {};
    return {found,
            "not found as written; using " + pathInSingleQuotes(found) + ", whose name differs in case"};
}

}  // namespace

FoundTexture findTexture(const fs::path& folder, const std::string& name) {
    FoundTexture found = findTextureAsWritten(folder, name);
    if (!found.path.empty() || !found.warning.empty()) return found;
    // Exporters often write the path the texture had on the author's machine ("C:\Users\…\wood.png",
    // "/home/…/wood.png"); as Blender's importer does, the file name alone is then looked for beside
    // the MTL file.
    std::string slashed = name;
    std::replace(slashed.begin(), slashed.end(), '\\', '/');
    const fs::path fileName = fs::path(slashed).filename();
    if (fileName.empty() || fileName == fs::path(slashed)) return found;
    FoundTexture beside = findTextureAsWritten(folder, fileName.string());
    if (beside.path.empty()) return found;
    beside.warning = "not found as written; using " + pathInSingleQuotes(beside.path) +
                     ", the file of that name beside the MTL file";
    return beside;
}

}  // namespace facet::obj
