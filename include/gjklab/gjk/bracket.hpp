// The proof behind a distance query's `converged`: a bracket [lower, upper] that holds the
// exact distance between the shapes whatever the rounding of the query, and the test that it
// is narrow enough.
//
// Every bound below is the floating-point value plus or minus E = 24u·μ, with u the unit
// roundoff of T and μ = √3·(M_A + M_B) the pair's magnitude (M the shape's largest
// |coordinate|): μ bounds ‖a‖ + ‖b‖ for any points a of A and b of B, hence every point of
// A − B and every distance between the shapes.
//
// Upper bound. The kept simplex points with weights λ_i ≥ 0 (S = Σ λ_i) name the point
// p = Σ (λ_i/S)(a_i − b_i) of A − B, whose norm is at least the distance. Σ λ_i a_i and Σ λ_i b_i
// in floating point are each within γ4·S·√3·M of their exact values (γ4 = 4u/(1 − 4u)), their
// difference within u of its size, the norm within 2u, S within γ4 and the division within u,
// each relative to quantities at most μ: in all within 13u·μ, and the final sum adds u·2μ, so
//   ‖p‖ ≤ fl(‖wa − wb‖/S) + E.
//
// Lower bound. For any direction d and the support point w = a − b the query took in −d, every
// point z of A − B has d·z ≥ d·w − 12u·‖d‖·μ: the support scan picks the vertex maximising the
// rounded dot products, each within γ3·‖d‖·‖x‖ of the exact one, so the exact optimum beats the
// chosen vertex by at most two such errors per shape; w's own subtraction and the rounded d·w
// add u and γ3 of ‖d‖‖w‖. The quotient by fl(‖d‖) adds 5u of the quotient (at most μ) and the
// subtraction u·μ, so
//   distance ≥ fl(d·w)/fl(‖d‖) − E.
// This holds only for supports that
// scan every vertex; a hill-climbing polytope's support is a local maximum of rounded values,
// whose gap to the global one has no such bound, and its lower bound is taken from a full scan
// in the final direction instead (gjk_distance.hpp).
//
// Acceptance. The reported distance r is put inside the bracket ([min(L, r), max(U, r)]), and
// the query's `converged` needs the bracket narrow enough: by the options' criterion applied
// to the proven numbers (GjkConvergence with ‖v‖² replaced by U² and v·w by U·L), or narrower
// than the pair's resolution, 192u·μ (2.1e-14 of the pair's magnitude in double): four times
// the widest bracket that rounding alone leaves (each bound's E, twice),
// the size below which the coordinates' own rounding decides, where near contact no relative
// criterion can be met. A contact answer (distance 0) is accepted only there: its upper bound
// must be within the resolution.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "gjklab/geometry/types.hpp"
#include "gjklab/gjk/options.hpp"
#include "gjklab/gjk/simplex.hpp"

