// The penetration-depth certificate: an EPA polytope checked exactly (see certificate.hpp).
// No CGAL here.
//
// Why the checks suffice. Let P be the hull of the vertices the faces use (points of A − B, so
// P ⊂ A − B). Every used vertex lies on or behind every triangle's plane and some vertex
// strictly behind it, so each triangle lies in a facet of P and faces outward, and P is
// three-dimensional. Every directed edge is matched by its reverse, so the triangles form a
// 2-cycle on the sphere ∂P, which covers every point of ∂P the same number of times d ≥ 1:
// every facet of P holds a triangle, and the triangles' planes are exactly P's facet planes.
// (The fan, Euler and distinct-vertex checks further make the covering single, d = 1.) With
// the origin on or behind each plane, it lies in P, and the distance from it to P's boundary
// is min over faces of c_f/‖n_f‖; since P ⊂ A − B the depth is at least that. A plane n·x = c
// that supports A − B bounds the depth from above by c/‖n‖, so equality at the nearest face
// proves depth² = c²/‖n‖² (including depth 0, c = 0).
#include <gmp.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "exact/arithmetic/gmp_support.hpp"
#include "exact/arithmetic/integer_geometry.hpp"
#include "exact/hull/hull.hpp"
#include "gjklab/exact/certificate.hpp"

