// Internal to src/exact/: a mesh file as read, before any check of its faces: the vertices in
// file order and each face as the list of vertex indices the file gives (any length, any
// value; an index counts from 0 whatever the format).
#pragma once

#include <cstddef>
#include <filesystem>
#include <vector>

#include "gjklab/geometry/types.hpp"

namespace gjklab::exact::detail {

struct MeshSoup {
  std::vector<Vec3> vertices;
  std::vector<std::vector<std::size_t>> faces;  ///< empty unless faces were asked for
};

/// Reads a .off, .obj, .ply or .stl file with the safety checks of read_mesh_vertices (header
/// counts against the file size, PLY coordinate types). With `keep_faces` the faces are kept
/// (STL: exactly equal vertices merged, in order of first appearance). No check of the
/// coordinates or the faces. Throws std::runtime_error naming the file.
MeshSoup read_mesh_soup(const std::filesystem::path& file, bool keep_faces);

}  // namespace gjklab::exact::detail
