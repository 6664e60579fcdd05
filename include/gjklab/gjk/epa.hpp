// Penetration depth with the expanding polytope algorithm (EPA; van den Bergen 2001), started
// from the final simplex of GJK.
//
// The GJK phase is Johnson's sub-algorithm with van den Bergen's backup procedure
// (gjk-johnson-backup), as in van den Bergen's own GJK-EPA: plain Johnson's stops with
// degenerate_simplex where no subset passes its tests (fcl issue 388's boxes, 1.7e-8 apart,
// answered 2.0e-8), and the backup gives the same answer wherever plain Johnson's decides.
// Where even that stops other than converged, the signed volumes answer (epa_gjk_phase).
//
// When GJK reports an intersection, its final simplex holds the origin. EPA
// first blows that simplex up to a tetrahedron inside A − B (searching support points off the
// simplex's line or plane when it has fewer than four points or is flat; the origin may end
// up on the tetrahedron's boundary), then repeats:
//   take the face f of the polytope closest to the origin (distance d_f, outward unit normal
//   n_f); evaluate w = s_{A−B}(n_f); stop when n_f·w − d_f is within tolerance; otherwise
//   remove every face that w sees (flood fill from f) and connect the horizon to w.
// Every face plane of the polytope is at least as far from the origin as the boundary of the
// polytope, and the polytope lies inside A − B, so min_f d_f is a lower bound of the depth;
// n_f·w = h_{A−B}(n_f) is an upper bound. The answer is the closest face: depth = max(d_f, 0),
// normal = n_f, witnesses from the barycentric coordinates of d_f·n_f in that face.
//
// Bounds and memory. The loop makes at most max_iterations support evaluations, and the
// polytope never has more than max_faces faces. Each query reserves its buffers once, before
// the loop (vertices: 4 + max_iterations; faces: max_faces; horizon: 3·max_faces edges), so
// nothing in the loop allocates; pass an EpaPolytope (epa_polytope.hpp) to reuse the buffers across
// queries. A closed triangulated polytope with V vertices has 2V − 4 faces, so after k expansions
// it has at most 4 + 2k faces: with max_faces ≥ 4 + 2·max_iterations the face buffer never binds.
//
// Termination. EPA's own stop reasons (EpaStop, kept in EpaResult::stop) map onto gjklab's
// Termination as follows:
//   EpaStop                Termination          answer
//   converged              converged            the closest face
//   repeated_support       converged            the closest face (w is already a vertex: in
//                                               exact arithmetic its gap would be 0)
//   flat_difference        converged            depth 0 (A − B has no interior, up to
//                                               relative_noise), GJK's contact witnesses
//   separated              GJK's (converged)    no overlap: GJK's distance and witnesses
//   gjk_failed             GJK's termination    GJK stopped without an answer; EPA not run
//   degenerate_polytope    degenerate_simplex   the closest face before the failed step
//   out_of_faces           step_limit           the closest face before the step
//   step_limit             step_limit           the closest face after max_iterations steps
//   non_finite             numerical_failure    the closest face before the step
// Visibility counts a face as seen by w when w lies in front of its plane or on it up to
// relative_noise·R (see EpaOptions).
// "degenerate_polytope" covers an expansion whose horizon is not one simple loop, a new face
// with no normal, and a new face plane closer to the origin than the current lower bound by
// more than the noise level (each means rounding has made the polytope non-convex); the
// polytope is left untouched and the last consistent answer is returned.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <vector>

#include "gjklab/geometry/enum_names.hpp"
#include "gjklab/geometry/support.hpp"
#include "gjklab/gjk/epa_polytope.hpp"
#include "gjklab/gjk/gjk_distance.hpp"
#include "gjklab/gjk/options.hpp"
#include "gjklab/gjk/result.hpp"
#include "gjklab/gjk/simplex.hpp"
#include "gjklab/gjk/subalgorithms.hpp"

