#include "io/obj_tinyobj.h"

#include <cstddef>
#include <istream>
#include <streambuf>
#include <type_traits>

namespace facet::obj {

namespace {

// tinyobjloader::tinyobjloader is the float build; the _double one compiles with TINYOBJLOADER_USE_DOUBLE.
static_assert(std::is_same_v<tinyobj::real_t, float>, "link tinyobjloader::tinyobjloader (float build)");

// The text as an input stream for tinyobjloader, read in place (an istringstream would copy it).
class TextStreamBuffer : public std::streambuf {
  public:
    explicit TextStreamBuffer(std::string& text) {
        setg(text.data(), text.data(), text.data() + text.size());
    }
};

}  // namespace

TinyobjRead readWithTinyobjloader(std::string& text, tinyobj::MaterialReader& reader,
                                  std::vector<tinyobj::material_t>& materials) {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::string warnings, errors;  // its warnings repeat what checkObj reports better
    TextStreamBuffer buffer(text);
    std::istream stream(&buffer);
    TinyobjRead read;
    read.parsed = tinyobj::LoadObj(&attrib, &shapes, &materials, &warnings, &errors, &stream, &reader,
                                   /*triangulate=*/false, /*default_vcols_fallback=*/false);
    if (!read.parsed) {
        read.error = errors.substr(0, errors.find('\n'));
        return read;
    }
    ObjGeometry& geometry = read.geometry;
    geometry.positions = std::move(attrib.vertices);
    geometry.texcoords = std::move(attrib.texcoords);
    geometry.normals = std::move(attrib.normals);
    const std::size_t texcoordCount = geometry.texcoords.size() / 2,
                      normalCount = geometry.normals.size() / 3;
    // checkObj warned of a texture coordinate or normal index out of range: the corner goes without it.
    const auto kept = [](int index, std::size_t size) {
        return index >= 0 && std::size_t(index) < size ? index : -1;
    };
    for (const tinyobj::shape_t& shape : shapes) {
        const tinyobj::mesh_t& mesh = shape.mesh;
        for (const tinyobj::index_t& corner : mesh.indices)
            geometry.corners.push_back({corner.vertex_index, kept(corner.texcoord_index, texcoordCount),
                                        kept(corner.normal_index, normalCount)});
        for (std::size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
            geometry.cornerCounts.push_back(mesh.num_face_vertices[f]);
            read.faceMaterials.push_back(f < mesh.material_ids.size() ? mesh.material_ids[f] : -1);
        }
    }
    return read;
}

}  // namespace facet::obj
