// Closed triangle meshes: read from an OFF, OBJ, PLY or STL file with their faces, or given as
// vertices and faces, and validated in exact arithmetic (CGAL, behind this interface). A mesh
// that fails a check is refused, never repaired.
//
// The checks, in this order (the first that fails is the error):
//  1. every coordinate finite and |x| <= kMaxMeshCoordinate;
//  2. every face index names a vertex;
//  3. no degenerate face: no repeated index, and the three vertices not collinear (exact
//     orientation predicate; two equal points are collinear);
//  4. at most kMaxMeshVertices vertices and kMaxMeshFaces faces;
//  5. closed: every edge is shared by exactly two faces (no boundary, no non-manifold edge);
//  6. consistently oriented: the two faces of an edge traverse it in opposite directions;
//     every vertex's faces form one fan (no non-manifold vertex); every vertex used by a face;
//  7. no self-intersection: two faces meet only in their shared edge or vertex (CGAL's
//     Polygon_mesh_processing::self_intersections, exact predicates);
//  8. not inverted: each connected component encloses a positive signed volume (summed
//     exactly), so its faces point outward;
//  9. no component lies inside another (a mesh of several components is accepted when they
//     are disjoint solids side by side; a cavity or a shell inside a shell is refused).
// Errors are std::runtime_error, "SOURCE: face F (vertices A, B, C): problem", naming the
// first offending face (lowest index) where a face is at fault.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string_view>
#include <vector>

#include "gjklab/geometry/triangle_mesh.hpp"

namespace gjklab::exact {

/// Largest |coordinate| accepted (absolute, length units). Exact arithmetic has no range
/// limit, but the floating-point queries on a mesh do: at 1e15 a triple product of coordinates
/// (1e45) and a squared distance (1e30) stay far below double's 1.8e308.
inline constexpr double kMaxMeshCoordinate = 1e15;
/// Largest number of faces and of vertices accepted. A closed mesh all of whose vertices are
/// used has at most as many vertices as faces, so the vertex limit follows from the face limit.
inline constexpr std::size_t kMaxMeshFaces = 1'000'000;
inline constexpr std::size_t kMaxMeshVertices = kMaxMeshFaces;

/// Reads a mesh file (.off, .obj, .ply or .stl, by extension; the safety checks of
/// read_mesh_vertices) with its faces, and validates it as above. STL files, which repeat each
/// vertex in every triangle, have exactly equal vertices merged (in order of first appearance).
/// A face of more than three vertices is refused, not triangulated. Throws std::runtime_error
/// naming the file.
TriangleMesh read_closed_mesh(const std::filesystem::path& file);

/// Validates `mesh` as above; `source` names it in messages (a file, or "line 3"). Throws
/// std::runtime_error.
void validate_closed_mesh(const TriangleMesh& mesh, std::string_view source);

}  // namespace gjklab::exact
