// Exact hull features: the extreme points come from hull_summary (hull.cpp); a full-dimensional
// set of extreme points is hulled again with CGAL::convex_hull_3 (Epick: exact predicates on
// the input doubles), which then has no vertex inside a facet or on an edge, and adjacent
// triangles whose four corners are coplanar (an exact predicate) are merged into one face by
// union-find. Normals and edge vectors are formed from the input doubles in GMP rationals
// (CGAL::Gmpq), so they are exact until the final canonical rounding (see hull_features.hpp).
#include "gjklab/exact/hull_features.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Gmpq.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include "exact/hull/hull.hpp"
#include "gjklab/geometry/polytope.hpp"

namespace gjklab::exact {

namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Q = CGAL::Gmpq;

struct QVec {
  Q x, y, z;
};

QVec exact(const Vec3& v) {
  return {Q(v.x()), Q(v.y()), Q(v.z())};  // a double converts to Gmpq exactly
}
QVec operator-(const QVec& a, const QVec& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
QVec cross(const QVec& a, const QVec& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
QVec negated(const QVec& a) {
  return {-a.x, -a.y, -a.z};
}
Q abs_of(const Q& q) {
  return q < 0 ? Q(-q) : q;
}

/// v divided exactly by `divisor`, rounded componentwise, then normalised in double. The
/// quotient's components lie in [−1, 1] with one of them ±1, so the normalisation cannot
/// overflow or lose the vector to underflow.
Vec3 round_and_normalise(const QVec& v, const Q& divisor) {
  const Vec3 r((v.x / divisor).to_double(), (v.y / divisor).to_double(),
               (v.z / divisor).to_double());
  return r / r.norm();
}

/// Index of the component of largest magnitude (the first one on ties).
int largest_component(const QVec& v) {
  const Q ax = abs_of(v.x), ay = abs_of(v.y), az = abs_of(v.z);
  if (ax >= ay && ax >= az) return 0;
  return ay >= az ? 1 : 2;
}
const Q& component(const QVec& v, int i) {
  return i == 0 ? v.x : (i == 1 ? v.y : v.z);
}

/// A normal keeps its orientation: divided by its largest absolute component.
Vec3 canonical_normal(const QVec& n) {
  return round_and_normalise(n, abs_of(component(n, largest_component(n))));
}
/// A direction loses its sign: divided by its largest component, which becomes +1.
Vec3 canonical_direction(const QVec& d) {
  return round_and_normalise(d, component(d, largest_component(d)));
}

bool lex_less(const Vec3& a, const Vec3& b) {
  if (a.x() != b.x()) return a.x() < b.x();
  if (a.y() != b.y()) return a.y() < b.y();
  return a.z() < b.z();
}

/// Sorts and removes bitwise duplicates.
void unique_directions(std::vector<Vec3>& d) {
  std::sort(d.begin(), d.end(), lex_less);
  d.erase(std::unique(d.begin(), d.end()), d.end());
}

/// Puts the faces (and their normals) in the lexicographic order of the normals, faces whose
/// rounded normals are bitwise equal in the lexicographic order of their vertex loops: the
/// order in which CGAL's hull lists its faces depends on heap addresses (it varied with the
/// thread a cloud was hulled on, and with the allocations made before the hull), and SAT's
/// early exit counts axes in this order. The tie-break is needed: two adjacent triangles of a
/// nearly flat quad (a UV sphere's) are distinct faces whose exact normals round to the same
/// double, and sums over the faces in either order (a body's centre of mass) differ in the
/// last bit. Loops are canonical (sorted vertices, each loop starting at its smallest index)
/// and distinct faces have distinct loops, so the order is total.
void sort_faces_by_normal(HullFeatures& out) {
  std::vector<std::size_t> order(out.face_normals.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    const Vec3& a = out.face_normals[i];
    const Vec3& b = out.face_normals[j];
    if (a != b) return lex_less(a, b);
    return out.faces[i] < out.faces[j];
  });
  std::vector<Vec3> normals;
  std::vector<std::vector<int>> faces;
  for (std::size_t i : order) {
    normals.push_back(out.face_normals[i]);
    faces.push_back(std::move(out.faces[i]));
  }
  out.face_normals = std::move(normals);
  out.faces = std::move(faces);
}

void flat_features(HullFeatures& out) {
  const std::vector<Vec3>& p = out.vertices;  // the polygon's corners, in cyclic order
  const int n = static_cast<int>(p.size());
  // Corners are strictly convex, so any three consecutive ones give the loop's orientation.
  const QVec q0 = exact(p[0]);
  const QVec m = cross(exact(p[1]) - q0, exact(p[2]) - q0);
  out.face_normals.push_back(canonical_normal(m));
  out.face_normals.push_back(canonical_normal(negated(m)));
  std::vector<int> loop(n);
  std::iota(loop.begin(), loop.end(), 0);
  out.faces.push_back(loop);
  std::reverse(loop.begin(), loop.end());
  out.faces.push_back(loop);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    const QVec e = exact(p[j]) - exact(p[i]);
    out.face_normals.push_back(canonical_normal(cross(e, m)));  // in-plane, outward
    out.edge_directions.push_back(canonical_direction(e));
    out.edges.push_back({i, j});
  }
  unique_directions(out.edge_directions);
}

using Mesh = CGAL::Surface_mesh<Epick::Point_3>;

/// For each mesh vertex, the index of its point in out.vertices. Every input point is extreme,
/// so the hull's vertices are exactly the input points; they keep their (lexicographic) input
/// order: the order of the mesh's vertices depends on heap addresses inside CGAL, and a peer's
/// answer can depend on the vertex order (FCL's Convex averages its vertices for an interior
/// point and breaks support ties by index).
std::vector<int> input_indices(const Mesh& mesh, const HullFeatures& out) {
  std::vector<int> index(mesh.number_of_vertices(), -1);
  for (Mesh::Vertex_index v : mesh.vertices()) {
    const Epick::Point_3& p = mesh.point(v);
    const Vec3 q(p.x(), p.y(), p.z());
    const auto found = std::lower_bound(out.vertices.begin(), out.vertices.end(), q, lex_less);
    if (found == out.vertices.end() || *found != q)
      throw std::logic_error("hull features: a hull vertex is not an input point");
    index[v.idx()] = static_cast<int>(found - out.vertices.begin());
  }
  return index;
}

/// The mesh's triangles grouped into faces: union-find of triangles that share an edge and lie
/// in one plane.
class CoplanarGroups {
 public:
  explicit CoplanarGroups(const Mesh& mesh) : mesh_(mesh), parent_(mesh.number_of_faces()) {
    std::iota(parent_.begin(), parent_.end(), 0);
    for (Mesh::Edge_index e : mesh.edges()) {
      const Mesh::Halfedge_index h = mesh.halfedge(e), o = mesh.opposite(h);
      const auto& p = mesh.point(mesh.source(h));
      const auto& q = mesh.point(mesh.target(h));
      const auto& r = mesh.point(mesh.target(mesh.next(h)));
      const auto& s = mesh.point(mesh.target(mesh.next(o)));
      if (CGAL::coplanar(p, q, r, s)) parent_[of(mesh.face(h))] = of(mesh.face(o));
    }
  }
  std::size_t size() const { return parent_.size(); }
  int of(Mesh::Face_index f) {
    int g = static_cast<int>(f.idx());
    while (parent_[g] != g)
      g = parent_[g] = parent_[parent_[g]];
    return g;
  }
  int of(Mesh::Halfedge_index h) { return of(mesh_.face(h)); }

