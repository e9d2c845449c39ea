// OBJ import: reads a Wavefront OBJ (and its MTL files) into a welded, triangulated Mesh.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/glm.hpp>

#include "scene/mesh.h"

namespace facet {

// Reads `path` (its MTL files through tinyobjloader), validates it and builds the mesh:
// - polygons are fan-triangulated; degenerate triangles (repeated corners, zero area) are skipped
//   and counted in stats.degenerateSkipped. A face with fewer than 3 corners is skipped too, counted
//   there as one degenerate triangle, and reported once as a warning (as Blender and tinyobjloader do);
// - corners are welded on their (position, normal, texcoord) index triple; a zero-length file normal
//   counts as no normal;
// - vertices without a normal in the file get a computed one, per face corner: the normalised sum of
//   the vector areas (unnormalised cross products: area weighting) of those faces around the corner's
//   position whose unit normal is within options.creaseAngleDegrees of the corner's own face's normal
//   (the face itself always counts; a face is the file's polygon, its normal its normalised vector
//   area). options.normals chooses the weights instead of the polygons' vector areas: the fan
//   triangles' cross products at the corner, or the polygon's unit normal times its corner angle. Corners
//   welded on their index triple but ending up with different sets of faces become separate vertices (counted
//   in stats.creaseSplits); corners with the same set share one. So at 60° a cube without normals has 24
//   vertices, at 180° (smooth everything) 8, and a finely tessellated sphere one per position. At a position
//   with more than 64 faces the faces are clustered greedily instead (each joins the first cluster whose
//   first face is within the angle). If a sum is zero (opposite faces cancelling), the normal of the first
//   triangle that used the vertex. File normals are never changed;
// - positive indices may refer forward; negative ones count back from the statement that uses them;
// - a `\` at the end of a line continues the statement on the next line, and `#` after a blank starts
//   a comment (tinyobjloader knows neither; the text is rewritten for it, keeping line numbers);
// - a missing MTL file, an unknown material or a missing texture is a warning (Mesh::warnings)
//   and falls back to the default material (or, for a texture, to the material without it). Every
//   file on an `mtllib` line is read. `d` wins over `Tr` whichever comes first (tinyobjloader's rule);
//   `Tr` alone gives opacity 1 - Tr. Mesh::materials holds the materials faces use, in first-use order;
// - huge but finite coordinates (1e30) are accepted;
// - a number with stray characters after it ("0.0000c", "1.5,") is read as the number, as tinyobjloader
//   and Blender read it, with one warning per file counting them; a texture coordinate or normal index
//   out of range is dropped from its corner with a warning (the corner gets a computed normal); MTL
//   numbers that cannot be used leave their statement out, out-of-range ones are clamped (warnings).
// Throws InputError with "file:line: what" for: a missing or unreadable file, a malformed statement,
// a position index out of range, any index 0, NaN/Inf coordinates (or ones beyond float range), a
// word or a decimal comma ("2,5") where a coordinate must be, a face with more than 255 corners, or a
// file with no triangles at all ("file: no triangles to draw ...").
// Throws std::invalid_argument if options.creaseAngleDegrees is NaN or outside [0, 180] (a caller's
// bug: the scene loader validates user input).
struct ObjOptions {
    // Computed normals only: two faces sharing a position are smoothed together when their face
    // normals differ by at most this angle (degrees, 0..180); a sharper edge stays hard (the vertex
    // is split). 180 smooths everything, 0 gives every face its own normal (faces of the same
    // direction, to within about 1e-4 degrees, still share one).
    float creaseAngleDegrees = 60.0f;
    // Computed normals only: how each face around a position is weighted (scene/mesh.h).
    VertexNormals normals = VertexNormals::PolygonArea;

    bool operator==(const ObjOptions&) const = default;
};
// How the computed normals at some positions were made, for the step mode's screen: loadObj fills it
// when given one, from the very sums it computes (nothing is recorded, and nothing costs, without it).
struct VertexNormalTrace {
    std::vector<glm::vec3> positions;  // the positions to record (object space, as the vertices hold them)
    bool all = false;                  // or every position with a computed normal
    // One face around a position: the file's polygon `face` (counted from 0 over the file's faces kept),
    // its unit normal, its weight at the position (see ObjOptions::normals), the cosine between its
    // normal and the group's own face's, and whether the crease rule smoothed it into the group.
    struct Face {
        std::uint32_t face = 0;
        glm::dvec3 unit{0.0}, weight{0.0};
        double cosine = 1.0;
        bool smoothed = true;
    };
    // One computed normal seen from one face at `position`, `ownFace`: the faces there its sum includes
    // or leaves out (in file order) by their angle to ownFace's, the weighted sum and the normal (the sum
    // normalised; zero when the faces cancel). Faces whose sums hold the same faces share one normal and
    // each has its own group here; a crowded position's greedy clusters are seen from their first face.
    struct Group {
        glm::vec3 position{0.0f};
        std::uint32_t ownFace = 0;
        std::vector<Face> faces;
        glm::dvec3 sum{0.0};
        glm::vec3 normal{0.0f};
        bool clustered = false;  // more than 64 faces: greedy clusters (see MeshBuilder)
    };
    std::vector<Group> groups;
    // A vertex as the file gives it, at a recorded position (or at every one, fileCornersOfAll): its
    // `v`, `vt` and `vn` (counted from 0, −1 where the corner has none) and their values as read,
    // before the normal is normalised. One for each distinct (v, vt, vn) of the corners, in file order.
    struct FileCorner {
        std::int64_t positionIndex = 0, texcoordIndex = -1, normalIndex = -1;
        glm::vec3 position{0.0f};
        glm::vec2 uv{0.0f};
        glm::vec3 normal{0.0f};      // as read (any length)
        glm::vec3 unitNormal{0.0f};  // normalised, as the mesh's vertex holds it (zero: unusable)
    };
    std::vector<FileCorner> fileCorners;
    bool fileCornersOfAll = false;
    VertexNormals weighting = VertexNormals::PolygonArea;
    double creaseCosine = 0.5;  // faces with a cosine at least this are smoothed together
    bool smoothAll = false;     // crease angle 180
};

Mesh loadObj(const std::filesystem::path& path, const ObjOptions& options = {},
             VertexNormalTrace* normalTrace = nullptr);

// Which code reads the OBJ text: Facet's own reader, or tinyobjloader, kept as the peer that tests and
// benchmarks compare it with. Both give the same mesh and the same messages for any file the checks
// accept; loadObj uses kFacet.
enum class ObjReader { kFacet, kTinyobjloader };
Mesh loadObjWith(const std::filesystem::path& path, ObjReader reader, const ObjOptions& options = {},
                 VertexNormalTrace* normalTrace = nullptr);

}  // namespace facet
