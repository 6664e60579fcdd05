// The state of one GJK distance query and the tests its loop takes (see gjk_distance.hpp):
// the support point of A − B, the query's proven bracket, how it reports why it stopped, and the
// stopping, separation and stall tests with their rounding bounds.
#pragma once

#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <utility>

#include "gjklab/geometry/support.hpp"
#include "gjklab/gjk/bracket.hpp"
#include "gjklab/gjk/closest_on_simplex.hpp"
#include "gjklab/gjk/options.hpp"
#include "gjklab/gjk/recentred.hpp"
#include "gjklab/gjk/result.hpp"
#include "gjklab/gjk/trace.hpp"

namespace gjklab {

namespace detail {

/// Support point of A − B in direction d, with its two parts (and their vertex indices when
/// the shapes are polytopes that can report them). Always inlined: every iteration of every
/// query waits for it, and inlined, its 80-byte result stays in registers instead of making a
/// round trip through memory.
template <SupportMap A, SupportMap B, class T>
[[gnu::always_inline]] inline SimplexVertexT<T> minkowski_support(const A& a, const B& b,
                                                                  const Vec3T<T>& d) {
  static_assert(std::same_as<shape_scalar_t<A>, T> && std::same_as<shape_scalar_t<B>, T>,
                "both shapes and the direction in one precision");
  SimplexVertexT<T> v;
  // Two polytopes that both scan: one call that overlaps the two searches (polytope.hpp).
  if constexpr (requires { scan_support_pair(a, d, b); }) {
    if (!a.uses_hill_climbing() && !b.uses_hill_climbing()) {
      const auto [i, j] = scan_support_pair(a, d, b);
      v.index_a = static_cast<std::int32_t>(i);
      v.index_b = static_cast<std::int32_t>(j);
      v.a = a.vertices()[i];
      v.b = b.vertices()[j];
      v.w = v.a - v.b;
      return v;
    }
  }
  if constexpr (requires { a.support_index(d); }) {
    const auto i = a.support_index(d);
    v.index_a = static_cast<std::int32_t>(i);
    v.a = a.vertices()[i];
  } else {
    v.a = a.support(d);
  }
  if constexpr (requires { b.support_index(d); }) {
    const auto j = b.support_index(-d);
    v.index_b = static_cast<std::int32_t>(j);
    v.b = b.vertices()[j];
  } else {
    v.b = b.support(-d);
  }
  v.w = v.a - v.b;
  return v;
}

/// After a separation certificate, a full simplex that seems to hold the origin holds it only
/// through rounding: the origin is outside A − B, hence outside the simplex, whose closest
/// point therefore lies on one of its four faces. Reduces `simplex` to the face whose closest
/// point (by the sub-algorithm) is nearest the origin; false, leaving it untouched, when no face
/// can be decided.
template <class Sub, class T>
bool reduce_to_closest_face(const Sub& sub, SimplexT<T>& simplex, ClosestOnSimplexT<T>& out) {
  const SimplexT<T> full = simplex;
  bool found = false;
  for (int drop = 0; drop < full.size(); ++drop) {
    SimplexT<T> face = full;
    face.keep(static_cast<std::uint8_t>(0xF & ~(1u << drop)));
    ClosestOnSimplexT<T> c;
    if (!sub.reduce(face, c) || !is_finite(c.v)) continue;
    if (!found || c.v.squaredNorm() < out.v.squaredNorm()) {
      simplex = face;
      out = c;
      found = true;
    }
  }
  return found;
}

/// Why a distance loop stopped: its termination, and whether it found contact.
struct DistanceStop {
  Termination termination;
  bool contact;
};

/// The termination a query reports for a loop's stop, given whether its bracket is accepted:
/// `converged` exactly when it is, for the stops that end on the answer's own merits (a
/// converged claim, no progress, a degenerate simplex); an unproven converged claim becomes
/// no_progress. The step limit and numerical failures are reported as they are.
inline Termination judged_termination(Termination stop, bool accepted) {
  switch (stop) {
    case Termination::converged:
    case Termination::no_progress:
    case Termination::degenerate_simplex:
      return accepted ? Termination::converged
                      : (stop == Termination::converged ? Termination::no_progress : stop);
    default:
      return stop;
  }
}

/// The state of one GJK distance query shared by the drivers (plain GJK and Nesterov's): the
/// result being built (its simplex is the working simplex), the best point so far and the
/// lower bound, with the steps every driver takes the same way. The result is the caller's
/// local, so that it is returned without a copy.
template <class T, class Observer>
struct DistanceQueryState {
  const GjkDistanceOptions& options;
  Observer& observer;
  DistanceResultT<T>& out;
  /// v and the weights of the simplex's points (witnesses are formed by finish()).
  ClosestOnSimplexT<T> best{};
  /// The best proven lower bound of the distance so far (bracket.hpp), length units.
  T lower_bound = 0;
  /// √3·(M_A + M_B), the scale of the pair's rounding (pair_magnitude), and the absolute term
  /// of the bracket's bounds at that scale (bracket_rounding).
  T magnitude = std::numeric_limits<T>::infinity();
  T rounding = std::numeric_limits<T>::infinity();
  /// Whether support planes prove lower bounds (both supports are full scans).
  bool planes_prove = false;

