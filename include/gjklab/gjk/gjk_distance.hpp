// GJK distance query (Gilbert, Johnson and Keerthi 1988) with an interchangeable
// sub-algorithm (Johnson's by default).
//
// Iterates v_k, the point of the current simplex closest to the origin, towards the point of
// A − B closest to the origin. Each iteration takes the support point w = s_A(−v) − s_B(v),
// tests termination, adds w to the simplex and reduces it with the sub-algorithm.
// Upper bound of the distance: ‖v‖; lower bound: v·w/‖v‖.
#pragma once

#include <cmath>
#include <concepts>
#include <limits>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "gjklab/geometry/support.hpp"
#include "gjklab/gjk/bracket.hpp"
#include "gjklab/gjk/directions.hpp"
#include "gjklab/gjk/johnson.hpp"
#include "gjklab/gjk/options.hpp"
#include "gjklab/gjk/precise_subsimplex.hpp"
#include "gjklab/gjk/recentred.hpp"
#include "gjklab/gjk/result.hpp"
#include "gjklab/gjk/simplex.hpp"
#include "gjklab/gjk/trace.hpp"

namespace gjklab {

/// The point of a simplex closest to the origin, with the matching points of A and B and the
/// barycentric weights of the (reduced) simplex points.
template <class T>
struct ClosestOnSimplexT {
  Vec3T<T> v = Vec3T<T>::Zero();
  Vec3T<T> witness_a = Vec3T<T>::Zero();
  Vec3T<T> witness_b = Vec3T<T>::Zero();
  std::array<T, 4> weights{};
};
using ClosestOnSimplex = ClosestOnSimplexT<double>;

/// A distance sub-algorithm: reduces the simplex to the sub-simplex whose convex hull holds
/// the point closest to the origin, and computes that point. Returns false, leaving the
/// simplex untouched, when it cannot decide (a degenerate simplex).
///
/// `solve` is the same computation without applying it: for the points y[0 … count−1] it
/// returns {found, subset (bitmask), weights (by point index), closest}, so that the driver
/// can test the answer before it changes its simplex.
template <class S>
concept SubAlgorithm = requires(const S& s, Simplex& simplex, ClosestOnSimplex& out,
                                const std::array<Vec3, 4>& y, int count) {
  { s.reduce(simplex, out) } -> std::same_as<bool>;
  { s.solve(y, count).found } -> std::convertible_to<bool>;
  { s.solve(y, count).subset } -> std::convertible_to<std::uint8_t>;
  { s.solve(y, count).weights } -> std::convertible_to<std::array<double, 4>>;
  { s.solve(y, count).closest } -> std::convertible_to<Vec3>;
};

namespace detail {

/// The witness points of the simplex's closest point: Σ λ_k a_k and Σ λ_k b_k over the kept
/// points, in order. The loops keep only v and the weights and form the witnesses once, at the
/// end.
template <class T>
void combine_witnesses(const SimplexT<T>& simplex, const std::array<T, 4>& weights,
                       Vec3T<T>& witness_a, Vec3T<T>& witness_b) {
  Vec3T<T> wa = Vec3T<T>::Zero(), wb = Vec3T<T>::Zero();
  for (int k = 0; k < simplex.size(); ++k) {
    wa += weights[k] * simplex[k].a;
    wb += weights[k] * simplex[k].b;
  }
  witness_a = wa;
  witness_b = wb;
}

/// Keeps the subset a sub-algorithm's solution chose and records v and the kept points'
/// weights, in order, in `out` (its witnesses are left alone).
template <class Solution, class T>
void keep_subset(const Solution& s, SimplexT<T>& simplex, ClosestOnSimplexT<T>& out) {
  std::array<T, 4> weights{};
  int kept = 0;
  for (int i = 0; i < simplex.size(); ++i)
    if (s.subset & (1u << i)) weights[kept++] = s.weights[i];
  simplex.keep(s.subset);
  out.v = s.closest;
  out.weights = weights;
}

/// Applies a sub-algorithm's answer (subset, weights by original index, closest point) to the
/// simplex and the closest-point record, witnesses included. False, leaving both untouched, if
/// nothing was found.
template <class Solution, class T>
bool keep_solution(const Solution& s, SimplexT<T>& simplex, ClosestOnSimplexT<T>& out) {
  if (!s.found) return false;
  keep_subset(s, simplex, out);
  combine_witnesses(simplex, out.weights, out.witness_a, out.witness_b);
  return true;
}

}  // namespace detail

/// Johnson's distance sub-algorithm (see johnson.hpp), as published: no backup procedure.
struct JohnsonSubAlgorithm {
  template <class T>
  JohnsonSolutionT<T> solve(const std::array<Vec3T<T>, 4>& y, int count) const {
    return johnson_closest_point(y, count);
  }
  template <class T>
  bool reduce(SimplexT<T>& simplex, ClosestOnSimplexT<T>& out) const {
    return detail::keep_solution(solve(simplex.points(), simplex.size()), simplex, out);
  }
};

/// The sub-simplex solve in double-word arithmetic (precise_subsimplex.hpp): what a query
/// continues with when its own sub-algorithm's answer could not be proven (see
/// gjk_distance_run_as_given). Not a registered algorithm of its own.
struct PreciseSubAlgorithm {
  template <class T>
  SubsimplexSolutionT<T> solve(const std::array<Vec3T<T>, 4>& y, int count) const {
    return precise_closest_point(y, count);
  }
  template <class T>
  bool reduce(SimplexT<T>& simplex, ClosestOnSimplexT<T>& out) const {
    return detail::keep_solution(solve(simplex.points(), simplex.size()), simplex, out);
  }
};

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

/// The starting simplex of a distance query and its closest point. Cold start (`warm` empty):
/// the support point of A − B in options.initial_direction (one support call). Warm start:
/// the given points, each re-evaluated on the current shapes from its vertex indices when the
/// shape reports them (so a previous query's final simplex stays valid after the shapes
/// moved); points without indices are taken as given and must be points of the current A and
/// B. Repeated and non-finite points are skipped, and the rest is reduced by the sub-algorithm;
/// when nothing usable remains or the reduction fails, the query starts cold.
///
/// Returns d_0, the direction the start minimised over A − B (the negated direction of the
/// first support call), or the start's closest point after a warm start (see directions.hpp).
template <SubAlgorithm Sub, SupportMap A, SupportMap B, class T>
Vec3T<T> start_simplex(const Sub& sub, const A& a, const B& b, const GjkDistanceOptions& options,
                       std::span<const SimplexVertexT<T>> warm, SimplexT<T>& simplex,
                       ClosestOnSimplexT<T>& best, int& support_calls) {
  simplex.clear();
  for (const SimplexVertexT<T>& given : warm) {
    if (simplex.full()) break;
    SimplexVertexT<T> v = given;
    if constexpr (requires { a.vertices(); }) {
      if (v.index_a >= 0 && static_cast<std::size_t>(v.index_a) < a.vertices().size())
        v.a = a.vertices()[v.index_a];
    }
    if constexpr (requires { b.vertices(); }) {
      if (v.index_b >= 0 && static_cast<std::size_t>(v.index_b) < b.vertices().size())
        v.b = b.vertices()[v.index_b];
    }
    v.w = v.a - v.b;
    if (is_finite(v.w) && !simplex.contains(v.w)) simplex.push(v);
  }
  if (!simplex.empty()) {
    SimplexT<T> reduced = simplex;
    if (sub.reduce(reduced, best) && is_finite(best.v)) {
      simplex = reduced;
      return best.v;
    }
  }
  Vec3T<T> centre;
  const bool from_centre =
      options.start == GjkDistanceStart::centre_direction && centre_difference(a, b, centre);
  const Vec3T<T> search =
      from_centre ? Vec3T<T>(-centre) : Vec3T<T>(options.initial_direction.cast<T>());
  const SimplexVertexT<T> first = minkowski_support(a, b, search);
  ++support_calls;
  simplex.clear();
  simplex.push(first);
  best = {first.w, first.a, first.b, {1, 0, 0, 0}};
  return -search;
}

/// What becomes of a step whose simplex plus w was solved: taken (‖v‖ decreased, or a bounded
/// stall), the momentum dropped (restart), or the query stops: converged when the gap is within
/// its rounding (optimal), else with no_progress (stop).
enum class StepOutcome : std::uint8_t { progressed, stalled, restart, optimal, stop };

/// The quantities of one iteration that the step needs: ‖v‖², v·s and ‖s‖² for the support
/// point s, and whether separation is proven.
template <class T>
struct StepInputs {
  T vv, vw, ww;
  bool separation_proven;
};

/// What a step did: the trace step to record, and the stop when the query ends there.
struct StepVerdict {
  GjkStep step;
  std::optional<DistanceStop> stop;
};

/// Solves the simplex plus the support point `next` with the sub-algorithm and takes the step
/// (contact, progress, a bounded stall), drops the momentum, or stops; the simplex changes only
/// once the answer is accepted.
template <class Sub, class T, class Observer>
StepVerdict solve_step(const Sub& sub, DistanceQueryState<T, Observer>& q,
                       const SimplexVertexT<T>& next, const StepInputs<T>& in, bool& accelerated,
                       int& stalls) {
  SimplexT<T>& simplex = q.simplex();
  ClosestOnSimplexT<T>& best = q.best;
  std::array<Vec3T<T>, 4> y = simplex.points();
  y[simplex.size()] = next.w;
  const auto s = sub.solve(y, simplex.size() + 1);
  if (!s.found) return {GjkStep::degenerate, DistanceStop{Termination::degenerate_simplex, false}};
  if (!is_finite(s.closest))
    return {GjkStep::non_finite, DistanceStop{Termination::numerical_failure, false}};
  const bool full = s.subset == 0xF;
  // A full simplex is contact unless its tetrahedron provably misses the origin: flat within
  // rounding, with the origin off its plane (kissing faces), where the sub-algorithm's
  // weights are rounding noise. Then the query goes on from the nearest face, as after a
  // separation certificate.
  const bool contact = full ? !origin_outside_tetrahedron(y)
                            : q.in_contact(s.closest, max_norm_squared(y, s.subset));
  if (!in.separation_proven && contact) {
    apply_solution(s, next, simplex, best);
    return {GjkStep::contact, DistanceStop{Termination::converged, true}};
  }
  // The upper bound ‖v‖ must decrease strictly. When rounding hides the decrease, a plain
  // query takes the step only as a bounded stall (may_stall), else keeps the old v and stops;
  // an accelerated query drops its momentum instead. The stop is convergence when the gap
  // ‖v‖² − v·w is not certified (within the rounding of its two products): then v·w/‖v‖ is a
  // lower bound of the distance to that rounding, and ‖v‖ is within 4·kDotRoundoff·(‖v‖ + ‖w‖)
  // of the distance, the precision of the pair's scale (near contact, where ‖v‖ ≪ ‖w‖, no
  // relative gap of ‖v‖² can be met). A certified gap left is a descent cut short: no_progress.
  auto judge = [&](T new_vv, bool keeps_next) {
    if (new_vv < in.vv) return StepOutcome::progressed;
    if (accelerated) return StepOutcome::restart;
    if (may_stall(in.vv, in.vw, in.ww, new_vv, keeps_next, stalls)) return StepOutcome::stalled;
    return gap_certified(in.vv, in.vw, in.ww) ? StepOutcome::stop : StepOutcome::optimal;
  };
  const auto taken = [](StepOutcome o) {
    return o == StepOutcome::progressed || o == StepOutcome::stalled;
  };
  StepOutcome outcome;
  if (full) {
    // Contact is ruled out (by the separation certificate or the tetrahedron test): the
    // closest point lies on one of the faces.
    SimplexT<T> reduced = simplex;
    reduced.push(next);
    ClosestOnSimplexT<T> candidate;
    if (!detail::reduce_to_closest_face(sub, reduced, candidate))
      return {GjkStep::degenerate, DistanceStop{Termination::degenerate_simplex, false}};
    outcome = judge(candidate.v.squaredNorm(), reduced.contains(next.w));
    if (taken(outcome)) {
      simplex = reduced;
      best = candidate;
    }
  } else {
    outcome = judge(s.closest.squaredNorm(), (s.subset >> simplex.size()) & 1u);
    if (taken(outcome)) apply_solution(s, next, simplex, best);
  }
  switch (outcome) {
    case StepOutcome::restart:
      accelerated = false;
      return {GjkStep::momentum_restart, std::nullopt};
    case StepOutcome::optimal:
      return {GjkStep::gap_converged, DistanceStop{Termination::converged, false}};
    case StepOutcome::stop:
      return {GjkStep::no_progress, DistanceStop{Termination::no_progress, false}};
    case StepOutcome::stalled:
      ++stalls;
      return {GjkStep::stalled, std::nullopt};
    case StepOutcome::progressed:
      break;
  }
  stalls = 0;
  return {GjkStep::continued, std::nullopt};
}

/// The iteration's search direction: the momentum direction while the query is accelerated,
/// else v. A vanishing or non-finite momentum direction carries no information: the query goes
/// plain from there.
template <class T, class Directions>
Vec3T<T> search_direction(Directions& directions, int iteration, const Vec3T<T>& v,
                          bool& accelerated) {
  if constexpr (Directions::momentum) {
    if (accelerated) {
      const Vec3T<T> d = directions.direction(iteration, v);
      if (is_finite(d) && !is_zero(d)) return d;
      accelerated = false;
    }
  }
  return v;
}

/// What the support point s found in direction −d says: the plane d·x = d·s supports A − B, so
/// for d·s > 0 the distance is at least about d·s/‖d‖ (the proven bound: bracket.hpp), and
/// d·s beyond its rounding certifies that the shapes do not intersect (dw = d·s, dd = ‖d‖²,
/// ww = ‖s‖²).
template <class T, class Observer>
void note_support_plane(DistanceQueryState<T, Observer>& q, bool& separation_proven, T dw, T dd,
                        T ww) {
  q.note_lower_bound(dw, dd);
  if (!separation_proven && separation_certified(dw, dd, ww)) separation_proven = true;
}

/// The GJK distance loop of every variant: the search direction comes from `directions` (see
/// directions.hpp), everything else is shared: the cold or warm start, the stopping tests, the
/// separation certificate, the sub-algorithm's step, stalls and the momentum restart.
/// q.out.simplex and q.best hold the answer when it returns.
template <SubAlgorithm Sub, SupportMap A, SupportMap B, class T, class Observer, class Directions>
DistanceStop gjk_distance_loop(const A& a, const B& b, std::span<const SimplexVertexT<T>> warm,
                               DistanceQueryState<T, Observer>& q, Directions& directions) {
  const Sub sub{};
  const GjkDistanceOptions& options = q.options;
  DistanceResultT<T>& out = q.out;
  SimplexT<T>& simplex = q.simplex();
  ClosestOnSimplexT<T>& best = q.best;
  const Vec3T<T> d0 = start_simplex(sub, a, b, options, warm, simplex, best, out.support_calls);

  if (!is_finite(simplex[0].w)) return {Termination::numerical_failure, false};
  // A warm start may begin with a tetrahedron that encloses the origin.
  if (simplex.full() || q.in_contact(best.v, simplex)) return {Termination::converged, true};

  // Set once some support point s satisfies d·s > 0 beyond rounding: then the plane d·x = d·s
  // separates the origin from A − B, a certificate that the shapes do not intersect. A
  // sub-algorithm that later claims contact has accepted a numerically flat simplex.
  bool separation_proven = false;
  // Steps in a row whose decrease of ‖v‖ rounding hid (see may_stall).
  int stalls = 0;
  bool accelerated = Directions::momentum;
  if constexpr (Directions::momentum) {
    const T n0 = d0.norm();
    directions.start(n0 > 0 ? Vec3T<T>(d0 / n0 * simplex[0].w.norm()) : best.v, simplex[0].w);
  }

  // A continuation (gjk_distance_run_as_given) counts on from the iterations already made.
  for (++out.iterations; out.iterations <= options.max_iterations; ++out.iterations) {
    const Vec3T<T> v = best.v;
    const T vv = v.squaredNorm();
    const Vec3T<T> d = search_direction(directions, out.iterations, v, accelerated);
    auto trace = [&](const SimplexVertexT<T>& w, T vw, GjkStep step) {
      q.trace(-d, w, vv, vw, step);
    };
    const SimplexVertexT<T> next = detail::minkowski_support(a, b, Vec3T<T>(-d));
    ++out.support_calls;
    if (!is_finite(next.w)) {
      trace(next, std::numeric_limits<T>::quiet_NaN(), GjkStep::non_finite);
      return {Termination::numerical_failure, false};
    }
    directions.observe(next.w);
    const T vw = v.dot(next.w);
    const T ww = next.w.squaredNorm();
    if (accelerated)
      note_support_plane(q, separation_proven, d.dot(next.w), d.squaredNorm(), ww);
    else
      note_support_plane(q, separation_proven, vw, vv, ww);

    // The duality gap at s: the stopping test when plain, the restart test when accelerated.
    const bool gap_met = gap_converged(options, vv, vw);
    // s already in the simplex: in exact arithmetic its gap would be 0 (every retained point
    // lies on the plane v·x = ‖v‖²), so the new point brings no information.
    const bool repeated = !gap_met && simplex.contains(next.w);
    if (accelerated && (gap_met || repeated)) {
      accelerated = false;
      trace(next, vw, GjkStep::momentum_restart);
      continue;
    }
    if (gap_met) {
      trace(next, vw, GjkStep::gap_converged);
      return {Termination::converged, false};
    }
    if (repeated) {
      trace(next, vw, GjkStep::repeated_support);
      return {Termination::converged, false};
    }
    const StepVerdict verdict =
        solve_step(sub, q, next, StepInputs<T>{vv, vw, ww, separation_proven}, accelerated, stalls);
    const bool last = out.iterations == options.max_iterations;
    trace(next, vw,
          verdict.stop || verdict.step == GjkStep::momentum_restart || !last ? verdict.step
                                                                             : GjkStep::step_limit);
    if (verdict.stop) return *verdict.stop;
  }
  out.iterations = options.max_iterations;
  return {Termination::step_limit, false};
}

/// For shapes whose support is not a full scan (hill climbing), the support plane that a full
/// scan of both shapes in the final direction −v proves (the loop's planes prove nothing
/// there, bracket.hpp); one scan per shape, once per query.
template <SupportMap A, SupportMap B, class T, class Observer>
void scan_lower_bound(const A& a, const B& b, DistanceQueryState<T, Observer>& q) {
  if constexpr (requires {
                  a.scan_support_index(q.best.v);
                  b.scan_support_index(q.best.v);
                }) {
    if (q.planes_prove || !std::isfinite(q.rounding) || is_zero(q.best.v)) return;
    const Vec3T<T>& v = q.best.v;
    const Vec3T<T> w =
        a.vertices()[a.scan_support_index(Vec3T<T>(-v))] - b.vertices()[b.scan_support_index(v)];
    q.planes_prove = true;
    q.note_lower_bound(v.dot(w), v.squaredNorm());
  }
}

/// Whether a loop's stop leaves a continuation something to try: its answer is not proven
/// (the termination finish() judged is not converged), it ended on its own merits rather than
/// on a NaN or the step limit, and iterations are left.
template <class T>
bool worth_continuing(const DistanceResultT<T>& r, const GjkDistanceOptions& options) {
  return r.termination != Termination::converged &&
         r.termination != Termination::numerical_failure &&
         r.termination != Termination::step_limit && r.iterations < options.max_iterations;
}

/// Runs the loop on the shapes as given and builds the result in the returned object itself.
///
/// Where the sub-algorithm's answer cannot be proven (its bracket is too wide, bracket.hpp), the
/// query goes on from its final simplex with the sub-simplex solved in double-word arithmetic
/// (PreciseSubAlgorithm) and plain directions, within the same iteration budget, and keeps the
/// answer with the narrower bracket: the stop of a needle triangle or of nearly parallel
/// segments, where every sub-algorithm's decisions in double are rounding noise, is then
/// decided at 106 bits. The lower bound carries over (every support plane is a proof).
template <SubAlgorithm Sub, SupportMap A, SupportMap B, class Observer, class Directions,
          class T = shape_scalar_t<A>>
DistanceResultT<T> gjk_distance_run_as_given(const A& a, const B& b,
                                             const GjkDistanceOptions& options,
                                             std::span<const SimplexVertexT<T>> warm,
                                             Observer& observer, Directions directions) {
  DistanceResultT<T> out;
  DistanceQueryState<T, Observer> q{options, observer, out};
  q.measure(a, b);
  const DistanceStop stop = gjk_distance_loop<Sub>(a, b, warm, q, directions);
  scan_lower_bound(a, b, q);
  q.finish(stop);
  if (!worth_continuing(out, options)) return out;

  DistanceResultT<T> again;
  again.iterations = out.iterations;
  again.support_calls = out.support_calls;
  DistanceQueryState<T, Observer> p{options, observer, again};
  p.measure(a, b);
  p.lower_bound = q.lower_bound;
  p.provable_contact = bracket_resolution(p.magnitude) - p.rounding;
  const SimplexT<T> start = out.simplex;
  PlainDirections plain;
  const DistanceStop precise_stop =
      gjk_distance_loop<PreciseSubAlgorithm>(a, b, start.vertices(), p, plain);
  scan_lower_bound(a, b, p);
  p.finish(precise_stop);
  const bool better = again.termination == Termination::converged ||
                      again.upper_bound - again.lower_bound < out.upper_bound - out.lower_bound;
  if (better) return again;
  // The first answer stands, judged again with the lower bound the continuation proved, at the
  // cost of both.
  q.lower_bound = std::max(q.lower_bound, p.lower_bound);
  q.finish(stop);
  out.iterations = again.iterations;
  out.support_calls = again.support_calls;
  return out;
}

/// Runs the query: on the exactly re-centred pair when options.recenter applies to two
/// clouds far from the origin (recentred.hpp), else on the shapes as given.
template <SubAlgorithm Sub, SupportMap A, SupportMap B, class Observer,
          class Directions = PlainDirections, class T = shape_scalar_t<A>>
DistanceResultT<T> gjk_distance_run(const A& a, const B& b, const GjkDistanceOptions& options,
                                    std::span<const SimplexVertexT<T>> warm, Observer&& observer,
                                    Directions directions = {}) {
  using Traced = std::remove_reference_t<Observer>;
  if constexpr (RecentrableCloud<A> && std::same_as<A, B>) {
    if (const auto t = recentring_of(a, b, options.recenter)) {
      const A moved_a = a.translated(-*t), moved_b = b.translated(-*t);
      // Warm-start points are re-read from their indices; points without indices move too.
      std::vector<SimplexVertexT<T>> start(warm.begin(), warm.end());
      for (SimplexVertexT<T>& v : start) {
        v.a -= *t;
        v.b -= *t;
      }
      TranslatedTrace<Traced> moved_trace{observer, t->template cast<double>()};
      DistanceResultT<T> out = gjk_distance_run_as_given<Sub>(
          moved_a, moved_b, options, std::span<const SimplexVertexT<T>>(start), moved_trace,
          directions);
      translate_answer(out, *t);
      return out;
    }
  }
  return gjk_distance_run_as_given<Sub>(a, b, options, warm, observer, directions);
}

}  // namespace detail

