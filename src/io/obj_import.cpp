// OBJ import: OBJ + MTL text → validated, welded, fan-triangulated Mesh.
// Facet reads the OBJ itself (obj_scan): one pass splits the text into statements, a second checks each
// statement (catching what tinyobjloader would accept silently: "nan" and "inf" read as 0, index 0,
// relative indices before the first vertex) and reads its numbers and indices, on several threads for a
// large file. MTL files are read by tinyobjloader (mtl_reader). tinyobjloader can still read the OBJ
// (ObjReader::kTinyobjloader), as the peer the tests and benchmarks compare against: same meshes.
// Computed normals weight each face by its area (they sum the faces' unnormalised cross products) and
// smooth only faces within the crease angle of each other (see MeshBuilder).
// The steps are separate modules: obj_scan (the reader), mtl_reader (MTL files, materials, textures),
// mesh_builder (welding and normals), obj_text (what they share: messages, tokens, numbers),
// obj_tinyobj (the peer).

#include "io/obj_import.h"

#include <cmath>
#include <cstdint>
#include <future>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include <tiny_obj_loader.h>

#include "base/errors.h"
#include "io/mesh_builder.h"
#include "io/mtl_reader.h"
#include "io/obj_scan.h"
#include "io/obj_text.h"
#include "io/obj_tinyobj.h"

namespace facet {

using namespace obj;  // the importer's own modules

namespace {

// Any value read that the checks did not foresee (a bug, not bad input) is still refused rather than
// drawn as NaN.
void checkFinite(const std::vector<float>& values, std::size_t stride, const char* what,
                 const std::string& file) {
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (!std::isfinite(values[i])) {
            fail(file, kNoLine, std::string(what) + " " + std::to_string(i / stride + 1) + " is not finite");
        }
    }
}

// The material statements in file order, as tinyobjloader takes them: every file named on an mtllib
// line is handed to `reader` (LibraryReader reads them all), and each usemtl names a material of the
// files read above it. Returns, per usemtl of the scan, its material (-1: unknown).
std::vector<int> resolveMaterials(const ObjScan& scan, tinyobj::MaterialReader& reader,
                                  std::vector<tinyobj::material_t>& materials) {
    std::map<std::string, int> byName;
    std::vector<int> materialOfUse(scan.useMaterials.size(), -1);
    std::size_t library = 0;
    for (std::size_t use = 0; use <= scan.useMaterials.size(); ++use) {
        const std::size_t line = use < scan.useMaterials.size() ? scan.useMaterials[use].line : SIZE_MAX;
        for (; library < scan.libraries.size() && scan.libraries[library].line < line; ++library) {
            for (const std::string& name : scan.libraries[library].names) {
                std::string warnings, errors;  // LibraryReader keeps its own
                reader(name, &materials, &byName, &warnings, &errors);
            }
        }
        if (use == scan.useMaterials.size()) break;
        const auto it = byName.find(scan.useMaterials[use].name);
        if (it != byName.end()) materialOfUse[use] = it->second;
    }
    return materialOfUse;
}

}  // namespace

Mesh loadObj(const std::filesystem::path& path, const ObjOptions& options, VertexNormalTrace* normalTrace) {
    return loadObjWith(path, ObjReader::kFacet, options, normalTrace);
}

