// OBJ import: OBJ + MTL text → validated, welded, fan-triangulated Mesh.
// tinyobjloader parses. A pre-scan of the same text first catches what it accepts silently ("nan" and
// "inf" read as 0, index 0, relative indices before the first vertex) and maps each face to its line.
// Computed normals weight each face by its area (they sum the faces' unnormalised cross products) and
// smooth only faces within the crease angle of each other (see MeshBuilder).

#include "io/obj_import.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

#include <tiny_obj_loader.h>

#include "base/errors.h"
#include "base/quote.h"

namespace facet {
namespace {

namespace fs = std::filesystem;

// tinyobjloader::tinyobjloader is the float build; the _double one compiles with TINYOBJLOADER_USE_DOUBLE.
static_assert(std::is_same_v<tinyobj::real_t, float>, "link tinyobjloader::tinyobjloader (float build)");

constexpr std::size_t kNoLine = 0;
constexpr std::size_t kMaxCorners = 255;  // tinyobjloader keeps a face's corner count in an unsigned char
constexpr std::uint32_t kNoVertex = std::numeric_limits<std::uint32_t>::max();

// ---- Messages -------------------------------------------------------------------------------------

std::string located(const std::string& file, std::size_t line, std::string_view what) {
    std::string message = file;
    if (line != kNoLine) {
        message += ':';
        message += std::to_string(line);
    }
    message += ": ";
    message += what;
    return message;
}

[[noreturn]] void fail(const std::string& file, std::size_t line, std::string_view what) {
    throw InputError(located(file, line, what));
}

std::string inSingleQuotes(std::string_view s) {
    return inQuotes(s, '\'');
}

// A path the importer resolved: shown whole (up to PATH_MAX), escaped like every quoted value.
std::string pathInSingleQuotes(const fs::path& path) {
    std::string quoted(1, '\'');
    quoted += printable(path.string(), 4096, '\'');
    quoted += '\'';
    return quoted;
}

// ---- Files ----------------------------------------------------------------------------------------

// Why a file cannot be read, or "" when `path` is a readable regular file; `text` gets its bytes.
// Every filesystem call takes an error_code: a filesystem_error must never escape as a crash.
std::string readTextFile(const fs::path& path, std::string& text) {
    std::error_code error;
    const fs::file_status status = fs::status(path, error);
    if (status.type() == fs::file_type::not_found) return "no such file";
    if (error) return "cannot open (" + error.message() + ")";
    if (fs::is_directory(status)) return "is a directory, not a file";
    // FIFOs and devices could block or never end.
    if (!fs::is_regular_file(status)) return "is not a regular file";

    std::ifstream in(path, std::ios::binary);
    if (!in) return std::string("cannot open (") + std::strerror(errno) + ")";
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    in.seekg(0, std::ios::beg);
    if (size < 0 || !in) return std::string("cannot read (") + std::strerror(errno) + ")";
    text.assign(static_cast<std::size_t>(size), '\0');
    in.read(text.data(), size);
    if (in.gcount() != size) return std::string("cannot read (") + std::strerror(errno) + ")";
    return "";
}

std::string readObjText(const fs::path& path, const std::string& file) {
    std::string text;
    if (std::string problem = readTextFile(path, text); !problem.empty()) fail(file, kNoLine, problem);
    if (text.find('\0') != std::string::npos) fail(file, kNoLine, "contains NUL bytes: not an OBJ text file");
    return text;
}

// ---- Tokens ---------------------------------------------------------------------------------------

bool isBlank(char c) {
    return c == ' ' || c == '\t';
}

// Splits on blanks, like tinyobjloader's strspn/strcspn(" \t").
class Tokens {
  public:
    explicit Tokens(std::string_view text) : rest_(text) {}
    bool next(std::string_view& token) {
        std::size_t begin = 0;
        while (begin < rest_.size() && isBlank(rest_[begin]))
            ++begin;
        if (begin == rest_.size()) return false;
        std::size_t end = begin;
        while (end < rest_.size() && !isBlank(rest_[end]))
            ++end;
        token = rest_.substr(begin, end - begin);
        rest_.remove_prefix(end);
        return true;
    }

  private:
    std::string_view rest_;
};

enum class NumberCheck { kFinite, kNotANumber, kNotFinite };

// Accepts what strtod accepts as a whole token (plus a leading '+'), and rejects what a float cannot
// hold: tinyobjloader reads "nan" and "inf" as 0 and 1e39 as inf, so they must be caught here.
NumberCheck checkNumber(std::string_view token) {
    std::string_view digits = token;
    if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-' && digits[1] != '+')
        digits.remove_prefix(1);
    double value = 0.0;
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (end != digits.data() + digits.size() || error == std::errc::invalid_argument) {
        // MSVC prints NaN and Inf as 1.#IND, 1.#QNAN, 1.#INF.
        if (error != std::errc::invalid_argument && *end == '#') return NumberCheck::kNotFinite;
        return NumberCheck::kNotANumber;
    }
    if (error == std::errc::result_out_of_range) {
        // Out of double range: overflow is not finite, underflow is a fine zero.
        const double rounded = std::strtod(std::string(digits).c_str(), nullptr);
        return std::isinf(rounded) ? NumberCheck::kNotFinite : NumberCheck::kFinite;
    }
    if (!std::isfinite(value) || std::abs(value) > double(std::numeric_limits<float>::max())) {
        return NumberCheck::kNotFinite;
    }
    return NumberCheck::kFinite;
}

enum class IndexParse { kOk, kMalformed, kTooLarge };

IndexParse parseIndex(std::string_view token, long long& index) {
    if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), index);
    if (token.empty() || end != token.data() + token.size() || error == std::errc::invalid_argument) {
        return IndexParse::kMalformed;
    }
    if (error == std::errc::result_out_of_range) return IndexParse::kTooLarge;
    return IndexParse::kOk;
}

// One face corner as written, "v", "v/vt", "v//vn" or "v/vt/vn".
struct CornerRef {
    long long position = 0;
    long long texcoord = 0;
    long long normal = 0;
    bool hasTexcoord = false;
    bool hasNormal = false;
};

// The names tinyobjloader's SplitString gives for an mtllib line: split on ' ', '\' escapes.
std::vector<std::string> splitLibraryNames(std::string_view text) {
    std::vector<std::string> names;
    std::string name;
    bool escaping = false;
    for (char c : text) {
        if (escaping) {
            escaping = false;
        } else if (c == '\\') {
            escaping = true;
            continue;
        } else if (c == ' ') {
            if (!name.empty()) names.push_back(std::move(name));
            name.clear();
            continue;
        }
        name += c;
    }
    if (!name.empty()) names.push_back(std::move(name));
    return names;
}

// ---- Pre-scan -------------------------------------------------------------------------------------

enum class Statement : std::uint8_t {
    kVertex,
    kTexcoord,
    kNormal,
    kFace,
    kLine,
    kPoint,
    kUseMaterial,
    kLibrary
};

// A statement the pre-scan checks: [offset, offset + length) of the cleaned text.
struct ScannedStatement {
    std::size_t offset;
    std::size_t length;
    std::size_t line;  // 1-based, the first physical line when `\` continues it
    Statement kind;
};

struct UseMaterial {
    std::size_t line;
    std::string name;
};

struct LibraryStatement {
    std::size_t line;
    std::vector<std::string> names;
};