 private:
  const Mesh& mesh_;
  std::vector<int> parent_;
};

/// A halfedge of group g's boundary (its opposite in another group), searching g's triangles.
Mesh::Halfedge_index boundary_halfedge(const Mesh& mesh, CoplanarGroups& groups, int g) {
  for (Mesh::Face_index t : mesh.faces()) {
    if (groups.of(t) != g) continue;
    for (Mesh::Halfedge_index h : CGAL::halfedges_around_face(mesh.halfedge(t), mesh))
      if (groups.of(mesh.opposite(h)) != g) return h;
  }
  throw std::logic_error("hull features: a face group has no boundary");
}

/// Group g's boundary loop as input indices, from the boundary halfedge `start`, starting at
/// its smallest index (not at whichever boundary halfedge came first).
std::vector<int> boundary_loop(const Mesh& mesh, CoplanarGroups& groups, int g,
                               Mesh::Halfedge_index start, const std::vector<int>& index) {
  std::vector<int> loop;
  Mesh::Halfedge_index h = start;
  do {
    loop.push_back(index[mesh.source(h).idx()]);
    Mesh::Halfedge_index n = mesh.next(h);
    while (groups.of(mesh.opposite(n)) == g)
      n = mesh.next(mesh.opposite(n));
    h = n;
    if (loop.size() > mesh.number_of_halfedges())
      throw std::logic_error("hull features: open face boundary");
  } while (h != start);
  std::rotate(loop.begin(), std::min_element(loop.begin(), loop.end()), loop.end());
  return loop;
}

/// One face per group: its normal from any of its triangles, its boundary loop.
void add_faces(const Mesh& mesh, CoplanarGroups& groups, const std::vector<int>& index,
               HullFeatures& out) {
  std::vector<bool> done(groups.size(), false);
  for (Mesh::Face_index f : mesh.faces()) {
    const int g = groups.of(f);
    if (done[g]) continue;
    done[g] = true;
    const Mesh::Halfedge_index h0 = mesh.halfedge(f);
    const QVec p = exact(out.vertices[index[mesh.source(h0).idx()]]);
    const QVec q = exact(out.vertices[index[mesh.target(h0).idx()]]);
    const QVec r = exact(out.vertices[index[mesh.target(mesh.next(h0)).idx()]]);
    out.face_normals.push_back(canonical_normal(cross(q - p, r - p)));
    out.faces.push_back(boundary_loop(mesh, groups, g, boundary_halfedge(mesh, groups, g), index));
  }
}

/// The edges between different faces, with their canonical directions.
void add_edges(const Mesh& mesh, CoplanarGroups& groups, const std::vector<int>& index,
               HullFeatures& out) {
  for (Mesh::Edge_index e : mesh.edges()) {
    const Mesh::Halfedge_index h = mesh.halfedge(e);
    if (groups.of(h) == groups.of(mesh.opposite(h))) continue;  // inside a merged face
    const int a = index[mesh.source(h).idx()], b = index[mesh.target(h).idx()];
    out.edges.push_back({std::min(a, b), std::max(a, b)});
    out.edge_directions.push_back(
        canonical_direction(exact(out.vertices[b]) - exact(out.vertices[a])));
  }
  std::sort(out.edges.begin(), out.edges.end());
  unique_directions(out.edge_directions);
}

void solid_features(HullFeatures& out) {
  std::vector<Epick::Point_3> points;
  points.reserve(out.vertices.size());
  for (const Vec3& v : out.vertices)
    points.emplace_back(v.x(), v.y(), v.z());
  Mesh mesh;
  CGAL::convex_hull_3(points.begin(), points.end(), mesh);
  const std::vector<int> index = input_indices(mesh, out);
  CoplanarGroups groups(mesh);
  add_faces(mesh, groups, index, out);
  add_edges(mesh, groups, index, out);
  sort_faces_by_normal(out);
}

}  // namespace

HullFeatures hull_features(std::span<const Vec3> cloud) {
  if (std::string problem = describe_invalid_cloud(cloud); !problem.empty())
    throw InvalidGeometry("hull features: " + problem);
  detail::HullSummary summary = detail::hull_summary(cloud);
  HullFeatures out;
  out.dimension = summary.dimension;
  out.vertices = std::move(summary.extreme_points);
  switch (out.dimension) {
    case 0:
      break;
    case 1: {
      out.edges.push_back({0, 1});
      out.edge_directions.push_back(
          canonical_direction(exact(out.vertices[1]) - exact(out.vertices[0])));
      break;
    }
    case 2:
      flat_features(out);
      break;
    default:
      solid_features(out);
      break;
  }
  return out;
}

}  // namespace gjklab::exact