  SimplexT<T>& simplex() { return out.simplex; }

  /// Reports the iteration to the observer when it is enabled (no work otherwise). Trace rows
  /// are in double whatever the query's precision.
  void trace(const Vec3T<T>& direction, const SimplexVertexT<T>& w, T vv, T vw, GjkStep step) {
    if constexpr (Observer::enabled) {
      GjkIterationTrace t;
      t.iteration = out.iterations;
      t.direction = direction.template cast<double>();
      t.support = to_double(w);
      t.v_norm_squared = static_cast<double>(vv);
      t.v_dot_w = static_cast<double>(vw);
      t.lower_bound = static_cast<double>(lower_bound);
      t.simplex = to_double(out.simplex);
      for (int k = 0; k < 4; ++k)
        t.weights[k] = static_cast<double>(best.weights[k]);
      t.step = step;
      observer.on_iteration(t);
    }
  }

  /// Takes the pair's rounding scale (bracket.hpp) before the first support plane.
  template <class A, class B>
  void measure(const A& a, const B& b) {
    magnitude = pair_magnitude<T>(a, b);
    rounding = bracket_rounding(magnitude);
    planes_prove = std::isfinite(rounding) && scans_support(a) && scans_support(b);
  }

  /// Raises the proven lower bound with the support plane d·x = d·w (dw = d·w, dd = ‖d‖²).
  void note_lower_bound(T dw, T dd) {
    if (planes_prove)
      lower_bound = std::max(lower_bound, support_plane_lower_bound(dw, dd, rounding));
  }

  /// Fills the result with the best point so far, its proven bracket and the stop's
  /// termination, which stays `converged` only where the bracket is accepted
  /// (bracket_accepted); an unproven claim becomes no_progress.
  ///
  /// A separated stop whose distance nothing bounds away from 0 (no support plane proved a
  /// positive lower bound) and whose upper bound is within the pair's resolution is reported
  /// as contact, as the contact test does for the sub-algorithm's v: its boolean is undecided
  /// at the precision of the coordinates, and "apart" would claim what no plane showed (rods
  /// 1e-9 deep said "apart, 4e-13").
  void finish(DistanceStop stop) {
    combine_witnesses(out.simplex, best.weights, out.witness_a, out.witness_b);
    const T upper = simplex_upper_bound(best.weights, out.simplex.size(), out.witness_a,
                                        out.witness_b, rounding);
    const bool contact =
        stop.contact || (!(lower_bound > 0) && upper <= bracket_resolution(magnitude));
    out.intersect = contact;
    out.closest = best.v;
    out.distance = contact ? T(0) : best.v.norm();
    DistanceBracketT<T> b;
    b.lower = contact ? T(0) : lower_bound;
    b.upper = upper;
    b = around(b, out.distance);
    out.lower_bound = b.lower;
    out.upper_bound = b.upper;
    out.termination = judged_termination(stop.termination, bracket_accepted(options, b, magnitude));
  }

