// OBJ import: OBJ + MTL text → validated, welded, fan-triangulated Mesh.
// tinyobjloader parses. A pre-scan of the same text first catches what it accepts silently ("nan" and
// "inf" read as 0, index 0, relative indices before the first vertex) and maps each face to its line.
// Computed normals weight each face by its area (they sum the faces' unnormalised cross products) and
// smooth only faces within the crease angle of each other (see MeshBuilder).
// The steps are separate modules: obj_scan (the pre-scan), mtl_reader (MTL files, materials, textures),
// mesh_builder (welding and normals), obj_text (what they share: messages, tokens, numbers).

#include "io/obj_import.h"

#include <cmath>
#include <cstdint>
#include <future>
#include <istream>
#include <map>
#include <set>
#include <stdexcept>
#include <streambuf>
#include <string>
#include <system_error>
#include <type_traits>
#include <vector>

#include <tiny_obj_loader.h>

#include "base/errors.h"
#include "io/mesh_builder.h"
#include "io/mtl_reader.h"
#include "io/obj_scan.h"
#include "io/obj_text.h"

namespace facet {

using namespace obj;  // the importer's own modules

namespace {

// tinyobjloader::tinyobjloader is the float build; the _double one compiles with TINYOBJLOADER_USE_DOUBLE.
static_assert(std::is_same_v<tinyobj::real_t, float>, "link tinyobjloader::tinyobjloader (float build)");

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

// The text as an input stream for tinyobjloader, read in place (an istringstream would copy it).
class TextStreamBuffer : public std::streambuf {
  public:
    explicit TextStreamBuffer(std::string& text) {
        setg(text.data(), text.data(), text.data() + text.size());
    }
};

}  // namespace

Mesh loadObj(const std::filesystem::path& path, const ObjOptions& options, VertexNormalTrace* normalTrace) {
    const float crease = options.creaseAngleDegrees;
    if (!(crease >= 0.0f && crease <= 180.0f)) {  // NaN fails both
        throw std::invalid_argument("loadObj: creaseAngleDegrees must be within [0, 180], not " +
                                    std::to_string(crease));
    }
    const std::string file = path.string();

    // 1. Read and split into statements; `text` is rewritten for tinyobjloader (continuations, comments).
    std::string text = readObjText(path, file);
    const ObjStatements statements = splitObj(text);

    // 2. Check every statement on a thread of its own while tinyobjloader parses the same text (both
    // only read it): the two passes take about as long. A pre-scan error still wins over whatever
    // tinyobjloader makes of the file, as the first in the file is the one to report.
    const auto check = [&] { return checkObj(text, statements, file); };
    std::future<ObjScan> checked;
    try {
        checked = std::async(std::launch::async, check);
    } catch (const std::system_error&) {  // no thread to be had: check after the parse instead
        checked = std::async(std::launch::deferred, check);
    }

    // 3. Parse with tinyobjloader, untriangulated: facet fans, and faces stay one-to-one with lines.
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> tinyMaterials;
    std::string tinyWarnings, tinyErrors;  // its warnings repeat what the pre-scan reports better
    LibraryReader libraries(path.parent_path());
    TextStreamBuffer buffer(text);
    std::istream stream(&buffer);
    const bool parsed =
        tinyobj::LoadObj(&attrib, &shapes, &tinyMaterials, &tinyWarnings, &tinyErrors, &stream, &libraries,
                         /*triangulate=*/false, /*default_vcols_fallback=*/false);
    const ObjScan scan = checked.get();  // rethrows the pre-scan's error
    if (!parsed) {
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
    MeshBuilder builder(attrib, cornerCount, crease, options.normals);
    if (normalTrace) builder.trace(normalTrace);
    std::vector<int> meshMaterialOf(tinyMaterials.size() + 1, -1);  // [0]: no material; [i + 1]: material i
    std::vector<int> tinyMaterialOf;  // mesh material → tinyobjloader's, or -1
    std::vector<std::vector<std::uint32_t>> buckets;
    std::set<std::string> unknownReported;
    std::size_t face = 0;
    std::vector<tinyobj::index_t> repaired;  // a face's corners with out-of-range attribute indices dropped
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
            // The pre-scan checked every index; this keeps a mismatch from reading out of bounds. A texture
            // coordinate or normal index out of range (the pre-scan warned of it) is dropped from a copy
            // of the corners: the corner is drawn without it.
            const auto outside = [](int index, std::size_t size) {
                return index < -1 || (index >= 0 && std::size_t(index) >= size);
            };
            const std::size_t texcoordCount = attrib.texcoords.size() / 2,
                              normalCount = attrib.normals.size() / 3;
            bool dropped = false;
            for (std::size_t c = 0; c < count; ++c) {
                const tinyobj::index_t& k = corners[c];
                if (k.vertex_index < 0 || std::size_t(k.vertex_index) >= attrib.vertices.size() / 3)
                    fail(file, line, "face index out of range");
                dropped = dropped || outside(k.texcoord_index, texcoordCount) ||
                          outside(k.normal_index, normalCount);
            }
            if (dropped) {
                repaired.assign(corners, corners + count);
                for (tinyobj::index_t& k : repaired) {
                    if (outside(k.texcoord_index, texcoordCount)) k.texcoord_index = -1;
                    if (outside(k.normal_index, normalCount)) k.normal_index = -1;
                }
                corners = repaired.data();
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