Mesh loadObjWith(const std::filesystem::path& path, ObjReader reader, const ObjOptions& options,
                 VertexNormalTrace* normalTrace) {
    const float crease = options.creaseAngleDegrees;
    if (!(crease >= 0.0f && crease <= 180.0f)) {  // NaN fails both
        throw std::invalid_argument("loadObj: creaseAngleDegrees must be within [0, 180], not " +
                                    std::to_string(crease));
    }
    const std::string file = path.string();

    // 1. Read and split into statements; `text` is rewritten for tinyobjloader (continuations, comments).
    std::string text = readObjText(path, file);
    const ObjStatements statements = splitObj(text);

    // 2. Check and read every statement (obj_scan), or check them on a thread of their own while
    // tinyobjloader reads the same text (both only read it). A check's error wins over whatever
    // tinyobjloader makes of the file, as the first in the file is the one to report.
    LibraryReader libraries(path.parent_path());
    std::vector<tinyobj::material_t> tinyMaterials;
    ObjScan scan;
    ObjGeometry geometry;
    std::vector<int> faceMaterials;  // per face: its material in tinyMaterials, -1 for none
    bool linesTrusted = true;        // scan.faceLines are the faces' lines
    if (reader == ObjReader::kFacet) {
        scan = checkObj(text, statements, file);
        geometry = std::move(scan.geometry);
        const std::vector<int> materialOfUse = resolveMaterials(scan, libraries, tinyMaterials);
        faceMaterials.reserve(scan.faceMaterial.size());
        for (const std::int32_t use : scan.faceMaterial)
            faceMaterials.push_back(use >= 0 ? materialOfUse[std::size_t(use)] : -1);
    } else {
        const auto check = [&] { return checkObj(text, statements, file, /*readGeometry=*/false, 1); };
        std::future<ObjScan> checked;
        try {
            checked = std::async(std::launch::async, check);
        } catch (const std::system_error&) {  // no thread to be had: check after the parse instead
            checked = std::async(std::launch::deferred, check);
        }
        TinyobjRead read = readWithTinyobjloader(text, libraries, tinyMaterials);
        scan = checked.get();  // rethrows the check's error
        if (!read.parsed)
            fail(file, kNoLine, read.error.empty() ? "tinyobjloader cannot parse it" : read.error);
        geometry = std::move(read.geometry);
        faceMaterials = std::move(read.faceMaterials);
        // The line map is only trusted when tinyobjloader saw the same faces as the check.
        linesTrusted =
            geometry.cornerCounts.size() == scan.faceLines.size() &&
            geometry.corners.size() == scan.cornerCount && geometry.positions.size() == 3 * scan.positions &&
            geometry.texcoords.size() == 2 * scan.texcoords && geometry.normals.size() == 3 * scan.normals;
    }
    checkFinite(geometry.positions, 3, "vertex", file);
    checkFinite(geometry.texcoords, 2, "texture coordinate", file);
    checkFinite(geometry.normals, 3, "normal", file);
    const std::size_t cornerCount = geometry.corners.size();

    Mesh mesh;
    mesh.stats.facesRead = scan.facesRead;
    mesh.stats.degenerateSkipped = scan.shortFaces;
    std::vector<std::string>& warnings = mesh.warnings;

    // 4. MTL problems, each reported once at the mtllib line naming the file.
    std::set<std::string> reported;
    for (const LibraryStatement& statement : scan.libraries) {
        if (statement.names.empty())
            warnings.push_back(located(file, statement.line, "mtllib names no file"));
        // The warnings of names not found are held back while those names may be the parts of one file
        // name with blanks (LibraryReader reads "My Model.mtl" when "My" and "Model.mtl" are not files).
        std::string missingRun;
        std::vector<std::string> held;
        for (const std::string& name : statement.names) {
            const Library* library = libraries.find(name);
            if (library == nullptr) continue;
            if (library->problem.empty()) {
                warnings.insert(warnings.end(), held.begin(), held.end());
                held.clear();
                missingRun.clear();
                if (reported.insert(name).second)
                    warnings.insert(warnings.end(), library->warnings.begin(), library->warnings.end());
                continue;
            }
            if (reported.insert(name).second)
                held.push_back(located(file, statement.line,
                                       "material library " + inSingleQuotes(name) + ": " + library->problem +
                                           "; its materials fall back to the default"));
            missingRun = missingRun.empty() ? name : missingRun + " " + name;
            const Library* joined = missingRun != name ? libraries.find(missingRun) : nullptr;
            if (joined == nullptr || !joined->problem.empty()) continue;
            held.clear();
            if (reported.insert(missingRun).second) {
                warnings.push_back(located(file, statement.line,
                                           "material library " + inSingleQuotes(missingRun) +
                                               " read as one file name with blanks (mtllib separates "
                                               "file names by blanks)"));
                warnings.insert(warnings.end(), joined->warnings.begin(), joined->warnings.end());
            }
            missingRun.clear();
        }
        warnings.insert(warnings.end(), held.begin(), held.end());
    }
    if (scan.strayNumbers > 0) {
        warnings.push_back(strayNumberWarning(file, scan.firstStrayLine, scan.firstStray,
                                              scan.firstStrayValue, scan.strayNumbers));
    }
    const auto indexWarning = [&](const IndexWarning& bad, const char* instead) {
        if (bad.count == 0) return;
        std::string what = bad.what + "; " + instead;
        if (bad.count > 1) what += " (" + std::to_string(bad.count) + " such corners in this file)";
        warnings.push_back(located(file, bad.line, what));
    };
    indexWarning(scan.badTexcoordIndices, "the corner is drawn without a texture coordinate");
    indexWarning(scan.badNormalIndices, "the corner gets a computed normal");
    if (scan.shortFaces > 0) {
        warnings.push_back(
            located(file, scan.firstShortFaceLine,
                    std::to_string(scan.shortFaces) + " face(s) with fewer than 3 corners skipped"));
    }

    // 5. Triangulate, weld and bucket the triangles by material, in first-use order.
    MeshBuilder builder(geometry, cornerCount, crease, options.normals);
    if (normalTrace) builder.trace(normalTrace);
    std::vector<int> meshMaterialOf(tinyMaterials.size() + 1, -1);  // [0]: no material; [i + 1]: material i
    std::vector<int> tinyMaterialOf;  // mesh material → tinyobjloader's, or -1
    std::vector<std::vector<std::uint32_t>> buckets;
    std::set<std::string> unknownReported;
    const std::size_t positionCount = geometry.positions.size() / 3;
    std::size_t offset = 0;
    for (std::size_t face = 0; face < geometry.cornerCounts.size(); ++face) {
        const std::size_t count = geometry.cornerCounts[face];
        const std::size_t line = linesTrusted ? scan.faceLines[face] : kNoLine;
        if (offset + count > cornerCount) fail(file, line, "face corners do not match tinyobjloader's");
        const ObjCorner* corners = &geometry.corners[offset];
        offset += count;
        if (count < 3) {  // neither reader keeps these; kept for safety
            ++mesh.stats.degenerateSkipped;
            continue;
        }
        // The check refused every position index out of range; this keeps a mismatch from reading out of
        // bounds.
        for (std::size_t c = 0; c < count; ++c) {
            if (corners[c].position < 0 || std::size_t(corners[c].position) >= positionCount)
                fail(file, line, "face index out of range");
        }

        int tinyMaterial = face < faceMaterials.size() ? faceMaterials[face] : -1;
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

    if (mesh.stats.trianglesKept == 0) {
        fail(file, kNoLine,
             scan.facesRead == 0 ? "no triangles to draw (the file has no faces)"
                                 : "no triangles to draw (all " + std::to_string(scan.facesRead) +
                                       " faces are degenerate or have fewer than 3 corners)");
    }

    // 6. Normals (splitting vertices at creases), then the index buffer: one part per material.
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
            mesh.materials.emplace_back().fallback = true;
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

    // 6b. Materials that draw nothing. `Tr` is written both ways by exporters (opacity, or its
    // complement, which the MTL format means), and some write `d 0` for opaque: a model whose every
    // part is fully transparent would render as an empty image reported as success, so it is drawn
    // opaque with a warning. Some parts invisible among visible ones may be meant (a glass pane, a
    // hidden helper mesh): only named.
    std::vector<std::string> invisible;
    std::size_t invisibleTriangles = 0;
    for (const MeshPart& part : mesh.parts) {
        const Material& material = mesh.materials[part.material];
        if (material.opacity > 0.0f) continue;
        invisible.push_back(inSingleQuotes(material.name));
        invisibleTriangles += part.indexCount / 3;
    }
    if (!invisible.empty() && invisible.size() == mesh.parts.size()) {
        for (Material& material : mesh.materials)
            material.opacity = 1.0f;
        warnings.push_back(located(file, kNoLine,
                                   "every material of the model is fully transparent (d 0, or Tr 1), which "
                                   "would draw nothing; drawing it opaque (some exporters write Tr as the "
                                   "opacity)"));
    } else if (!invisible.empty()) {
        std::string names = invisible.front();
        for (std::size_t k = 1; k < invisible.size() && k < 3; ++k)
            names += ", " + invisible[k];
        if (invisible.size() > 3) names += " and " + std::to_string(invisible.size() - 3) + " more";
        warnings.push_back(located(
            file, kNoLine,
            (invisible.size() > 1 ? "materials " + names + " are" : "material " + names + " is") +
                " fully transparent (d 0, or Tr 1): " +
                (invisibleTriangles == 1 ? std::string("1 triangle draws nothing")
                                         : std::to_string(invisibleTriangles) + " triangles draw nothing")));
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
