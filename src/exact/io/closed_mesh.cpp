// Closed triangle meshes: the exact geometric checks (CGAL's exact predicates and Polygon Mesh
// Processing) over the combinatorial ones of mesh_checks.cpp. The order of the checks is
// closed_mesh.hpp's; each refuses at its first offending face.
#include "gjklab/exact/closed_mesh.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <functional>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "exact/io/mesh_checks.hpp"
#include "exact/io/mesh_soup.hpp"

namespace gjklab::exact {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using detail::face_label;
using detail::refuse;

Point point_of(const Vec3& p) {
  return {p.x(), p.y(), p.z()};
}

/// Check 3: no repeated index, no three collinear vertices (Epick's predicate is exact: a
/// floating-point filter with an exact fallback; two equal points count as collinear).
void check_degenerate_faces(const TriangleMesh& mesh, std::string_view source) {
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const MeshFace& t = mesh.faces[f];
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      refuse(source, face_label(mesh, f) + ": a degenerate face (a repeated vertex index)");
    if (CGAL::collinear(point_of(mesh.vertices[t[0]]), point_of(mesh.vertices[t[1]]),
                        point_of(mesh.vertices[t[2]])))
      refuse(source, face_label(mesh, f) +
                         ": a degenerate face (its three vertices are collinear, or two coincide)");
  }
}

/// The mesh as CGAL's halfedge structure: vertex i and face i keep their index. Faces are
/// added as CGAL's own soup-to-mesh conversion adds them (Euler::add_face), which accepts them
/// in any order once the combinatorial checks passed.
Mesh surface_mesh(const TriangleMesh& mesh, std::string_view source) {
  Mesh out;
  out.reserve(static_cast<Mesh::size_type>(mesh.vertices.size()),
              static_cast<Mesh::size_type>(3 * mesh.faces.size() / 2),
              static_cast<Mesh::size_type>(mesh.faces.size()));
  for (const Vec3& p : mesh.vertices)
    out.add_vertex(point_of(p));
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const MeshFace& t = mesh.faces[f];
    const std::array<Mesh::Vertex_index, 3> corners = {
        Mesh::Vertex_index(t[0]), Mesh::Vertex_index(t[1]), Mesh::Vertex_index(t[2])};
    if (CGAL::Euler::add_face(corners, out) == Mesh::null_face())
      refuse(source, face_label(mesh, f) + ": cannot be joined to the faces before it");
  }
  return out;
}

/// Check 7: two faces meet only in their shared edge or vertex. CGAL's self_intersections with
/// an exact-predicates kernel; sequential, so the pair it finds first is the same every run.
void check_self_intersections(const TriangleMesh& mesh, const Mesh& tm, std::string_view source) {
  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> pairs;
  PMP::self_intersections<CGAL::Sequential_tag>(tm, std::back_inserter(pairs),
                                                CGAL::parameters::maximum_number(1));
  if (pairs.empty()) return;
  std::size_t f = pairs[0].first.idx(), g = pairs[0].second.idx();
  if (g < f) std::swap(f, g);
  refuse(source, face_label(mesh, f) + ": intersects " + face_label(mesh, g) +
                     " (a self-intersecting mesh; faces may meet only at a shared edge or vertex)");
}

/// det(a, b, c) = a · (b × c) for face f's vertices a, b, c, in T (each double converted
/// exactly; an interval or a rational).
template <class T>
T determinant(const TriangleMesh& mesh, std::size_t f) {
  const auto v = [&](int k, int i) { return T(mesh.vertices[mesh.faces[f][k]][i]); };
  return v(0, 0) * (v(1, 1) * v(2, 2) - v(1, 2) * v(2, 1)) +
         v(0, 1) * (v(1, 2) * v(2, 0) - v(1, 0) * v(2, 2)) +
         v(0, 2) * (v(1, 0) * v(2, 1) - v(1, 1) * v(2, 0));
}

