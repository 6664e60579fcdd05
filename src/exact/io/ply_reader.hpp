// Internal to src/exact/: the vertex coordinates of a PLY file, read by gjklab itself.
//
// Each list count is checked against the bytes left before its items are read (and every
// element count against the file size, by mesh_io.cpp's header check), so no header or body,
// however garbled, can make the reader allocate or read more than the file holds (CGAL's
// reader, used before, trusted them: a face list count of 1.7·10⁸ in a garbled binary file read
// far past its end). ASCII and binary (little and big endian) files, every PLY scalar type.
// The elements other than the vertices are read to check the file and dropped, except the
// faces' vertex index lists when they are asked for.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "exact/io/mesh_soup.hpp"
#include "gjklab/geometry/types.hpp"

namespace gjklab::exact::detail {

/// The x, y, z of every vertex, in file order. Throws std::runtime_error naming the file (and
/// the header line, or the vertex) and the problem.
std::vector<Vec3> read_ply_vertices(const std::filesystem::path& file);

/// The vertices and, with `keep_faces`, the index list of each record of the first `face`
/// element (its list property `vertex_indices`, or `vertex_index`, in file order). Throws as
/// read_ply_vertices, and for a face index that is not a non-negative integer or a face
/// element without that list.
MeshSoup read_ply_mesh(const std::filesystem::path& file, bool keep_faces);

}  // namespace gjklab::exact::detail
