// Exact truth for two closed triangle meshes (see gjklab/exact/mesh_truth.hpp).
//
// Three phases, each exact where it decides:
// 1. Triangles that meet: the face pairs whose boxes overlap (exact comparisons of the given
//    doubles) are tested with CGAL's triangle–triangle intersection under exact predicates.
// 2. Containment, when no triangles meet: then either solid holds the other entirely or they
//    are apart, so one vertex of each decides (CGAL's Side_of_triangle_mesh, exact predicates),
//    and only when one root box lies inside the other's.
// 3. The distance: a best-first walk over both trees finds the nearest pair in double; its
//    exact squared distance (CGAL, rationals) is the first upper bound. A second walk then
//    evaluates exactly only the pairs whose proven lower bound (triangle_tree.hpp) does not
//    exceed the best exact value so far, rounded up.
#include "gjklab/exact/mesh_truth.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Gmpq.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/intersections.h>
#include <CGAL/squared_distance_3.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "exact/arithmetic/gmp_support.hpp"
#include "exact/mesh/triangle_tree.hpp"

namespace gjklab::exact {

namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Rational3 = CGAL::Simple_cartesian<CGAL::Gmpq>;

Epick::Point_3 epick(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}
Epick::Triangle_3 epick_triangle(const MeshView& m, std::uint32_t face) {
  const auto& f = m.faces[face];
  return {epick(m.vertices[f[0]]), epick(m.vertices[f[1]]), epick(m.vertices[f[2]])};
}
Rational3::Point_3 rational(const Vec3& v) {
  return {CGAL::Gmpq(v.x()), CGAL::Gmpq(v.y()), CGAL::Gmpq(v.z())};
}
Rational3::Triangle_3 rational_triangle(const MeshView& m, std::uint32_t face) {
  const auto& f = m.faces[face];
  return {rational(m.vertices[f[0]]), rational(m.vertices[f[1]]), rational(m.vertices[f[2]])};
}

/// Refuses what the answer cannot be given for: no faces, an index out of range, a non-finite
/// coordinate, a face whose corners are collinear (exact predicate).
void check_mesh(const MeshView& m, const char* side) {
  auto fail = [&](const std::string& what) {
    throw std::invalid_argument(std::string("mesh ") + side + ": " + what);
  };
  if (m.faces.empty()) fail("has no faces");
  for (std::size_t i = 0; i < m.vertices.size(); ++i)
    if (!m.vertices[i].allFinite()) fail("vertex " + std::to_string(i) + " is not finite");
  for (std::size_t f = 0; f < m.faces.size(); ++f) {
    for (std::uint32_t v : m.faces[f])
      if (v >= m.vertices.size())
        fail("face " + std::to_string(f) + " names vertex " + std::to_string(v) + " of " +
             std::to_string(m.vertices.size()));
    const auto& t = m.faces[f];
    if (CGAL::collinear(epick(m.vertices[t[0]]), epick(m.vertices[t[1]]), epick(m.vertices[t[2]])))
      fail("face " + std::to_string(f) + " is degenerate (its corners are collinear)");
  }
}

/// Whether the box `inner` lies in the closed box `outer` (exact comparisons).
bool box_inside(const mesh::Box& inner, const mesh::Box& outer) {
  return (inner.lo.array() >= outer.lo.array()).all() &&
         (inner.hi.array() <= outer.hi.array()).all();
}

/// Whether the point lies strictly inside the solid the closed mesh bounds.
bool inside_solid(const Vec3& point, const MeshView& m) {
  using SurfaceMesh = CGAL::Surface_mesh<Epick::Point_3>;
  SurfaceMesh surface;
  std::vector<SurfaceMesh::Vertex_index> vertex;
  vertex.reserve(m.vertices.size());
  for (const Vec3& v : m.vertices)
    vertex.push_back(surface.add_vertex(epick(v)));
  for (std::size_t f = 0; f < m.faces.size(); ++f) {
    const auto& t = m.faces[f];
    if (surface.add_face(vertex[t[0]], vertex[t[1]], vertex[t[2]]) == SurfaceMesh::null_face())
      throw std::invalid_argument("mesh face " + std::to_string(f) +
                                  " makes the surface non-manifold; the solid is undefined");
  }
  const CGAL::Side_of_triangle_mesh<SurfaceMesh, Epick> side(surface);
  return side(epick(point)) == CGAL::ON_BOUNDED_SIDE;
}

/// The first corner of the first face: a point of the surface.
Vec3 surface_point(const MeshView& m) {
  return m.vertices[m.faces[0][0]];
}

/// The nearest face pair by the double computation (a seed for the exact walk, not proven).
std::pair<std::uint32_t, std::uint32_t> nearest_in_double(const mesh::TriangleTree& ta,
                                                          const mesh::TriangleTree& tb) {
  double best = std::numeric_limits<double>::infinity();
  std::pair<std::uint32_t, std::uint32_t> pair{ta.order()[0], tb.order()[0]};
  mesh::near_faces(
      ta, tb, [&] { return best; },
      [&](std::uint32_t fa, std::uint32_t fb) {
        const double d2 =
            mesh::approximate_closest(ta.triangle(fa), tb.triangle(fb)).distance_squared;
        if (d2 < best) {
          best = d2;
          pair = {fa, fb};
        }
      });
  return pair;
}

/// A double ≥ q (the nearest double, stepped up once).
double rounded_up(const CGAL::Gmpq& q) {
  return std::nextafter(detail::nearest_double(q.mpq()), std::numeric_limits<double>::infinity());
}

void set_distance(MeshTruth& out, const CGAL::Gmpq& squared) {
  out.distance_squared = detail::to_rational(squared.mpq());
  out.distance = detail::nearest_sqrt(squared.mpq());
}

/// Phase 3: the exact minimum over face pairs of the exact squared distances.
void separated_distance(const MeshView& a, const MeshView& b, const mesh::TriangleTree& ta,
                        const mesh::TriangleTree& tb, MeshTruth& out) {
  auto exact = [&](std::uint32_t fa, std::uint32_t fb) {
    ++out.exact_distance_evaluations;
    return CGAL::squared_distance(rational_triangle(a, fa), rational_triangle(b, fb));
  };
  const auto seed = nearest_in_double(ta, tb);
  CGAL::Gmpq best = exact(seed.first, seed.second);
  out.face_a = seed.first;
  out.face_b = seed.second;
  double bound = rounded_up(best);
  mesh::near_faces(
      ta, tb, [&] { return bound; },
      [&](std::uint32_t fa, std::uint32_t fb) {
        if (fa == seed.first && fb == seed.second) return;
        const mesh::Triangle x = ta.triangle(fa), y = tb.triangle(fb);
        const mesh::ApproxClosest near = mesh::approximate_closest(x, y);
        if (mesh::direction_gap_squared_lower(x, y, near.on_b - near.on_a) > bound) return;
        const CGAL::Gmpq d2 = exact(fa, fb);
        if (d2 < best) {
          best = d2;
          out.face_a = fa;
          out.face_b = fb;
          bound = rounded_up(best);
        }
      });
  set_distance(out, best);
}

}  // namespace

