// Exact convex hulls for the oracle: extreme points of a cloud and the penetration depth.
//
// Extreme points. Input points are doubles, so CGAL's Epick kernel (exact predicates on
// double input, filtered) decides every orientation exactly. The affine dimension is found
// first; a collinear cloud has its two lexicographic extremes, a coplanar cloud is projected
// onto a coordinate plane on which the projection is injective and hulled with Andrew's
// monotone chain keeping strict turns only, and a full-dimensional cloud is hulled with
// CGAL::convex_hull_3. That hull is a triangulated surface whose vertices are on the boundary
// but need not be extreme (quickhull may keep a point that lies inside a flat facet or on an
// edge), so each vertex is then tested: v is extreme iff no neighbour w of v lies, with v, in
// the plane of every triangle around v (such a w would mean the facet normals at v do not
// span space; conversely a vertex inside a facet or an edge has such a neighbour).
//
// Depth. The Minkowski difference A − B is the hull of the pairwise differences of the
// extreme points. The differences are not doubles, so they are built in CGAL's Epeck kernel
// (lazy exact constructions, filtered predicates), hulled, and the minimum over hull facets
// of (n·p)²/(n·n) is taken with exact comparisons; that minimum is read back exactly.
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Gmpq.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#ifdef CGAL_USE_GMPXX
#include <gmpxx.h>
#endif

#include <algorithm>
#include <array>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "exact/hull/hull.hpp"

namespace gjklab::exact::detail {

namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;

bool lex_less(const Vec3& a, const Vec3& b) {
  if (a.x() != b.x()) return a.x() < b.x();
  if (a.y() != b.y()) return a.y() < b.y();
  return a.z() < b.z();
}

Epick::Point_3 to_epick(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}
Vec3 to_vec(const Epick::Point_3& p) {
  return {p.x(), p.y(), p.z()};
}

/// Extreme points of a coplanar cloud of distinct points; p0, p1, p2 are not collinear.
std::vector<Vec3> planar_extreme_points(const std::vector<Vec3>& pts, const Vec3& p0,
                                        const Vec3& p1, const Vec3& p2) {
  // Drop a coordinate along which the plane's normal has a non-zero component: projecting
  // along it is an affine bijection of the plane, so it preserves extremality. Projected
  // coordinates are the input doubles, so the 2D orientation tests stay exact.
  int u = 0, v = 1;
  for (int drop : {2, 0, 1}) {
    const int cu = (drop + 1) % 3, cv = (drop + 2) % 3;
    const Epick::Point_2 a(p0[cu], p0[cv]), b(p1[cu], p1[cv]), c(p2[cu], p2[cv]);
    if (CGAL::orientation(a, b, c) != CGAL::COLLINEAR) {
      u = cu;
      v = cv;
      break;
    }
  }
  struct Item {
    Epick::Point_2 q;
    std::size_t index;
  };
  std::vector<Item> items;
  items.reserve(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i)
    items.push_back({{pts[i][u], pts[i][v]}, i});
  std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
    return a.q.x() != b.q.x() ? a.q.x() < b.q.x() : a.q.y() < b.q.y();
  });
  // Andrew's monotone chain; a point is kept only where the chain turns strictly left, so
  // points in the interior of hull edges are dropped.
  std::vector<const Item*> chain;
  chain.reserve(2 * items.size());
  auto push = [&chain](const Item& item, std::size_t floor) {
    while (chain.size() >= floor + 2 &&
           CGAL::orientation(chain[chain.size() - 2]->q, chain.back()->q, item.q) !=
               CGAL::LEFT_TURN)
      chain.pop_back();
    chain.push_back(&item);
  };
  for (const Item& item : items)
    push(item, 0);
  const std::size_t lower = chain.size();
  for (std::size_t i = items.size() - 1; i-- > 0;)
    push(items[i], lower - 1);
  chain.pop_back();  // the last point closes the loop at the first
  std::vector<Vec3> out;
  out.reserve(chain.size());
  for (const Item* item : chain)
    out.push_back(pts[item->index]);
  return out;
}

