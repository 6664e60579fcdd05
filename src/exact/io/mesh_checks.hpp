// Internal to src/exact/: the checks of a closed triangle mesh that need no geometry predicate
// (closed_mesh.cpp makes the exact geometric ones with CGAL). No CGAL here. Each check throws
// std::runtime_error "SOURCE: problem" at the first offending face (lowest index).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "exact/io/mesh_soup.hpp"
#include "gjklab/geometry/triangle_mesh.hpp"

namespace gjklab::exact::detail {

/// Throws std::runtime_error "SOURCE: problem".
[[noreturn]] void refuse(std::string_view source, const std::string& problem);

/// "face 3 (vertices 0, 5, 2)": how messages name a face (indices from 0, in file order).
std::string face_label(const TriangleMesh& mesh, std::size_t face);

/// Check 1: every coordinate finite and within kMaxMeshCoordinate (the message names the
/// vertex and the first face that uses it).
void check_coordinates(const MeshSoup& soup, std::string_view source);
void check_coordinates(const TriangleMesh& mesh, std::string_view source);

/// The triangles of a soup whose coordinates passed check 1. Check 2 and arity: a face of
/// other than three vertices, or with an index out of range, is refused (nothing is
/// triangulated).
TriangleMesh triangles_of(MeshSoup soup, std::string_view source);

/// Check 2 on a mesh given as data: every face index names a vertex.
void check_indices(const TriangleMesh& mesh, std::string_view source);

/// Check 4: at least one face; at most kMaxMeshVertices vertices and kMaxMeshFaces faces.
void check_sizes(const TriangleMesh& mesh, std::string_view source);

/// The connected components of a mesh that passed checks 5 and 6 (faces joined by edges).
struct MeshComponents {
  std::vector<std::uint32_t> of_face;     ///< component of each face
  std::vector<std::uint32_t> first_face;  ///< lowest face index of each component
};

/// Checks 5 and 6: closed (each edge in exactly two faces), consistently oriented (the two
/// traverse it in opposite directions), every vertex's faces one fan, every vertex used.
/// Returns the connected components.
MeshComponents check_topology(const TriangleMesh& mesh, std::string_view source);

}  // namespace gjklab::exact::detail