namespace gjklab {

struct EpaDefaults {
  /// Concentric round shapes are EPA's worst case (every face about equally near): two
  /// concentric 482-point UV spheres need 378 steps, offset ones 30 to 140.
  static constexpr int max_iterations = 256;
  static constexpr int max_faces = 4 + 2 * max_iterations;
  static constexpr double relative_gap = 1e-12;
  static constexpr double relative_noise = 1e-13;
};

/// Options of `epa` (the GJK phase before it has its own GjkDistanceOptions).
struct EpaOptions {
  /// Upper bound on expansion steps, each costing one support evaluation (≥ 0). The few
  /// support evaluations that blow up a small GJK simplex (at most 12, from a single point)
  /// are not counted.
  int max_iterations = EpaDefaults::max_iterations;
  /// Capacity of the face buffer (≥ 4). An expansion that would need more faces stops the
  /// query with EpaStop::out_of_faces.
  int max_faces = EpaDefaults::max_faces;
  /// Relative to the depth, not squared (dimensionless): converged when the upper bound
  /// n_f·w and the lower bound d_f of the closest face f satisfy n_f·w − d_f ≤ relative_gap·d_f,
  /// so the reported depth d_f is within a factor (1 − relative_gap) of the true one.
  double relative_gap = EpaDefaults::relative_gap;
  /// Relative to the polytope's radius R = max ‖w_i‖ over the support points seen, not squared:
  /// lengths up to relative_noise·R are rounding noise. It is the absolute floor of the gap test
  /// (n_f·w − d_f ≤ relative_noise·R also converges, which ends touching contacts), the
  /// threshold for "off the line/plane" when blowing up a small simplex (A − B thinner than
  /// that is reported flat, depth 0), the distance within which a support point counts as on
  /// a face's plane (so that face is replaced), and the slack allowed for a new face plane
  /// closer to the origin than the current lower bound.
  double relative_noise = EpaDefaults::relative_noise;
};

/// Why EPA stopped (see the mapping onto Termination in the header comment).
enum class EpaStop : std::uint8_t {
  converged,
  repeated_support,
  flat_difference,
  separated,
  gjk_failed,
  degenerate_polytope,
  out_of_faces,
  step_limit,
  non_finite,
};

inline constexpr auto kEpaStopNames = std::to_array<EnumName<EpaStop>>({
    {EpaStop::converged, "converged"},
    {EpaStop::repeated_support, "repeated_support"},
    {EpaStop::flat_difference, "flat_difference"},
    {EpaStop::separated, "separated"},
    {EpaStop::gjk_failed, "gjk_failed"},
    {EpaStop::degenerate_polytope, "degenerate_polytope"},
    {EpaStop::out_of_faces, "out_of_faces"},
    {EpaStop::step_limit, "step_limit"},
    {EpaStop::non_finite, "non_finite"},
});
static_assert(in_value_order(kEpaStopNames) && ends_at(kEpaStopNames, EpaStop::non_finite));

constexpr std::string_view to_string(EpaStop v) {
  return name_of(kEpaStopNames, v);
}

/// The Termination an EPA stop reports when EPA ran (separated and gjk_failed report GJK's).
constexpr Termination to_termination(EpaStop s) {
  switch (s) {
    case EpaStop::converged:
    case EpaStop::repeated_support:
    case EpaStop::flat_difference:
    case EpaStop::separated:
      return Termination::converged;
    case EpaStop::degenerate_polytope:
      return Termination::degenerate_simplex;
    case EpaStop::out_of_faces:
    case EpaStop::step_limit:
      return Termination::step_limit;
    case EpaStop::non_finite:
      return Termination::numerical_failure;
    case EpaStop::gjk_failed:
      break;
  }
  return Termination::invalid_input;  // gjk_failed carries GJK's termination instead
}

/// The answer of `epa`. `iterations` counts EPA's expansion steps only; GJK's are in
/// gjk_iterations, and support_calls counts both phases and the blow-up.
template <class T>
struct EpaResultT : PenetrationResultT<T> {
  EpaStop stop = EpaStop::converged;
  int gjk_iterations = 0;
  /// Smallest support value n_f·w seen (an upper bound of the depth; +∞ if no step was made).
  T depth_upper_bound = std::numeric_limits<T>::infinity();
  int faces = 0;  ///< faces of the final polytope (0 when EPA did not build one)
};
using EpaResult = EpaResultT<double>;

/// The answer in double (exact from float; long double rounded to nearest).
template <class T>
EpaResult to_double(const EpaResultT<T>& r) {
  if constexpr (std::is_same_v<T, double>) {
    return r;
  } else {
    EpaResult out;
    static_cast<PenetrationResult&>(out) = to_double(static_cast<const PenetrationResultT<T>&>(r));
    out.stop = r.stop;
    out.gjk_iterations = r.gjk_iterations;
    out.depth_upper_bound = static_cast<double>(r.depth_upper_bound);
    out.faces = r.faces;
    return out;
  }
}

namespace detail {

inline void validate(const EpaOptions& o) {
  if (o.max_iterations < 0 || o.max_iterations > (1 << 24))
    throw std::invalid_argument("epa: max_iterations must be in [0, 2^24]");
  if (o.max_faces < 4 || o.max_faces > (1 << 26))
    throw std::invalid_argument("epa: max_faces must be in [4, 2^26]");
  if (!(o.relative_gap >= 0) || !std::isfinite(o.relative_gap))
    throw std::invalid_argument("epa: relative_gap must be finite and non-negative");
  if (!(o.relative_noise >= 0) || !std::isfinite(o.relative_noise))
    throw std::invalid_argument("epa: relative_noise must be finite and non-negative");
}

/// Barycentric coordinates of the orthogonal projection of x onto the plane of (p0, p1, p2);
/// false if the triangle has no area.
template <class T>
bool barycentric(const Vec3T<T>& x, const Vec3T<T>& p0, const Vec3T<T>& p1, const Vec3T<T>& p2,
                 std::array<T, 3>& out) {
  const Vec3T<T> n = (p1 - p0).cross(p2 - p0);
  const T nn = n.squaredNorm();
  if (!(nn > 0) || !std::isfinite(nn)) return false;
  out[0] = n.dot((p1 - x).cross(p2 - x)) / nn;
  out[1] = n.dot((p2 - x).cross(p0 - x)) / nn;
  out[2] = T(1) - out[0] - out[1];
  return true;
}

/// A vector orthogonal to e (unit length; e ≠ 0).
template <class T>
Vec3T<T> any_orthogonal(const Vec3T<T>& e) {
  int axis = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(e[i]) < std::abs(e[axis])) axis = i;
  return e.cross(Vec3T<T>::Unit(axis)).normalized();
}

}  // namespace detail