struct ObjScan {
    std::size_t positions = 0, texcoords = 0, normals = 0;  // v, vt, vn statements
    std::size_t facesRead = 0;                              // every f statement
    std::vector<std::size_t> faceLines;                     // each face with >= 3 corners, in file order
    std::vector<std::int32_t> faceMaterial;  // per such face: index into useMaterials, -1 before any
    std::size_t cornerCount = 0;             // over those faces
    std::size_t shortFaces = 0;              // f statements with < 3 corners
    std::size_t firstShortFaceLine = kNoLine;
    std::vector<UseMaterial> useMaterials;
    std::vector<LibraryStatement> libraries;
};

// Which statement tinyobjloader would see in `s` (leading blanks removed), in its own order of tests:
// a keyword then a blank, except "usemtl", which it matches as a bare prefix.
bool classify(std::string_view s, Statement& kind) {
    auto keyword = [&](std::string_view word) {
        return s.size() > word.size() && s.substr(0, word.size()) == word && isBlank(s[word.size()]);
    };
    if (keyword("v"))
        kind = Statement::kVertex;
    else if (keyword("vn"))
        kind = Statement::kNormal;
    else if (keyword("vt"))
        kind = Statement::kTexcoord;
    else if (keyword("l"))
        kind = Statement::kLine;
    else if (keyword("p"))
        kind = Statement::kPoint;
    else if (keyword("f"))
        kind = Statement::kFace;
    else if (s.substr(0, 6) == "usemtl")
        kind = Statement::kUseMaterial;
    else if (keyword("mtllib"))
        kind = Statement::kLibrary;
    else
        return false;
    return true;
}

// Pass 1: splits `text` into lines as tinyobjloader does (LF, CRLF or a lone CR) and rewrites it in
// place for tinyobjloader without moving a byte: a trailing `\` and the line break after it become
// blanks (joining the lines), so do comments starting with a `#` after a blank, and a UTF-8 BOM.
// Returns the statements pass 2 checks, and counts v/vt/vn so that pass 2 knows the file's totals.
std::vector<ScannedStatement> cleanAndSplit(std::string& text, ObjScan& scan) {
    std::vector<ScannedStatement> statements;
    statements.reserve(text.size() / 24);
    if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.replace(0, 3, "   ");

    std::size_t physicalLine = 1;
    std::size_t pos = 0;
    while (pos < text.size()) {
        const std::size_t begin = pos;
        const std::size_t firstLine = physicalLine;
        bool isComment = false;  // a comment line is never continued
        std::size_t end = pos;
        for (bool firstPiece = true;; firstPiece = false) {
            end = std::min(text.find_first_of("\r\n", pos), text.size());
            std::size_t next = end;
            if (next < text.size())
                next += (text[next] == '\r' && next + 1 < text.size() && text[next + 1] == '\n') ? 2 : 1;
            if (firstPiece) {
                std::size_t first = pos;
                while (first < end && isBlank(text[first]))
                    ++first;
                isComment = first < end && text[first] == '#';
            }
            std::size_t last = end;
            while (last > pos && isBlank(text[last - 1]))
                --last;
            ++physicalLine;
            if (isComment || last == pos || text[last - 1] != '\\') {
                pos = next;
                break;
            }
            std::fill(text.begin() + static_cast<std::ptrdiff_t>(last - 1),
                      text.begin() + static_cast<std::ptrdiff_t>(next), ' ');
            pos = next;
            if (pos == text.size()) {
                end = pos;
                break;
            }
        }

        std::size_t first = begin;
        while (first < end && isBlank(text[first]))
            ++first;
        if (first == end || text[first] == '#') continue;
        for (std::size_t i = first + 1; i < end; ++i) {
            if (text[i] == '#' && isBlank(text[i - 1])) {
                std::fill(text.begin() + static_cast<std::ptrdiff_t>(i),
                          text.begin() + static_cast<std::ptrdiff_t>(end), ' ');
                break;
            }
        }
        // Skin weights (`vw joint weight ...`) are not used by Facet, and tinyobjloader converts their joint
        // ids to int unchecked (undefined for 1e999 or 3e9): blank the statement out.
        if (end - first > 2 && text.compare(first, 2, "vw") == 0 && isBlank(text[first + 2])) {
            std::fill(text.begin() + static_cast<std::ptrdiff_t>(first),
                      text.begin() + static_cast<std::ptrdiff_t>(end), ' ');
            continue;
        }
        Statement kind;
        if (!classify(std::string_view(text).substr(first, end - first), kind)) continue;
        statements.push_back({first, end - first, firstLine, kind});
        if (kind == Statement::kVertex) ++scan.positions;
        if (kind == Statement::kTexcoord) ++scan.texcoords;
        if (kind == Statement::kNormal) ++scan.normals;
    }
    return statements;
}

// The numbers of a v/vt/vn statement: all must be finite, and there must be at least `required`.
void checkNumbers(std::string_view body, std::size_t required, const char* what, const char* needs,
                  const std::string& file, std::size_t line) {
    Tokens tokens(body);
    std::string_view token;
    std::size_t count = 0;
    while (tokens.next(token)) {
        switch (checkNumber(token)) {
            case NumberCheck::kNotANumber:
                fail(file, line, std::string(what) + " " + inSingleQuotes(token) + " is not a number");
            case NumberCheck::kNotFinite:
                fail(file, line, std::string(what) + " " + inSingleQuotes(token) + " is not a finite number");
            case NumberCheck::kFinite:
                break;
        }
        ++count;
    }
    if (count < required) fail(file, line, std::string(needs) + ", found " + std::to_string(count));
}

// One index of a corner against the counts: `before` defined above this line, `total` in the file.
void checkIndex(long long index, std::size_t before, std::size_t total, const char* what, const char* plural,
                const std::string& file, std::size_t line) {
    const std::string name = std::string("face ") + what + "index " + std::to_string(index);
    if (index == 0) fail(file, line, name + " is invalid (OBJ indices start at 1)");
    if (index > 0 && static_cast<unsigned long long>(index) > total) {
        fail(file, line,
             name + " is out of range (the file has " + std::to_string(total) + " " + plural + ")");
    }
    if (index < 0 && index < -static_cast<long long>(before)) {  // not -index: LLONG_MIN has no negation
        fail(file, line,
             name + " is out of range (" + std::to_string(before) + " " + plural +
                 " are defined before this line)");
    }
}

// Parses "v", "v/vt", "v//vn" or "v/vt/vn"; false when the corner is malformed.
bool parseCorner(std::string_view token, CornerRef& corner, const std::string& file, std::size_t line) {
    std::string_view parts[3];
    std::size_t partCount = 0;
    for (;;) {
        const std::size_t slash = token.find('/');
        if (partCount == 3) return false;
        parts[partCount++] = token.substr(0, slash);
        if (slash == std::string_view::npos) break;
        token.remove_prefix(slash + 1);
    }
    long long* targets[3] = {&corner.position, &corner.texcoord, &corner.normal};
    corner.hasTexcoord = partCount >= 2 && !(partCount == 3 && parts[1].empty());  // v//vn has none
    corner.hasNormal = partCount == 3;
    for (std::size_t i = 0; i < partCount; ++i) {
        if (i == 1 && !corner.hasTexcoord) continue;
        switch (parseIndex(parts[i], *targets[i])) {
            case IndexParse::kMalformed:
                return false;
            case IndexParse::kTooLarge:
                fail(file, line, "face index " + inSingleQuotes(parts[i]) + " is out of range");
            case IndexParse::kOk:
                break;
        }
    }
    return true;
}

