#include "io/obj_scan.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <string_view>
#include <utility>

#include "base/quote.h"

namespace facet::obj {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMaxCorners = 255;  // tinyobjloader keeps a face's corner count in an unsigned char

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
            end = lineEnd(text, pos);
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

// The numbers of a v/vt/vn statement: all must be finite, and there must be at least `required`. A number
// with stray characters after it ("0.0000c", "1.5,") is read as the number, as tinyobjloader reads it,
// and counted for one warning; a decimal comma ("2,5", read as 2 by tinyobjloader) would bend every
// coordinate of the model, so it is refused, as are words, NaN and Inf (read as 0 by tinyobjloader).
void checkNumbers(std::string_view body, std::size_t required, const char* what, const char* needs,
                  const std::string& file, std::size_t line, ObjScan& scan) {
    Tokens tokens(body);
    std::string_view token;
    std::size_t count = 0;
    while (tokens.next(token)) {
        const NumberRead read = readNumber(token);
        switch (read.check) {
            case NumberCheck::kNotANumber:
                fail(file, line, std::string(what) + " " + inSingleQuotes(token) + " is not a number");
            case NumberCheck::kNotFinite:
                fail(file, line, std::string(what) + " " + inSingleQuotes(token) + " is not a finite number");
            case NumberCheck::kDecimalComma: {
                std::string pointed(token);
                pointed[read.length] = '.';
                fail(file, line,
                     std::string(what) + " " + inSingleQuotes(token) +
                         " has a decimal comma; OBJ numbers are written with a point, like " +
                         inSingleQuotes(pointed));
            }
            case NumberCheck::kStrayCharacters:
                if (scan.strayNumbers++ == 0) {
                    scan.firstStrayLine = line;
                    scan.firstStray = std::string(token.substr(0, 64));
                    scan.firstStrayValue = read.value;
                }
                break;
            case NumberCheck::kFinite:
                break;
        }
        ++count;
    }
    if (count < required) fail(file, line, std::string(needs) + ", found " + std::to_string(count));
}

// Why one index of a corner is not valid against the counts, `before` defined above this line and `total`
// in the file, or "" when it is valid.
std::string indexProblem(long long index, std::size_t before, std::size_t total, const char* what,
                         const char* plural) {
    const bool inRange = index > 0 ? static_cast<unsigned long long>(index) <= total
                                   : index < 0 && index >= -static_cast<long long>(before);
    if (inRange) return {};  // the message below is only built for a bad index (this runs per corner)
    const std::string name = std::string("face ") + what + "index " + std::to_string(index);
    if (index == 0) return name + " is invalid (OBJ indices start at 1)";
    if (index > 0)
        return name + " is out of range (the file has " + std::to_string(total) + " " + plural + ")";
    // index < -before; not -index: LLONG_MIN has no negation
    return name + " is out of range (" + std::to_string(before) + " " + plural +
           " are defined before this line)";
}

void checkIndex(long long index, std::size_t before, std::size_t total, const char* what, const char* plural,
                const std::string& file, std::size_t line) {
    if (std::string problem = indexProblem(index, before, total, what, plural); !problem.empty())
        fail(file, line, problem);
}

// A texture coordinate or normal index: out of range, the corner is drawn without it (as Blender does),
// counted for one warning; 0 is refused, as tinyobjloader refuses the whole file for it.
void checkAttributeIndex(long long index, std::size_t before, std::size_t total, const char* what,
                         const char* plural, const std::string& file, std::size_t line,
                         IndexWarning& warning) {
    if (index == 0) checkIndex(index, before, total, what, plural, file, line);
    std::string problem = indexProblem(index, before, total, what, plural);
    if (problem.empty()) return;
    if (warning.count++ == 0) {
        warning.line = line;
        warning.what = std::move(problem);
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

}  // namespace

std::string readObjText(const fs::path& path, const std::string& file) {
    std::string text;
    if (std::string problem = readTextFile(path, text); !problem.empty()) fail(file, kNoLine, problem);
    if (text.find('\0') != std::string::npos) fail(file, kNoLine, "contains NUL bytes: not an OBJ text file");
    return text;
}

ObjScan scanObj(std::string& text, const std::string& file) {
    const ObjStatements statements = splitObj(text);
    return checkObj(text, statements, file);
}

ObjStatements splitObj(std::string& text) {
    ObjStatements split;
    split.statements = cleanAndSplit(text, split.counts);
    return split;
}

ObjScan checkObj(std::string_view text, const ObjStatements& split, const std::string& file) {
    ObjScan scan = split.counts;
    const std::vector<ScannedStatement>& statements = split.statements;
    scan.faceLines.reserve(scan.positions * 2 + 16);
    scan.faceMaterial.reserve(scan.positions * 2 + 16);

    std::size_t positions = 0, texcoords = 0, normals = 0;
    std::int32_t currentMaterial = -1;
    const std::string_view all = text;
    for (const ScannedStatement& statement : statements) {
        const std::string_view s = all.substr(statement.offset, statement.length);
        const std::size_t line = statement.line;
        switch (statement.kind) {
            case Statement::kVertex:
                checkNumbers(s.substr(1), 3, "vertex coordinate", "a vertex needs 3 coordinates (x y z)",
                             file, line, scan);
                ++positions;
                break;
            case Statement::kTexcoord:
                checkNumbers(s.substr(2), 1, "texture coordinate", "a texture coordinate needs at least u",
                             file, line, scan);
                ++texcoords;
                break;
            case Statement::kNormal:
                checkNumbers(s.substr(2), 3, "normal component", "a normal needs 3 components (x y z)", file,
                             line, scan);
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
                            checkAttributeIndex(corner.texcoord, texcoords, scan.texcoords,
                                                "texture coordinate ", "texture coordinates", file, line,
                                                scan.badTexcoordIndices);
                        }
                        if (corner.hasNormal) {
                            checkAttributeIndex(corner.normal, normals, scan.normals, "normal ", "normals",
                                                file, line, scan.badNormalIndices);
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

}  // namespace facet::obj