namespace detail {

/// EPA's scale of rounding noise: R = max ‖w_i‖ over the support points seen, and lengths up to
/// relative_noise·R are noise (see EpaOptions::relative_noise). R grows with every point taken.
template <class T>
struct EpaScale {
  T relative_noise = 0;
  T radius = 0;
  T noise() const { return relative_noise * radius; }
  /// Takes a support point into the scale; false if it is not finite.
  bool take(const SimplexVertexT<T>& s) {
    if (!s.w.allFinite()) return false;
    radius = std::max(radius, s.w.norm());
    return true;
  }
};

/// GJK's final simplex without repeated points, into p; returns their number.
template <class T>
int distinct_simplex_points(const SimplexT<T>& simplex, std::array<SimplexVertexT<T>, 4>& p,
                            EpaScale<T>& scale) {
  int k = 0;
  for (int i = 0; i < simplex.size(); ++i) {
    const SimplexVertexT<T>& s = simplex[i];
    bool seen = false;
    for (int j = 0; j < k; ++j)
      seen = seen || p[j].w == s.w;
    if (seen) continue;
    p[k++] = s;
    scale.radius = std::max(scale.radius, s.w.norm());
  }
  return k;
}

/// Reduces a simplex holding the origin that is flat, collinear or coincident within the
/// noise to fewer points that still hold it; returns their number.
template <class T>
int drop_degenerate_points(std::array<SimplexVertexT<T>, 4>& p, int k, const EpaScale<T>& scale) {
  if (k == 4) {
    const Vec3T<T> e1 = p[1].w - p[0].w, e2 = p[2].w - p[0].w, e3 = p[3].w - p[0].w;
    const T volume6 = e1.dot(e2.cross(e3));
    static constexpr std::array<std::array<int, 3>, 4> kTriangles = {
        {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}}};
    T largest_face = 0;
    for (const auto& t : kTriangles)
      largest_face =
          std::max(largest_face, (p[t[1]].w - p[t[0]].w).cross(p[t[2]].w - p[t[0]].w).norm());
    // The smallest height of the tetrahedron is |volume6| / largest_face.
    if (!(std::abs(volume6) > scale.noise() * largest_face)) {
      // Flat: the origin lies in the planar hull of the four points, so in one of the four
      // triangles; keep the one that holds it best.
      int best = 0;
      T best_score = -std::numeric_limits<T>::infinity();
      for (int t = 0; t < 4; ++t) {
        std::array<T, 3> l;
        const auto& tri = kTriangles[t];
        if (!barycentric<T>(Vec3T<T>::Zero(), p[tri[0]].w, p[tri[1]].w, p[tri[2]].w, l)) continue;
        const T score = std::min({l[0], l[1], l[2]});
        if (score > best_score) {
          best_score = score;
          best = t;
        }
      }
      const auto tri = kTriangles[best];
      p = {p[tri[0]], p[tri[1]], p[tri[2]], SimplexVertexT<T>{}};
      k = 3;
    }
  }
  if (k == 3) {
    const T twice_area = (p[1].w - p[0].w).cross(p[2].w - p[0].w).norm();
    int longest = 0;  // edge (longest, longest + 1 mod 3)
    T length = 0;
    for (int i = 0; i < 3; ++i) {
      const T l = (p[(i + 1) % 3].w - p[i].w).norm();
      if (l > length) {
        length = l;
        longest = i;
      }
    }
    // Height on the longest edge within the noise: collinear; the longest edge covers the
    // other point, hence the origin.
    if (!(twice_area > scale.noise() * length)) {
      p = {p[longest], p[(longest + 1) % 3], SimplexVertexT<T>{}, SimplexVertexT<T>{}};
      k = 2;
    }
  }
  if (k == 2 && !((p[1].w - p[0].w).norm() > scale.noise())) k = 1;
  return k;
}