// Pass 2: checks every statement in file order, so the error reported is the first in the file.
ObjScan scanObj(std::string& text, const std::string& file) {
    ObjScan scan;
    const std::vector<ScannedStatement> statements = cleanAndSplit(text, scan);
    scan.faceLines.reserve(scan.positions * 2 + 16);
    scan.faceMaterial.reserve(scan.positions * 2 + 16);

    std::size_t positions = 0, texcoords = 0, normals = 0;
    std::int32_t currentMaterial = -1;
    const std::string_view all(text);
    for (const ScannedStatement& statement : statements) {
        const std::string_view s = all.substr(statement.offset, statement.length);
        const std::size_t line = statement.line;
        switch (statement.kind) {
            case Statement::kVertex:
                checkNumbers(s.substr(1), 3, "vertex coordinate", "a vertex needs 3 coordinates (x y z)",
                             file, line);
                ++positions;
                break;
            case Statement::kTexcoord:
                checkNumbers(s.substr(2), 1, "texture coordinate", "a texture coordinate needs at least u",
                             file, line);
                ++texcoords;
                break;
            case Statement::kNormal:
                checkNumbers(s.substr(2), 3, "normal component", "a normal needs 3 components (x y z)", file,
                             line);
                ++normals;
                break;
            case Statement::kFace:
            case Statement::kLine:
            case Statement::kPoint: {
                const bool isFace = statement.kind == Statement::kFace;
                Tokens tokens(s.substr(1));
                std::string_view token;
                std::size_t corners = 0;
                while (tokens.next(token)) {
                    CornerRef corner;
                    if (!parseCorner(token, corner, file, line)) {
                        fail(file, line,
                             "malformed corner " + inSingleQuotes(token) +
                                 " (expected v, v/vt, v//vn or v/vt/vn with integer indices)");
                    }
                    if (isFace) {
                        checkIndex(corner.position, positions, scan.positions, "", "vertices", file, line);
                        if (corner.hasTexcoord) {
                            checkIndex(corner.texcoord, texcoords, scan.texcoords, "texture coordinate ",
                                       "texture coordinates", file, line);
                        }
                        if (corner.hasNormal) {
                            checkIndex(corner.normal, normals, scan.normals, "normal ", "normals", file,
                                       line);
                        }
                    } else if (corner.position == 0 || (corner.hasTexcoord && corner.texcoord == 0) ||
                               (corner.hasNormal && corner.normal == 0)) {
                        // Lines and points are not drawn, but tinyobjloader rejects index 0 in them too.
                        fail(file, line, "index 0 is invalid (OBJ indices start at 1)");
                    }
                    ++corners;
                }
                if (!isFace) break;
                ++scan.facesRead;
                if (corners > kMaxCorners) {
                    fail(file, line,
                         "a face with " + std::to_string(corners) + " corners; at most " +
                             std::to_string(kMaxCorners) + " are supported");
                }
                if (corners < 3) {
                    if (scan.shortFaces++ == 0) scan.firstShortFaceLine = line;
                    break;
                }
                scan.faceLines.push_back(line);
                scan.faceMaterial.push_back(currentMaterial);
                scan.cornerCount += corners;
                break;
            }
            case Statement::kUseMaterial: {
                // tinyobjloader's parseString: the first blank-delimited word.
                Tokens tokens(s.substr(6));
                std::string_view name;  // stays empty for a bare "usemtl"
                tokens.next(name);
                currentMaterial = static_cast<std::int32_t>(scan.useMaterials.size());
                scan.useMaterials.push_back({line, std::string(name)});
                break;
            }
            case Statement::kLibrary:
                scan.libraries.push_back({line, splitLibraryNames(s.substr(7))});
                break;
        }
    }
    return scan;
}

// ---- MTL files ------------------------------------------------------------------------------------

struct Library {
    fs::path path;
    std::string problem;  // why it was not read; empty when it was
    std::string error;    // "file:line: ..." of a number that cannot be used: loading the OBJ fails with it
    std::vector<std::string> warnings;                    // "file:line: ..." about its contents
    std::map<std::string, std::size_t> diffuseMapLines;   // material name → line of its map_Kd
    std::map<std::string, std::size_t> emissionMapLines;  // material name → line of its map_Ke
};