namespace gjklab {

/// A proven enclosure of the exact distance: lower ≤ distance ≤ upper (length units).
template <class T>
struct DistanceBracketT {
  T lower = 0;
  T upper = std::numeric_limits<T>::infinity();
};

/// The shapes whose support is the argmax of rounded dot products over points whose largest
/// |coordinate| they report (Polytope, ScalarCloud): the ones a bracket can be proven for.
template <class S>
concept MagnitudeReporting = requires(const S& s) {
  {s.max_magnitude()};
};

/// The scale of every rounding bound of the pair: √3·(M_A + M_B), bounding ‖a‖ + ‖b‖ for any
/// points a of A and b of B; infinity for shapes that do not report their magnitude (no
/// bracket is then proven, and such queries never claim `converged`).
template <class T, class A, class B>
T pair_magnitude(const A& a, const B& b) {
  if constexpr (MagnitudeReporting<A> && MagnitudeReporting<B>) {
    return std::sqrt(T(3)) *
           (static_cast<T>(a.max_magnitude()) + static_cast<T>(b.max_magnitude()));
  } else {
    return std::numeric_limits<T>::infinity();
  }
}

/// True if the shape's support is a full scan (Polytope's hill climbing is not).
template <class S>
bool scans_support(const S& s) {
  if constexpr (requires { s.uses_hill_climbing(); })
    return !s.uses_hill_climbing();
  else
    return true;
}

namespace detail {

template <class T>
constexpr T unit_roundoff = std::numeric_limits<T>::epsilon() / 2;

}  // namespace detail

/// E = 24u·magnitude: the rounding term of both bounds (see the file comment).
template <class T>
T bracket_rounding(T magnitude) {
  return 24 * detail::unit_roundoff<T> * magnitude;
}

/// 192u·magnitude: the width below which a bracket is accepted whatever the criterion asks.
template <class T>
T bracket_resolution(T magnitude) {
  return 8 * bracket_rounding(magnitude);
}

/// The lower bound that the support plane of direction d (‖d‖² = dd) through the support
/// point w (d·w = dw, both rounded) proves; 0 when it proves nothing. `rounding` is
/// bracket_rounding of the pair's magnitude.
template <class T>
T support_plane_lower_bound(T dw, T dd, T rounding) {
  if (!(dw > 0) || !(dd > 0)) return 0;
  const T bound = dw / std::sqrt(dd) - rounding;
  return bound > 0 ? bound : T(0);
}

/// The upper bound that the first `count` weights prove, given the sums Σ λ_k a_k = wa and
/// Σ λ_k b_k = wb formed in floating point from zero in the simplex's order (as
/// combine_witnesses forms the witnesses, which the query has anyway); infinity when the
/// weights do not name a point (negative, zero sum, not finite).
template <class T>
T simplex_upper_bound(const std::array<T, 4>& weights, int count, const Vec3T<T>& wa,
                      const Vec3T<T>& wb, T rounding) {
  T total = 0;
  for (int k = 0; k < count; ++k) {
    if (!(weights[k] >= 0)) return std::numeric_limits<T>::infinity();
    total += weights[k];
  }
  if (!(total > 0)) return std::numeric_limits<T>::infinity();
  const T upper = (wa - wb).norm() / total + rounding;
  return std::isfinite(upper) ? upper : std::numeric_limits<T>::infinity();
}

/// The bracket put around the reported distance r (so that |r − distance| ≤ upper − lower).
template <class T>
DistanceBracketT<T> around(DistanceBracketT<T> b, T reported) {
  b.lower = std::min(b.lower, reported);
  b.upper = std::max(b.upper, reported);
  return b;
}

/// Whether a gap ‖v‖² − v·w (squared length units) meets the tolerances of
/// options.convergence (see GjkConvergence), for ‖v‖² = vv; the tolerances are the user's,
/// rounded to T. The one statement of the criterion: the distance loop's stopping test
/// (gap_converged) and the bracket's acceptance both apply it.
template <class T>
bool gap_within_tolerance(const GjkDistanceOptions& options, T gap, T vv) {
  switch (options.convergence) {
    case GjkConvergence::relative:
      return gap <= static_cast<T>(options.relative_gap) * vv ||
             gap <= static_cast<T>(options.absolute_gap_squared);
    case GjkConvergence::absolute:
      return gap <= static_cast<T>(options.absolute_gap_squared);
    case GjkConvergence::duality_gap:
      return 2 * gap <= static_cast<T>(options.duality_gap_tolerance);
  }
  return false;
}

/// Whether the bracket is narrow enough for `converged` (see the file comment): the options'
/// criterion on U and L, or a width within the pair's resolution (bracket_resolution).
template <class T>
bool bracket_accepted(const GjkDistanceOptions& options, const DistanceBracketT<T>& b,
                      T magnitude) {
  // Each side is rounded up by 4u, more than the rounding of the products it is made of, so
  // that a width accepted in floating point is within the tolerance in exact arithmetic.
  const T up = 1 + 4 * detail::unit_roundoff<T>;
  const T width = (b.upper - b.lower) * up;
  if (!(width >= 0) || !std::isfinite(width)) return false;
  if (width <= bracket_resolution(magnitude)) return true;
  // U² − U·L = U·(U − L), in squared length units, against the criterion's tolerances.
  return gap_within_tolerance(options, b.upper * width * up, b.upper * b.upper);
}

}  // namespace gjklab