/// Extreme points of a full-dimensional cloud, in lexicographic order. CGAL's hull lists its
/// vertices in an order that depends on heap addresses (its quickhull keys a std::map by vertex
/// handles, and its containers iterate in storage order), so that order is not used.
std::vector<Vec3> solid_extreme_points(const std::vector<Vec3>& pts) {
  std::vector<Epick::Point_3> points;
  points.reserve(pts.size());
  for (const Vec3& p : pts)
    points.push_back(to_epick(p));
  using Mesh = CGAL::Surface_mesh<Epick::Point_3>;
  Mesh mesh;
  CGAL::convex_hull_3(points.begin(), points.end(), mesh);

  std::vector<Vec3> out;
  std::vector<std::array<Epick::Point_3, 2>> around;  // the other two corners of each triangle
  std::vector<Epick::Point_3> neighbours;
  for (Mesh::Vertex_index vtx : mesh.vertices()) {
    const Epick::Point_3& p = mesh.point(vtx);
    around.clear();
    neighbours.clear();
    for (Mesh::Halfedge_index h : CGAL::halfedges_around_target(mesh.halfedge(vtx), mesh)) {
      neighbours.push_back(mesh.point(mesh.source(h)));
      if (!mesh.is_border(h))
        around.push_back({mesh.point(mesh.source(h)), mesh.point(mesh.target(mesh.next(h)))});
    }
    const bool flat_direction =
        std::any_of(neighbours.begin(), neighbours.end(), [&](const Epick::Point_3& w) {
          return std::all_of(around.begin(), around.end(),
                             [&](const auto& tri) { return CGAL::coplanar(p, tri[0], tri[1], w); });
        });
    if (!flat_direction) out.push_back(to_vec(p));
  }
  std::sort(out.begin(), out.end(), lex_less);
  return out;
}

// Reading an exact Epeck number back as a GMP rational. Which exact type Epeck uses depends
// on how CGAL was configured; the generic fallback goes through CGAL's "num/den" output.
[[maybe_unused]] void assign(mpq_ptr out, const CGAL::Gmpq& x) {
  mpq_set(out, x.mpq());
}
#ifdef CGAL_USE_GMPXX
[[maybe_unused]] void assign(mpq_ptr out, const mpq_class& x) {
  mpq_set(out, x.get_mpq_t());
}
#endif
template <class T>
void assign(mpq_ptr out, const T& x) {
  std::ostringstream text;
  text << x;
  if (mpq_set_str(out, text.str().c_str(), 10) != 0)
    throw std::logic_error("exact oracle: cannot read exact number '" + text.str() + "'");
  mpq_canonicalize(out);
}

}  // namespace

HullSummary hull_summary(std::span<const Vec3> cloud) {
  std::vector<Vec3> pts(cloud.begin(), cloud.end());
  std::sort(pts.begin(), pts.end(), lex_less);
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());  // == is exact equality

  HullSummary out;
  if (pts.size() == 1) {
    out.dimension = 0;
    out.extreme_points = pts;
    return out;
  }
  const Epick::Point_3 p0 = to_epick(pts[0]), p1 = to_epick(pts[1]);
  std::size_t i2 = 2;
  while (i2 < pts.size() && CGAL::collinear(p0, p1, to_epick(pts[i2])))
    ++i2;
  if (i2 == pts.size()) {
    // On a line the lexicographic order is monotone along the line: the ends are extreme.
    out.dimension = 1;
    out.extreme_points = {pts.front(), pts.back()};
    return out;
  }
  const Epick::Point_3 p2 = to_epick(pts[i2]);
  std::size_t i3 = 2;
  while (i3 < pts.size() && CGAL::coplanar(p0, p1, p2, to_epick(pts[i3])))
    ++i3;
  if (i3 == pts.size()) {
    out.dimension = 2;
    out.extreme_points = planar_extreme_points(pts, pts[0], pts[1], pts[i2]);
    return out;
  }
  out.dimension = 3;
  out.extreme_points = solid_extreme_points(pts);
  return out;
}