// Reads the MTL files an OBJ names, relative to the OBJ's folder, and remembers where each material
// came from (textures resolve against that file's folder) and where its map_Kd line is (for warnings).
class LibraryReader final : public tinyobj::MaterialReader {
  public:
    explicit LibraryReader(fs::path objFolder) : objFolder_(std::move(objFolder)) {}

    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* materialIds, std::string* /*warn*/,
                    std::string* /*err*/) override {
        // Returning false makes tinyobjloader go on to the next name of the same mtllib line: the
        // format reads them all, tinyobjloader alone stops at the first one found.
        if (name.empty() || byName_.count(name) != 0) return false;
        Library library;
        library.path = objFolder_ / name;
        std::string text;
        library.problem = readTextFile(library.path, text);
        if (library.problem.empty()) library.error = checkMtlNumbers(text, library.path.string());
        if (library.problem.empty() && library.error.empty()) {
            std::istringstream stream(text);
            std::string ignoredWarnings, ignoredErrors;  // LoadMtl only warns of d + Tr, even when they agree
            tinyobj::LoadMtl(materialIds, materials, &stream, &ignoredWarnings, &ignoredErrors);
            scanMtl(text, library);
            materialLibrary_.resize(materials->size(), libraries_.size());
        }
        byName_[name] = libraries_.size();
        libraries_.push_back(std::move(library));
        return false;
    }

    const Library* find(const std::string& name) const {
        const auto it = byName_.find(name);
        return it == byName_.end() ? nullptr : &libraries_[it->second];
    }
    // The file material `index` (tinyobjloader's numbering) came from.
    const Library* libraryOf(std::size_t material) const {
        return material < materialLibrary_.size() ? &libraries_[materialLibrary_[material]] : nullptr;
    }

  private:
    // The first numeric statement of an MTL file whose numbers cannot be used, as "file:line: ...",
    // or "". tinyobjloader reads what it cannot parse (nan, a word, a missing number) as 0 and
    // 1e39 as inf, so "Kd nan 1 1" would silently lose its red; each statement it reads numbers from
    // is checked first, its numbers as it takes them (the first one or three; the rest it ignores,
    // like the "illum 2" that follows "Tr 0" on one line of cube-mcguire's MTL).
    static std::string checkMtlNumbers(std::string_view text, const std::string& file) {
        struct Rule {
            std::string_view keyword;
            int count;               // numbers read: 3 (a colour) or 1
            double lowest, highest;  // the range allowed, both included
            bool whole;
        };
        constexpr double kAny = std::numeric_limits<float>::max();
        constexpr double kColor = kMaxColorComponent;
        constexpr Rule kRules[] = {
            {"Ka", 3, 0, kColor, false},
            {"Kd", 3, 0, kColor, false},
            {"Ks", 3, 0, kColor, false},
            {"Ke", 3, 0, kColor, false},
            {"Kt", 3, 0, kColor, false},
            {"Tf", 3, 0, kColor, false},
            {"Ns", 1, 0, kAny, false},
            {"Ni", 1, -kAny, kAny, false},
            {"d", 1, 0, 1, false},
            {"Tr", 1, 0, 1, false},
            {"illum", 1, 0, 10, true},
            {"Pr", 1, -kAny, kAny, false},
            {"Pm", 1, -kAny, kAny, false},
            {"Ps", 1, -kAny, kAny, false},
            {"Pc", 1, -kAny, kAny, false},
            {"Pcr", 1, -kAny, kAny, false},
            {"aniso", 1, -kAny, kAny, false},
            {"anisor", 1, -kAny, kAny, false},
        };
        std::size_t lineNumber = 0;
        std::size_t pos = 0;
        while (pos < text.size()) {
            const std::size_t end = std::min(text.find_first_of("\r\n", pos), text.size());
            std::string_view s = text.substr(pos, end - pos);
            pos = end + ((end + 1 < text.size() && text[end] == '\r' && text[end + 1] == '\n') ? 2 : 1);
            ++lineNumber;
            while (!s.empty() && isBlank(s.front()))
                s.remove_prefix(1);
            // Matched as LoadMtl matches: the keyword, then a blank (so "Kd" alone is no statement).
            const Rule* rule = nullptr;
            for (const Rule& r : kRules) {
                if (s.size() > r.keyword.size() && s.substr(0, r.keyword.size()) == r.keyword &&
                    isBlank(s[r.keyword.size()]))
                    rule = &r;
            }
            if (rule == nullptr) continue;

            Tokens tokens(s.substr(rule->keyword.size()));
            std::string_view token;
            std::string got;
            bool usable = true, inRange = true;
            for (int i = 0; i < rule->count; ++i) {
                if (!tokens.next(token)) {
                    usable = false;
                    break;
                }
                if (!got.empty()) got += ' ';
                got.append(token);
                if (checkNumber(token) != NumberCheck::kFinite) {
                    usable = false;
                    continue;
                }
                const double value = std::strtod(std::string(token).c_str(), nullptr);
                if (value < rule->lowest || value > rule->highest ||
                    (rule->whole && value != std::floor(value)))
                    inRange = false;
            }
            const std::string keyword(rule->keyword);
            if (!usable || (rule->whole && !inRange)) {
                const std::string expected = rule->whole        ? "a whole number from 0 to 10"
                                             : rule->count == 3 ? "three finite numbers"
                                                                : "a finite number";
                return located(file, lineNumber,
                               keyword + " expects " + expected + " (got " + inQuotes(got) + ")");
            }
            if (!inRange) {
                std::string range = rule->highest == kAny
                                        ? "must not be negative"
                                        : "must be from 0 to " + std::to_string(int(rule->highest));
                if (rule->count == 3) range += " in each component";
                return located(file, lineNumber, keyword + " " + range + " (got " + inQuotes(got) + ")");
            }
        }
        return "";
    }

    // Finds each material's map_Kd line, and d and Tr that disagree (d 1 with Tr 0 is common and
    // fine), splitting lines and names the way LoadMtl does.
    static void scanMtl(const std::string& text, Library& library) {
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
                library.warnings.push_back(
                    located(library.path.string(), std::max(d.line, tr.line), what.str()));
            }
            d = tr = Opacity{};
        };
        std::size_t lineNumber = 0;
        std::size_t pos = 0;
        while (pos < text.size()) {
            std::size_t end = std::min(text.find_first_of("\r\n", pos), text.size());
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

    // The texture statement starting `s` if Facet ignores it ("map_Ks", "bump", ...), else empty.
    // map_Kd and map_Ke are used.
    static std::string_view unusedMap(std::string_view s) {
        static constexpr std::string_view kOthers[] = {"bump", "disp", "decal", "refl", "norm"};
        const std::string_view word = s.substr(0, s.find_first_of(" \t"));
        if (word.size() == s.size()) return {};  // a statement needs a file name after it
        if (word.rfind("map_", 0) == 0)
            return word == "map_Kd" || word == "map_Ke" ? std::string_view{} : word;
        for (const std::string_view other : kOthers)
            if (word == other) return word;
        return {};
    }

    fs::path objFolder_;
    std::vector<Library> libraries_;
    std::map<std::string, std::size_t> byName_;
    std::vector<std::size_t> materialLibrary_;  // tinyobjloader material index → libraries_ index
};

// A used MTL material in facet's terms. checkMtlNumbers has refused non-finite and out-of-range
// numbers; should tinyobjloader still read one differently, the default is used and opacity clamped.
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
    if (replaced) {
        warnings.push_back(
            located(libraryFile, kNoLine,
                    "material " + inSingleQuotes(m.name) + " has a non-finite number; its default is used"));
    }
    return m;
}