/// Six times the signed volume of each component, as its sign: the sum over its faces of
/// det(a, b, c) = a · (b × c) (the tetrahedra from the origin; exact whatever the origin for a
/// closed surface). Interval arithmetic first; GMP rationals for a component whose interval
/// holds 0.
std::vector<int> volume_signs(const TriangleMesh& mesh, const detail::MeshComponents& c) {
  using Interval = CGAL::Interval_nt<false>;
  std::vector<Interval> sums(c.first_face.size(), Interval(0));
  {
    const CGAL::Protect_FPU_rounding<true> upward;  // what Interval_nt<false> needs
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      sums[c.of_face[f]] += determinant<Interval>(mesh, f);
    }
  }
  std::vector<int> signs(sums.size(), 0);
  for (std::size_t k = 0; k < sums.size(); ++k) {
    if (sums[k].inf() > 0 || sums[k].sup() < 0) {
      signs[k] = sums[k].inf() > 0 ? 1 : -1;
      continue;
    }
    mpq_class exact = 0;
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
      if (c.of_face[f] == k) exact += determinant<mpq_class>(mesh, f);
    }
    signs[k] = sgn(exact);
  }
  return signs;
}

std::string component_text(const detail::MeshComponents& c, std::size_t k) {
  if (c.first_face.size() == 1) return "the mesh";
  return "its connected component (" + std::to_string(k) + " of " +
         std::to_string(c.first_face.size()) + ", counted from 0 by lowest face)";
}

/// Check 8: each component encloses a positive signed volume (outward faces).
void check_outward(const TriangleMesh& mesh, const detail::MeshComponents& c,
                   std::string_view source) {
  const std::vector<int> signs = volume_signs(mesh, c);
  for (std::size_t k = 0; k < signs.size(); ++k) {
    if (signs[k] > 0) continue;
    const std::string where = face_label(mesh, c.first_face[k]) + ": " + component_text(c, k);
    if (signs[k] < 0)
      refuse(source, where +
                         " encloses a negative signed volume: its faces point inward (an "
                         "inverted mesh, or a cavity; reverse the order of every face's vertices)");
    refuse(source, where + " encloses no volume");
  }
}

/// Check 9: no component inside another (CGAL's volume_connected_components, nesting only:
/// side-of-mesh tests with exact predicates). Scanning faces in order names the lowest face of
/// the lowest nested component, whatever CGAL's own numbering of components.
void check_not_nested(const TriangleMesh& mesh, Mesh& tm, const detail::MeshComponents& c,
                      std::string_view source) {
  if (c.first_face.size() < 2) return;
  std::vector<std::size_t> levels;
  auto volume_of_face = tm.add_property_map<Mesh::Face_index, std::size_t>("f:volume", 0).first;
  auto cgal_component = tm.add_property_map<Mesh::Face_index, std::size_t>("f:cc", 0).first;
  PMP::volume_connected_components(tm, volume_of_face,
                                   CGAL::parameters::nesting_levels(std::ref(levels))
                                       .do_orientation_tests(false)
                                       .face_connected_component_map(cgal_component));
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    if (levels[cgal_component[Mesh::Face_index(static_cast<Mesh::size_type>(f))]] == 0) continue;
    const std::size_t k = c.of_face[f];
    refuse(source, face_label(mesh, c.first_face[k]) + ": " + component_text(c, k) +
                       " lies inside another component (nested shells are refused: each "
                       "component must be a separate solid)");
  }
}

void validate_triangles(const TriangleMesh& mesh, std::string_view source) {
  check_degenerate_faces(mesh, source);
  detail::check_sizes(mesh, source);
  const detail::MeshComponents components = detail::check_topology(mesh, source);
  Mesh tm = surface_mesh(mesh, source);
  check_self_intersections(mesh, tm, source);
  check_outward(mesh, components, source);
  check_not_nested(mesh, tm, components, source);
}

}  // namespace

void validate_closed_mesh(const TriangleMesh& mesh, std::string_view source) {
  detail::check_coordinates(mesh, source);
  detail::check_indices(mesh, source);
  validate_triangles(mesh, source);
}

TriangleMesh read_closed_mesh(const std::filesystem::path& file) {
  const std::string name = file.string();
  detail::MeshSoup soup = detail::read_mesh_soup(file, true);
  detail::check_coordinates(soup, name);
  const TriangleMesh mesh = detail::triangles_of(std::move(soup), name);
  validate_triangles(mesh, name);
  return mesh;
}

}  // namespace gjklab::exact
