#include "io/obj_scan.h"

#include <algorithm>
#include <cstring>
#include <exception>
#include <future>
#include <iterator>
#include <limits>
#include <string_view>
#include <system_error>
#include <thread>
#include <utility>

#include "base/quote.h"

namespace facet::obj {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kMaxCorners =
    255;  // a face's corner count is kept in a byte, as tinyobjloader keeps it
// checkObj's runs: the fewest statements worth a thread, and the most threads (see docs/performance.md).
constexpr std::size_t kRunStatements = 50000;
constexpr std::size_t kRunBytes = 1 << 20;  // splitObj's runs
constexpr std::size_t kMaxRuns = 8;

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
// Splits the text's lines in [begin, end), which starts a line and ends one that no `\` continues,
// counting lines from 1 there; `lines` gets how many it holds.
std::vector<ScannedStatement> cleanAndSplit(std::string& text, std::size_t runBegin, std::size_t runEnd,
                                            ObjScan& scan, std::size_t& lines) {
    std::vector<ScannedStatement> statements;
    statements.reserve((runEnd - runBegin) / 24);
    if (runBegin == 0 && text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.replace(0, 3, "   ");

    std::size_t physicalLine = 1;
    std::size_t pos = runBegin;
    while (pos < runEnd) {
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
            if (pos == runEnd) {
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
    lines = physicalLine - 1;
    return statements;
}

// Where a run of lines may start at or after `pos`: just after a '\n' that ends a line no `\` continues
// (conservatively, one whose last blank-trimmed character is not a `\`), or text.size().
std::size_t runBoundary(std::string_view text, std::size_t pos) {
    while (pos < text.size()) {
        const void* newline = std::memchr(text.data() + pos, '\n', text.size() - pos);
        if (!newline) return text.size();
        const std::size_t at = static_cast<std::size_t>(static_cast<const char*>(newline) - text.data());
        std::size_t last = at;
        if (last > 0 && text[last - 1] == '\r') --last;
        while (last > 0 && isBlank(text[last - 1]))
            --last;
        if (last == 0 || text[last - 1] != '\\') return at + 1;
        pos = at + 1;
    }
    return text.size();
}

// The numbers of a v/vt/vn statement: all must be finite, and there must be at least `required`. A number
// with stray characters after it ("0.0000c", "1.5,") is read as the number, as tinyobjloader reads it,
// and counted for one warning; a decimal comma ("2,5", read as 2 by tinyobjloader) would bend every
// coordinate of the model, so it is refused, as are words, NaN and Inf (read as 0 by tinyobjloader).
// With `values`, the first `valueCount` numbers go there as floats (0 for those missing: a vt's v).
void checkNumbers(std::string_view body, std::size_t required, const char* what, const char* needs,
                  const std::string& file, std::size_t line, ObjScan& scan, float* values,
                  std::size_t valueCount) {
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
        if (values && count < valueCount) values[count] = objCoordinate(token.substr(0, read.length));
        ++count;
    }
    if (count < required) fail(file, line, std::string(needs) + ", found " + std::to_string(count));
    for (; values && count < valueCount; ++count)
        values[count] = 0.0f;
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
// Returns whether the corner keeps it.
bool checkAttributeIndex(long long index, std::size_t before, std::size_t total, const char* what,
                         const char* plural, const std::string& file, std::size_t line,
                         IndexWarning& warning) {
    if (index == 0) checkIndex(index, before, total, what, plural, file, line);
    std::string problem = indexProblem(index, before, total, what, plural);
    if (problem.empty()) return true;
    if (warning.count++ == 0) {
        warning.line = line;
        warning.what = std::move(problem);
    }
    return false;
}

// A valid OBJ index (1-based, or negative: counting back from the `before` defined so far) from 0.
std::int32_t zeroBased(long long index, std::size_t before) {
    return static_cast<std::int32_t>(index > 0 ? index - 1 : static_cast<long long>(before) + index);
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

namespace {

// run(r) for every run r in [0, runs): run 0 on the calling thread, each other on a thread of its own,
// returning when all are done. A thread the system refuses is no error: the calling thread runs that
// run after its own.
template <class Run>
void runEachOnAThread(std::size_t runs, const Run& run) {
    std::vector<std::future<void>> others;
    for (std::size_t r = 1; r < runs; ++r) {
        try {
            others.push_back(std::async(std::launch::async, run, r));
        } catch (const std::system_error&) {
            others.push_back(std::async(std::launch::deferred, run, r));
        }
    }
    run(0);
    for (std::future<void>& other : others)
        other.get();
}

}  // namespace

ObjStatements splitObj(std::string& text, unsigned threads) {
    // Runs of at least kRunBytes, each split on a thread of its own, then joined in file order.
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t runs =
        std::clamp<std::size_t>(text.size() / kRunBytes, 1, std::min<std::size_t>(threads, kMaxRuns));
    std::vector<std::size_t> bounds(runs + 1, text.size());
    bounds[0] = 0;
    for (std::size_t r = 1; r < runs; ++r)
        bounds[r] = runBoundary(text, std::max(bounds[r - 1], text.size() * r / runs));

    std::vector<ObjStatements> splits(runs);
    std::vector<std::size_t> lines(runs);
    const auto split = [&](std::size_t r) {
        splits[r].statements = cleanAndSplit(text, bounds[r], bounds[r + 1], splits[r].counts, lines[r]);
    };
    runEachOnAThread(runs, split);

    ObjStatements joined = std::move(splits[0]);
    std::size_t linesBefore = lines[0];
    for (std::size_t r = 1; r < runs; ++r) {
        joined.counts.positions += splits[r].counts.positions;
        joined.counts.texcoords += splits[r].counts.texcoords;
        joined.counts.normals += splits[r].counts.normals;
        const std::size_t first = joined.statements.size();
        joined.statements.insert(joined.statements.end(), splits[r].statements.begin(),
                                 splits[r].statements.end());
        for (std::size_t k = first; k < joined.statements.size(); ++k)
            joined.statements[k].line += linesBefore;
        linesBefore += lines[r];
    }
    return joined;
}

namespace {

// Where a run of statements starts: the v, vt and vn statements before it.
struct RunStart {
    std::size_t positions = 0, texcoords = 0, normals = 0;
};

// Pass 2 over statements [begin, end): see checkObj. The run's faces before its first usemtl get
// faceMaterial -1 (joinRuns gives them the usemtl before the run); its v, vt and vn values go to
// `geometry`'s arrays (sized for the whole file) at the run's place, its faces to the run's own.
ObjScan checkRun(std::string_view text, const ObjStatements& split, std::size_t begin, std::size_t end,
                 RunStart start, const std::string& file, ObjGeometry* geometry) {
    ObjScan scan;
    const ObjScan& totals = split.counts;
    const std::size_t expectedFaces = (end - begin) * 2 / 3 + 16;  // most statements of a mesh are faces
    scan.faceLines.reserve(expectedFaces);
    scan.faceMaterial.reserve(expectedFaces);
    if (geometry) {
        scan.geometry.cornerCounts.reserve(expectedFaces);
        scan.geometry.corners.reserve(expectedFaces * 3);
    }

    std::size_t positions = start.positions, texcoords = start.texcoords, normals = start.normals;
    std::int32_t currentMaterial = -1;
    for (std::size_t k = begin; k < end; ++k) {
        const ScannedStatement& statement = split.statements[k];
        const std::string_view s = text.substr(statement.offset, statement.length);
        const std::size_t line = statement.line;
        switch (statement.kind) {
            case Statement::kVertex:
                checkNumbers(s.substr(1), 3, "vertex coordinate", "a vertex needs 3 coordinates (x y z)",
                             file, line, scan, geometry ? &geometry->positions[3 * positions] : nullptr, 3);
                ++positions;
                break;
            case Statement::kTexcoord:
                checkNumbers(s.substr(2), 1, "texture coordinate", "a texture coordinate needs at least u",
                             file, line, scan, geometry ? &geometry->texcoords[2 * texcoords] : nullptr, 2);
                ++texcoords;
                break;
            case Statement::kNormal:
                checkNumbers(s.substr(2), 3, "normal component", "a normal needs 3 components (x y z)", file,
                             line, scan, geometry ? &geometry->normals[3 * normals] : nullptr, 3);
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
                        ObjCorner read;
                        checkIndex(corner.position, positions, totals.positions, "", "vertices", file, line);
                        read.position = zeroBased(corner.position, positions);
                        if (corner.hasTexcoord &&
                            checkAttributeIndex(corner.texcoord, texcoords, totals.texcoords,
                                                "texture coordinate ", "texture coordinates", file, line,
                                                scan.badTexcoordIndices)) {
                            read.texcoord = zeroBased(corner.texcoord, texcoords);
                        }
                        if (corner.hasNormal &&
                            checkAttributeIndex(corner.normal, normals, totals.normals, "normal ", "normals",
                                                file, line, scan.badNormalIndices)) {
                            read.normal = zeroBased(corner.normal, normals);
                        }
                        if (geometry) scan.geometry.corners.push_back(read);
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
                    if (geometry) scan.geometry.corners.resize(scan.geometry.corners.size() - corners);
                    break;
                }
                scan.faceLines.push_back(line);
                scan.faceMaterial.push_back(currentMaterial);
                scan.cornerCount += corners;
                if (geometry) scan.geometry.cornerCounts.push_back(static_cast<std::uint8_t>(corners));
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

// The first of two counted warnings stays; the counts add.
void joinWarning(IndexWarning& into, IndexWarning&& next) {
    if (into.count == 0) {
        into = std::move(next);
    } else {
        into.count += next.count;
    }
}

// Appends run `next` (the statements after `into`'s) to `into`.
void joinRuns(ObjScan& into, ObjScan&& next) {
    into.facesRead += next.facesRead;
    if (into.shortFaces == 0) into.firstShortFaceLine = next.firstShortFaceLine;
    into.shortFaces += next.shortFaces;
    if (into.strayNumbers == 0) {
        into.firstStrayLine = next.firstStrayLine;
        into.firstStray = std::move(next.firstStray);
        into.firstStrayValue = next.firstStrayValue;
    }
    into.strayNumbers += next.strayNumbers;
    joinWarning(into.badTexcoordIndices, std::move(next.badTexcoordIndices));
    joinWarning(into.badNormalIndices, std::move(next.badNormalIndices));
    into.faceLines.insert(into.faceLines.end(), next.faceLines.begin(), next.faceLines.end());
    const auto usesBefore = static_cast<std::int32_t>(into.useMaterials.size());
    for (const std::int32_t use : next.faceMaterial)
        into.faceMaterial.push_back(use >= 0 ? use + usesBefore : usesBefore - 1);
    into.cornerCount += next.cornerCount;
    std::move(next.useMaterials.begin(), next.useMaterials.end(), std::back_inserter(into.useMaterials));
    std::move(next.libraries.begin(), next.libraries.end(), std::back_inserter(into.libraries));
    ObjGeometry& geometry = into.geometry;
    geometry.corners.insert(geometry.corners.end(), next.geometry.corners.begin(),
                            next.geometry.corners.end());
    geometry.cornerCounts.insert(geometry.cornerCounts.end(), next.geometry.cornerCounts.begin(),
                                 next.geometry.cornerCounts.end());
}

}  // namespace

ObjScan checkObj(std::string_view text, const ObjStatements& split, const std::string& file,
                 bool readGeometry, unsigned threads) {
    const ObjScan& totals = split.counts;
    ObjGeometry attributes;
    if (readGeometry) {
        attributes.positions.resize(3 * totals.positions);
        attributes.texcoords.resize(2 * totals.texcoords);
        attributes.normals.resize(3 * totals.normals);
    }
    ObjGeometry* const geometry = readGeometry ? &attributes : nullptr;

    // Runs of at least kRunStatements: below that a thread's start costs more than it saves.
    const std::size_t count = split.statements.size();
    if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t runs =
        std::clamp<std::size_t>(count / kRunStatements, 1, std::min<std::size_t>(threads, kMaxRuns));

    std::vector<std::size_t> bounds(runs + 1, count);
    std::vector<RunStart> starts(runs);
    RunStart at;
    for (std::size_t r = 0, k = 0; r < runs; ++r) {
        bounds[r] = k;
        starts[r] = at;
        const std::size_t next = count * (r + 1) / runs;
        for (; k < next; ++k) {
            const Statement kind = split.statements[k].kind;
            at.positions += kind == Statement::kVertex;
            at.texcoords += kind == Statement::kTexcoord;
            at.normals += kind == Statement::kNormal;
        }
    }

    std::vector<ObjScan> scans(runs);
    std::vector<std::exception_ptr> errors(runs);
    const auto check = [&](std::size_t r) {
        try {
            scans[r] = checkRun(text, split, bounds[r], bounds[r + 1], starts[r], file, geometry);
        } catch (...) {
            errors[r] = std::current_exception();
        }
    };
    runEachOnAThread(runs, check);
    for (const std::exception_ptr& error : errors) {
        if (error) std::rethrow_exception(error);
    }

    ObjScan scan = std::move(scans[0]);
    for (std::size_t r = 1; r < runs; ++r)
        joinRuns(scan, std::move(scans[r]));
    scan.positions = totals.positions;
    scan.texcoords = totals.texcoords;
    scan.normals = totals.normals;
    if (readGeometry) {
        scan.geometry.positions = std::move(attributes.positions);
        scan.geometry.texcoords = std::move(attributes.texcoords);
        scan.geometry.normals = std::move(attributes.normals);
    }
    return scan;
}

}  // namespace facet::obj
