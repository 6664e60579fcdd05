// The penetration-depth certificate: an EPA polytope checked exactly (see certificate.hpp).
// No CGAL here.
//
// Why the checks suffice. Let P be the hull of the hint's vertices (points of A − B, so
// P ⊂ A − B) and S the union of its triangles. If S is a closed surface (every directed edge
// matched by its reverse, every vertex's triangles one fan) and every vertex lies on or behind
// every triangle's plane, S lies on the boundary of the intersection H of those half-spaces,
// which is then a convex body whose whole boundary S is: H = P and the triangles' planes are
// P's facet planes. With the origin on or behind each of them, the distance from the origin
// to P's boundary is min over faces of c_f/‖n_f‖; since P ⊂ A − B, the depth is at least that.
// A plane n·x = c that supports A − B bounds the depth from above by c/‖n‖, so equality at the
// nearest face proves depth² = c²/‖n‖².
#include <gmp.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "gjklab/exact/certificate.hpp"
#include "gmp_support.hpp"
#include "integer_geometry.hpp"

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
/// of the exact points at most m in magnitude, its error is below 460u·m³ (input rounding
/// 290u·m³, arithmetic 170u·m³), and the filter uses 1024u·m³ plus an underflow margin.
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
  const auto used = static_cast<long>(
      std::count(outgoing.begin(), outgoing.end(), -1));
  const long edges = static_cast<long>(edge_face.size()) / 2;
  return used - edges + static_cast<long>(faces.size()) == 2;
}

/// The hint's vertices as exact and rounded points; nullopt if an index is out of range or
/// two vertices coincide.
std::optional<std::vector<PolytopeVertex>> polytope_vertices(std::span<const Vec3> a,
                                                             std::span<const Vec3> b,
                                                             const DepthHint& hint,
                                                             long exponent) {
  std::vector<PolytopeVertex> out;
  out.reserve(hint.vertices.size());
  for (const IndexPair& p : hint.vertices) {
    if (p.a < 0 || static_cast<std::size_t>(p.a) >= a.size() || p.b < 0 ||
        static_cast<std::size_t>(p.b) >= b.size())
      return std::nullopt;
    PolytopeVertex v;
    v.exact = detail::to_integer(a[p.a], exponent) - detail::to_integer(b[p.b], exponent);
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

}  // namespace

std::optional<DepthCertificate> certify_depth(std::span<const Vec3> a, std::span<const Vec3> b,
                                      const DepthHint& hint) {
  if (a.empty() || b.empty() || hint.faces.size() < 4) return std::nullopt;
  const detail::IntegerFrame frame = detail::integer_frame(a, b);
  const auto vertices = polytope_vertices(a, b, hint, frame.exponent);
  if (!vertices) return std::nullopt;
  std::vector<bool> used(vertices->size(), false);
  for (const auto& t : hint.faces)
    for (int v : t) {
      if (v < 0 || static_cast<std::size_t>(v) >= vertices->size()) return std::nullopt;
      used[v] = true;
    }
  if (!is_closed_sphere(hint.faces, vertices->size())) return std::nullopt;

  std::vector<PolytopeFace> faces;
  faces.reserve(hint.faces.size());
  for (const auto& t : hint.faces) {
    PolytopeFace f;
    f.v = t;
    const IntVec& p0 = (*vertices)[t[0]].exact;
    f.normal = cross((*vertices)[t[1]].exact - p0, (*vertices)[t[2]].exact - p0);
    if (detail::is_zero(f.normal)) return std::nullopt;
    f.offset = dot(f.normal, p0);
    if (sgn(f.offset) < 0) return std::nullopt;  // the origin is in front of this face
    faces.push_back(std::move(f));
  }
  if (!is_convex(faces, *vertices, used)) return std::nullopt;

  // The nearest face plane: least c²/‖n‖², compared exactly by cross-multiplication.
  std::size_t nearest = 0;
  std::vector<Int> c2(faces.size()), n2(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    c2[f] = faces[f].offset * faces[f].offset;
    n2[f] = dot(faces[f].normal, faces[f].normal);
    if (f > 0 && c2[f] * n2[nearest] < c2[nearest] * n2[f]) nearest = f;
  }
  // Its plane must support A − B: max over a of n·A − min over b of n·B = c.
  const PolytopeFace& f = faces[nearest];
  const detail::Extreme high = detail::extreme_point(a, f.normal, frame, true);
  const detail::Extreme low = detail::extreme_point(b, f.normal, frame, false);
  if (high.value - low.value != f.offset) return std::nullopt;

  // depth² = c²/‖n‖² in frame units²: c has units 2^(3e) and n 2^(2e), so ×4^e.
  detail::Mpq depth2;
  mpq_set_num(depth2.get(), c2[nearest].get_mpz_t());
  mpq_set_den(depth2.get(), n2[nearest].get_mpz_t());
  mpq_canonicalize(depth2.get());
  const long e = frame.exponent;
  if (e > 0) mpq_mul_2exp(depth2.get(), depth2.get(), static_cast<mp_bitcnt_t>(2 * e));
  if (e < 0) mpq_div_2exp(depth2.get(), depth2.get(), static_cast<mp_bitcnt_t>(-2 * e));
  DepthCertificate out;
  out.depth_squared = detail::to_rational(depth2.get());
  out.normal = unit_direction(f.normal);
  return out;
}

}  // namespace gjklab::exact