std::vector<std::array<int, 3>> difference_hull_triangles(std::span<const Vec3> a,
                                                          std::span<const Vec3> b) {
  std::vector<Epeck::Point_3> points;
  points.reserve(a.size());
  for (std::size_t k = 0; k < a.size(); ++k)
    points.push_back(CGAL::ORIGIN + (Epeck::Point_3(a[k].x(), a[k].y(), a[k].z()) -
                                     Epeck::Point_3(b[k].x(), b[k].y(), b[k].z())));
  std::vector<std::array<int, 3>> out;
  if (points.size() < 4) return out;
  using Mesh = CGAL::Surface_mesh<Epeck::Point_3>;
  Mesh mesh;
  CGAL::convex_hull_3(points.begin(), points.end(), mesh);
  if (mesh.number_of_faces() < 4) return out;  // flat, a segment or a point
  auto input_index = [&](const Epeck::Point_3& p) {
    for (std::size_t k = 0; k < points.size(); ++k)
      if (points[k] == p) return static_cast<int>(k);
    return -1;
  };
  for (Mesh::Face_index f : mesh.faces()) {
    std::array<int, 3> t{};
    int i = 0;
    for (Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
      if (i < 3) t[i++] = input_index(mesh.point(v));
    if (i != 3 || t[0] < 0 || t[1] < 0 || t[2] < 0) return {};
    out.push_back(t);
  }
  return out;
}

void penetration_depth_squared(std::span<const Vec3> a_points, std::span<const Vec3> b_points,
                               mpq_ptr out) {
  mpq_set_ui(out, 0, 1);
  auto to_epeck = [](const Vec3& v) { return Epeck::Point_3(v.x(), v.y(), v.z()); };
  std::vector<Epeck::Point_3> pb;
  pb.reserve(b_points.size());
  for (const Vec3& b : b_points)
    pb.push_back(to_epeck(b));
  std::vector<Epeck::Point_3> diff;
  diff.reserve(a_points.size() * b_points.size());
  for (const Vec3& a : a_points) {
    const Epeck::Point_3 pa = to_epeck(a);
    for (const Epeck::Point_3& b : pb)
      diff.push_back(CGAL::ORIGIN + (pa - b));  // exact
  }

  // A − B without interior (flat, a segment or a point): no penetration depth.
  if (diff.empty()) return;
  const Epeck::Point_3& d0 = diff[0];
  auto find = [&diff](std::size_t from, auto&& pred) {
    while (from < diff.size() && !pred(diff[from]))
      ++from;
    return from;
  };
  const std::size_t i1 = find(1, [&](const Epeck::Point_3& p) { return p != d0; });
  if (i1 == diff.size()) return;
  const Epeck::Point_3& d1 = diff[i1];
  const std::size_t i2 =
      find(i1 + 1, [&](const Epeck::Point_3& p) { return !CGAL::collinear(d0, d1, p); });
  if (i2 == diff.size()) return;
  const Epeck::Point_3& d2 = diff[i2];
  const std::size_t i3 =
      find(i2 + 1, [&](const Epeck::Point_3& p) { return !CGAL::coplanar(d0, d1, d2, p); });
  if (i3 == diff.size()) return;

  using Mesh = CGAL::Surface_mesh<Epeck::Point_3>;
  Mesh mesh;
  CGAL::convex_hull_3(diff.begin(), diff.end(), mesh);
  std::optional<Epeck::FT> best;
  for (Mesh::Face_index f : mesh.faces()) {
    const Mesh::Halfedge_index h = mesh.halfedge(f);
    const Epeck::Point_3& p = mesh.point(mesh.source(h));
    const Epeck::Point_3& q = mesh.point(mesh.target(h));
    const Epeck::Point_3& r = mesh.point(mesh.target(mesh.next(h)));
    const Epeck::Vector_3 n = CGAL::cross_product(q - p, r - p);
    const Epeck::FT nn = n.squared_length();
    if (CGAL::is_zero(nn)) continue;  // degenerate triangle: its plane is another facet's
    const Epeck::FT s = n * (p - CGAL::ORIGIN);
    const Epeck::FT value = s * s / nn;  // squared distance from the origin to the plane
    if (!best || value < *best) best = value;
  }
  if (!best) throw std::logic_error("exact oracle: Minkowski difference hull has no facet");
  assign(out, CGAL::exact(*best));
}

}  // namespace gjklab::exact::detail
