// GJK distance query (Gilbert, Johnson and Keerthi 1988) with Johnson's sub-algorithm.
//
// Iterates v_k, the point of the current simplex closest to the origin, towards the point of
// A − B closest to the origin. Each iteration takes the support point w = s_A(−v) − s_B(v),
// tests termination, adds w to the simplex and reduces it with Johnson's sub-algorithm.
// Upper bound of the distance: ‖v‖; lower bound: v·w/‖v‖.
#pragma once

#include <cmath>

#include "gjklab/geometry/support.hpp"
#include "gjklab/gjk/johnson.hpp"
#include "gjklab/gjk/options.hpp"
#include "gjklab/gjk/result.hpp"
#include "gjklab/gjk/simplex.hpp"

namespace gjklab {

namespace detail {

/// Support point of A − B in direction d, with its two parts.
template <SupportMap A, SupportMap B>
SimplexVertex minkowski_support(const A& a, const B& b, const Vec3& d) {
  SimplexVertex v;
  v.a = a.support(d);
  v.b = b.support(-d);
  v.w = v.a - v.b;
  return v;
}

/// The point of a simplex closest to the origin, with the matching points of A and B.
struct ClosestOnSimplex {
  Vec3 v = Vec3::Zero();
  Vec3 witness_a = Vec3::Zero();
  Vec3 witness_b = Vec3::Zero();
};

/// Reduces the simplex to Johnson's sub-simplex and computes its closest point and witnesses.
/// Returns false (simplex untouched) when Johnson's tests accept no subset.
inline bool johnson_reduce(Simplex& simplex, ClosestOnSimplex& out) {
  std::array<Vec3, 4> y;
  for (int i = 0; i < simplex.size(); ++i) y[i] = simplex[i].w;
  const JohnsonSolution s = johnson_closest_point(y, simplex.size());
  if (!s.found) return false;
  out = {s.closest, Vec3::Zero(), Vec3::Zero()};
  for (int i = 0; i < simplex.size(); ++i) {
    if (!(s.subset & (1u << i))) continue;
    out.witness_a += s.weights[i] * simplex[i].a;
    out.witness_b += s.weights[i] * simplex[i].b;
  }
  simplex.keep(s.subset);
  return true;
}

}  // namespace detail

/// Relative error bound of a rounded 3-vector dot product, |fl(x·y) − x·y| ≤ 3u‖x‖‖y‖ with
/// u = 2^-53, rounded up: about 4.5u.
inline constexpr double kDotRoundoff = 1e-15;

/// Default first search direction. Any fixed direction keeps the query scale-invariant.
inline const Vec3 kDefaultInitialDirection = Vec3(1, 0, 0);

/// Distance between two convex shapes given by support maps (both in the same frame).
/// The result's termination says why the loop stopped; on any stop other than `converged` the
/// answer is the best upper bound found so far (‖v‖ and its witnesses).
template <SupportMap A, SupportMap B>
DistanceResult gjk_distance(const A& a, const B& b, const GjkDistanceOptions& options = {},
                            const Vec3& initial_direction = kDefaultInitialDirection) {
  DistanceResult out;
  const SimplexVertex first = detail::minkowski_support(a, b, initial_direction);
  out.support_calls = 1;
  Simplex simplex;
  simplex.push(first);
  detail::ClosestOnSimplex best{first.w, first.a, first.b};

  auto finish = [&](Termination t, bool contact) {
    out.intersect = contact;
    out.closest = best.v;
    out.witness_a = best.witness_a;
    out.witness_b = best.witness_b;
    out.distance = contact ? 0.0 : best.v.norm();
    out.termination = t;
    return out;
  };
  // Relative to the simplex, not squared: ‖v‖ ≤ relative_contact · max‖y_i‖ means v is
  // indistinguishable from the rounding noise of the points it was computed from.
  auto in_contact = [&](const Vec3& v, const Simplex& s) {
    const double tol = options.relative_contact;
    return v.squaredNorm() <= tol * tol * s.max_norm_squared();
  };

  if (!first.w.allFinite()) return finish(Termination::numerical_failure, false);
  if (in_contact(best.v, simplex)) return finish(Termination::converged, true);

  // Set once some support point satisfies v·w > 0: then the plane v·x = v·w separates the
  // origin from A − B, a certificate that the shapes do not intersect. A sub-algorithm that
  // later claims contact has accepted a numerically flat simplex.
  bool separation_proven = false;

  for (out.iterations = 1; out.iterations <= options.max_iterations; ++out.iterations) {
    const Vec3 v = best.v;
    const double vv = v.squaredNorm();
    const SimplexVertex next = detail::minkowski_support(a, b, -v);
    ++out.support_calls;
    if (!next.w.allFinite()) return finish(Termination::numerical_failure, false);

    // Duality gap ‖v‖² − v·w ≥ ‖v‖² − ‖v‖·dist: relative test (van den Bergen) and an
    // optional absolute floor, both on squared lengths.
    const double vw = v.dot(next.w);
    const double gap = vv - vw;
    if (gap <= options.relative_gap * vv || gap <= options.absolute_gap_squared)
      return finish(Termination::converged, false);
    // w already in the simplex: in exact arithmetic its gap would be 0 (every retained point
    // lies on the plane v·x = ‖v‖²), so the new point brings no information.
    if (simplex.contains(next.w)) return finish(Termination::converged, false);
    // Relative rounding bound of a dot product of two 3-vectors (about 4.5 units in the last
    // place): v·w above it is a separation certificate, not noise.
    if (vw > kDotRoundoff * std::sqrt(vv) * next.w.norm()) separation_proven = true;

    Simplex reduced = simplex;
    reduced.push(next);
    detail::ClosestOnSimplex candidate;
    if (!detail::johnson_reduce(reduced, candidate))
      return finish(Termination::degenerate_simplex, false);
    if (!candidate.v.allFinite()) return finish(Termination::numerical_failure, false);
    if (reduced.full() || in_contact(candidate.v, reduced)) {
      if (separation_proven) return finish(Termination::degenerate_simplex, false);
      best = candidate;
      return finish(Termination::converged, true);
    }
    // The upper bound ‖v‖ must decrease strictly; when rounding stops it, keep the old v.
    if (!(candidate.v.squaredNorm() < vv)) return finish(Termination::no_progress, false);
    simplex = reduced;
    best = candidate;
  }
  out.iterations = options.max_iterations;
  return finish(Termination::step_limit, false);
}

}  // namespace gjklab
