// The OBJ pre-scan: the statements tinyobjloader accepts silently ("nan" and "inf" read as 0, index 0,
// relative indices before the first vertex) caught with their line, each face mapped to its line, and
// the text rewritten for tinyobjloader (`\` continuations, comments). Internal to the OBJ importer.
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

// Pass 1's result: the statements to check, and the v/vt/vn totals (in `counts`).
struct ObjStatements {
    std::vector<ScannedStatement> statements;
    ObjScan counts;
};

// Pass 1: splits `text` into statements and rewrites it in place for tinyobjloader (continuations
// joined, comments blanked), without moving a byte.
ObjStatements splitObj(std::string& text);

// Pass 2: checks every statement in file order, so the error reported is the first in the file; throws
// InputError. It only reads the text, so it may run while tinyobjloader parses the same text.
ObjScan checkObj(std::string_view text, const ObjStatements& statements, const std::string& file);

// Both passes, one after the other.
ObjScan scanObj(std::string& text, const std::string& file);

}  // namespace facet::obj
