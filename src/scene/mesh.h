// The mesh the importer hands to the renderer: welded vertices, triangle indices, parts by material.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "pipeline/names.h"

namespace facet {

// How a vertex without a file normal weighs the faces around it (the crease angle applies to all):
// each face at the vertex's position adds a vector along its unit normal, and the normal is their sum,
// normalised.
enum class VertexNormals : std::uint8_t {
    TriangleArea,  // Σ over the fan triangles at the vertex of their cross products (twice their vector
                   // areas): the common convention, but a polygon's triangulation changes the result
    PolygonArea,   // each polygon's whole vector area (the sum of its fan triangles' cross products)
    Angle,  // each polygon's unit normal times its interior angle at the vertex (Thürmer & Wüthrich 1998):
            // independent of how the polygons are triangulated and of how finely a surface is cut
};
inline constexpr EnumName<VertexNormals> kVertexNormalsNames[] = {
    {VertexNormals::PolygonArea, "polygon-area"},
    {VertexNormals::TriangleArea, "triangle-area"},
    {VertexNormals::Angle, "angle"}};
constexpr std::span<const EnumName<VertexNormals>> enumNames(VertexNormals) {
    return kVertexNormalsNames;
}

// The largest colour component or light intensity a scene or MTL file may give. Light can be bright,
// but decoded from sRGB (1e6 becomes 2.5e14), multiplied by a material and summed over eight lights,
// it must stay far below the largest float, or the pixel becomes infinite.
inline constexpr float kMaxColorComponent = 1e6f;

// A material as written in an MTL file (colours are the file's numbers, not yet decoded to linear).
struct Material {
    std::string name = "default";
    glm::vec3 ambient{0.8f};   // Ka (the default material reflects ambient light like diffuse)
    glm::vec3 diffuse{0.8f};   // Kd
    glm::vec3 specular{0.2f};  // Ks
    float shininess = 32.0f;   // Ns, the Phong exponent
    glm::vec3 emission{0.0f};  // Ke
    float opacity = 1.0f;      // d, or 1 - Tr
    float ior = 1.0f;          // Ni, the optical density (index of refraction); 1 when not given
    std::filesystem::path
        diffuseTexture;  // map_Kd, resolved against the MTL's folder; empty if none or missing
    std::filesystem::path emissionTexture;  // map_Ke, the same way
    // No material of a file: the faces have no usemtl, or name one no MTL file defines. These
    // defaults are then Facet's; the gl preset lights such faces with OpenGL's (kGlDefaultMaterial).
    bool fallback = false;
};

struct MeshVertex {
    glm::vec3 position;  // object space
    glm::vec3 normal;    // object space, unit length
    glm::vec2 uv;        // texture coordinates (0,0 when the file has none)
};

// A run of triangles that share one material: indices[firstIndex, firstIndex + indexCount).
struct MeshPart {
    std::uint32_t firstIndex = 0;
    std::uint32_t indexCount = 0;
    std::uint32_t material = 0;  // index into Mesh::materials
};

struct ImportStats {
    std::size_t facesRead = 0;          // 'f' statements
    std::size_t trianglesKept = 0;      // after fan triangulation and skipping degenerate ones
    std::size_t degenerateSkipped = 0;  // triangles with zero area or repeated corners
    std::size_t normalsComputed = 0;    // vertices whose normal was computed (area-weighted)
    std::size_t creaseSplits = 0;       // of those, vertices added by splitting a welded one at a crease
};

struct Mesh {
    std::vector<MeshVertex> vertices;
    std::vector<std::uint32_t> indices;  // three per triangle
    std::vector<MeshPart> parts;
    std::vector<Material> materials;  // never empty: a neutral default when the file names none
    bool hasTexcoords = false;
    ImportStats stats;
    std::vector<std::string> warnings;  // one line each, "file:line: ..." (missing MTL, missing texture, ...)
    glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};  // object-space bounding box of the used vertices
};

}  // namespace facet