std::string lowerCase(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

// A texture file found for an MTL's name, and what to say about how.
struct FoundTexture {
    fs::path path;        // empty when not found
    std::string warning;  // found by a case-insensitive match, or several such matches: why none
};

// The texture file `name` from the MTL in `folder`; a Windows path ("maps\wood.png") is tried with '/'.
// Models made on Windows or macOS often name files in another case than they have on disk
// ("SP_LUK.JPG" for sp_luk.JPG): when the exact name is missing, each component of the path that is
// missing is matched without regard to case in its folder, if exactly one entry matches.
FoundTexture findTexture(const fs::path& folder, const std::string& name) {
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

// ---- Mesh building --------------------------------------------------------------------------------

struct CornerKey {
    std::int32_t position, texcoord, normal;  // tinyobjloader indices, -1 when absent
    bool operator==(const CornerKey&) const = default;
};

struct CornerKeyHash {
    std::size_t operator()(const CornerKey& k) const noexcept {
        std::uint64_t h = std::uint32_t(k.position);
        h = (h * 0x9E3779B97F4A7C15ull) ^ std::uint32_t(k.texcoord);
        h = (h * 0xC2B2AE3D27D4EB4Full) ^ std::uint32_t(k.normal);
        // splitmix64's finaliser: neighbouring indices must not share buckets.
        h ^= h >> 30;
        h *= 0xBF58476D1CE4E5B9ull;
        h ^= h >> 27;
        h *= 0x94D049BB133111EBull;
        h ^= h >> 31;
        return static_cast<std::size_t>(h);
    }
};

// Builds the mesh in two steps. addPolygon fan-triangulates and welds corners on their (position,
// normal, texcoord) index triple into "base" vertices, and hands out corner ids, not vertex indices.
// finishNormals then gives each base vertex without a file normal its computed normal, one per
// smoothing group of the faces at its position: a base vertex whose corners fall into several groups
// is split, one vertex per group. Vertices are numbered in the order their first corner was added,
// so with nothing split (crease angle 180) the output is the plain welded mesh.
//
// The crease rule: a corner's normal is the normalised sum of the vector areas (unnormalised cross
// products) of the faces around its position whose unit normal is within the crease angle of its own
// face's. A face is the file's polygon: its vector area is the sum of its fan triangles' cross
// products, its direction that, normalised; every position of the polygon gets the whole area once.
// Faces count whether or not their corners have file normals; the face itself always counts.
//
// Cost. Only the faces at one position are compared, never all faces. With k faces at a position the
// exact rule compares every pair, O(k²) dot products, giving each face a 64-bit mask of the faces its
// corners' sum includes; corners with equal masks share a vertex. That is done while k <= kExactFaces
// (64): at most 32 dot products per (face, position) pair over the mesh, typically k ~ 6, so O(n) in
// the faces. At 180° every position is one group, summed in O(k). A crowded position (a fan apex, a
// pole with thousands of faces) below 180° is clustered greedily instead: in file order each face
// joins the earliest cluster whose first face is within the crease angle of it, or starts a new one;
// all faces of a cluster share one sum and vertex. A hash grid over the clusters' unit normals, with
// cells as wide as the chord of the crease angle, finds the candidates in the 27 cells around a
// normal, so each face costs O(1) (at most a few clusters fit in a cell, as their first faces are more
// than the crease angle apart): O(k) per crowded position. That differs from the exact rule only where
// "within the crease angle" is not transitive.
class MeshBuilder {
  public:
    MeshBuilder(const tinyobj::attrib_t& attrib, std::size_t cornerCount, float creaseAngleDegrees)
        : attrib_(attrib),
          smoothAll_(creaseAngleDegrees >= 180.0f),
          creaseCos_(std::cos(double(creaseAngleDegrees) * (std::numbers::pi / 180.0)) - kCosTolerance),
          cellSize_(2.0 * std::sin(double(creaseAngleDegrees) * (std::numbers::pi / 360.0)) * 1.0001 + 1e-5) {
        const std::size_t positionCount = attrib.vertices.size() / 3;
        plainVertex_.assign(positionCount, kNoVertex);
        welded_.reserve(cornerCount / 2 + 16);
        baseVertices_.reserve(cornerCount / 3 + 16);
        cornerVertex_.reserve(cornerCount);  // exact for triangles; polygons have more
        cornerIncidence_.reserve(cornerCount);
        incidencePosition_.reserve(cornerCount);
        incidenceFace_.reserve(cornerCount);

        // File normals, normalised once; a zero-length one counts as absent.
        const std::size_t normalCount = attrib.normals.size() / 3;
        fileNormals_.resize(normalCount);
        usableNormal_.assign(normalCount, false);
        for (std::size_t i = 0; i < normalCount; ++i) {
            const glm::dvec3 n(attrib.normals[3 * i], attrib.normals[3 * i + 1], attrib.normals[3 * i + 2]);
            const double length = glm::length(n);
            if (length > 0.0 && std::isfinite(length)) {
                fileNormals_[i] = glm::vec3(n / length);
                usableNormal_[i] = true;
            }
        }
    }

    glm::dvec3 position(std::size_t index) const {
        const std::size_t i = index * 3;
        return {attrib_.vertices[i], attrib_.vertices[i + 1], attrib_.vertices[i + 2]};
    }

    // Adds one polygon: fan-triangulated, degenerate triangles counted, the rest into `out` as corner
    // ids (vertexOf maps them to vertices after finishNormals). Returns the number of triangles kept.
    std::size_t addPolygon(const tinyobj::index_t* corners, std::size_t count,
                           std::vector<std::uint32_t>& out, std::size_t& degenerate) {
        kept_.clear();
        glm::dvec3 area(0.0);  // the polygon's vector area ×2: the sum of its fan triangles' cross products
        const glm::dvec3 p0 = position(std::size_t(corners[0].vertex_index));
        for (std::size_t i = 1; i + 1 < count; ++i) {
            const tinyobj::index_t &a = corners[0], &b = corners[i], &c = corners[i + 1];
            if (a.vertex_index == b.vertex_index || b.vertex_index == c.vertex_index ||
                a.vertex_index == c.vertex_index) {
                ++degenerate;
                continue;
            }
            // Doubles: a float cross product of 1e30-sized coordinates would overflow.
            const glm::dvec3 cross = glm::cross(position(std::size_t(b.vertex_index)) - p0,
                                                position(std::size_t(c.vertex_index)) - p0);
            if (cross == glm::dvec3(0.0)) {
                ++degenerate;
                continue;
            }
            area += cross;
            kept_.push_back(i);
        }
        if (kept_.empty()) return 0;

        // Every position of the polygon gets its whole area once, whichever fan triangles it is in, so
        // that a cube's corner normal is the symmetric (1,1,1)/√3: one incidence per distinct position.
        const auto face = static_cast<std::uint32_t>(faceAreas_.size());
        faceAreas_.push_back(area);
        polygonIncidence_.resize(count);
        for (std::size_t i = 0; i < count; ++i) {
            std::size_t j = 0;
            while (corners[j].vertex_index != corners[i].vertex_index)
                ++j;
            if (j < i) {
                polygonIncidence_[i] = polygonIncidence_[j];
                continue;
            }
            polygonIncidence_[i] = static_cast<std::uint32_t>(incidenceFace_.size());
            incidencePosition_.push_back(static_cast<std::uint32_t>(corners[i].vertex_index));
            incidenceFace_.push_back(face);
        }
        for (const std::size_t second : kept_) {
            for (const std::size_t c : {std::size_t(0), second, second + 1}) {
                out.push_back(static_cast<std::uint32_t>(cornerVertex_.size()));
                cornerVertex_.push_back(baseVertexFor(corners[c]));
                cornerIncidence_.push_back(polygonIncidence_[c]);
            }
        }
        return kept_.size();
    }

    // Groups the faces around each position that needs a computed normal, then numbers the final
    // vertices: a base vertex per smoothing group of its corners. Counts the computed normals and the
    // vertices split off by the crease angle.
    void finishNormals(std::size_t& normalsComputed, std::size_t& creaseSplits) {
        const std::vector<std::uint32_t> groupOf = groupFaces();

        // Final vertices, numbered by first corner. A base vertex's first group keeps it; further
        // groups (rare, at hard edges) are found through a map.
        const std::size_t baseCount = baseVertices_.size();
        std::vector<std::uint32_t> firstVertex(baseCount, kNoVertex), firstGroup(baseCount, kNoGroup);
        std::unordered_map<std::uint64_t, std::uint32_t> split;
        vertices_.reserve(baseCount);
        normalsComputed = creaseSplits = 0;
        for (std::size_t corner = 0; corner < cornerVertex_.size(); ++corner) {
            const std::uint32_t base = cornerVertex_[corner];
            const std::uint32_t group = computedNormal_[base] ? groupOf[cornerIncidence_[corner]] : kNoGroup;
            std::uint32_t* slot = &firstVertex[base];
            if (*slot != kNoVertex && firstGroup[base] != group) {
                slot = &split.try_emplace((std::uint64_t(base) << 32) | group, kNoVertex).first->second;
                if (*slot == kNoVertex) ++creaseSplits;
            }
            if (*slot == kNoVertex) {
                if (firstVertex[base] == kNoVertex) firstGroup[base] = group;
                *slot = static_cast<std::uint32_t>(vertices_.size());
                MeshVertex vertex = baseVertices_[base];
                if (group != kNoGroup) {
                    // Opposite faces can cancel (a two-sided sheet): then this corner's triangle's normal.
                    vertex.normal = groupNormals_[group] != glm::vec3(0.0f) ? groupNormals_[group]
                                                                            : triangleNormal(corner / 3);
                    ++normalsComputed;
                }
                vertices_.push_back(vertex);
            }
            cornerVertex_[corner] = *slot;
        }
    }

    // The vertex of a corner id that addPolygon put in `out`; valid after finishNormals.
    std::uint32_t vertexOf(std::uint32_t corner) const { return cornerVertex_[corner]; }
    std::vector<MeshVertex> takeVertices() { return std::move(vertices_); }
    bool hasTexcoords() const { return hasTexcoords_; }

  private:
    // Faces whose normals' cosine falls short of the crease angle's by at most this still count as
    // within it (an angle of about 1e-6 radians at 0°): rounding must not split coplanar faces.
    static constexpr double kCosTolerance = 1e-12;
    static constexpr std::size_t kExactFaces = 64;  // the faces a 64-bit mask holds
    static constexpr std::uint32_t kNoGroup = std::numeric_limits<std::uint32_t>::max();

    // A face's unit normal, or zero when its vector area is zero (opposite halves cancelling).
    static glm::dvec3 unitNormal(const glm::dvec3& area) {
        const double length = glm::length(area);
        return length > 0.0 && std::isfinite(length) ? area / length : glm::dvec3(0.0);
    }

    // Whether faces with unit normals `a` and `b` (zero: no direction) are smoothed together. A face
    // without a direction is smoothed with others only at 180°.
    bool within(const glm::dvec3& a, const glm::dvec3& b) const {
        return smoothAll_ || (a != glm::dvec3(0.0) && b != glm::dvec3(0.0) && glm::dot(a, b) >= creaseCos_);
    }

    // The normal of kept triangle t (corners 3t, 3t+1, 3t+2 as added), as its faceNormal was computed.
    glm::vec3 triangleNormal(std::size_t t) const {
        const auto at = [&](std::size_t corner) {
            return position(incidencePosition_[cornerIncidence_[corner]]);
        };
        const glm::dvec3 p0 = at(3 * t);
        return glm::vec3(glm::normalize(glm::cross(at(3 * t + 1) - p0, at(3 * t + 2) - p0)));
    }

    // Per incidence (face at a position) its smoothing group, an index into groupNormals_; kNoGroup
    // at positions where every vertex has a file normal.
    std::vector<std::uint32_t> groupFaces() {
        // Incidences by position (counting sort; stable, so each position's faces stay in file order),
        // only at positions with a computed normal.
        const std::size_t positionCount = plainVertex_.size();
        std::vector<char> needed(positionCount, 0);
        for (std::size_t v = 0; v < baseVertices_.size(); ++v) {
            if (computedNormal_[v]) needed[basePosition_[v]] = 1;
        }
        std::vector<std::uint32_t> start(positionCount + 1, 0);
        for (const std::uint32_t p : incidencePosition_) {
            if (needed[p]) ++start[p + 1];
        }
        for (std::size_t p = 0; p < positionCount; ++p)
            start[p + 1] += start[p];
        std::vector<std::uint32_t> byPosition(start[positionCount]);
        {
            std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
            for (std::size_t i = 0; i < incidencePosition_.size(); ++i) {
                const std::uint32_t p = incidencePosition_[i];
                if (needed[p]) byPosition[next[p]++] = static_cast<std::uint32_t>(i);
            }
        }

        std::vector<std::uint32_t> groupOf(incidencePosition_.size(), kNoGroup);
        groupNormals_.clear();
        for (std::size_t p = 0; p < positionCount; ++p) {
            const std::uint32_t* incidences = byPosition.data() + start[p];
            const std::size_t k = start[p + 1] - start[p];
            if (k == 0) continue;
            if (smoothAll_) {
                smoothTogether(incidences, k, groupOf);
                continue;
            }
            units_.resize(k);
            for (std::size_t j = 0; j < k; ++j)
                units_[j] = unitNormal(faceAreas_[incidenceFace_[incidences[j]]]);
            if (k <= kExactFaces)
                groupExactly(incidences, k, groupOf);
            else
                groupByClusters(incidences, k, groupOf);
        }
        return groupOf;
    }

    // Crease angle 180: all k faces at a position in one group, summed in file order.
    void smoothTogether(const std::uint32_t* incidences, std::size_t k, std::vector<std::uint32_t>& groupOf) {
        glm::dvec3 sum(0.0);
        for (std::size_t j = 0; j < k; ++j)
            sum += faceAreas_[incidenceFace_[incidences[j]]];
        const auto group = static_cast<std::uint32_t>(groupNormals_.size());
        groupNormals_.push_back(normalOfSum(sum));
        for (std::size_t j = 0; j < k; ++j)
            groupOf[incidences[j]] = group;
    }

    // The exact rule for k <= 64 faces at a position: one group per distinct set of faces summed.
    void groupExactly(const std::uint32_t* incidences, std::size_t k, std::vector<std::uint32_t>& groupOf) {
        masks_.assign(k, 0);
        for (std::size_t j = 0; j < k; ++j) {
            masks_[j] |= std::uint64_t(1) << j;
            for (std::size_t l = j + 1; l < k; ++l) {
                if (within(units_[j], units_[l])) {
                    masks_[j] |= std::uint64_t(1) << l;
                    masks_[l] |= std::uint64_t(1) << j;
                }
            }
        }
        for (std::size_t j = 0; j < k; ++j) {
            std::size_t same = 0;
            while (masks_[same] != masks_[j])
                ++same;
            if (same < j) {
                groupOf[incidences[j]] = groupOf[incidences[same]];
                continue;
            }
            glm::dvec3 sum(0.0);  // in file order, the order the faces were added in
            for (std::size_t l = 0; l < k; ++l) {
                if ((masks_[j] >> l) & 1) sum += faceAreas_[incidenceFace_[incidences[l]]];
            }
            groupOf[incidences[j]] = static_cast<std::uint32_t>(groupNormals_.size());
            groupNormals_.push_back(normalOfSum(sum));
        }
    }

    // Greedy clusters for a crowded position (see the class comment).
    void groupByClusters(const std::uint32_t* incidences, std::size_t k,
                         std::vector<std::uint32_t>& groupOf) {
        struct Cluster {
            glm::dvec3 unit;  // its first face's
            glm::dvec3 sum;
        };
        std::vector<Cluster> clusters;
        std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;  // cell → clusters starting in it
        const auto cellOf = [&](const glm::dvec3& n) {
            // |n| <= 1 and cellSize_ >= 1e-5: each coordinate's cell fits 21 bits after the offset.
            return glm::ivec3(glm::floor(n / cellSize_)) + glm::ivec3(1 << 20);
        };
        const auto key = [](glm::ivec3 c) {
            return std::uint64_t(c.x) << 42 | std::uint64_t(c.y) << 21 | std::uint64_t(c.z);
        };
        std::vector<std::uint32_t> clusterOf(k);
        for (std::size_t j = 0; j < k; ++j) {
            const glm::dvec3& n = units_[j];
            std::uint32_t found = kNoGroup;
            if (n != glm::dvec3(0.0)) {
                const glm::ivec3 cell = cellOf(n);
                for (int dx = -1; dx <= 1; ++dx) {
                    for (int dy = -1; dy <= 1; ++dy) {
                        for (int dz = -1; dz <= 1; ++dz) {
                            const auto it = grid.find(key(cell + glm::ivec3(dx, dy, dz)));
                            if (it == grid.end()) continue;
                            for (const std::uint32_t c : it->second) {
                                if (c < found && within(clusters[c].unit, n)) found = c;
                            }
                        }
                    }
                }
            }
            if (found == kNoGroup) {
                found = static_cast<std::uint32_t>(clusters.size());
                clusters.push_back({n, glm::dvec3(0.0)});
                if (n != glm::dvec3(0.0)) grid[key(cellOf(n))].push_back(found);
            }
            clusters[found].sum += faceAreas_[incidenceFace_[incidences[j]]];
            clusterOf[j] = found;
        }
        const auto firstGroup = static_cast<std::uint32_t>(groupNormals_.size());
        for (const Cluster& cluster : clusters)
            groupNormals_.push_back(normalOfSum(cluster.sum));
        for (std::size_t j = 0; j < k; ++j)
            groupOf[incidences[j]] = firstGroup + clusterOf[j];
    }

    // A group's normal: its normalised sum, or zero when the faces cancel.
    static glm::vec3 normalOfSum(const glm::dvec3& sum) {
        const double length = glm::length(sum);
        return length > 0.0 && std::isfinite(length) ? glm::vec3(sum / length) : glm::vec3(0.0f);
    }

    std::uint32_t baseVertexFor(const tinyobj::index_t& corner) {
        int normal = corner.normal_index;
        if (normal >= 0 && !usableNormal_[static_cast<std::size_t>(normal)]) normal = -1;
        const int texcoord = corner.texcoord_index;
        const std::size_t positionIndex = static_cast<std::size_t>(corner.vertex_index);

        // Most meshes have positions only: an array beats hashing there.
        std::uint32_t* slot;
        if (texcoord < 0 && normal < 0) {
            slot = &plainVertex_[positionIndex];
        } else {
            const auto [it, inserted] =
                welded_.try_emplace(CornerKey{corner.vertex_index, texcoord, normal}, kNoVertex);
            slot = &it->second;
        }
        if (*slot != kNoVertex) return *slot;

        MeshVertex vertex;
        vertex.position = glm::vec3(position(positionIndex));
        vertex.uv = glm::vec2(0.0f);
        if (texcoord >= 0) {
            const std::size_t t = static_cast<std::size_t>(texcoord) * 2;
            vertex.uv = glm::vec2(attrib_.texcoords[t], attrib_.texcoords[t + 1]);
            hasTexcoords_ = true;
        }
        vertex.normal = normal >= 0 ? fileNormals_[static_cast<std::size_t>(normal)] : glm::vec3(0.0f);
        *slot = static_cast<std::uint32_t>(baseVertices_.size());
        baseVertices_.push_back(vertex);
        basePosition_.push_back(static_cast<std::uint32_t>(positionIndex));
        computedNormal_.push_back(normal < 0);
        return *slot;
    }

    const tinyobj::attrib_t& attrib_;
    const bool smoothAll_;    // crease angle 180: one group per position
    const double creaseCos_;  // within the crease angle: dot of the unit normals >= this
    const double cellSize_;   // of the cluster grid: the chord of the crease angle, with a margin
    std::vector<glm::vec3> fileNormals_;
    std::vector<bool> usableNormal_;
    std::vector<std::uint32_t> plainVertex_;  // per position: its base vertex without texcoord or normal
    std::unordered_map<CornerKey, std::uint32_t, CornerKeyHash> welded_;
    std::vector<MeshVertex> baseVertices_;     // welded on the index triple, computed normals still zero
    std::vector<std::uint32_t> basePosition_;  // per base vertex: its position index
    std::vector<bool> computedNormal_;         // per base vertex: no usable file normal
    std::vector<glm::dvec3> faceAreas_;        // per face (kept polygon): its vector area ×2
    std::vector<std::uint32_t> incidencePosition_, incidenceFace_;  // per (face, distinct position of it)
    std::vector<std::uint32_t> cornerVertex_;     // per corner id: its base vertex; its vertex once finished
    std::vector<std::uint32_t> cornerIncidence_;  // per corner id: its (face, position) incidence
    std::vector<glm::vec3> groupNormals_;         // per smoothing group; zero when its faces cancel
    std::vector<MeshVertex> vertices_;            // the final vertices
    std::vector<std::size_t> kept_;  // scratch: the kept fan triangles (0, i, i + 1) of a polygon
    std::vector<std::uint32_t> polygonIncidence_;  // scratch: per polygon corner, its incidence
    std::vector<glm::dvec3> units_;                // scratch: unit normals of the faces at one position
    std::vector<std::uint64_t> masks_;  // scratch: per face at a position, the faces it smooths with
    bool hasTexcoords_ = false;
};

// Any value tinyobjloader produced that the pre-scan did not foresee (a bug, not bad input) is still
// refused rather than drawn as NaN.
void checkFinite(const std::vector<tinyobj::real_t>& values, std::size_t stride, const char* what,
                 const std::string& file) {
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (!std::isfinite(values[i])) {
            fail(file, kNoLine, std::string(what) + " " + std::to_string(i / stride + 1) + " is not finite");
        }
    }
}

}  // namespace