/// How growing the simplex into a tetrahedron ended.
template <class T>
struct EpaSeed {
  enum class Kind : std::uint8_t { tetrahedron, flat, non_finite } kind = Kind::tetrahedron;
  Vec3T<T> flat_normal = Vec3T<T>::UnitX();  ///< for `flat`: a normal of the flat A − B
};

/// Grows k = 1 … 4 points holding the origin into a tetrahedron inside A − B that holds it
/// (possibly on its boundary), with support points off the current point, line or plane;
/// reports A − B flat (a point, segment or planar set, within the noise) otherwise.
template <class T, class Support>
EpaSeed<T> grow_to_tetrahedron(std::array<SimplexVertexT<T>, 4>& p, int k, EpaScale<T>& scale,
                               Support&& support) {
  using Kind = typename EpaSeed<T>::Kind;
  using Point = Vec3T<T>;
  if (k == 1) {
    const std::array<Point, 6> axes = {Point(1, 0, 0),  Point(-1, 0, 0), Point(0, 1, 0),
                                       Point(0, -1, 0), Point(0, 0, 1),  Point(0, 0, -1)};
    for (const Point& d : axes) {
      const SimplexVertexT<T> s = support(d);
      if (!scale.take(s)) return {Kind::non_finite};
      if ((s.w - p[0].w).norm() > scale.noise()) {
        p[k++] = s;
        break;
      }
    }
    if (k == 1) return {Kind::flat, Point::UnitX()};  // A − B is a point
  }
  if (k == 2) {
    const Point e = p[1].w - p[0].w;
    const Point u = any_orthogonal(e);
    const Point v = e.cross(u).normalized();
    const T e_norm = e.norm();
    const std::array<Point, 4> directions = {u, -u, v, -v};
    for (const Point& d : directions) {
      const SimplexVertexT<T> s = support(d);
      if (!scale.take(s)) return {Kind::non_finite};
      if ((s.w - p[0].w).cross(e).norm() / e_norm > scale.noise()) {
        p[k++] = s;
        break;
      }
    }
    if (k == 2) return {Kind::flat, u};  // A − B is a segment
  }
  if (k == 3) {
    const Point m = (p[1].w - p[0].w).cross(p[2].w - p[0].w).normalized();
    const SimplexVertexT<T> above = support(m);
    if (!scale.take(above)) return {Kind::non_finite};
    const SimplexVertexT<T> below = support(Point(-m));
    if (!scale.take(below)) return {Kind::non_finite};
    const T h_above = m.dot(above.w - p[0].w), h_below = -m.dot(below.w - p[0].w);
    if (!(std::max(h_above, h_below) > scale.noise())) return {Kind::flat, m};  // A − B is flat
    // One apex only: the tetrahedron is convex whatever the apexes' positions (a double
    // pyramid need not be). The origin then lies on its base, which EPA expands first.
    p[3] = h_above >= h_below ? above : below;
  }
  return {Kind::tetrahedron};
}