namespace gjklab::exact {

namespace {

using detail::Int;
using detail::IntVec;
using detail::operator-;
using detail::cross;
using detail::dot;

constexpr double kUnitRoundoff = 0x1p-53;

/// A vertex of the polytope: its point of A − B exactly, and rounded to doubles.
struct PolytopeVertex {
  IntVec exact;
  Vec3 approx;  ///< fl(a − b): |approx − exact| ≤ 2^-53·|exact| per coordinate
};

struct PolytopeFace {
  std::array<int, 3> v{};
  IntVec normal;  ///< (p1 − p0) × (p2 − p0), outward for a counter-clockwise face
  Int offset;     ///< normal·p0
};

/// The sign of normal_f · (x − p0) for a vertex x of the polytope, decided by a filter on
/// the doubles and exactly when the filter cannot tell. The filter evaluates the orientation
/// determinant det[p1 − p0, p2 − p0, x − p0] from the rounded points; with every coordinate
/// of the exact points at most m in magnitude, its error is below 530u·m³ (input rounding
/// 290u·m³, arithmetic γ5·6·(2m)³ ≈ 240u·m³), and the filter uses 1024u·m³ plus an underflow
/// margin (2^-1000, which covers the underflow terms for m ≤ 2^70, the m³ term above that).
int side_of_face(const PolytopeFace& f, const std::vector<PolytopeVertex>& p, int x, double m) {
  const Vec3& p0 = p[f.v[0]].approx;
  const Vec3 d1 = p[f.v[1]].approx - p0, d2 = p[f.v[2]].approx - p0, d3 = p[x].approx - p0;
  const double det = d3.dot(d1.cross(d2));
  const double bound = 1024 * kUnitRoundoff * m * m * m + 0x1p-1000;
  if (std::isfinite(det) && std::isfinite(bound) && std::abs(det) > bound) return det > 0 ? 1 : -1;
  return sgn(dot(f.normal, p[x].exact) - f.offset);
}

/// Every directed edge has its reverse, every vertex's faces form one fan, and
/// V − E + F = 2 over the vertices the faces use: the faces close into a sphere.
bool is_closed_sphere(const std::vector<std::array<int, 3>>& faces, std::size_t vertex_count) {
  std::map<std::pair<int, int>, int> edge_face;  // directed edge → the face that has it
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int e = 0; e < 3; ++e) {
      const std::pair<int, int> edge{faces[f][e], faces[f][(e + 1) % 3]};
      if (edge.first == edge.second || !edge_face.emplace(edge, static_cast<int>(f)).second)
        return false;
    }
  std::vector<int> outgoing(vertex_count, 0);
  for (const auto& [edge, face] : edge_face) {
    if (!edge_face.count({edge.second, edge.first})) return false;
    ++outgoing[edge.first];
  }
  // Around vertex v, face (v, x, y) is followed by the face that holds the edge (v, y).
  for (const auto& [edge, first_face] : edge_face) {
    const int v = edge.first;
    if (outgoing[v] < 0) continue;  // this vertex's fan was already walked
    int length = 0;
    std::pair<int, int> e = edge;
    do {
      const auto& t = faces[edge_face.at(e)];
      const int at = static_cast<int>(std::find(t.begin(), t.end(), v) - t.begin());
      e = {v, t[(at + 2) % 3]};
      ++length;
    } while (e != edge && length <= outgoing[v]);
    if (e != edge || length != outgoing[v]) return false;
    outgoing[v] = -1;
  }
  const auto used = static_cast<long>(std::count(outgoing.begin(), outgoing.end(), -1));
  const long edges = static_cast<long>(edge_face.size()) / 2;
  return used - edges + static_cast<long>(faces.size()) == 2;
}

/// The hint's vertices as exact and rounded points; nullopt if an index is out of range or
/// two vertices coincide.
std::optional<std::vector<PolytopeVertex>> polytope_vertices(std::span<const Vec3> a,
                                                             std::span<const Vec3> b,
                                                             const DepthHint& hint, long exponent) {
  std::vector<PolytopeVertex> out;
  out.reserve(hint.vertices.size());
  for (const IndexPair& p : hint.vertices) {
    if (p.a < 0 || static_cast<std::size_t>(p.a) >= a.size() || p.b < 0 ||
        static_cast<std::size_t>(p.b) >= b.size())
      return std::nullopt;
    PolytopeVertex v;
    v.exact = detail::to_integer<Int>(a[p.a], exponent) - detail::to_integer<Int>(b[p.b], exponent);
    v.approx = a[p.a] - b[p.b];
    // Rounding is monotone, so equal exact points have equal rounded points.
    for (const PolytopeVertex& u : out)
      if (u.approx == v.approx && u.exact == v.exact) return std::nullopt;
    out.push_back(std::move(v));
  }
  return out;
}

/// True if every vertex the faces use is on or behind every face plane, and some vertex is
/// strictly behind each.
bool is_convex(const std::vector<PolytopeFace>& faces, const std::vector<PolytopeVertex>& p,
               const std::vector<bool>& used) {
  double m = 0;  // bound on |exact coordinate|: the rounded one, rounded up
  for (std::size_t k = 0; k < p.size(); ++k)
    if (used[k]) m = std::max(m, p[k].approx.cwiseAbs().maxCoeff());
  m *= 1 + 4 * kUnitRoundoff;
  for (const PolytopeFace& f : faces) {
    bool strictly_behind = false;
    for (std::size_t k = 0; k < p.size(); ++k) {
      if (!used[k]) continue;
      const int side = side_of_face(f, p, static_cast<int>(k), m);
      if (side > 0) return false;
      strictly_behind = strictly_behind || side < 0;
    }
    if (!strictly_behind) return false;
  }
  return true;
}

/// n/‖n‖ for an integer vector n ≠ 0, in doubles (components scaled to a common exponent
/// first, so that no intermediate overflows).
Vec3 unit_direction(const IntVec& n) {
  std::array<long, 3> e{};
  std::array<double, 3> m{};
  long top = -(1L << 40);
  for (int i = 0; i < 3; ++i) {
    m[i] = mpz_get_d_2exp(&e[i], n[i].get_mpz_t());
    if (m[i] != 0) top = std::max(top, e[i]);
  }
  Vec3 d;
  for (int i = 0; i < 3; ++i)
    d[i] = m[i] == 0 ? 0.0 : std::ldexp(m[i], static_cast<int>(std::max(e[i] - top, -2000L)));
  return d.normalized();
}

/// A hint's polytope once every check of the certificate has passed.
struct CheckedPolytope {
  std::vector<PolytopeVertex> vertices;
  std::vector<PolytopeFace> faces;
};

/// The hint's polytope if it is closed, convex, made of distinct points of A − B, and holds
/// the origin on or behind every face plane; nullopt otherwise.
std::optional<CheckedPolytope> checked_polytope(std::span<const Vec3> a, std::span<const Vec3> b,
                                                const DepthHint& hint, long exponent) {
  // The checks cost O(V² + F·V): a polytope larger than any EPA run builds is not a hint.
  constexpr std::size_t kMaxHintVertices = 4096;
  if (hint.faces.size() < 4 || hint.vertices.size() > kMaxHintVertices ||
      hint.faces.size() > 2 * kMaxHintVertices)
    return std::nullopt;
  auto vertices = polytope_vertices(a, b, hint, exponent);
  if (!vertices) return std::nullopt;
  std::vector<bool> used(vertices->size(), false);
  for (const auto& t : hint.faces)
    for (int v : t) {
      if (v < 0 || static_cast<std::size_t>(v) >= vertices->size()) return std::nullopt;
      used[v] = true;
    }
  if (!is_closed_sphere(hint.faces, vertices->size())) return std::nullopt;
  CheckedPolytope p{std::move(*vertices), {}};
  p.faces.reserve(hint.faces.size());
  for (const auto& t : hint.faces) {
    PolytopeFace f;
    f.v = t;
    const IntVec& p0 = p.vertices[t[0]].exact;
    f.normal = cross(p.vertices[t[1]].exact - p0, p.vertices[t[2]].exact - p0);
    if (detail::is_zero(f.normal)) return std::nullopt;
    f.offset = dot(f.normal, p0);
    if (sgn(f.offset) < 0) return std::nullopt;  // the origin is in front of this face
    p.faces.push_back(std::move(f));
  }
  if (!is_convex(p.faces, p.vertices, used)) return std::nullopt;
  return p;
}

/// The face whose plane is nearest the origin: least c²/‖n‖², compared exactly.
std::size_t nearest_face(const std::vector<PolytopeFace>& faces) {
  std::size_t nearest = 0;
  Int c2_best = faces[0].offset * faces[0].offset, n2_best = dot(faces[0].normal, faces[0].normal);
  for (std::size_t f = 1; f < faces.size(); ++f) {
    Int c2 = faces[f].offset * faces[f].offset, n2 = dot(faces[f].normal, faces[f].normal);
    if (c2 * n2_best < c2_best * n2) {
      nearest = f;
      c2_best = std::move(c2);
      n2_best = std::move(n2);
    }
  }
  return nearest;
}

/// One exact EPA step, as a new hint: the polytope's hull with the point `next` (which lies
/// beyond at least one face): the faces that `next` sees strictly are replaced by the cone from
/// their horizon to `next`. The result is checked again like any hint.
DepthHint expanded(const DepthHint& hint, const CheckedPolytope& p, const IndexPair& next,
                   const IntVec& next_point) {
  std::vector<bool> visible(p.faces.size());
  std::map<std::pair<int, int>, std::size_t> edge_face;
  for (std::size_t f = 0; f < p.faces.size(); ++f) {
    visible[f] = dot(p.faces[f].normal, next_point) > p.faces[f].offset;
    for (int e = 0; e < 3; ++e)
      edge_face[{p.faces[f].v[e], p.faces[f].v[(e + 1) % 3]}] = f;
  }
  DepthHint out;
  out.vertices = hint.vertices;
  out.vertices.push_back(next);
  const int apex = static_cast<int>(out.vertices.size()) - 1;
  for (std::size_t f = 0; f < p.faces.size(); ++f) {
    const auto& v = p.faces[f].v;
    if (!visible[f]) {
      out.faces.push_back(v);
      continue;
    }
    for (int e = 0; e < 3; ++e) {  // a horizon edge: its twin's face is not visible
      const auto twin = edge_face.find({v[(e + 1) % 3], v[e]});
      if (twin != edge_face.end() && !visible[twin->second])
        out.faces.push_back({v[e], v[(e + 1) % 3], apex});
    }
  }
  return out;
}

/// The hint with its faces replaced by the exact hull of its (valid) vertices; no faces when
/// an index is out of range or the points do not span space.
DepthHint rebuilt_from_hull(std::span<const Vec3> a, std::span<const Vec3> b,
                            const DepthHint& hint) {
  DepthHint out;
  std::vector<Vec3> pa, pb;
  for (const IndexPair& p : hint.vertices) {
    if (p.a < 0 || static_cast<std::size_t>(p.a) >= a.size() || p.b < 0 ||
        static_cast<std::size_t>(p.b) >= b.size())
      return out;
    pa.push_back(a[p.a]);
    pb.push_back(b[p.b]);
  }
  out.vertices = hint.vertices;
  out.faces = detail::difference_hull_triangles(pa, pb);
  return out;
}

}  // namespace

