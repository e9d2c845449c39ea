// MTL files: read for tinyobjloader with their numbers checked first, each material's file and texture
// lines remembered for messages; a material in Facet's terms; a texture file found for an MTL's name.
// Internal to the OBJ importer.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <tiny_obj_loader.h>

#include "io/obj_text.h"
#include "scene/mesh.h"

namespace facet::obj {

namespace fs = std::filesystem;

struct Library {
    fs::path path;
    std::string problem;                                  // why it was not read; empty when it was
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
                    std::string* /*err*/) override;

    const Library* find(const std::string& name) const {
        const auto it = byName_.find(name);
        return it == byName_.end() ? nullptr : &libraries_[it->second];
    }
    // The file material `index` (tinyobjloader's numbering) came from.
    const Library* libraryOf(std::size_t material) const {
        return material < materialLibrary_.size() ? &libraries_[materialLibrary_[material]] : nullptr;
    }

  private:
    // The MTL text as LoadMtl is to read it, the same lines with some statements rewritten, and warnings
    // of what was changed. tinyobjloader reads what it cannot parse (nan, a word, a missing number) as 0
    // and 1e39 as inf, so "Kd nan 1 1" would silently lose its red: each statement it reads numbers from
    // is checked first, its numbers as it takes them (the first one or three; the rest it ignores, like
    // the "illum 2" that follows "Tr 0" on one line of cube-mcguire's MTL). A material is optional to the
    // image, so nothing here refuses the file: a statement whose numbers cannot be used is left out (the
    // material is as without it), one out of range is clamped, a number with stray characters after it
    // ("0.0000c") is read as the number, and "Kd r" is "Kd r r r" (the MTL format's rule). The first
    // three statements left out or clamped are warned of, then a count; numbers with stray characters
    // are one warning with their count.
    static std::string checkMtlNumbers(std::string_view text, const std::string& file,
                                       std::vector<std::string>& warnings);

    // Finds each material's map_Kd line, and d and Tr that disagree (d 1 with Tr 0 is common and
    // fine), splitting lines and names the way LoadMtl does.
    static void scanMtl(const std::string& text, Library& library);

    // The texture statement starting `s` if Facet ignores it ("map_Ks", "bump", ...), else empty.
    // map_Kd and map_Ke are used.
    static std::string_view unusedMap(std::string_view s);

    // Reads the MTL file `name` (relative to the OBJ's folder) and records it under that name.
    void read(const std::string& name, std::vector<tinyobj::material_t>* materials,
              std::map<std::string, int>* materialIds);

    fs::path objFolder_;
    // The names of the current mtllib line not found so far, joined by blanks: exporters write file
    // names with blanks ("mtllib My Model.mtl"), which the format splits into several names.
    std::string missingRun_;
    std::vector<Library> libraries_;
    std::map<std::string, std::size_t> byName_;
    std::vector<std::size_t> materialLibrary_;  // tinyobjloader material index → libraries_ index
};

// A used MTL material in facet's terms. checkMtlNumbers has left out non-finite numbers and clamped
// out-of-range ones; should tinyobjloader still read one differently, the default is used and opacity
// clamped.
Material convertMaterial(const tinyobj::material_t& source, std::vector<std::string>& warnings,
                         const std::string& libraryFile);

// A texture file found for an MTL's name, and what to say about how.
struct FoundTexture {
    fs::path path;        // empty when not found
    std::string warning;  // found by a case-insensitive match, or several such matches: why none
};

// The texture file `name` from the MTL in `folder`; a Windows path ("maps\wood.png") is tried with '/'.
// Models made on Windows or macOS often name files in another case than they have on disk
// ("SP_LUK.JPG" for sp_luk.JPG): when the exact name is missing, each component of the path that is
// missing is matched without regard to case in its folder, if exactly one entry matches. A path not
// found at all (often the one the texture had on the author's machine) falls back to its file name
// alone beside the MTL file, with a warning.
FoundTexture findTexture(const fs::path& folder, const std::string& name);

}  // namespace facet::obj