/// The answer's part that GJK gives: its counts and witnesses; for separated pairs and GJK
/// failures, the whole answer (GJK's, passed through; see EpaStop).
template <class T>
EpaResultT<T> epa_start_from_gjk(const DistanceResultT<T>& gjk) {
  EpaResultT<T> out;
  out.gjk_iterations = gjk.iterations;
  out.support_calls = gjk.support_calls;
  out.witness_a = gjk.witness_a;
  out.witness_b = gjk.witness_b;
  if (!gjk.intersect) {
    out.intersect = false;
    out.distance = gjk.distance;
    const Vec3T<T> ab = gjk.witness_b - gjk.witness_a;
    const T n = ab.norm();
    if (n > 0 && std::isfinite(n)) out.normal = ab / n;
    out.termination = gjk.termination;
    out.stop = gjk.termination == Termination::converged ? EpaStop::separated : EpaStop::gjk_failed;
    return out;
  }
  out.intersect = true;
  out.distance = 0;
  return out;
}

/// The expansion: until the closest face's plane is within the tolerances of A − B's support
/// in its normal, or a limit or a degeneracy stops it. Returns why it stopped; `closest` is
/// then the face that answers.
template <class T, class Support>
EpaStop expand_polytope(EpaPolytopeT<T>& polytope, const EpaOptions& options, EpaScale<T>& scale,
                        Support&& support, EpaResultT<T>& out, int& closest) {
  for (int step = 0;; ++step) {
    closest = polytope.closest_face();
    const Vec3T<T> n = polytope.faces[closest].normal;
    const T lower = polytope.faces[closest].distance;
    if (out.iterations >= options.max_iterations) return EpaStop::step_limit;
    ++out.iterations;
    const SimplexVertexT<T> w = support(n);
    if (!scale.take(w)) return EpaStop::non_finite;
    const T upper = n.dot(w.w);
    out.depth_upper_bound = std::min(out.depth_upper_bound, upper);
    const T gap = upper - lower;
    if (gap <= static_cast<T>(options.relative_gap) * lower || gap <= scale.noise())
      return EpaStop::converged;
    if (polytope.has_vertex(w.w)) return EpaStop::repeated_support;
    // Faces that w sees, by flood fill from the closest one (which it sees: gap > noise). A
    // face whose plane holds w up to the noise level counts as seen: removing it keeps the
    // polytope convex, drops vertices that are not extreme (support points of A − B on a face
    // of A − B, which ties produce), and never leaves w on the line of a horizon edge, which
    // would make a new face without area.
    const int visible = polytope.mark_visible(closest, w.w, scale.noise(), step);
    if (!polytope.cone_fits(visible, options.max_faces)) return EpaStop::out_of_faces;
    // The horizon must be one simple loop (a visible region that is a disc); otherwise
    // rounding has made the visibility inconsistent and the expansion would break the mesh.
    if (!polytope.link_horizon()) return EpaStop::degenerate_polytope;
    if (!polytope.add_cone(w, step, lower, scale.noise())) return EpaStop::degenerate_polytope;
  }
}

/// The answer of a face of the polytope: its depth and normal, and the witnesses of the
/// origin's projection on it.
template <class T>
void take_face_answer(const EpaPolytopeT<T>& polytope, int closest, EpaResultT<T>& out) {
  const typename EpaPolytopeT<T>::Face& f = polytope.faces[closest];
  out.depth = std::max(f.distance, T(0));
  out.normal = f.normal;
  const Vec3T<T> x = f.distance * f.normal;
  std::array<T, 3> l;
  const auto& v = polytope.vertices;
  const SimplexVertexT<T>&v0 = v[f.v[0]], &v1 = v[f.v[1]], &v2 = v[f.v[2]];
  if (barycentric(x, v0.w, v1.w, v2.w, l)) {
    out.witness_a = l[0] * v0.a + l[1] * v1.a + l[2] * v2.a;
    out.witness_b = l[0] * v0.b + l[1] * v1.b + l[2] * v2.b;
  }
  out.faces = polytope.alive();
}

}  // namespace detail

