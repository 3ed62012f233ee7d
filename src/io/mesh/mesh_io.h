// Triangle-mesh readers shared by every scene format: OFF, PLY (ASCII and binary) and OBJ.
// Polygons are fan-triangulated. Errors throw ParseError with the mesh file's line (and column).
#pragma once

#include <string>
#include <vector>

#include "scene/shape.h"

namespace phos::io {

// A mesh read from a file, with the per-face material names an OBJ/MTL file may carry.
struct LoadedMesh {
    scene::TriangleMesh mesh;
    // OBJ: per triangle, an index into `material_names` (-1: none); empty for OFF/PLY.
    std::vector<int> triangle_materials;
    std::vector<std::string> material_names;
};

scene::TriangleMesh read_off(const std::string& path);
scene::TriangleMesh read_ply(const std::string& path);
LoadedMesh read_obj(const std::string& path);
// Dispatches on the extension (.off, .ply, .obj); throws ParseError for anything else.
LoadedMesh read_mesh(const std::string& path);

}  // namespace phos::io