Mesh loadObj(const std::filesystem::path& path, const ObjOptions& options) {
    const float crease = options.creaseAngleDegrees;
    if (!(crease >= 0.0f && crease <= 180.0f)) {  // NaN fails both
        throw std::invalid_argument("loadObj: creaseAngleDegrees must be within [0, 180], not " +
                                    std::to_string(crease));
    }
    const std::string file = path.string();

    // 1. Read and pre-scan; `text` is rewritten for tinyobjloader (continuations, comments).
    std::string text = readObjText(path, file);
    const ObjScan scan = scanObj(text, file);

    // 2. Parse with tinyobjloader, untriangulated: facet fans, and faces stay one-to-one with lines.
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> tinyMaterials;
    std::string tinyWarnings, tinyErrors;  // its warnings repeat what the pre-scan reports better
    LibraryReader libraries(path.parent_path());
    std::istringstream stream(std::move(text));
    if (!tinyobj::LoadObj(&attrib, &shapes, &tinyMaterials, &tinyWarnings, &tinyErrors, &stream, &libraries,
                          /*triangulate=*/false, /*default_vcols_fallback=*/false)) {
        std::string what = tinyErrors.substr(0, tinyErrors.find('\n'));
        fail(file, kNoLine, what.empty() ? "tinyobjloader cannot parse it" : what);
    }
    checkFinite(attrib.vertices, 3, "vertex", file);
    checkFinite(attrib.texcoords, 2, "texture coordinate", file);
    checkFinite(attrib.normals, 3, "normal", file);

    // The line map is only trusted when tinyobjloader saw the same faces as the pre-scan.
    std::size_t faceCount = 0, cornerCount = 0;
    for (const tinyobj::shape_t& shape : shapes) {
        faceCount += shape.mesh.num_face_vertices.size();
        cornerCount += shape.mesh.indices.size();
    }
    const bool linesTrusted = faceCount == scan.faceLines.size() && cornerCount == scan.cornerCount &&
                              attrib.vertices.size() == 3 * scan.positions &&
                              attrib.texcoords.size() == 2 * scan.texcoords &&
                              attrib.normals.size() == 3 * scan.normals;

    Mesh mesh;
    mesh.stats.facesRead = scan.facesRead;
    mesh.stats.degenerateSkipped = scan.shortFaces;
    std::vector<std::string>& warnings = mesh.warnings;

    // 3. MTL problems, each reported once at the mtllib line naming the file.
    std::set<std::string> reported;
    for (const LibraryStatement& statement : scan.libraries) {
        if (statement.names.empty())
            warnings.push_back(located(file, statement.line, "mtllib names no file"));
        for (const std::string& name : statement.names) {
            const Library* library = libraries.find(name);
            if (library == nullptr || !reported.insert(name).second) continue;
            if (!library->error.empty()) throw InputError(library->error);
            if (!library->problem.empty()) {
                warnings.push_back(located(file, statement.line,
                                           "material library " + inSingleQuotes(name) + ": " +
                                               library->problem +
                                               "; its materials fall back to the default"));
            }
            warnings.insert(warnings.end(), library->warnings.begin(), library->warnings.end());
        }
    }
    if (scan.shortFaces > 0) {
        warnings.push_back(
            located(file, scan.firstShortFaceLine,
                    std::to_string(scan.shortFaces) + " face(s) with fewer than 3 corners skipped"));
    }

    // 4. Triangulate, weld and bucket the triangles by material, in first-use order.
    MeshBuilder builder(attrib, cornerCount, crease);
    std::vector<int> meshMaterialOf(tinyMaterials.size() + 1, -1);  // [0]: no material; [i + 1]: material i
    std::vector<int> tinyMaterialOf;  // mesh material → tinyobjloader's, or -1
    std::vector<std::vector<std::uint32_t>> buckets;
    std::set<std::string> unknownReported;
    std::size_t face = 0;
    for (const tinyobj::shape_t& shape : shapes) {
        const tinyobj::mesh_t& m = shape.mesh;
        std::size_t offset = 0;
        for (std::size_t f = 0; f < m.num_face_vertices.size(); ++f, ++face) {
            const std::size_t count = m.num_face_vertices[f];
            const std::size_t line = linesTrusted ? scan.faceLines[face] : kNoLine;
            if (offset + count > m.indices.size())
                fail(file, line, "face corners do not match tinyobjloader's");
            const tinyobj::index_t* corners = &m.indices[offset];
            offset += count;
            if (count < 3) {  // tinyobjloader drops these itself; kept for safety
                ++mesh.stats.degenerateSkipped;
                continue;
            }
            // The pre-scan checked every index; this keeps a mismatch from reading out of bounds.
            for (std::size_t c = 0; c < count; ++c) {
                const tinyobj::index_t& k = corners[c];
                if (k.vertex_index < 0 || std::size_t(k.vertex_index) >= attrib.vertices.size() / 3 ||
                    k.texcoord_index < -1 ||
                    (k.texcoord_index >= 0 && std::size_t(k.texcoord_index) >= attrib.texcoords.size() / 2) ||
                    k.normal_index < -1 ||
                    (k.normal_index >= 0 && std::size_t(k.normal_index) >= attrib.normals.size() / 3)) {
                    fail(file, line, "face index out of range");
                }
            }

            int tinyMaterial = f < m.material_ids.size() ? m.material_ids[f] : -1;
            if (tinyMaterial < 0 || std::size_t(tinyMaterial) >= tinyMaterials.size()) {
                tinyMaterial = -1;
                const std::int32_t use = linesTrusted ? scan.faceMaterial[face] : -1;
                if (use >= 0) {
                    const UseMaterial& statement = scan.useMaterials[std::size_t(use)];
                    if (unknownReported.insert(statement.name).second) {
                        warnings.push_back(located(file, statement.line,
                                                   "unknown material " + inSingleQuotes(statement.name) +
                                                       "; using the default material"));
                    }
                }
            }
            int& meshMaterial = meshMaterialOf[std::size_t(tinyMaterial + 1)];
            if (meshMaterial < 0) {
                meshMaterial = static_cast<int>(buckets.size());
                buckets.emplace_back();
                tinyMaterialOf.push_back(tinyMaterial);
            }
            mesh.stats.trianglesKept += builder.addPolygon(corners, count, buckets[std::size_t(meshMaterial)],
                                                           mesh.stats.degenerateSkipped);
        }
    }

    if (mesh.stats.trianglesKept == 0) {
        fail(file, kNoLine,
             scan.facesRead == 0 ? "no triangles to draw (the file has no faces)"
                                 : "no triangles to draw (all " + std::to_string(scan.facesRead) +
                                       " faces are degenerate or have fewer than 3 corners)");
    }

    // 5. Normals (splitting vertices at creases), then the index buffer: one part per material.
    builder.finishNormals(mesh.stats.normalsComputed, mesh.stats.creaseSplits);
    mesh.hasTexcoords = builder.hasTexcoords();
    mesh.vertices = builder.takeVertices();
    mesh.indices.reserve(mesh.stats.trianglesKept * 3);
    for (std::size_t b = 0; b < buckets.size(); ++b) {
        if (buckets[b].empty()) continue;  // a material whose faces were all degenerate
        MeshPart part;
        part.firstIndex = static_cast<std::uint32_t>(mesh.indices.size());
        part.indexCount = static_cast<std::uint32_t>(buckets[b].size());
        part.material = static_cast<std::uint32_t>(mesh.materials.size());
        for (const std::uint32_t corner : buckets[b])
            mesh.indices.push_back(builder.vertexOf(corner));
        mesh.parts.push_back(part);

        // 6. The part's material, its texture resolved against its own MTL file's folder.
        const int tinyMaterial = tinyMaterialOf[b];
        if (tinyMaterial < 0) {
            mesh.materials.emplace_back();
            continue;
        }
        const tinyobj::material_t& source = tinyMaterials[std::size_t(tinyMaterial)];
        const Library* library = libraries.libraryOf(std::size_t(tinyMaterial));
        const std::string libraryFile = library ? library->path.string() : file;
        Material material = convertMaterial(source, warnings, libraryFile);
        const fs::path folder = library ? library->path.parent_path() : path.parent_path();
        // A texture statement's file, or a warning why there is none.
        const auto resolve = [&](const std::string& statement, const std::string& texname, std::size_t line) {
            if (texname.empty()) {
                // tinyobjloader's "-o u [v [w]]" and "-s", "-t" eat the file name when given fewer numbers.
                if (line != kNoLine)
                    warnings.push_back(located(libraryFile, line,
                                               statement + " of material " + inSingleQuotes(source.name) +
                                                   " names no texture file that could be read; drawing "
                                                   "without it"));
                return fs::path();
            }
            const FoundTexture found = findTexture(folder, texname);
            const std::string texture =
                "texture " + inSingleQuotes(texname) + " of material " + inSingleQuotes(source.name);
            if (found.path.empty())
                warnings.push_back(located(libraryFile, line,
                                           texture +
                                               (found.warning.empty() ? " not found" : " " + found.warning) +
                                               "; drawing without it"));
            else if (!found.warning.empty())
                warnings.push_back(located(libraryFile, line, texture + " " + found.warning));
            return found.path;
        };
        const auto lineOf = [&](std::map<std::string, std::size_t> Library::*lines) {
            if (!library) return kNoLine;
            const auto it = (library->*lines).find(source.name);
            return it == (library->*lines).end() ? kNoLine : it->second;
        };
        material.diffuseTexture =
            resolve("map_Kd", source.diffuse_texname, lineOf(&Library::diffuseMapLines));
        material.emissionTexture =
            resolve("map_Ke", source.emissive_texname, lineOf(&Library::emissionMapLines));
        mesh.materials.push_back(std::move(material));
    }

    // 7. Bounds: every vertex is used, as vertices are only made for kept triangles.
    mesh.boundsMin = mesh.boundsMax = mesh.vertices.front().position;
    for (const MeshVertex& v : mesh.vertices) {
        mesh.boundsMin = glm::min(mesh.boundsMin, v.position);
        mesh.boundsMax = glm::max(mesh.boundsMax, v.position);
    }
    return mesh;
}

}  // namespace facet