/// EPA on the pair after GJK: `gjk` must be gjk_distance's answer for the same pair (its
/// final simplex starts the expansion). Separated pairs and GJK failures pass GJK's answer
/// through (see EpaStop). Throws std::invalid_argument if the options are invalid. The parts:
/// the GJK simplex reduced (drop_degenerate_points) and grown into a tetrahedron
/// (grow_to_tetrahedron), then the expansion (expand_polytope) on the polytope
/// (epa_polytope.hpp).
template <SupportMap A, SupportMap B, class T>
EpaResultT<T> epa_from_gjk(const A& a, const B& b, const DistanceResultT<T>& gjk,
                           const EpaOptions& options, EpaPolytopeT<T>& polytope) {
  using Point = Vec3T<T>;
  detail::validate(options);
  EpaResultT<T> out = detail::epa_start_from_gjk(gjk);
  if (!gjk.intersect) return out;

  auto support = [&](const Point& d) {
    ++out.support_calls;
    return detail::minkowski_support(a, b, d);
  };
  auto finish = [&](EpaStop stop) -> EpaResultT<T>& {
    out.stop = stop;
    out.termination = to_termination(stop);
    return out;
  };

  // The noise tolerance is stated for double and scaled to T's rounding (rounding_scaled).
  detail::EpaScale<T> scale{rounding_scaled<T>(options.relative_noise)};
  std::array<SimplexVertexT<T>, 4> p;
  const int k = detail::distinct_simplex_points(gjk.simplex, p, scale);
  if (k == 0) return finish(EpaStop::degenerate_polytope);
  const detail::EpaSeed<T> seed =
      detail::grow_to_tetrahedron(p, detail::drop_degenerate_points(p, k, scale), scale, support);
  using SeedKind = typename detail::EpaSeed<T>::Kind;
  if (seed.kind == SeedKind::non_finite) return finish(EpaStop::non_finite);
  if (seed.kind == SeedKind::flat) {
    // A − B has no interior (up to the noise level): depth 0 at GJK's contact point.
    out.depth = 0;
    out.normal = seed.flat_normal;
    return finish(EpaStop::flat_difference);
  }
  polytope.prepare(options.max_iterations, options.max_faces);
  if (!polytope.start_tetrahedron(p)) return finish(EpaStop::degenerate_polytope);

  int closest = 0;
  const EpaStop stop = detail::expand_polytope(polytope, options, scale, support, out, closest);
  detail::take_face_answer(polytope, closest, out);
  return finish(stop);
}

/// EPA's GJK phase: the distance query with Johnson's sub-algorithm and its backup procedure,
/// the most accurate distances of the variants (property test: 1e-15 of the pair's size, the
/// signed volumes' 1e-13). Where that query stops other than converged, the signed-volumes
/// query answers instead, with both runs' iterations and support calls counted: Johnson's
/// cofactors lose the decision on a tetrahedron with a long sliver face (nearly parallel
/// ridges 2e-8 deep: "apart, 1.4e-9", no_progress), where the signed volumes decide contact.
template <SupportMap A, SupportMap B>
DistanceResultT<shape_scalar_t<A>> epa_gjk_phase(const A& a, const B& b,
                                                 const GjkDistanceOptions& options) {
  const auto johnson = gjk_distance_with<JohnsonBackupSubAlgorithm>(a, b, options);
  if (johnson.termination == Termination::converged) return johnson;
  auto signed_volumes = gjk_distance_with<SignedVolumesSubAlgorithm>(a, b, options);
  signed_volumes.iterations += johnson.iterations;
  signed_volumes.support_calls += johnson.support_calls;
  return signed_volumes;
}

/// `epa`: GJK distance (epa_gjk_phase: Johnson's sub-algorithm with the backup procedure, the
/// signed volumes where that fails), then EPA when the shapes intersect, in the shapes' scalar
/// type (double, or float / long double for ScalarCloud).
template <SupportMap A, SupportMap B, class T = shape_scalar_t<A>>
EpaResultT<T> gjk_epa(const A& a, const B& b, const GjkDistanceOptions& gjk_options,
                      const EpaOptions& options, EpaPolytopeT<T>& ws) {
  detail::validate(options);
  // Re-centred once for both phases (gjk_options.recenter, see recentred.hpp): EPA's support
  // values are compared at the scale of the pair too.
  if constexpr (detail::RecentrableCloud<A> && std::same_as<A, B>) {
    if (const auto t = detail::recentring_of(a, b, gjk_options.recenter)) {
      const A moved_a = a.translated(-*t), moved_b = b.translated(-*t);
      EpaResultT<T> out =
          epa_from_gjk(moved_a, moved_b, epa_gjk_phase(moved_a, moved_b, gjk_options), options, ws);
      detail::translate_answer<T>(out, *t);
      return out;
    }
  }
  return epa_from_gjk(a, b, epa_gjk_phase(a, b, gjk_options), options, ws);
}

template <SupportMap A, SupportMap B>
EpaResultT<shape_scalar_t<A>> gjk_epa(const A& a, const B& b,
                                      const GjkDistanceOptions& gjk_options = {},
                                      const EpaOptions& options = {}) {
  EpaPolytopeT<shape_scalar_t<A>> polytope;
  return gjk_epa(a, b, gjk_options, options, polytope);
}

}  // namespace gjklab