  /// Relative to the simplex, not squared: ‖v‖ ≤ relative_contact · max‖y_i‖ means v is
  /// indistinguishable from the rounding noise of the points it was computed from (the
  /// tolerance is stated for double and scaled to T's rounding, see rounding_scaled).
  bool in_contact(const Vec3T<T>& v, const SimplexT<T>& s) const {
    return in_contact(v, s.max_norm_squared());
  }
  /// The same test given max‖y_i‖² over the points v was computed from.
  bool in_contact(const Vec3T<T>& v, T max_norm_squared) const {
    const T tol = rounding_scaled<T>(options.relative_contact);
    const T vv = v.squaredNorm();
    return vv <= tol * tol * max_norm_squared && vv <= provable_contact * provable_contact;
  }

  /// ‖v‖ up to which contact may be claimed: unbounded for the query's own sub-algorithm (its
  /// option relative_contact decides); for the double-word continuation, the norm whose upper
  /// bound the bracket still accepts (bracket_resolution − bracket_rounding), so that a claim it
  /// makes is one it can prove: a pair 1.5e-12 deep whose triangle passes 4e-13 from the origin
  /// goes on to the tetrahedron that holds the origin instead of stopping on the triangle.
  T provable_contact = std::numeric_limits<T>::infinity();
};

/// Largest ‖y_i‖² over the points of y in `subset` (bit i ↔ y[i]).
template <class T>
T max_norm_squared(const std::array<Vec3T<T>, 4>& y, std::uint8_t subset) {
  T m = 0;
  for (int i = 0; i < 4; ++i)
    if (subset & (1u << i)) m = std::max(m, y[i].squaredNorm());
  return m;
}

/// Applies a sub-algorithm's solution for the simplex plus `next` (solved as point
/// simplex.size()): adds next, keeps the chosen subset, and records v and the kept weights.
template <class Solution, class T>
void apply_solution(const Solution& s, const SimplexVertexT<T>& next, SimplexT<T>& simplex,
                    ClosestOnSimplexT<T>& best) {
  simplex.push(next);
  keep_subset(s, simplex, best);
}

}  // namespace detail

/// Relative error bound of a rounded 3-vector dot product, |fl(x·y) − x·y| ≤ 3u‖x‖‖y‖ with
/// u = 2^-53, rounded up: about 4.5u.
inline constexpr double kDotRoundoff = 1e-15;
/// The same bound in the scalar type T (scaled by T's unit roundoff; kDotRoundoff for double).
template <class T>
inline constexpr T dot_roundoff = rounding_scaled<T>(kDotRoundoff);

/// The stopping test of options.convergence for ‖v‖² = vv and v·w = vw (see GjkConvergence).
/// The tolerances are the user's, rounded to T.
template <class T>
bool gap_converged(const GjkDistanceOptions& options, T vv, T vw) {
  // Duality gap ‖v‖² − v·w ≥ ‖v‖² − ‖v‖·dist, on squared lengths.
  return gap_within_tolerance(options, vv - vw, vv);
}

namespace detail {

/// True if v·w = vw is a separation certificate: above the relative rounding bound of the dot
/// product, vw > kDotRoundoff·‖v‖·‖w‖, for ‖v‖² = vv and ‖w‖² = ww. Compared squared, so that no
/// square root (which shares a unit with the sub-algorithm's divisions that the next iteration
/// waits for) is taken, except where the squared threshold is not a normal double (‖v‖‖w‖
/// below about 1e-139 or above 1e169): there the comparison is made unsquared, as stated.
template <class T>
bool separation_certified(T vw, T vv, T ww) {
  if (!(vw > 0)) return false;
  const T threshold_squared = dot_roundoff<T> * dot_roundoff<T> * vv * ww;
  if (std::isnormal(threshold_squared)) return vw * vw > threshold_squared;
  return vw > dot_roundoff<T> * std::sqrt(vv) * std::sqrt(ww);
}

/// True if the origin is certainly outside the tetrahedron y[0..3]: for some face, on the
/// other side of the face's plane from the opposite vertex, or farther from that plane than the
/// opposite vertex, by more than the rounding of the signed distances. (Inside, the origin
/// lies between every face plane and its opposite vertex.) The bound covers the rounding of
/// the face normal n = e1 × e2 (componentwise within 3u‖e1‖‖e2‖) and of the dot products with
/// points of norm ≤ 2M, M = max‖y_i‖, with a factor 2 to spare; faces with n = 0 decide nothing.
template <class T>
bool origin_outside_tetrahedron(const std::array<Vec3T<T>, 4>& y) {
  T m = 0;
  for (const Vec3T<T>& p : y)
    m = std::max(m, p.norm());
  for (int k = 0; k < 4; ++k) {
    const Vec3T<T>& y0 = y[(k + 1) % 4];
    const Vec3T<T> e1 = y[(k + 2) % 4] - y0, e2 = y[(k + 3) % 4] - y0;
    const Vec3T<T> n = e1.cross(e2);
    const T n_norm = n.norm();
    if (!(n_norm > 0)) continue;
    const T bound = 16 * dot_roundoff<T> * m * (n_norm + e1.norm() * e2.norm());
    T s_origin = -n.dot(y0);        // the origin's signed distance, times ‖n‖
    T s_vertex = n.dot(y[k] - y0);  // the opposite vertex's, times ‖n‖
    if (s_vertex < 0) {
      s_origin = -s_origin;
      s_vertex = -s_vertex;
    }
    if (s_origin < -bound || s_origin > s_vertex + bound) return true;
  }
  return false;
}

/// Consecutive stalled steps (GjkStep::stalled) a distance loop takes before it stops with
/// no_progress: each costs one support call, and a stall that lasts longer is rounding noise.
inline constexpr int kMaxStalledSteps = 4;

/// True if the gap ‖v‖² − v·w = vv − vw is positive beyond the rounding of both products
/// (each within kDotRoundoff of ‖v‖‖w‖ resp. ‖v‖², for ‖w‖² = ww): exact GJK would then
/// decrease ‖v‖ strictly by adding w, even where the decrease is below double resolution.
template <class T>
bool gap_certified(T vv, T vw, T ww) {
  return vv - vw > 2 * dot_roundoff<T> * (vv + std::sqrt(vv * ww));
}

/// Whether a step that did not decrease ‖v‖ in floating point may still be taken (a stalled
/// step): the gap is certified, the new point stays in the simplex (so the simplex changes and
/// v turns), the new ‖v‖² = new_vv is not above vv by more than rounding (relative 1e-12 in
/// double, scaled to T's rounding), and
/// fewer than kMaxStalledSteps stalls came in a row. Near-parallel edges need these steps: the
/// exact decrease there is a relative 1e-17 per step, while the simplex still moves towards
/// the feature that decides the answer.
template <class T>
bool may_stall(T vv, T vw, T ww, T new_vv, bool keeps_new_point, int stalls) {
  return stalls < kMaxStalledSteps && keeps_new_point &&
         new_vv <= vv * (1 + rounding_scaled<T>(1e-12)) && gap_certified(vv, vw, ww);
}

/// c_A − c_B for shapes that have an interior point (vertex_mean(), as Polytope), written to
/// `out`; false, leaving `out` alone, for other shapes or when the difference is zero or not
/// finite (then the query falls back to its fixed first direction).
template <class A, class B, class T>
bool centre_difference(const A& a, const B& b, Vec3T<T>& out) {
  if constexpr (requires {
                  { a.vertex_mean() } -> std::convertible_to<Vec3T<T>>;
                  { b.vertex_mean() } -> std::convertible_to<Vec3T<T>>;
                }) {
    const Vec3T<T> c = a.vertex_mean() - b.vertex_mean();
    if (!is_finite(c) || is_zero(c)) return false;
    out = c;
    return true;
  } else {
    return false;
  }
}

}  // namespace detail

}  // namespace gjklab