MeshTruth mesh_truth(const MeshView& a, const MeshView& b) {
  check_mesh(a, "A");
  check_mesh(b, "B");
  const mesh::TriangleTree ta(a), tb(b);
  MeshTruth out;
  const bool meet = mesh::any_overlapping_faces(ta, tb, [&](std::uint32_t fa, std::uint32_t fb) {
    ++out.exact_intersection_tests;
    if (!CGAL::do_intersect(epick_triangle(a, fa), epick_triangle(b, fb))) return false;
    out.face_a = fa;
    out.face_b = fb;
    return true;
  });
  if (meet) {
    out.intersect = true;
    out.contact = MeshContact::triangles_meet;
    return out;  // distance_squared 0, distance 0
  }
  const mesh::Box &box_a = ta.nodes()[0].box, &box_b = tb.nodes()[0].box;
  if (box_inside(box_a, box_b) && inside_solid(surface_point(a), b)) {
    out.intersect = true;
    out.contact = MeshContact::a_inside_b;
    return out;
  }
  if (box_inside(box_b, box_a) && inside_solid(surface_point(b), a)) {
    out.intersect = true;
    out.contact = MeshContact::b_inside_a;
    return out;
  }
  separated_distance(a, b, ta, tb, out);
  return out;
}

}  // namespace gjklab::exact
