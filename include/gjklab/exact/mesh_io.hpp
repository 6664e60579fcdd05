// Mesh files as point clouds: the vertices of an OFF, OBJ, PLY or STL file (read with CGAL's
// I/O, compiled only in src/exact/), whose convex hull is the shape. Faces are ignored here;
// exact/closed_mesh.hpp reads them, for closed triangle meshes.
#pragma once

#include <filesystem>
#include <vector>

#include "gjklab/geometry/types.hpp"

namespace gjklab::exact {

/// The vertices of a mesh file (.off, .obj, .ply or .stl, by extension). Throws
/// std::runtime_error naming the file when it cannot be read, has no vertex or a non-finite one.
std::vector<Vec3> read_mesh_vertices(const std::filesystem::path& file);

/// True for the extensions read_mesh_vertices reads (case-insensitive).
bool is_mesh_file(const std::filesystem::path& file);

/// The mesh files `path` names: the file itself, or a folder's mesh files in name order.
/// Throws std::runtime_error naming the path when it does not exist or the folder holds none.
std::vector<std::filesystem::path> mesh_files(const std::filesystem::path& path);

}  // namespace gjklab::exact