/// Distance between two convex shapes given by support maps (both in the same frame), with
/// sub-algorithm Sub and an observer that receives a trace of every iteration when enabled.
/// The result's termination says why the loop stopped; on any stop other than `converged` the
/// answer is the best upper bound found so far (‖v‖ and its witnesses). The query runs in the
/// shapes' scalar type (double; float or long double for ScalarCloud, scalar_cloud.hpp).
template <SubAlgorithm Sub, SupportMap A, SupportMap B, class Observer = NoTrace>
DistanceResultT<shape_scalar_t<A>> gjk_distance_with(const A& a, const B& b,
                                                     const GjkDistanceOptions& options,
                                                     Observer&& observer = {}) {
  return detail::gjk_distance_run<Sub>(a, b, options, {}, std::forward<Observer>(observer));
}

/// The same query warm-started from a simplex, typically the previous query's final simplex
/// (`result.simplex.vertices()`) in a sequence of queries on a moving pair. Polytopes report
/// vertex indices, so each point is re-evaluated on the current shapes (see
/// detail::start_simplex); a usable start costs no support call. Same answer and termination
/// vocabulary as the cold query, usually in fewer iterations when the pair moved little.
template <SubAlgorithm Sub, SupportMap A, SupportMap B, class Observer = NoTrace>
DistanceResultT<shape_scalar_t<A>> gjk_distance_warm_with(
    const A& a, const B& b, std::span<const SimplexVertexT<shape_scalar_t<A>>> start,
    const GjkDistanceOptions& options, Observer&& observer = {}) {
  return detail::gjk_distance_run<Sub>(a, b, options, start, std::forward<Observer>(observer));
}

/// `gjk-johnson`: GJK distance with Johnson's sub-algorithm.
template <SupportMap A, SupportMap B, class Observer = NoTrace>
DistanceResultT<shape_scalar_t<A>> gjk_distance(const A& a, const B& b,
                                                const GjkDistanceOptions& options = {},
                                                Observer&& observer = {}) {
  return gjk_distance_with<JohnsonSubAlgorithm>(a, b, options, std::forward<Observer>(observer));
}

}  // namespace gjklab
