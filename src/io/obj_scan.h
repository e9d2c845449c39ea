// The OBJ reader: the text split into statements (`\` continuations joined, comments blanked), every
// statement checked (what tinyobjloader would accept silently, "nan" and "inf" read as 0, index 0,
// relative indices before the first vertex, is refused with its line), and the file's attributes and
// faces read in the same pass, each face mapped to its line. Internal to the OBJ importer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "io/obj_text.h"

namespace facet::obj {

struct UseMaterial {
    std::size_t line;
    std::string name;
};

struct LibraryStatement {
    std::size_t line;
    std::vector<std::string> names;
};

// Corners whose texture coordinate (or normal) index is out of range: the first, and how many.
struct IndexWarning {
    std::size_t count = 0;
    std::size_t line = kNoLine;
    std::string what;  // "face normal index 1 is out of range (the file has 0 normals)"
};

// A face corner: 0-based indices into ObjGeometry's arrays, -1 where the corner has none (a texture
// coordinate or normal index out of range is dropped: ObjScan warns of it).
struct ObjCorner {
    std::int32_t position = -1, texcoord = -1, normal = -1;
    bool operator==(const ObjCorner&) const = default;
};

// What the file holds for the mesh: its v, vt and vn values as floats (x y z, u v, x y z each), and its
// faces of 3 or more corners in file order.
struct ObjGeometry {
    std::vector<float> positions, texcoords, normals;
    std::vector<ObjCorner> corners;          // the faces' corners, one face after another
    std::vector<std::uint8_t> cornerCounts;  // per face: how many of `corners` are its own (3..255)
};

struct ObjScan {
    std::size_t positions = 0, texcoords = 0, normals = 0;  // v, vt, vn statements
    std::size_t facesRead = 0;                              // every f statement
    std::vector<std::size_t> faceLines;                     // each face with >= 3 corners, in file order
    std::vector<std::int32_t> faceMaterial;  // per such face: index into useMaterials, -1 before any
    std::size_t cornerCount = 0;             // over those faces
    std::size_t shortFaces = 0;              // f statements with < 3 corners
    std::size_t firstShortFaceLine = kNoLine;
    std::size_t strayNumbers = 0;  // v/vt/vn numbers with stray characters after them ("0.0000c")
    std::size_t firstStrayLine = kNoLine;
    std::string firstStray;  // the first such token, as written
    double firstStrayValue = 0.0;
    IndexWarning badTexcoordIndices, badNormalIndices;  // drawn without them
    std::vector<UseMaterial> useMaterials;
    std::vector<LibraryStatement> libraries;
    ObjGeometry geometry;  // empty when checkObj was asked to check only
};

// The OBJ file's text; InputError when it cannot be read or holds NUL bytes. `file` names it in messages.
std::string readObjText(const std::filesystem::path& path, const std::string& file);

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

// Pass 1's result: the statements to check and read, and the v/vt/vn totals (in `counts`).
struct ObjStatements {
    std::vector<ScannedStatement> statements;
    ObjScan counts;
};

// Pass 1: splits `text` into statements and rewrites it in place (continuations joined, comments
// blanked) without moving a byte, so that tinyobjloader, the measured peer, reads the same statements.
// A large text is split in runs of lines on threads of their own (`threads` at most, 0: the machine's),
// cut only where no `\` continues a line, and joined in file order: the same statements and lines.
ObjStatements splitObj(std::string& text, unsigned threads = 0);

// Pass 2: checks every statement and, with `readGeometry`, reads the attributes and faces into
// ObjScan::geometry. Throws InputError for the first error in the file. Large files are split into
// runs of statements checked on threads of their own (`threads` at most, 0: the machine's), each
// starting from the v/vt/vn counts before it; the runs' results are joined in file order, and the
// first run's error wins, so the result and the error are those of one pass in file order.
ObjScan checkObj(std::string_view text, const ObjStatements& statements, const std::string& file,
                 bool readGeometry = true, unsigned threads = 0);

}  // namespace facet::obj
