// tinyobjloader's reading of an OBJ, kept as the measured peer of Facet's own reader (obj_scan): the
// importer can read a file either way (ObjReader), the tests check that both give the same meshes, and
// `facet_microbench` times both. Internal to the OBJ importer.
#pragma once

#include <string>
#include <vector>

#include <tiny_obj_loader.h>

#include "io/obj_scan.h"

namespace facet::obj {

struct TinyobjRead {
    ObjGeometry geometry;            // corners with out-of-range texcoord or normal indices dropped
    std::vector<int> faceMaterials;  // per face: its material in `materials` (-1: none)
    std::string error;               // tinyobjloader's first error line when it refused the file
    bool parsed = false;
};

// Reads `text`, as splitObj rewrote it, with tinyobjloader (untriangulated, so that faces stay one to one
// with the file's), its MTL files through `reader` into `materials`. Only reads the text: it may run
// while checkObj checks the same text.
TinyobjRead readWithTinyobjloader(std::string& text, tinyobj::MaterialReader& reader,
                                  std::vector<tinyobj::material_t>& materials);

}  // namespace facet::obj