std::optional<DepthCertificate> certify_depth(std::span<const Vec3> a, std::span<const Vec3> b,
                                              const DepthHint& hint, int max_steps) {
  if (a.empty() || b.empty()) return std::nullopt;
  const detail::IntegerFrame frame = detail::integer_frame(a, b);
  DepthHint current = hint;
  bool rebuilt = false;
  for (int step = 0; step <= max_steps; ++step) {
    std::optional<CheckedPolytope> p = checked_polytope(a, b, current, frame.exponent);
    if (!p && !rebuilt) {
      // The hint's faces fail (a floating-point EPA may leave a face slightly concave or a
      // vertex slightly outside): its points are still points of A − B, so take their exact
      // hull instead, once, and check that like any hint.
      current = rebuilt_from_hull(a, b, current);
      rebuilt = true;
      p = checked_polytope(a, b, current, frame.exponent);
    }
    if (!p) return std::nullopt;
    const PolytopeFace& f = p->faces[nearest_face(p->faces)];
    // Its plane must support A − B: max over a of n·A − min over b of n·B = c (the maximum is
    // at least c, since the face's own vertices are points of A − B).
    const detail::Extreme<Int> high = detail::extreme_point(a, f.normal, frame, true);
    const detail::Extreme<Int> low = detail::extreme_point(b, f.normal, frame, false);
    if (high.value - low.value == f.offset) {
      // depth² = c²/‖n‖² in frame units²: c has units 2^(3e) and n 2^(2e), so ×4^e.
      detail::Mpq depth2;
      const Int c2 = f.offset * f.offset, n2 = dot(f.normal, f.normal);
      mpq_set_num(depth2.get(), c2.get_mpz_t());
      mpq_set_den(depth2.get(), n2.get_mpz_t());
      mpq_canonicalize(depth2.get());
      const long e = frame.exponent;
      if (e > 0) mpq_mul_2exp(depth2.get(), depth2.get(), static_cast<mp_bitcnt_t>(2 * e));
      if (e < 0) mpq_div_2exp(depth2.get(), depth2.get(), static_cast<mp_bitcnt_t>(-2 * e));
      DepthCertificate out;
      out.depth_squared = detail::to_rational(depth2.get());
      out.normal = unit_direction(f.normal);
      out.repair_steps = step;
      return out;
    }
    if (step == max_steps) break;
    const IndexPair next{static_cast<std::int32_t>(high.index),
                         static_cast<std::int32_t>(low.index)};
    current = expanded(current, *p, next,
                       detail::to_integer<Int>(a[high.index], frame.exponent) -
                           detail::to_integer<Int>(b[low.index], frame.exponent));
  }
  return std::nullopt;
}

}  // namespace gjklab::exact
